// metrics.cpp: trajectory scores as evo's APE and RPE compute them, on the top view: APE
// without and with SE(2) alignment, RPE per frame, path length, pose NEES per frame.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mapping/slam/slam.hpp"

namespace hc::slam {

Pose se2_alignment(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("se2_alignment: trajectories of different or zero length");
    Vec2 me = Vec2::Zero(), mt = Vec2::Zero();
    for (size_t k = 0; k < truth.size(); ++k) {
        me += estimate[k].head<2>();
        mt += truth[k].head<2>();
    }
    me /= static_cast<double>(truth.size());
    mt /= static_cast<double>(truth.size());
    // the rotation φ maximising Σ (t − t̄)·R(φ)(e − ē)
    double sc = 0, ss = 0;
    for (size_t k = 0; k < truth.size(); ++k) {
        const Vec2 e = estimate[k].head<2>() - me, t = truth[k].head<2>() - mt;
        sc += e.x() * t.x() + e.y() * t.y();
        ss += e.x() * t.y() - e.y() * t.x();
    }
    const double phi = (sc == 0 && ss == 0) ? 0.0 : std::atan2(ss, sc);
    Mat2 R;
    R << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    const Vec2 t = mt - R * me;
    return {t.x(), t.y(), phi};
}

TrajectoryMetrics score_trajectory(const std::vector<Pose>& estimate, const std::vector<Pose>& truth,
                                   const std::vector<Mat3>& cov) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("score_trajectory: trajectories of different or zero length");
    if (!cov.empty() && cov.size() != truth.size())
        throw std::invalid_argument("score_trajectory: one covariance per pose");
    const size_t n = truth.size();
    TrajectoryMetrics m;
    m.ape = absolute_trajectory_error(estimate, truth);
    const Pose A = se2_alignment(estimate, truth);
    double s = 0;
    for (size_t k = 0; k < n; ++k) s += (compose(A, estimate[k]) - truth[k]).head<2>().squaredNorm();
    m.ape_se2 = std::sqrt(s / n);
    double rt = 0, rh = 0;
    for (size_t k = 1; k < n; ++k) {
        const Motion dt = between(truth[k - 1], truth[k]), de = between(estimate[k - 1], estimate[k]);
        rt += (de - dt).head<2>().squaredNorm();
        rh += std::pow(wrap_angle(de(2) - dt(2)), 2);
        m.path_length += (truth[k] - truth[k - 1]).head<2>().norm();
    }
    if (n > 1) {
        m.rpe = std::sqrt(rt / (n - 1));
        m.rpe_heading = std::sqrt(rh / (n - 1));
    }
    m.final_error = (estimate.back() - truth.back()).head<2>().norm();
    double sum = 0;
    for (size_t k = 0; k < n; ++k) {
        double e = std::numeric_limits<double>::quiet_NaN();
        if (!cov.empty()) {
            Eigen::VectorXd d = estimate[k] - truth[k];
            d(2) = wrap_angle(d(2));
            e = nees(d, cov[k]);
        }
        m.nees.push_back(e);
        if (std::isfinite(e)) {
            sum += e;
            ++m.nees_frames;
        }
    }
    m.nees_mean = m.nees_frames ? sum / m.nees_frames : std::numeric_limits<double>::quiet_NaN();
    if (m.nees_frames) {
        const double dof = 3.0 * m.nees_frames, point = chi2_quantile(0.95, 3);
        m.nees_lo = chi2_quantile(0.025, dof) / m.nees_frames;
        m.nees_hi = chi2_quantile(0.975, dof) / m.nees_frames;
        int within = 0;
        for (double e : m.nees) within += std::isfinite(e) && e <= point;
        m.nees_within_95 = static_cast<double>(within) / m.nees_frames;
    }
    return m;
}

}  // namespace hc::slam

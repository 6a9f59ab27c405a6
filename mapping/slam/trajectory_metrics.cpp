// trajectory_metrics.cpp: trajectory scores as evo's APE and RPE compute them: APE in 3-D and,
// on the top view, without and with SE(2) alignment (a pass over the poses, or running sums),
// RPE per frame, path length, pose NEES per frame.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mapping/slam/trajectory_metrics.hpp"
#include "mapping/slam/consistency.hpp"

namespace hc::slam {

double absolute_trajectory_error_3d(const std::vector<Mat34>& estimate, const std::vector<Mat34>& truth) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("absolute_trajectory_error_3d: trajectories of different or zero length");
    double s = 0;
    for (size_t k = 0; k < truth.size(); ++k) s += (estimate[k].col(3) - truth[k].col(3)).squaredNorm();
    return std::sqrt(s / static_cast<double>(truth.size()));
}

double absolute_trajectory_error(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("absolute_trajectory_error: trajectories of different or zero length");
    double s = 0;
    for (size_t k = 0; k < truth.size(); ++k) s += (estimate[k] - truth[k]).head<2>().squaredNorm();
    return std::sqrt(s / truth.size());
}

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

void AlignedApeSums::add(const Vec2& e, const Vec2& t) {
    ++n_;
    const Vec2 de = e - me_, dt = t - mt_;
    me_ += de / static_cast<double>(n_);
    mt_ += dt / static_cast<double>(n_);
    const Vec2 ce = e - me_, ct = t - mt_;   // against the updated means (Welford)
    see_ += de.dot(ce);
    stt_ += dt.dot(ct);
    dot_ += de.x() * ct.x() + de.y() * ct.y();
    cross_ += de.x() * ct.y() - de.y() * ct.x();
}

double AlignedApeSums::ape() const {
    if (n_ == 0) throw std::invalid_argument("AlignedApeSums: no pose added");
    // Σ|R(φ)(e − ē) − (t − t̄)|² at φ = atan2(cross, dot): cos φ·dot + sin φ·cross = hypot(dot, cross)
    const double residual = see_ + stt_ - 2 * std::hypot(dot_, cross_);
    return std::sqrt(std::max(residual, 0.0) / static_cast<double>(n_));
}

double TrajectoryScore::add(const Pose& estimate, const Pose& truth, const Mat3* cov) {
    ape_ss_ += (estimate - truth).head<2>().squaredNorm();
    aligned_.add(estimate.head<2>(), truth.head<2>());
    if (n_ > 0) {
        const Motion dt = between(last_truth_, truth), de = between(last_estimate_, estimate);
        rpe_ss_ += (de - dt).head<2>().squaredNorm();
        rpe_heading_ss_ += std::pow(wrap_angle(de(2) - dt(2)), 2);
        path_ += (truth - last_truth_).head<2>().norm();
    }
    final_ = (estimate - truth).head<2>().norm();
    last_estimate_ = estimate;
    last_truth_ = truth;
    ++n_;
    double e = std::numeric_limits<double>::quiet_NaN();
    if (cov) {
        Eigen::VectorXd d = estimate - truth;
        d(2) = wrap_angle(d(2));
        e = nees(d, *cov);
    }
    if (std::isfinite(e)) {
        nees_sum_ += e;
        ++nees_frames_;
        nees_within_ += e <= chi2_quantile(0.95, 3);
    }
    return e;
}

TrajectoryMetrics TrajectoryScore::metrics() const {
    if (n_ == 0) throw std::invalid_argument("TrajectoryScore: no frame scored");
    TrajectoryMetrics m;
    m.ape = std::sqrt(ape_ss_ / static_cast<double>(n_));
    m.ape_se2 = aligned_.ape();
    if (n_ > 1) {
        m.rpe = std::sqrt(rpe_ss_ / static_cast<double>(n_ - 1));
        m.rpe_heading = std::sqrt(rpe_heading_ss_ / static_cast<double>(n_ - 1));
    }
    m.path_length = path_;
    m.final_error = final_;
    m.nees_frames = nees_frames_;
    m.nees_mean = nees_frames_ ? nees_sum_ / nees_frames_ : std::numeric_limits<double>::quiet_NaN();
    if (nees_frames_) {
        const double dof = 3.0 * nees_frames_;
        m.nees_lo = chi2_quantile(0.025, dof) / nees_frames_;
        m.nees_hi = chi2_quantile(0.975, dof) / nees_frames_;
        m.nees_within_95 = static_cast<double>(nees_within_) / nees_frames_;
    }
    return m;
}

double aligned_ape(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
    const Pose A = se2_alignment(estimate, truth);
    double s = 0;
    for (size_t k = 0; k < truth.size(); ++k) s += (compose(A, estimate[k]) - truth[k]).head<2>().squaredNorm();
    return std::sqrt(s / static_cast<double>(truth.size()));
}

TrajectoryMetrics score_trajectory(const std::vector<Pose>& estimate, const std::vector<Pose>& truth,
                                   const std::vector<Mat3>& cov) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("score_trajectory: trajectories of different or zero length");
    if (!cov.empty() && cov.size() != truth.size())
        throw std::invalid_argument("score_trajectory: one covariance per pose");
    TrajectoryScore score;
    std::vector<double> per_frame;
    per_frame.reserve(truth.size());
    for (size_t k = 0; k < truth.size(); ++k)
        per_frame.push_back(score.add(estimate[k], truth[k], cov.empty() ? nullptr : &cov[k]));
    TrajectoryMetrics m = score.metrics();
    m.nees = std::move(per_frame);
    m.ape_se2 = aligned_ape(estimate, truth);
    return m;
}

}  // namespace hc::slam

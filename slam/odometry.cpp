// odometry.cpp: stereo visual odometry on the top view: descriptor matches between the
// landmarks of consecutive frames, RANSAC over pairs of matches with the closed-form 2-D
// rigid alignment, weighted Gauss-Newton on the inliers and the covariance of its solution.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>

#include "slam/odometry.hpp"

namespace hc::slam {

void VisualOdometryConfig::validate() const {
    if (!(max_hamming_fraction >= 0 && max_hamming_fraction <= 1))
        throw InputError("the odometry's Hamming fraction must be in [0, 1], got " + std::to_string(max_hamming_fraction));
    if (!(min_range >= 0 && max_range > min_range)) throw InputError("the odometry's range limits are not 0 <= min < max");
    if (ransac_iterations < 1) throw InputError("the odometry needs at least one RANSAC iteration");
    if (!(inlier_probability > 0 && inlier_probability < 1))
        throw InputError("the odometry's inlier probability must be in (0, 1)");
    if (min_inliers < 2) throw InputError("the odometry needs at least 2 inliers");
    if (!(max_step > 0)) throw InputError("the odometry's largest step must be positive");
    if (!(fail_sigma_xy > 0) || !(fail_sigma_theta > 0))
        throw InputError("the odometry's failure standard deviations must be positive");
}

std::pair<Vec2, Mat2> top_view(const StereoLandmarkObs& o) {
    Eigen::Matrix<double, 2, 3> J;
    J << 0, 0, 1, -1, 0, 0;
    Mat2 C = J * o.cov * J.transpose();
    return {Vec2(o.p_cam.z(), -o.p_cam.x()), (C + C.transpose()) / 2};
}

namespace {

struct Point {
    int index;
    Vec2 q;
    Mat2 C;
    const std::vector<uint8_t>* desc;
};

std::vector<Point> usable(const StereoFrame& f, const VisualOdometryConfig& c) {
    std::vector<Point> out;
    for (int i = 0; i < static_cast<int>(f.size()); ++i) {
        if (!(f[i].p_cam.z() > 0) || f[i].descriptor.empty()) continue;
        const auto [q, C] = top_view(f[i]);
        const double r = q.norm();
        if (r < c.min_range || r > c.max_range) continue;
        out.push_back({i, q, C, &f[i].descriptor});
    }
    return out;
}

Mat2 rotation(double a) {
    Mat2 R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
}

struct Match {
    const Point* p;   // previous
    const Point* c;   // current
};

/// Mahalanobis distance of q_prev − (R q_cur + t) under C_prev + R C_cur Rᵀ.
double residual2(const Match& m, const Mat2& R, const Vec2& t) {
    const Vec2 r = m.p->q - R * m.c->q - t;
    const Mat2 C = m.p->C + R * m.c->C * R.transpose();
    return r.dot(C.ldlt().solve(r));
}

/// Weighted Gauss-Newton on the matches from u; returns the information matrix at the end.
Mat3 refine(const std::vector<const Match*>& in, Motion& u) {
    Mat3 H = Mat3::Zero();
    for (int it = 0; it < 10; ++it) {
        const Mat2 R = rotation(u(2));
        Mat2 dR;
        dR << -std::sin(u(2)), -std::cos(u(2)), std::cos(u(2)), -std::sin(u(2));
        H.setZero();
        Eigen::Vector3d g = Eigen::Vector3d::Zero();
        for (const Match* m : in) {
            const Vec2 r = m->p->q - R * m->c->q - u.head<2>();
            const Mat2 W = (m->p->C + R * m->c->C * R.transpose()).inverse();
            Eigen::Matrix<double, 2, 3> J;
            J.leftCols<2>() = -Mat2::Identity();
            J.col(2) = -dR * m->c->q;
            H += J.transpose() * W * J;
            g += J.transpose() * W * r;
        }
        const Eigen::Vector3d d = -H.ldlt().solve(g);
        u += d;
        u(2) = wrap_angle(u(2));
        if (d.head<2>().norm() < 1e-12 && std::abs(d(2)) < 1e-12) break;
    }
    return H;
}

}  // namespace

MotionEstimate estimate_motion(const StereoFrame& previous, const StereoFrame& current,
                               const VisualOdometryConfig& cfg) {
    cfg.validate();
    MotionEstimate est;
    const std::vector<Point> P = usable(previous, cfg), C = usable(current, cfg);
    if (P.empty() || C.empty()) return est;
    // mutual nearest neighbours by Hamming distance under the relative threshold
    std::vector<int> best_c(P.size(), -1), best_p(C.size(), -1);
    std::vector<int> dist_c(P.size(), std::numeric_limits<int>::max()), dist_p(C.size(), std::numeric_limits<int>::max());
    for (size_t i = 0; i < P.size(); ++i)
        for (size_t j = 0; j < C.size(); ++j) {
            const int d = hamming_distance(*P[i].desc, *C[j].desc);
            if (d < dist_c[i]) dist_c[i] = d, best_c[i] = static_cast<int>(j);
            if (d < dist_p[j]) dist_p[j] = d, best_p[j] = static_cast<int>(i);
        }
    std::vector<Match> matches;
    for (size_t i = 0; i < P.size(); ++i) {
        const int j = best_c[i];
        if (j < 0 || best_p[j] != static_cast<int>(i)) continue;
        if (dist_c[i] > hamming_threshold(cfg.max_hamming_fraction, std::max(P[i].desc->size(), C[j].desc->size())))
            continue;
        matches.push_back({&P[i], &C[j]});
    }
    est.candidates = static_cast<int>(matches.size());
    if (matches.size() < 2) return est;
    const double gate = chi2_quantile(cfg.inlier_probability, 2);
    // RANSAC over pairs: the rotation that turns the current pair's chord into the previous one's
    std::mt19937_64 rng(0x5eed);
    std::uniform_int_distribution<size_t> pick(0, matches.size() - 1);
    int best_n = -1;
    double best_cost = 0;
    Motion best = Motion::Zero();
    for (int it = 0; it < cfg.ransac_iterations; ++it) {
        const size_t a = pick(rng), b = pick(rng);
        if (a == b) continue;
        const Vec2 dp = matches[b].p->q - matches[a].p->q, dc = matches[b].c->q - matches[a].c->q;
        if (dp.norm() < 0.5 || dc.norm() < 0.5) continue;
        const double th = wrap_angle(std::atan2(dp.y(), dp.x()) - std::atan2(dc.y(), dc.x()));
        const Mat2 R = rotation(th);
        const Vec2 t = (matches[a].p->q + matches[b].p->q) / 2 - R * (matches[a].c->q + matches[b].c->q) / 2;
        if (t.norm() > cfg.max_step) continue;
        int n = 0;
        double cost = 0;
        for (const auto& m : matches) {
            const double d2 = residual2(m, R, t);
            if (d2 <= gate) {
                ++n;
                cost += d2;
            }
        }
        if (n > best_n || (n == best_n && cost < best_cost)) {
            best_n = n;
            best_cost = cost;
            best = Motion(t.x(), t.y(), th);
        }
    }
    if (best_n < 2) return est;
    Motion u = best;
    std::vector<const Match*> in;
    Mat3 H = Mat3::Zero();
    for (int round = 0; round < 3; ++round) {
        const Mat2 R = rotation(u(2));
        std::vector<const Match*> next;
        for (const auto& m : matches)
            if (residual2(m, R, u.head<2>()) <= gate) next.push_back(&m);
        if (next.size() < 2) return est;
        const bool same = next == in;
        in.swap(next);
        H = refine(in, u);
        if (same) break;
    }
    est.inliers = static_cast<int>(in.size());
    if (est.inliers < cfg.min_inliers || u.head<2>().norm() > cfg.max_step) return est;
    est.u = u;
    est.cov = H.inverse();
    est.cov = (est.cov + est.cov.transpose()) / 2;
    est.ok = true;
    for (const Match* m : in) est.matches.emplace_back(m->p->index, m->c->index);
    return est;
}

VisualOdometry visual_odometry(const std::vector<StereoFrame>& frames, const VisualOdometryConfig& cfg) {
    cfg.validate();
    VisualOdometry vo;
    Motion last = Motion::Zero();
    const Mat3 fail = Eigen::Vector3d(cfg.fail_sigma_xy * cfg.fail_sigma_xy, cfg.fail_sigma_xy * cfg.fail_sigma_xy,
                                      cfg.fail_sigma_theta * cfg.fail_sigma_theta)
                          .asDiagonal();
    for (size_t k = 1; k < frames.size(); ++k) {
        MotionEstimate e = estimate_motion(frames[k - 1], frames[k], cfg);
        if (e.ok) {
            last = e.u;
            vo.motions.push_back(e.u);
            vo.covariances.push_back(e.cov);
        } else {
            ++vo.failures;
            vo.motions.push_back(last);
            vo.covariances.push_back(fail);
        }
        vo.estimates.push_back(std::move(e));
    }
    return vo;
}

SequenceRun run_visual_sequence(const std::vector<StereoFrame>& frames, const std::vector<Pose>& truth,
                                const VisualOdometryConfig& cfg, const AssociationConfig& association,
                                VisualOdometry* odometry) {
    if (frames.size() < 2) throw InputError("a sequence needs at least 2 frames, got " + std::to_string(frames.size()));
    if (truth.size() != frames.size())
        throw InputError("a sequence needs one pose per frame to score: " + std::to_string(frames.size()) +
                         " frames, " + std::to_string(truth.size()) + " poses");
    VisualOdometry vo = visual_odometry(frames, cfg);
    SequenceRun run = run_filter(frames, vo.motions, vo.covariances, Pose::Zero(), association, truth);
    if (odometry) *odometry = std::move(vo);
    return run;
}

}  // namespace hc::slam

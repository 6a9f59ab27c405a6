// odometry.cpp: stereo visual odometry: descriptor matches between the landmarks of
// consecutive frames, then RANSAC, weighted Gauss-Newton on the inliers and the covariance of
// its solution, on pixel residuals (6-DoF) or on the top view (3-DoF).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

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
    if (residual == OdometryResidual::pixels) {
        if (!rig) throw InputError("visual odometry on pixel residuals needs the rig the frames were triangulated through");
        rig->validate();
    }
}

std::pair<Vec2, Mat2> top_view(const StereoLandmarkObs& o) {
    Eigen::Matrix<double, 2, 3> J;
    J << 0, 0, 1, -1, 0, 0;
    Mat2 C = J * o.cov * J.transpose();
    return {Vec2(o.p_cam.z(), -o.p_cam.x()), (C + C.transpose()) / 2};
}

namespace {

using Vec3 = Eigen::Vector3d;

/// (u_l, v, u_r) of the camera-frame point X through the rig, and its Jacobian in X.
Vec3 rig_pixels(const stereo::RectifiedRig& g, const Vec3& X, Mat3* J = nullptr) {
    const double iz = 1 / X.z();
    const Vec3 m((g.fx * X.x() + g.tx0) * iz + g.cx0, (g.fy * X.y() + g.ty) * iz + g.cy,
                 (g.fx * X.x() + g.tx1) * iz + g.cx1);
    if (J)
        *J << g.fx * iz, 0, -(g.fx * X.x() + g.tx0) * iz * iz,  //
            0, g.fy * iz, -(g.fy * X.y() + g.ty) * iz * iz,      //
            g.fx * iz, 0, -(g.fx * X.x() + g.tx1) * iz * iz;
    return m;
}

struct Point {
    int index;
    Vec2 q;     // top view and its covariance
    Mat2 C;
    Vec3 X;     // camera frame and its covariance
    Mat3 C3;
    Vec3 m;     // with a rig: where the rig saw it, (u_l, v, u_r), and that covariance
    Mat3 M;
    const std::vector<uint8_t>* desc;
};

std::vector<Point> usable(const StereoFrame& f, const VisualOdometryConfig& c) {
    std::vector<Point> out;
    for (int i = 0; i < static_cast<int>(f.size()); ++i) {
        if (!(f[i].p_cam.z() > 0) || f[i].descriptor.empty()) continue;
        const auto [q, C] = top_view(f[i]);
        const double r = q.norm();
        if (r < c.min_range || r > c.max_range) continue;
        Point p{i, q, C, f[i].p_cam, f[i].cov, Vec3::Zero(), Mat3::Zero(), &f[i].descriptor};
        if (c.rig) {
            Mat3 J;
            p.m = rig_pixels(*c.rig, p.X, &J);
            p.M = J * p.C3 * J.transpose();
        }
        out.push_back(p);
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

/// Mutual nearest neighbours by Hamming distance under the relative threshold.
std::vector<Match> descriptor_matches(const std::vector<Point>& P, const std::vector<Point>& C,
                                      const VisualOdometryConfig& cfg) {
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
    return matches;
}

/// The inliers and the motion of one residual model, in its own parameters.
struct Solved {
    std::vector<const Match*> inliers;
    Motion u = Motion::Zero();
    Mat3 cov = Mat3::Identity();
    bool ok = false;
};

/// A hypothesis's support: the matches within `gate` of it (`distance2(m)`, a Mahalanobis
/// distance²) and the sum of their distances².
template <class Distance2>
std::pair<int, double> support(const std::vector<Match>& matches, double gate, Distance2 distance2) {
    int n = 0;
    double cost = 0;
    for (const auto& m : matches) {
        const double d2 = distance2(m);
        if (d2 <= gate) {
            ++n;
            cost += d2;
        }
    }
    return {n, cost};
}

/// The matches within `gate` of the hypothesis `within(m)` (a Mahalanobis distance²).
template <class Distance2>
std::vector<const Match*> select_inliers(const std::vector<Match>& matches, double gate, Distance2 within) {
    std::vector<const Match*> in;
    for (const auto& m : matches)
        if (within(m) <= gate) in.push_back(&m);
    return in;
}

Solved top_view_motion(const std::vector<Match>& matches, const VisualOdometryConfig& cfg) {
    Solved out;
    if (matches.size() < 2) return out;
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
        const auto [n, cost] = support(matches, gate, [&](const Match& m) { return residual2(m, R, t); });
        if (n > best_n || (n == best_n && cost < best_cost)) {
            best_n = n;
            best_cost = cost;
            best = Motion(t.x(), t.y(), th);
        }
    }
    if (best_n < 2) return out;
    Motion u = best;
    Mat3 H = Mat3::Zero();
    for (int round = 0; round < 3; ++round) {
        const Mat2 R = rotation(u(2));
        std::vector<const Match*> next =
            select_inliers(matches, gate, [&](const Match& m) { return residual2(m, R, u.head<2>()); });
        if (next.size() < 2) return out;
        const bool same = next == out.inliers;
        out.inliers.swap(next);
        H = refine(out.inliers, u);
        if (same) break;
    }
    out.u = u;
    out.cov = H.inverse();
    out.ok = true;
    return out;
}

// ---- pixel residuals, 6-DoF -----------------------------------------------------------------

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// The current camera in the previous one's frame: X_prev = R X_cur + t.
struct Rigid {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
};

/// T moved by d = (ω, δt): R Exp(ω), t + δt.
Rigid perturbed(const Rigid& T, const Vec6& d) {
    const Vec3 w = d.head<3>();
    const double a = w.norm();
    Rigid out = T;
    if (a > 0) out.R = T.R * Eigen::AngleAxisd(a, w / a).toRotationMatrix();
    out.t = T.t + d.tail<3>();
    return out;
}

Motion planar_motion(const Rigid& T) {
    Mat34 M;
    M << T.R, T.t;
    return planar_pose(M);
}

/// Where the current frame saw match m's point, minus where the previous frame's point lands in
/// the current camera under T, in pixels (u_l, v, u_r); S, its covariance: both points'
/// covariances carried into those pixels. false when the moved point is not in front.
bool pixel_residual(const Match& m, const Rigid& T, const stereo::RectifiedRig& g, Vec3& r, Mat3* S = nullptr) {
    const Vec3 X = T.R.transpose() * (m.p->X - T.t);
    if (!(X.z() > 0.1)) return false;
    Mat3 J;
    r = m.c->m - rig_pixels(g, X, S ? &J : nullptr);
    if (S) {
        const Mat3 A = J * T.R.transpose();
        *S = m.c->M + A * m.p->C3 * A.transpose();
    }
    return true;
}

double pixel_distance2(const Match& m, const Rigid& T, const stereo::RectifiedRig& g) {
    Vec3 r;
    Mat3 S;
    if (!pixel_residual(m, T, g, r, &S)) return std::numeric_limits<double>::infinity();
    return r.dot(S.ldlt().solve(r));
}

/// Weighted Gauss-Newton in (ω, δt) from T (each match's weight at the current T; Jacobians
/// by central differences); returns the information matrix at the end.
Mat6 refine_pixels(const std::vector<const Match*>& in, const stereo::RectifiedRig& g, Rigid& T) {
    Mat6 H = Mat6::Zero();
    constexpr double h = 1e-6;
    for (int it = 0; it < 10; ++it) {
        H.setZero();
        Vec6 grad = Vec6::Zero();
        for (const Match* m : in) {
            Vec3 r, rp, rm;
            Mat3 S;
            if (!pixel_residual(*m, T, g, r, &S)) continue;
            Eigen::Matrix<double, 3, 6> J;
            for (int k = 0; k < 6; ++k) {
                const Vec6 d = Vec6::Unit(k) * h;
                pixel_residual(*m, perturbed(T, d), g, rp);
                pixel_residual(*m, perturbed(T, -d), g, rm);
                J.col(k) = (rp - rm) / (2 * h);
            }
            const Mat3 W = S.inverse();
            H += J.transpose() * W * J;
            grad += J.transpose() * W * r;
        }
        const Vec6 d = -H.ldlt().solve(grad);
        T = perturbed(T, d);
        if (d.norm() < 1e-12) break;
    }
    return H;
}

/// RANSAC over triples of matches: the closed-form rigid alignment of their 3-D points; each
/// hypothesis that beats the best unrefined one is also refined on its inliers (locally
/// optimised RANSAC), since a triple's depth errors put its alignment off by more than the
/// pixel gate allows. `best_n`: the support of the hypothesis returned.
Rigid pixel_hypothesis(const std::vector<Match>& matches, const VisualOdometryConfig& cfg, int& best_n) {
    const stereo::RectifiedRig& g = *cfg.rig;
    const double gate = chi2_quantile(cfg.inlier_probability, 3);
    std::mt19937_64 rng(0x5eed);
    std::uniform_int_distribution<size_t> pick(0, matches.size() - 1);
    std::pair<int, double> best{-1, 0}, best_raw{-1, 0};
    const auto better = [](const std::pair<int, double>& a, const std::pair<int, double>& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
    };
    Rigid best_T;
    for (int it = 0; it < cfg.ransac_iterations; ++it) {
        const size_t a = pick(rng), b = pick(rng), c = pick(rng);
        if (a == b || a == c || b == c) continue;
        Mat3 cur, prev;
        cur << matches[a].c->X, matches[b].c->X, matches[c].c->X;
        prev << matches[a].p->X, matches[b].p->X, matches[c].p->X;
        if ((cur.col(1) - cur.col(0)).cross(cur.col(2) - cur.col(0)).norm() < 0.25) continue;
        const Eigen::Matrix4d M = Eigen::umeyama(cur, prev, false);
        Rigid T{M.topLeftCorner<3, 3>(), M.topRightCorner<3, 1>()};
        if (T.t.norm() > cfg.max_step) continue;
        refine_pixels({&matches[a], &matches[b], &matches[c]}, g, T);
        if (!(T.t.norm() <= cfg.max_step)) continue;
        const auto raw = support(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (!better(raw, best_raw)) continue;
        best_raw = raw;
        if (better(raw, best)) best = raw, best_T = T;
        const std::vector<const Match*> in =
            select_inliers(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (in.size() < 3) continue;
        refine_pixels(in, g, T);
        if (T.t.norm() > cfg.max_step) continue;
        const auto refined = support(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (better(refined, best)) best = refined, best_T = T;
    }
    best_n = best.first;
    return best_T;
}

Solved pixel_motion(const std::vector<Match>& matches, const VisualOdometryConfig& cfg) {
    Solved out;
    if (matches.size() < 3) return out;
    const stereo::RectifiedRig& g = *cfg.rig;
    const double gate = chi2_quantile(cfg.inlier_probability, 3);
    int best_n = 0;
    Rigid T = pixel_hypothesis(matches, cfg, best_n);
    if (best_n < 3) return out;
    Mat6 H = Mat6::Zero();
    for (int round = 0; round < 3; ++round) {
        std::vector<const Match*> next =
            select_inliers(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (next.size() < 3) return out;
        const bool same = next == out.inliers;
        out.inliers.swap(next);
        H = refine_pixels(out.inliers, g, T);
        if (same) break;
    }
    // the top view of T and its covariance: Jacobian of planar_motion in (ω, δt), central differences
    out.u = planar_motion(T);
    Eigen::Matrix<double, 3, 6> J;
    constexpr double h = 1e-7;
    for (int k = 0; k < 6; ++k) {
        Motion d = planar_motion(perturbed(T, Vec6::Unit(k) * h)) - planar_motion(perturbed(T, -Vec6::Unit(k) * h));
        d(2) = wrap_angle(d(2));
        J.col(k) = d / (2 * h);
    }
    out.cov = J * H.inverse() * J.transpose();
    out.ok = true;
    return out;
}

}  // namespace

MotionEstimate estimate_motion(const StereoFrame& previous, const StereoFrame& current,
                               const VisualOdometryConfig& cfg) {
    cfg.validate();
    MotionEstimate est;
    const std::vector<Point> P = usable(previous, cfg), C = usable(current, cfg);
    const std::vector<Match> matches = descriptor_matches(P, C, cfg);
    est.candidates = static_cast<int>(matches.size());
    const Solved s = cfg.residual == OdometryResidual::pixels ? pixel_motion(matches, cfg) : top_view_motion(matches, cfg);
    if (!s.ok) return est;
    est.inliers = static_cast<int>(s.inliers.size());
    if (est.inliers < cfg.min_inliers || s.u.head<2>().norm() > cfg.max_step) return est;
    est.u = s.u;
    est.cov = (s.cov + s.cov.transpose()) / 2;
    est.ok = true;
    for (const Match* m : s.inliers) est.matches.emplace_back(m->p->index, m->c->index);
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

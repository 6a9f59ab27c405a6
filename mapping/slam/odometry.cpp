// odometry.cpp: stereo visual odometry: descriptor matches between the landmarks of
// consecutive frames, then RANSAC, weighted Gauss-Newton on the inliers and the covariance of
// its solution, on pixel residuals (6-DoF) or on the top view (3-DoF).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "mapping/slam/odometry.hpp"
#include "mapping/slam/consistency.hpp"
#include "mapping/slam/trajectory.hpp"

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
    if (!(disparity_offset_significance >= 0))
        throw InputError("the odometry's disparity-correction significance must not be negative");
    if (!(noise_tolerance > 0)) throw InputError("the odometry's noise tolerance must be positive");
    if (noise_rounds < 0) throw InputError("the odometry's noise rounds must not be negative");
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
Vec3 rig_pixels(const landmarks::RectifiedRig& g, const Vec3& X, Mat3* J = nullptr) {
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
    double disparity_offset = 0, disparity_offset_sigma = 0;   // pixels with the offset estimated
    Mat3 rotation = Mat3::Identity();                           // pixels: the 6-DoF motion and the
    Vec3 translation = Vec3::Zero();                            // covariance of (ω, δt)
    Eigen::Matrix<double, 6, 6> cov6 = Eigen::Matrix<double, 6, 6>::Zero();
    double residual_chi2 = 0;   // Σ of the inliers' squared Mahalanobis residuals at the estimate
    int residual_dof = 0;       // residuals minus parameters
    double offset_used = 0, offset_variance = 0;   // pixels: MotionEstimate's
    Eigen::Matrix<double, 6, 1> offset_sensitivity6 = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Vector3d offset_sensitivity = Eigen::Vector3d::Zero();
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
    const Mat2 R = rotation(u(2));
    for (const Match* m : out.inliers) out.residual_chi2 += residual2(*m, R, u.head<2>());
    out.residual_dof = 2 * static_cast<int>(out.inliers.size()) - 3;
    out.ok = true;
    return out;
}

// ---- pixel residuals, 6-DoF and the disparity correction -------------------------------------

using Mat7 = Eigen::Matrix<double, 7, 7>;
using Vec7 = Eigen::Matrix<double, 7, 1>;

/// The current camera in the previous one's frame, X_prev = R X_cur + t, and the disparity
/// correction c (px) of both frames' measurements: a point seen at (u_l, v, u_r) is taken at
/// (u_l, v, u_r − c), its disparity c larger.
struct Rigid {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    double c = 0;
};

/// T moved by d = (ω, δt, δc): R Exp(ω), t + δt, c + δc.
Rigid perturbed(const Rigid& T, const Vec7& d) {
    const Vec3 w = d.head<3>();
    const double a = w.norm();
    Rigid out = T;
    if (a > 0) out.R = T.R * Eigen::AngleAxisd(a, w / a).toRotationMatrix();
    out.t = T.t + d.segment<3>(3);
    out.c = T.c + d(6);
    return out;
}

/// The point the rig sees at m = (u_l, v, u_r): rig_pixels' inverse (stereo.hpp's model).
Vec3 rig_point(const landmarks::RectifiedRig& g, const Vec3& m) {
    const double D = m(0) - m(2) - (g.cx0 - g.cx1), Z = (g.tx0 - g.tx1) / D;
    return Vec3(((m(0) - g.cx0) * Z - g.tx0) / g.fx, ((m(1) - g.cy) * Z - g.ty) / g.fy, Z);
}

/// Where the current frame saw match m's point, minus where the previous frame's point lands in
/// the current camera under T, in pixels (u_l, v, u_r), both frames' measurements corrected by
/// T.c; S, its covariance: both points' covariances carried into those pixels. false when the
/// moved point is not in front.
bool pixel_residual(const Match& m, const Rigid& T, const landmarks::RectifiedRig& g, Vec3& r, Mat3* S = nullptr) {
    const Vec3 corr(0, 0, T.c);
    const Vec3 Xp = T.c == 0 ? m.p->X : rig_point(g, m.p->m - corr);
    if (!(Xp.z() > 0)) return false;
    const Vec3 X = T.R.transpose() * (Xp - T.t);
    if (!(X.z() > 0.1)) return false;
    Mat3 J;
    r = (m.c->m - corr) - rig_pixels(g, X, S ? &J : nullptr);
    if (S) {
        const Mat3 A = J * T.R.transpose();
        *S = m.c->M + A * m.p->C3 * A.transpose();
    }
    return true;
}

double pixel_distance2(const Match& m, const Rigid& T, const landmarks::RectifiedRig& g) {
    Vec3 r;
    Mat3 S;
    if (!pixel_residual(m, T, g, r, &S)) return std::numeric_limits<double>::infinity();
    return r.dot(S.ldlt().solve(r));
}

/// Weighted Gauss-Newton in (ω, δt), and δc when `offset`, from T (each match's weight at
/// the current T; Jacobians by central differences); returns the information matrix at the
/// end (7 × 7; without `offset` its c row and column are those of a fixed c: H(6, 6) = 1).
/// With `offset` and prior.sigma > 0, the prior on c enters as one more residual, c − mean.
Mat7 refine_pixels(const std::vector<const Match*>& in, const landmarks::RectifiedRig& g, Rigid& T, bool offset,
                   const DisparityPrior& prior = {}) {
    Mat7 H = Mat7::Zero();
    constexpr double h = 1e-6;
    const int dof = offset ? 7 : 6;
    for (int it = 0; it < 10; ++it) {
        H.setZero();
        Vec7 grad = Vec7::Zero();
        for (const Match* m : in) {
            Vec3 r, rp, rm;
            Mat3 S;
            if (!pixel_residual(*m, T, g, r, &S)) continue;
            Eigen::Matrix<double, 3, 7> J = Eigen::Matrix<double, 3, 7>::Zero();
            for (int k = 0; k < dof; ++k) {
                const Vec7 d = Vec7::Unit(k) * h;
                pixel_residual(*m, perturbed(T, d), g, rp);
                pixel_residual(*m, perturbed(T, -d), g, rm);
                J.col(k) = (rp - rm) / (2 * h);
            }
            const Mat3 W = S.inverse();
            H += J.transpose() * W * J;
            grad += J.transpose() * W * r;
        }
        if (!offset) {
            H(6, 6) = 1;
        } else if (prior.sigma > 0) {
            const double w = 1 / (prior.sigma * prior.sigma);
            H(6, 6) += w;
            grad(6) += w * (T.c - prior.mean);
        }
        const Vec7 d = -H.ldlt().solve(grad);
        T = perturbed(T, d);
        if (d.norm() < 1e-12) break;
    }
    return H;
}

/// RANSAC over triples of matches: the closed-form rigid alignment of their 3-D points; each
/// hypothesis that beats the best unrefined one is also refined on its inliers (locally
/// optimised RANSAC), since a triple's depth errors put its alignment off by more than the
/// pixel gate allows. `best_n`: the support of the hypothesis returned.
/// The correction the motion is computed at: the prior's mean once it differs from 0 by more
/// than disparity_offset_significance of its standard deviations, else 0.
double applied_offset(const DisparityPrior& prior, const VisualOdometryConfig& cfg) {
    return prior.sigma > 0 && std::abs(prior.mean) > cfg.disparity_offset_significance * prior.sigma ? prior.mean : 0;
}

/// Hypotheses keep the disparity correction c0.
Rigid pixel_hypothesis(const std::vector<Match>& matches, const VisualOdometryConfig& cfg, double c0, int& best_n) {
    const landmarks::RectifiedRig& g = *cfg.rig;
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
        Rigid T{M.topLeftCorner<3, 3>(), M.topRightCorner<3, 1>(), c0};
        if (T.t.norm() > cfg.max_step) continue;
        refine_pixels({&matches[a], &matches[b], &matches[c]}, g, T, false);
        if (!(T.t.norm() <= cfg.max_step)) continue;
        const auto raw = support(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (!better(raw, best_raw)) continue;
        best_raw = raw;
        if (better(raw, best)) best = raw, best_T = T;
        const std::vector<const Match*> in =
            select_inliers(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (in.size() < 3) continue;
        refine_pixels(in, g, T, false);
        if (T.t.norm() > cfg.max_step) continue;
        const auto refined = support(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (better(refined, best)) best = refined, best_T = T;
    }
    best_n = best.first;
    return best_T;
}

Mat3 skew(const Vec3& w) {
    Mat3 K;
    K << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    return K;
}

/// Two-view refinement of the motion T (its rotation and translation; c kept) on the inliers
/// `in`: each inlier's point X (in the current camera) is estimated with the motion from its
/// pixels in both frames, (u_l, v, u_r) − (0, 0, c) against π(X) in the current camera and
/// π(R X + t) in the previous one, each under that frame's own pixel covariance; the points
/// are eliminated by their Schur complement (Gauss-Newton, at most 10 iterations). Returns the
/// covariance of (ω, δt), the Schur complement's inverse; `chi2` the residuals' squared
/// Mahalanobis sum at the end (6 residuals, 3 point parameters each: 3n − 6 dof).
Eigen::Matrix<double, 6, 6> refine_two_view(const std::vector<const Match*>& in, const landmarks::RectifiedRig& g,
                                            Rigid& T, double& chi2) {
    using Mat6 = Eigen::Matrix<double, 6, 6>;
    using Mat63 = Eigen::Matrix<double, 6, 3>;
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    const Vec3 corr(0, 0, T.c);
    std::vector<Vec3> X;
    std::vector<Mat3> Wc, Wp;
    for (const Match* m : in) {
        X.push_back(T.c == 0 ? m->c->X : rig_point(g, m->c->m - corr));
        Wc.push_back(m->c->M.inverse());
        Wp.push_back(m->p->M.inverse());
    }
    Mat6 S = Mat6::Identity();
    for (int it = 0; it < 10; ++it) {
        S.setZero();
        Vec6 b = Vec6::Zero();
        std::vector<Mat63> HTX(in.size());
        std::vector<Mat3> HXXi(in.size());
        std::vector<Vec3> bX(in.size());
        chi2 = 0;
        for (size_t i = 0; i < in.size(); ++i) {
            Mat3 Jc, Jp;
            const Vec3 Y = T.R * X[i] + T.t;
            const Vec3 rc = (in[i]->c->m - corr) - rig_pixels(g, X[i], &Jc);
            const Vec3 rp = (in[i]->p->m - corr) - rig_pixels(g, Y, &Jp);
            chi2 += rc.dot(Wc[i] * rc) + rp.dot(Wp[i] * rp);
            Eigen::Matrix<double, 3, 6> JT;   // ∂π(Y)/∂(ω, δt), R·Exp(ω): ∂Y/∂ω = −R [X]×
            JT.leftCols<3>() = -Jp * T.R * skew(X[i]);
            JT.rightCols<3>() = Jp;
            const Mat3 JXp = Jp * T.R;
            S += JT.transpose() * Wp[i] * JT;
            b += JT.transpose() * Wp[i] * rp;
            HTX[i] = JT.transpose() * Wp[i] * JXp;
            HXXi[i] = (Jc.transpose() * Wc[i] * Jc + JXp.transpose() * Wp[i] * JXp).inverse();
            bX[i] = Jc.transpose() * Wc[i] * rc + JXp.transpose() * Wp[i] * rp;
            S -= HTX[i] * HXXi[i] * HTX[i].transpose();
            b -= HTX[i] * HXXi[i] * bX[i];
        }
        const Vec6 d = S.ldlt().solve(b);
        Vec7 d7 = Vec7::Zero();
        d7.head<6>() = d;
        T = perturbed(T, d7);
        for (size_t i = 0; i < in.size(); ++i) X[i] += HXXi[i] * (bX[i] - HTX[i].transpose() * d);
        if (d.norm() < 1e-10) break;
    }
    return S.inverse();
}

/// The sensitivity of the motion T (refined on the inliers `in` at its correction T.c) to that
/// correction: the same final refinement (two-view or on the previous frame's points) solved
/// again from T at T.c ± h, central differences. Returns ∂(ω, δt)/∂c (T's perturbation,
/// MotionEstimate::cov6's parameters) and, in `top`, ∂u/∂c of the top view in the previous
/// camera's frame.
Eigen::Matrix<double, 6, 1> offset_sensitivity(const std::vector<const Match*>& in, const landmarks::RectifiedRig& g,
                                               const Rigid& T, bool two_view, Vec3& top) {
    constexpr double h = 1e-3;   // px
    Rigid plus = T, minus = T;
    plus.c += h;
    minus.c -= h;
    for (Rigid* X : {&plus, &minus}) {
        double chi2 = 0;
        if (two_view)
            refine_two_view(in, g, *X, chi2);
        else
            refine_pixels(in, g, *X, false);
    }
    const auto delta = [&](const Rigid& X) {   // (ω, δt) with X = T moved by it
        const Eigen::AngleAxisd w(T.R.transpose() * X.R);
        Eigen::Matrix<double, 6, 1> d;
        d << w.angle() * w.axis(), X.t - T.t;
        return d;
    };
    const Eigen::Matrix<double, 6, 6> none = Eigen::Matrix<double, 6, 6>::Zero();
    Motion du = levelled_motion(Mat3::Identity(), plus.R, plus.t, none) - levelled_motion(Mat3::Identity(), minus.R, minus.t, none);
    du(2) = wrap_angle(du(2));
    top = du / (2 * h);
    return (delta(plus) - delta(minus)) / (2 * h);
}

Solved pixel_motion(const std::vector<Match>& matches, const VisualOdometryConfig& cfg, const DisparityPrior& prior) {
    Solved out;
    if (matches.size() < 3) return out;
    const landmarks::RectifiedRig& g = *cfg.rig;
    const double gate = chi2_quantile(cfg.inlier_probability, 3);
    int best_n = 0;
    // the motion at the correction the earlier steps established
    Rigid T = pixel_hypothesis(matches, cfg, cfg.estimate_disparity_offset ? applied_offset(prior, cfg) : 0, best_n);
    if (best_n < 3) return out;
    Mat7 H = Mat7::Zero();
    for (int round = 0; round < 3; ++round) {
        std::vector<const Match*> next =
            select_inliers(matches, gate, [&](const Match& m) { return pixel_distance2(m, T, g); });
        if (next.size() < 3) return out;
        const bool same = next == out.inliers;
        out.inliers.swap(next);
        H = refine_pixels(out.inliers, g, T, false);
        if (same) break;
    }
    // the top view of T in the previous camera's frame, and its covariance
    if (cfg.two_view_points) {
        out.cov6 = refine_two_view(out.inliers, g, T, out.residual_chi2);
    } else {
        out.cov6 = H.inverse().topLeftCorner<6, 6>();
        for (const Match* m : out.inliers) out.residual_chi2 += pixel_distance2(*m, T, g);
    }
    if (cfg.estimate_disparity_offset) {   // the correction's estimate with this step's inliers
        Rigid T7 = T;
        const Mat7 H7 = refine_pixels(out.inliers, g, T7, true, prior);
        out.disparity_offset = T7.c;
        out.disparity_offset_sigma = std::sqrt(H7.inverse()(6, 6));
        // the uncertainty of the correction T was computed at (MotionEstimate::offset_variance)
        const DisparityPrior known = prior.sigma > 0 ? prior : DisparityPrior{T7.c, out.disparity_offset_sigma};
        out.offset_used = T.c;
        out.offset_variance = (known.mean - T.c) * (known.mean - T.c) + known.sigma * known.sigma;
        out.offset_sensitivity6 = offset_sensitivity(out.inliers, g, T, cfg.two_view_points, out.offset_sensitivity);
        if (cfg.offset_uncertainty)
            out.cov6 += out.offset_variance * out.offset_sensitivity6 * out.offset_sensitivity6.transpose();
    }
    out.rotation = T.R;
    out.translation = T.t;
    out.u = levelled_motion(Mat3::Identity(), T.R, T.t, out.cov6, &out.cov);
    out.residual_dof = 3 * static_cast<int>(out.inliers.size()) - 6;
    out.ok = true;
    return out;
}

}  // namespace

Mat3 tilt_of(const Mat3& M) {
    const double psi = std::atan2(-M(0, 2), M(2, 2)), c = std::cos(psi), s = std::sin(psi);
    Mat3 Y;   // kitti_pose's rotation of heading ψ
    Y << c, 0, -s, 0, 1, 0, s, 0, c;
    return Y.transpose() * M;
}

Motion levelled_motion(const Mat3& A, const Mat3& R, const Vec3& t, const Eigen::Matrix<double, 6, 6>& cov6,
                       Mat3* cov) {
    const auto top = [&](const Rigid& T) {
        Mat34 M;
        M << A * T.R, A * T.t;
        return planar_pose(M);
    };
    const Rigid T{R, t, 0};
    if (cov) {   // Jacobian in (ω, δt) by central differences
        Eigen::Matrix<double, 3, 6> J;
        constexpr double h = 1e-7;
        for (int k = 0; k < 6; ++k) {
            Motion d = top(perturbed(T, Vec7::Unit(k) * h)) - top(perturbed(T, -Vec7::Unit(k) * h));
            d(2) = wrap_angle(d(2));
            J.col(k) = d / (2 * h);
        }
        *cov = J * cov6 * J.transpose();
        *cov = (*cov + cov->transpose()) / 2;
    }
    return top(T);
}

StereoFrame levelled(const StereoFrame& frame, const Mat3& A) {
    StereoFrame out = frame;
    for (StereoLandmarkObs& o : out) {
        o.p_cam = A * o.p_cam;
        o.cov = A * o.cov * A.transpose();
        o.cov = (o.cov + o.cov.transpose()) / 2;
    }
    return out;
}

MotionEstimate estimate_motion(const StereoFrame& previous, const StereoFrame& current,
                               const VisualOdometryConfig& cfg, const DisparityPrior& prior) {
    cfg.validate();
    MotionEstimate est;
    const std::vector<Point> P = usable(previous, cfg), C = usable(current, cfg);
    const std::vector<Match> matches = descriptor_matches(P, C, cfg);
    est.candidates = static_cast<int>(matches.size());
    const Solved s = cfg.residual == OdometryResidual::pixels ? pixel_motion(matches, cfg, prior) : top_view_motion(matches, cfg);
    if (!s.ok) return est;
    est.inliers = static_cast<int>(s.inliers.size());
    if (est.inliers < cfg.min_inliers || s.u.head<2>().norm() > cfg.max_step) return est;
    est.u = s.u;
    est.cov = (s.cov + s.cov.transpose()) / 2;
    est.disparity_offset = s.disparity_offset;
    est.disparity_offset_sigma = s.disparity_offset_sigma;
    est.rotation = s.rotation;
    est.translation = s.translation;
    est.cov6 = s.cov6;
    est.residual_chi2 = s.residual_chi2;
    est.residual_dof = s.residual_dof;
    est.offset_used = s.offset_used;
    est.offset_variance = s.offset_variance;
    est.offset_sensitivity6 = s.offset_sensitivity6;
    est.offset_sensitivity = s.offset_sensitivity;
    est.ok = true;
    for (const Match* m : s.inliers) est.matches.emplace_back(m->p->index, m->c->index);
    return est;
}

VisualOdometryStream::VisualOdometryStream(const VisualOdometryConfig& cfg, bool keep)
    : cfg_(cfg),
      keep_(keep),
      fail_(Eigen::Vector3d(cfg.fail_sigma_xy * cfg.fail_sigma_xy, cfg.fail_sigma_xy * cfg.fail_sigma_xy,
                            cfg.fail_sigma_theta * cfg.fail_sigma_theta)
                .asDiagonal()),
      level_(cfg.level && cfg.residual == OdometryResidual::pixels) {
    cfg_.validate();
    if (keep_) vo_.tilt.push_back(tilt_);
}

void VisualOdometryStream::step(const StereoFrame& previous, const StereoFrame& current) {
    MotionEstimate e = estimate_motion(previous, current, cfg_, offset_);
    if (e.ok) {
        Mat3 Q = e.cov;
        last_ = level_ ? levelled_motion(tilt_, e.rotation, e.translation, e.cov6, &Q) : e.u;
        if (level_) tilt_ = tilt_of(tilt_ * e.rotation);
        last_cov_ = Q;
        if (e.disparity_offset_sigma > 0) offset_ = {e.disparity_offset, e.disparity_offset_sigma};
    } else {
        ++vo_.failures;
        last_cov_ = fail_;
    }
    // frame 0 takes step 1's correction, frame k step k's
    frame_offset_ = applied_offset(offset_, cfg_);
    if (keep_) {
        vo_.motions.push_back(last_);
        vo_.covariances.push_back(last_cov_);
        if (vo_.disparity_offset.empty()) vo_.disparity_offset.push_back(frame_offset_);
        vo_.disparity_offset.push_back(frame_offset_);
        vo_.tilt.push_back(tilt_);
        vo_.estimates.push_back(e);
    }
    last_estimate_ = std::move(e);
}

VisualOdometry visual_odometry(const std::vector<StereoFrame>& frames, const VisualOdometryConfig& cfg) {
    VisualOdometryStream s(cfg);
    for (size_t k = 1; k < frames.size(); ++k) s.step(frames[k - 1], frames[k]);
    VisualOdometry vo = s.take();
    if (vo.disparity_offset.empty()) vo.disparity_offset.push_back(0);
    return vo;
}

StereoFrame with_disparity_offset(const StereoFrame& frame, const landmarks::RectifiedRig& g, double c) {
    const Vec3 shift(0, 0, c);
    const auto moved = [&](const Vec3& X) { return rig_point(g, rig_pixels(g, X) - shift); };
    StereoFrame out;
    out.reserve(frame.size());
    for (const StereoLandmarkObs& o : frame) {
        const Vec3 m = rig_pixels(g, o.p_cam) - shift;
        if (!(m(0) - m(2) - (g.cx0 - g.cx1) > 0)) continue;
        StereoLandmarkObs r = o;
        r.p_cam = rig_point(g, m);
        Mat3 J;   // d(moved)/dX by central differences, steps relative to the depth
        const double h = 1e-6 * std::max(1.0, o.p_cam.z());
        for (int k = 0; k < 3; ++k) J.col(k) = (moved(o.p_cam + h * Vec3::Unit(k)) - moved(o.p_cam - h * Vec3::Unit(k))) / (2 * h);
        r.cov = J * o.cov * J.transpose();
        r.cov = (r.cov + r.cov.transpose()) / 2;
        out.push_back(std::move(r));
    }
    return out;
}

double residual_variance_factor(const VisualOdometry& vo, const VisualOdometryConfig& cfg) {
    double chi2 = 0;
    long dof = 0;
    for (const MotionEstimate& e : vo.estimates)
        if (e.ok) chi2 += e.residual_chi2, dof += e.residual_dof;
    if (dof <= 0) return 1;
    const double d = cfg.residual == OdometryResidual::pixels ? 3 : 2, g = chi2_quantile(cfg.inlier_probability, d);
    const double truncated = regularized_gamma_p(d / 2 + 1, g / 2) / regularized_gamma_p(d / 2, g / 2);
    return chi2 / static_cast<double>(dof) / truncated;
}

StereoFrame with_noise_scaled(const StereoFrame& frame, double factor) {
    if (!(factor > 0)) throw InputError("a noise scale must be positive, got " + std::to_string(factor));
    StereoFrame out = frame;
    for (StereoLandmarkObs& o : out) o.cov *= factor;
    return out;
}

namespace {

/// Visual odometry on `frames`, with noise_from_residuals on the frames scaled by the variance
/// factor of its own residuals until it settles; `scaled` gets the frames it ran on (empty:
/// `frames` themselves).
VisualOdometry odometry_on_measured_noise(const std::vector<StereoFrame>& frames, const VisualOdometryConfig& cfg,
                                          std::vector<StereoFrame>& scaled) {
    VisualOdometry vo = visual_odometry(frames, cfg);
    if (!cfg.noise_from_residuals) return vo;
    double scale = 1;
    for (int round = 0; round < cfg.noise_rounds; ++round) {
        const double f = residual_variance_factor(vo, cfg);
        if (std::abs(f - 1) <= cfg.noise_tolerance) break;
        scale *= f;
        scaled.clear();
        for (const StereoFrame& fr : frames) scaled.push_back(with_noise_scaled(fr, scale));
        vo = visual_odometry(scaled, cfg);
    }
    vo.noise_scale = scale;
    return vo;
}

}  // namespace

void SpatialTracker::step(const MotionEstimate& e) {
    stepped_ = true;
    if (!e.ok) return;
    p_ += M_ * e.translation;
    M_ = M_ * e.rotation;
}

Mat3 SpatialTracker::tilt() const { return stepped_ ? tilt_of(M_) : M_; }

SpatialTrack spatial_track(const VisualOdometry& vo) {
    SpatialTrack s;
    SpatialTracker t;
    s.tilt.push_back(t.tilt());
    s.height.push_back(t.height());
    for (const MotionEstimate& e : vo.estimates) {
        t.step(e);
        s.tilt.push_back(t.tilt());
        s.height.push_back(t.height());
    }
    return s;
}

namespace {

/// The frame the filter sees of a frame: corrected by the disparity correction `c` when it is
/// estimated and not 0, levelled by `tilt`; `f` itself when neither applies (else built in `buf`).
const StereoFrame& seen_frame(const StereoFrame& f, double c, const Mat3& tilt, const VisualOdometryConfig& cfg,
                              StereoFrame& buf) {
    const bool pixels = cfg.residual == OdometryResidual::pixels;
    const bool offset = pixels && cfg.estimate_disparity_offset, level = pixels && cfg.level;
    if (!offset && !level) return f;
    const bool corrected = offset && c != 0;   // a frame given no correction is seen as measured
    if (!level) return corrected ? buf = with_disparity_offset(f, *cfg.rig, c) : f;
    return buf = levelled(corrected ? with_disparity_offset(f, *cfg.rig, c) : f, tilt);
}

/// The final, smallest and largest of the disparity corrections the frames were given.
void note_offset(SequenceRun& run, double c) {
    run.disparity_min = run.disparity_estimated ? std::min(run.disparity_min, c) : c;
    run.disparity_max = run.disparity_estimated ? std::max(run.disparity_max, c) : c;
    run.disparity_final = c;
    run.disparity_estimated = true;
}

/// run_visual_stream's loop on frames whose noise is as given (`noise_scale` is recorded).
SequenceRun visual_run(const FrameSource& frames, const std::vector<Pose>& truth, const VisualOdometryConfig& cfg,
                       const AssociationConfig& association, VisualOdometry* odometry, double noise_scale,
                       RunRecord record) {
    const bool keep = record.keep, pixels = cfg.residual == OdometryResidual::pixels;
    const bool offsets = pixels && cfg.estimate_disparity_offset;
    VisualOdometryStream vos(cfg, keep);
    FilterRun filter(Pose::Zero(), association, truth, std::move(record));
    SpatialTracker track;   // the height and tilt of the 6-DoF poses, on pixels
    SequenceRun offset_range;
    StereoFrame previous, current, buf;
    size_t k = 0;
    if (frames(previous)) {
        for (k = 1; frames(current); ++k) {
            vos.step(previous, current);
            for (const auto& [p, c] : vos.estimate().matches) current[static_cast<std::size_t>(c)].odometry_inlier = true;
            if (offsets) note_offset(offset_range, vos.disparity_offset());
            if (k == 1) {
                if (pixels) filter.set_spatial(track.tilt(), track.height());
                filter.first_frame(seen_frame(previous, vos.disparity_offset(), Mat3::Identity(), cfg, buf));
            }
            track.step(vos.estimate());
            if (pixels) filter.set_spatial(track.tilt(), track.height());
            filter.next_frame(vos.motion(), vos.covariance(), seen_frame(current, vos.disparity_offset(), vos.tilt(), cfg, buf));
            std::swap(previous, current);
        }
    }
    if (k < 2) throw InputError("a sequence needs at least 2 frames, got " + std::to_string(k));
    if (truth.size() > k)
        throw InputError("a sequence needs at most one pose per frame to score: " + std::to_string(k) + " frames, " +
                         std::to_string(truth.size()) + " poses");
    SequenceRun run = filter.finish();
    VisualOdometry vo = vos.take();
    if (offsets) {
        run.disparity_estimated = true;
        run.disparity_final = offset_range.disparity_final;
        run.disparity_min = offset_range.disparity_min;
        run.disparity_max = offset_range.disparity_max;
        if (keep) run.disparity_offset = vo.disparity_offset;
    }
    vo.noise_scale = noise_scale;
    run.noise_scale = noise_scale;
    run.spatial_from_odometry = pixels;
    if (odometry) *odometry = std::move(vo);
    return run;
}

}  // namespace

namespace {
/// run_visual_sequence with the filter's `record`.
SequenceRun held_run(const std::vector<StereoFrame>& frames_in, const std::vector<Pose>& truth,
                     const VisualOdometryConfig& cfg, const AssociationConfig& association, VisualOdometry* odometry,
                     RunRecord record) {
    if (frames_in.size() < 2)
        throw InputError("a sequence needs at least 2 frames, got " + std::to_string(frames_in.size()));
    if (truth.size() > frames_in.size())
        throw InputError("a sequence needs at most one pose per frame to score: " + std::to_string(frames_in.size()) +
                         " frames, " + std::to_string(truth.size()) + " poses");
    cfg.validate();
    std::vector<StereoFrame> scaled;
    double scale = 1;
    if (cfg.noise_from_residuals) scale = odometry_on_measured_noise(frames_in, cfg, scaled).noise_scale;
    // the odometry is run again on the frames it settled on (deterministic: the same motions)
    return visual_run(frames_of(scaled.empty() ? frames_in : scaled), truth, cfg, association, odometry, scale,
                      std::move(record));
}
}  // namespace

SequenceRun run_visual_sequence(const std::vector<StereoFrame>& frames_in, const std::vector<Pose>& truth,
                                const VisualOdometryConfig& cfg, const AssociationConfig& association,
                                VisualOdometry* odometry) {
    return held_run(frames_in, truth, cfg, association, odometry, {});
}

SequenceRun run_visual_stream(const FrameSource& frames, const std::vector<Pose>& truth, const VisualOdometryConfig& cfg,
                              const AssociationConfig& association, VisualOdometry* odometry, RunRecord record) {
    cfg.validate();
    if (!cfg.noise_from_residuals) return visual_run(frames, truth, cfg, association, odometry, 1, std::move(record));
    std::vector<StereoFrame> all;
    StereoFrame f;
    while (frames(f)) all.push_back(std::move(f));
    return held_run(all, truth, cfg, association, odometry, std::move(record));
}

}  // namespace hc::slam

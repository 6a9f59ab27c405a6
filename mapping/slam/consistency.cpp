// consistency.cpp: chi-square quantiles, NEES, simulated runs and their Monte-Carlo
// consistency (mean NEES over runs against the two-sided chi-square bounds, Bar-Shalom,
// Li & Kirubarajan, "Estimation with applications to tracking and navigation", 2001, 5.4).
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>

#include "mapping/slam/consistency.hpp"

namespace hc::slam {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// x in [lo, hi] with f(x) = target for an increasing f, by bisection.
template <class F>
double bisect(F f, double target, double lo, double hi) {
    for (int i = 0; i < 400 && hi - lo > 1e-13 * std::max(1.0, std::abs(hi)); ++i) {
        const double mid = (lo + hi) / 2;
        (f(mid) < target ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
}
}  // namespace

double normal_quantile(double p) {
    if (!(p > 0 && p < 1)) throw std::invalid_argument("normal_quantile: p must be in (0, 1)");
    const auto cdf = [](double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); };
    return bisect(cdf, p, -40.0, 40.0);
}

double regularized_gamma_p(double a, double x) {
    if (!(a > 0)) throw std::invalid_argument("regularized_gamma_p: a must be positive");
    if (x <= 0) return 0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1) {
        // series: P = e^-x x^a / Γ(a) · Σ_n x^n / (a (a+1) ... (a+n))
        double term = 1 / a, sum = term, ap = a;
        for (int n = 0; n < 100000 && std::abs(term) > std::abs(sum) * 1e-16; ++n) {
            ap += 1;
            term *= x / ap;
            sum += term;
        }
        return sum * std::exp(log_prefactor);
    }
    // continued fraction for Q = 1 − P (modified Lentz)
    constexpr double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-16) break;
    }
    return 1 - std::exp(log_prefactor) * h;
}

double chi2_quantile(double p, double dof) {
    if (!(p > 0 && p < 1)) throw std::invalid_argument("chi2_quantile: p must be in (0, 1)");
    if (!(dof > 0)) throw std::invalid_argument("chi2_quantile: dof must be positive");
    const auto cdf = [dof](double x) { return regularized_gamma_p(dof / 2, x / 2); };
    double hi = std::max(1.0, 2 * dof);
    while (cdf(hi) < p) hi *= 2;
    return bisect(cdf, p, 0.0, hi);
}

double chi2_quantile_wilson_hilferty(double p, double dof) {
    const double v = 2 / (9 * dof);
    const double t = 1 - v + normal_quantile(p) * std::sqrt(v);
    return dof * t * t * t;
}

double nees(const Eigen::VectorXd& e, const Eigen::MatrixXd& P) {
    const Eigen::LLT<Eigen::MatrixXd> llt(P);
    if (llt.info() != Eigen::Success || !(llt.rcond() > 1e-12)) return nan;
    return e.dot(llt.solve(e));
}

RunTrace run_simulation(const SimConfig& config, uint64_t seed, UpdateForm form) {
    Simulator sim(config, seed);
    Ekf ekf(sim.start_pose(), Mat3::Zero(), config.landmarks);
    const double f2 = config.filter_sigma_scale * config.filter_sigma_scale;
    const Mat2 N = f2 * config.odometry.covariance();
    const Mat2 R = f2 * Eigen::Vector2d(config.sensor.sigma_range * config.sensor.sigma_range,
                                        config.sensor.sigma_bearing * config.sensor.sigma_bearing)
                            .asDiagonal();
    RunTrace t;
    t.world = sim.world();
    const auto record = [&] {
        const Pose truth = sim.true_pose(), est = ekf.pose();
        Eigen::VectorXd e = truth - est;
        e(2) = wrap_angle(e(2));
        const Mat3 Prr = ekf.pose_covariance();
        t.truth.push_back(truth);
        t.estimate.push_back(est);
        t.pose_cov.push_back(Prr);
        t.pose_nees.push_back(nees(e, Prr));
        const auto& ids = ekf.landmark_ids();
        const int m = static_cast<int>(ids.size());
        Eigen::VectorXd eM(2 * m);
        double sq = 0;
        for (int k = 0; k < m; ++k) {
            eM.segment<2>(2 * k) = sim.world().landmarks[ids[k]] - ekf.landmark(ids[k]);
            sq += eM.segment<2>(2 * k).squaredNorm();
        }
        t.map_nees.push_back(m ? nees(eM, ekf.covariance().bottomRightCorner(2 * m, 2 * m)) : nan);
        t.map_dof.push_back(2 * m);
        t.map_rmse.push_back(m ? std::sqrt(sq / m) : nan);
    };
    const auto sense = [&] {
        for (const auto& o : sim.observe()) {
            if (ekf.has_landmark(o.id))
                ekf.correct(o.id, o.y, R, form);
            else
                ekf.add_landmark(o.id, o.y, R);
        }
    };
    sense();
    record();
    for (int k = 0; k < config.steps; ++k) {
        ekf.predict(sim.step(), N);
        sense();
        record();
    }
    t.final_filter = ekf;
    for (int id : ekf.landmark_ids()) {
        t.final_map.push_back(ekf.landmark(id));
        t.final_map_cov.push_back(ekf.landmark_covariance(id));
    }
    return t;
}

RunErrors run_errors(const RunTrace& t) {
    RunErrors e;
    e.pose_nees = t.pose_nees;
    e.map_nees = t.map_nees;
    e.map_dof = t.map_dof;
    e.map_rmse = t.map_rmse;
    for (size_t k = 0; k < t.truth.size(); ++k) {
        e.position_sq.push_back((t.truth[k] - t.estimate[k]).head<2>().squaredNorm());
        const double eh = wrap_angle(t.truth[k](2) - t.estimate[k](2));
        e.heading_sq.push_back(eh * eh);
    }
    return e;
}

MonteCarlo monte_carlo(const SimConfig& config, int runs, uint64_t first_seed, double confidence,
                       const std::function<void(int, int)>& progress) {
    config.validate();
    if (runs < 1) throw InputError("--runs must be at least 1, got " + std::to_string(runs));
    if (!(confidence > 0 && confidence < 1)) throw InputError("the confidence must be in (0, 1)");
    std::vector<RunErrors> errors;
    RunTrace first;
    for (int r = 0; r < runs; ++r) {
        RunTrace t = run_simulation(config, first_seed + r);
        errors.push_back(run_errors(t));
        if (r == 0) first = std::move(t);
        if (progress) progress(r + 1, runs);
    }
    MonteCarlo mc = fold_monte_carlo(errors, std::move(first), confidence);
    mc.first_seed = first_seed;
    return mc;
}

MonteCarlo fold_monte_carlo(const std::vector<RunErrors>& errors, RunTrace first, double confidence) {
    const int runs = static_cast<int>(errors.size());
    if (runs < 1) throw InputError("a Monte-Carlo fold needs at least one run");
    if (!(confidence > 0 && confidence < 1)) throw InputError("the confidence must be in (0, 1)");
    const int T = static_cast<int>(errors.front().pose_nees.size());
    for (const auto& e : errors)
        if (static_cast<int>(e.pose_nees.size()) != T || static_cast<int>(e.map_nees.size()) != T ||
            static_cast<int>(e.map_dof.size()) != T || static_cast<int>(e.map_rmse.size()) != T ||
            static_cast<int>(e.position_sq.size()) != T || static_cast<int>(e.heading_sq.size()) != T)
            throw InputError("Monte-Carlo runs of different lengths cannot be folded");
    std::vector<double> pose_sum(T, 0), map_sum(T, 0), pos_sq(T, 0), head_sq(T, 0), map_sq(T, 0);
    std::vector<int> pose_n(T, 0), map_n(T, 0);
    std::vector<long> dof_sum(T, 0);
    MonteCarlo mc;
    mc.runs = runs;
    mc.confidence = confidence;
    for (const RunErrors& t : errors) {
        for (int k = 0; k < T; ++k) {
            if (std::isfinite(t.pose_nees[k])) {
                pose_sum[k] += t.pose_nees[k];
                ++pose_n[k];
            }
            if (std::isfinite(t.map_nees[k])) {
                map_sum[k] += t.map_nees[k];
                dof_sum[k] += t.map_dof[k];
                ++map_n[k];
                map_sq[k] += t.map_rmse[k] * t.map_rmse[k];
            }
            pos_sq[k] += t.position_sq[k];
            head_sq[k] += t.heading_sq[k];
        }
    }
    mc.first = std::move(first);
    const double lo_p = (1 - confidence) / 2, hi_p = (1 + confidence) / 2;
    mc.pose_lo = chi2_quantile(lo_p, 3.0 * runs) / runs;
    mc.pose_hi = chi2_quantile(hi_p, 3.0 * runs) / runs;
    int pose_defined = 0, pose_in = 0, map_defined = 0, map_in = 0;
    double pose_avg = 0, map_avg = 0;
    for (int k = 0; k < T; ++k) {
        // a step's mean is defined when every run has a defined NEES there
        const double pn = pose_n[k] == runs ? pose_sum[k] / runs : nan;
        mc.pose_nees.push_back(pn);
        if (std::isfinite(pn)) {
            ++pose_defined;
            pose_avg += pn;
            pose_in += pn >= mc.pose_lo && pn <= mc.pose_hi;
        }
        if (map_n[k] == runs && dof_sum[k] > 0) {
            const double d = static_cast<double>(dof_sum[k]);
            const double v = map_sum[k] / d, lo = chi2_quantile(lo_p, d) / d, hi = chi2_quantile(hi_p, d) / d;
            mc.map_nees_per_dof.push_back(v);
            mc.map_lo.push_back(lo);
            mc.map_hi.push_back(hi);
            ++map_defined;
            map_avg += v;
            map_in += v >= lo && v <= hi;
        } else {
            mc.map_nees_per_dof.push_back(nan);
            mc.map_lo.push_back(nan);
            mc.map_hi.push_back(nan);
        }
        mc.position_rmse.push_back(std::sqrt(pos_sq[k] / runs));
        mc.heading_rmse.push_back(std::sqrt(head_sq[k] / runs));
        mc.map_rmse.push_back(map_n[k] ? std::sqrt(map_sq[k] / map_n[k]) : nan);
    }
    mc.pose_inside = pose_defined ? static_cast<double>(pose_in) / pose_defined : 0;
    mc.map_inside = map_defined ? static_cast<double>(map_in) / map_defined : 0;
    mc.pose_nees_average = pose_defined ? pose_avg / pose_defined : nan;
    mc.map_nees_per_dof_average = map_defined ? map_avg / map_defined : nan;
    return mc;
}

}  // namespace hc::slam

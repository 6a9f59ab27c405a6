// consistency.hpp: the filter's consistency (slam.hpp): NEES against chi-square bounds over
// Monte-Carlo runs of the simulator.
#pragma once

#include "mapping/slam/simulator.hpp"

#include <cstdint>
#include <functional>

namespace hc::slam {

/// Standard normal quantile (Acklam's rational approximation refined by one Halley step).
double normal_quantile(double p);
/// Regularised lower incomplete gamma P(a, x) (series / continued fraction).
double regularized_gamma_p(double a, double x);
/// Chi-square quantile: the x with P(dof/2, x/2) = p, by bisection to 1e-12 relative.
double chi2_quantile(double p, double dof);
/// Wilson-Hilferty's approximation of the chi-square quantile (for comparison).
double chi2_quantile_wilson_hilferty(double p, double dof);

/// Normalised estimation error squared eᵀ P⁻¹ e; NaN when P is not positive definite.
double nees(const Eigen::VectorXd& e, const Eigen::MatrixXd& P);

/// One simulated run, step by step (index 0 = before the first motion).
struct RunTrace {
    std::vector<Pose> truth, estimate;
    std::vector<Mat3> pose_cov;
    std::vector<double> pose_nees;     ///< NaN while P_rr is singular (first motion)
    std::vector<double> map_nees;      ///< joint NEES of all mapped landmarks
    std::vector<int> map_dof;          ///< 2 × mapped landmarks
    std::vector<double> map_rmse;      ///< RMS landmark position error (m)
    World world;
    Ekf final_filter;                  ///< the filter at the end (not carried by sharded runs' results)
    std::vector<Vec2> final_map;       ///< the filter's landmark estimates at the end, in state order
    std::vector<Mat2> final_map_cov;   ///< their covariances
};
/// Runs the filter on a simulated run (known data association, landmarks initialised on
/// first sight).
RunTrace run_simulation(const SimConfig& config, uint64_t seed, UpdateForm form = UpdateForm::Structured);

/// Monte-Carlo consistency over `runs` seeds first_seed, first_seed+1, ...
struct MonteCarlo {
    int runs = 0;
    std::uint64_t first_seed = 1;              ///< the runs' seeds: first_seed, first_seed + 1, ...
    double confidence = 0.95;
    std::vector<double> pose_nees;             ///< mean over runs, per step (NaN if undefined)
    double pose_lo = 0, pose_hi = 0;           ///< bounds of the mean: χ²(3·runs)/runs
    std::vector<double> map_nees_per_dof;      ///< Σ NEES / Σ dof, per step
    std::vector<double> map_lo, map_hi;        ///< bounds per step: χ²(Σdof)/Σdof
    std::vector<double> position_rmse, heading_rmse, map_rmse;   ///< over runs, per step
    /// Fractions of the steps (with a defined NEES) whose mean lies inside its bounds.
    double pose_inside = 0, map_inside = 0;
    double pose_nees_average = 0, map_nees_per_dof_average = 0;   ///< over steps
    RunTrace first;   ///< the run of first_seed, for the plots
};
/// One run's contributions to the Monte-Carlo statistics, per step.
struct RunErrors {
    std::vector<double> pose_nees, map_nees;   ///< NaN where undefined
    std::vector<int> map_dof;
    std::vector<double> map_rmse;              ///< NaN while no landmark is mapped
    std::vector<double> position_sq;           ///< squared planar position error (m²)
    std::vector<double> heading_sq;            ///< squared wrapped heading error (rad²)
};
RunErrors run_errors(const RunTrace& t);
/// A run's errors and what the report draws of a run's trace (the filter itself is not
/// carried) as JSON: lists of numbers, NaN as null, bit for bit back; matrices row-major.
/// mapping/slam/simulation_json.cpp.
void to_json(nlohmann::json& j, const RunErrors& e);
void from_json(const nlohmann::json& j, RunErrors& e);
void to_json(nlohmann::json& j, const RunTrace& t);
void from_json(const nlohmann::json& j, RunTrace& t);
/// The statistics of runs of consecutive seeds, folded in the order given (seed order: the
/// order fixes every floating-point sum, so runs computed anywhere and folded here give the
/// same bits as monte_carlo()). `first` is the first seed's trace. Throws InputError for
/// no runs, runs of different lengths or a confidence outside (0, 1).
MonteCarlo fold_monte_carlo(const std::vector<RunErrors>& runs, RunTrace first, double confidence = 0.95);
/// run_simulation() of every seed, then fold_monte_carlo(). `progress` (may be empty) is
/// called after each run with (done, total).
MonteCarlo monte_carlo(const SimConfig& config, int runs, uint64_t first_seed, double confidence = 0.95,
                       const std::function<void(int, int)>& progress = {});

}  // namespace hc::slam

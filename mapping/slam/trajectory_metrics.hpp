// trajectory_metrics.hpp: trajectory scores against ground truth (slam.hpp), as evo computes
// them: APE in 3-D and on the top view (without and with SE(2) alignment, over the poses or as
// running sums), RPE per frame, path length, pose NEES per frame.
#pragma once

#include "mapping/slam/ekf.hpp"

#include <cstddef>
#include <vector>

namespace hc::slam {

/// 3-D absolute trajectory error: RMS distance between the positions (the 3×4 poses' last
/// columns), poses paired by index, no alignment: what evo_ape computes on the two KITTI files by
/// default. Throws std::invalid_argument on size mismatch.
double absolute_trajectory_error_3d(const std::vector<Mat34>& estimate, const std::vector<Mat34>& truth);
/// Absolute trajectory error: RMS planar position error, poses paired by index, no
/// alignment (both start at the same pose). Throws std::invalid_argument on size mismatch.
double absolute_trajectory_error(const std::vector<Pose>& estimate, const std::vector<Pose>& truth);

/// Trajectory scores against ground truth, as evo computes them on the top view.
struct TrajectoryMetrics {
    double ape = 0;              ///< APE, translation RMSE, no alignment (m) (= absolute_trajectory_error)
    double ape_se2 = 0;          ///< APE after the least-squares SE(2) alignment of estimate to truth (m)
    double rpe = 0;              ///< RPE per frame (delta 1), translation RMSE (m)
    double rpe_heading = 0;      ///< RPE per frame, heading RMSE (rad)
    double path_length = 0;      ///< length of the ground-truth path (m)
    double final_error = 0;      ///< position error of the last pose (m)
    std::vector<double> nees;    ///< per frame, pose NEES (3 dof) against truth; NaN where P is singular
    double nees_mean = 0;        ///< mean over the frames with a defined NEES (NaN if none)
    int nees_frames = 0;         ///< frames with a defined NEES
    /// 95 % bounds of the mean of nees_frames independent χ²(3) (χ²(0.025 / 0.975; 3 N) / N);
    /// a trajectory's errors are correlated from frame to frame, so these are narrower than the
    /// spread of one run's mean. 0 when no NEES is defined.
    double nees_lo = 0, nees_hi = 0;
    double nees_within_95 = 0;   ///< fraction of those frames whose NEES is ≤ χ²(0.95; 3) = 7.81
    double ape_percent() const { return path_length > 0 ? 100 * ape / path_length : 0; }
};
/// The SE(2)-aligned APE (aligned_ape) from running sums, pose by pose: the means of the
/// estimate's and the truth's positions and their centred second moments (Σ|e − ē|², Σ|t − t̄|²,
/// Σ (e − ē)·(t − t̄), Σ (e − ē)×(t − t̄)), updated as Welford's running moments. The closed form
/// of the 2-D alignment (Horn; Umeyama without scale): the rotation φ = atan2(Σ×, Σ·) leaves the
/// residual Σ|e − ē|² + Σ|t − t̄|² − 2·hypot(Σ·, Σ×), so no pose is kept. Not aligned_ape's bits:
/// the residual is a difference of sums, with an absolute error of about 1e-16 times the
/// positions' spread squared (relative 1e-9 or better when the aligned error is above about 1e-3
/// of that spread, tested).
class AlignedApeSums {
public:
    void add(const Vec2& estimate, const Vec2& truth);
    size_t count() const { return n_; }
    /// The aligned APE of the poses added (m); std::invalid_argument before the first.
    double ape() const;

private:
    size_t n_ = 0;
    Vec2 me_ = Vec2::Zero(), mt_ = Vec2::Zero();
    double see_ = 0, stt_ = 0, dot_ = 0, cross_ = 0;
};
/// score_trajectory's metrics as running sums, frame by frame: APE, RPE, path length, final
/// error and the NEES count, mean and share within χ²(0.95; 3), summed in frame order as
/// score_trajectory sums them (the same bits), and the SE(2)-aligned APE from AlignedApeSums
/// (not aligned_ape's bits: relative 1e-9). Held: the sums and the previous frame's poses.
class TrajectoryScore {
public:
    /// The next frame's estimate and true pose, and the estimate's covariance (nullptr: no
    /// NEES); returns the frame's pose NEES (NaN where it is not defined).
    double add(const Pose& estimate, const Pose& truth, const Mat3* cov);
    size_t frames() const { return n_; }
    /// The metrics of the frames added so far (at least one), ape_se2 from the running sums, no
    /// per-frame NEES (add returned them). Throws std::invalid_argument before the first frame.
    TrajectoryMetrics metrics() const;

private:
    AlignedApeSums aligned_;
    size_t n_ = 0;
    double ape_ss_ = 0, rpe_ss_ = 0, rpe_heading_ss_ = 0, path_ = 0, final_ = 0, nees_sum_ = 0;
    int nees_frames_ = 0, nees_within_ = 0;
    Pose last_estimate_ = Pose::Zero(), last_truth_ = Pose::Zero();
};
/// APE after the SE(2) alignment of `estimate` to `truth` (se2_alignment): RMS of the aligned
/// position errors (m). Throws std::invalid_argument on size mismatch.
double aligned_ape(const std::vector<Pose>& estimate, const std::vector<Pose>& truth);
/// The metrics of `estimate` against `truth` (same length ≥ 1); `cov` (empty or one per pose)
/// gives the NEES: TrajectoryScore over the frames, and aligned_ape (the pass over the poses,
/// not the running sums) as ape_se2. Throws
/// std::invalid_argument on size mismatch.
TrajectoryMetrics score_trajectory(const std::vector<Pose>& estimate, const std::vector<Pose>& truth,
                                   const std::vector<Mat3>& cov = {});
/// The rigid motion (x, y, θ) that maps `estimate`'s positions onto `truth`'s with least
/// squares (Umeyama without scale, in 2-D). Throws std::invalid_argument on size mismatch.
Pose se2_alignment(const std::vector<Pose>& estimate, const std::vector<Pose>& truth);

}  // namespace hc::slam

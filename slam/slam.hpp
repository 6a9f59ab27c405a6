// slam.hpp: 2-D top-view EKF-SLAM (the thesis's section 2.5 and 5.4, a port of the
// structure of J. Solà's EKF-SLAM course code, "Simultaneous localization and mapping with
// the extended Kalman filter", 2013/2014), with its simulator, its consistency measures
// (NEES against chi-square bounds) and the stereo-landmark front end for KITTI sequences.
//
// Conventions
// - Robot pose r = (x, y, θ), θ in radians, wrapped to (-π, π]; robot frame: x forward,
//   y left. Landmarks are 2-D points p = (x, y) in the world frame.
// - Observation y = (range, bearing), bearing in the robot frame, wrapped.
// - Every event function returns its value and, when asked (non-null pointers), its
//   Jacobians, named from the math as in Solà's slamtb: `R_r` = ∂r'/∂r, `R_n` = ∂r'/∂n,
//   `Y_r` = ∂y/∂r, `Y_p` = ∂y/∂p, `P_r` = ∂p/∂r, `P_y` = ∂p/∂y.
// - The filter (Ekf) stores the covariance's lower triangle only (the upper one is not
//   maintained); covariance() returns the full symmetric matrix.
// - Errors in user input (bad configuration values, unreadable pose files) throw
//   hc::slam::InputError, which the command line maps to exit status 2.
#pragma once

#include "slam/landmarks/stereo.hpp"
#include "io/util/errors.hpp"
#include <Eigen/Core>
#include <Eigen/Dense>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace hc::slam {

/// Bad user input (configuration values, files); the CLI prints what() and exits with 2.
struct InputError : hc::InputError {
    using hc::InputError::InputError;
};

using Pose = Eigen::Vector3d;   ///< (x, y, θ)
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Mat32 = Eigen::Matrix<double, 3, 2>;
using Mat34 = Eigen::Matrix<double, 3, 4>;

// ---- geometry and the events of the filter (thesis Figure 8) ----------------------------

/// The angle a wrapped to (-π, π].
double wrap_angle(double a);

/// p (world) expressed in frame F = (x, y, θ) (slamtb toFrame). PF_f = ∂/∂F, PF_p = ∂/∂p.
Vec2 to_frame(const Pose& F, const Vec2& p, Mat23* PF_f = nullptr, Mat2* PF_p = nullptr);
/// pf (in frame F) expressed in the world (slamtb fromFrame). PW_f = ∂/∂F, PW_pf = ∂/∂pf.
Vec2 from_frame(const Pose& F, const Vec2& pf, Mat23* PW_f = nullptr, Mat2* PW_pf = nullptr);
/// Cartesian point -> (range, bearing) (slamtb scan). Y_p = ∂y/∂p. p must not be the origin.
Vec2 scan(const Vec2& p, Mat2* Y_p = nullptr);
/// (range, bearing) -> Cartesian point (slamtb invScan). P_y = ∂p/∂y.
Vec2 inv_scan(const Vec2& y, Mat2* P_y = nullptr);

/// Motion with odometry u = (dx, dθ) and perturbation n (added to u): the robot turns by
/// (dθ+nθ)/2, advances dx+nx, turns the other half (exact for arcs of constant curvature;
/// Solà's course code advances along the old heading, then turns).
Pose move(const Pose& r, const Vec2& u, const Vec2& n, Mat3* R_r = nullptr, Mat32* R_n = nullptr);
/// Observation of world point p from pose r: scan(to_frame(r, p)).
Vec2 observe(const Pose& r, const Vec2& p, Mat23* Y_r = nullptr, Mat2* Y_p = nullptr);
/// Inverse observation: the world point seen at y from pose r: from_frame(r, inv_scan(y)).
Vec2 inv_observe(const Pose& r, const Vec2& y, Mat23* P_r = nullptr, Mat2* P_y = nullptr);

/// A relative motion u = (dx, dy, dθ): the pose of the new robot frame in the old one.
using Motion = Eigen::Vector3d;
/// r ⊕ u: position r + R(θ)·(dx, dy), heading θ + dθ (wrapped). R_r = ∂/∂r, R_u = ∂/∂u.
/// The 3-DoF motion model of sequences (stereo odometry); exact for any planar motion.
Pose compose(const Pose& r, const Motion& u, Mat3* R_r = nullptr, Mat3* R_u = nullptr);
/// The motion u with compose(a, u) = b: u = (R(θa)ᵀ(b − a), wrap(θb − θa)).
Motion between(const Pose& a, const Pose& b);

// ---- the filter ---------------------------------------------------------------------------

/// How correct() updates the covariance. All give the same state and covariance up to
/// rounding; they differ in cost:
/// - Structured: P·Hᵀ from the 5 non-zero columns of H (robot + one landmark), then the
///   symmetric rank-2 update P ← P − W·Wᵀ with W = P·Hᵀ·L⁻ᵀ, Z = L·Lᵀ, on the lower
///   triangle. O(n²) per update, half the memory traffic of a full update.
/// - DenseKzk: dense 2×n H, K = P·Hᵀ·Z⁻¹, P ← P − K·Z·Kᵀ (the thesis's eq. 2.18). O(n²).
/// - Dense: dense 2×n H, K = P·Hᵀ·Z⁻¹, P ← (I − K·H)·P, an n×n by n×n product. O(n³).
enum class UpdateForm { Structured, DenseKzk, Dense };

/// An innovation: z = y − h(x̂) (bearing wrapped), its covariance Z and zᵀZ⁻¹z.
struct Innovation {
    Vec2 z = Vec2::Zero();
    Mat2 Z = Mat2::Zero();
    double mahalanobis2 = 0;
};

/// EKF-SLAM: state x = (r, p_1, ..., p_m), joint covariance P (thesis eq. 2.10).
class Ekf {
public:
    /// Map initialisation (eq. 2.11 with the defaults: pose 0, zero covariance).
    /// `capacity` landmarks are reserved; the map grows beyond it when needed.
    explicit Ekf(const Pose& r0 = Pose::Zero(), const Mat3& P0 = Mat3::Zero(), int capacity = 64);

    /// Prediction (eqs. 2.12, 2.13): r ← move(r, u, 0), P_rr ← R_r P_rr R_rᵀ + R_n N R_nᵀ,
    /// P_rm ← R_r P_rm. N is the covariance of the perturbation of u.
    void predict(const Vec2& u, const Mat2& N);
    /// Prediction with a 3-DoF motion u and its covariance Q: r ← compose(r, u),
    /// P_rr ← R_r P_rr R_rᵀ + R_u Q R_uᵀ, P_rm ← R_r P_rm.
    void predict_motion(const Motion& u, const Mat3& Q);

    /// The innovation of observing landmark `id` at y with noise covariance R, without
    /// changing the filter (for gating). Throws std::out_of_range for an unknown id.
    Innovation innovation(int id, const Vec2& y, const Mat2& R) const;

    /// Correction with the observation y of landmark `id` (eqs. 2.14-2.18). Returns the
    /// innovation used. Throws std::out_of_range for an unknown id.
    Innovation correct(int id, const Vec2& y, const Mat2& R, UpdateForm form = UpdateForm::Structured);

    /// Landmark initialisation by inverse observation (eqs. 2.19-2.21). Throws
    /// std::invalid_argument when `id` is already mapped.
    void add_landmark(int id, const Vec2& y, const Mat2& R);

    /// Removes landmark `id` and its rows and columns (no effect if absent).
    void remove_landmark(int id);

    bool has_landmark(int id) const { return index_.count(id) != 0; }
    int landmark_count() const { return static_cast<int>(ids_.size()); }
    int dimension() const { return n_; }
    /// Landmark ids in state order.
    const std::vector<int>& landmark_ids() const { return ids_; }
    /// Index in the state of landmark `id`'s x coordinate. Throws std::out_of_range.
    int state_index(int id) const;

    Pose pose() const { return x_.head<3>(); }
    Mat3 pose_covariance() const;
    Vec2 landmark(int id) const { return x_.segment<2>(state_index(id)); }
    Mat2 landmark_covariance(int id) const;
    Eigen::VectorXd mean() const { return x_.head(n_); }
    /// The full symmetric covariance (n×n).
    Eigen::MatrixXd covariance() const;
    /// The symmetric sub-matrix P(idx, idx) of the given state indices (read from the lower
    /// triangle), e.g. robot and candidate landmarks for a joint compatibility test.
    Eigen::MatrixXd covariance_of(const std::vector<int>& idx) const;

private:
    void reserve(int dim);
    /// Columns j and j+1.. (k columns) of the symmetric P, read from its lower triangle.
    void symmetric_columns(int j, int k, Eigen::Ref<Eigen::MatrixXd> out) const;
    Eigen::MatrixXd full_covariance() const;

    Eigen::VectorXd x_;
    Eigen::MatrixXd P_;   ///< capacity × capacity; lower triangle of the top-left n×n used
    int n_ = 3;
    std::vector<int> ids_;
    std::unordered_map<int, int> index_;   ///< id -> position in ids_
};

// ---- simulator ----------------------------------------------------------------------------

/// A range-bearing sensor: field of view (full angle), range limit, Gaussian noise.
struct SensorModel {
    double sigma_range = 0.05;          ///< m
    double sigma_bearing = 0.01745;     ///< rad (1°)
    double max_range = 6.0;             ///< m
    double fov = 3.14159265358979;      ///< rad, full angle centred on the heading
};

/// Odometry u = (dx, dθ) read with Gaussian noise of these standard deviations.
struct OdometryModel {
    double sigma_dx = 0.01;       ///< m per step
    double sigma_dtheta = 0.005;  ///< rad per step
    Mat2 covariance() const;
};

enum class Layout { Cloister, Random };

/// A simulated run: a world of landmarks around a circular trajectory.
struct SimConfig {
    Layout layout = Layout::Cloister;
    int landmarks = 40;          ///< world landmarks (> 0)
    double half_size = 5.0;      ///< m: the world spans [-half_size, half_size]²
    double radius = 3.75;        ///< m: radius of the robot's circle (centred at the origin)
    double step = 0.1;           ///< m advanced per step
    int steps = 236;             ///< motion steps (2π·radius/step ≈ 236: one loop)
    SensorModel sensor;
    OdometryModel odometry;
    /// The filter assumes noise standard deviations this many times the simulator's
    /// (1 = matched; below 1 an over-confident filter, to show that the NEES test fails).
    double filter_sigma_scale = 1.0;
    /// Throws InputError naming the first bad value (non-positive noise, empty world, ...).
    void validate() const;
};

/// A world: landmark positions (index = landmark id).
struct World {
    std::vector<Vec2> landmarks;
};

/// The cloister (landmarks on two concentric squares, half_size and half_size/2, like
/// Solà's `cloister`) or a uniform random layout in [-half_size, half_size]².
World make_world(Layout layout, int count, double half_size, uint64_t seed);

/// One measured landmark.
struct Observation {
    int id = 0;
    Vec2 y = Vec2::Zero();
};

/// The simulator: ground-truth robot on a circle through the world, noisy odometry and
/// noisy range-bearing observations of the landmarks within field of view and range.
/// Seeded: the same config and seed give the same run.
class Simulator {
public:
    Simulator(const SimConfig& config, uint64_t seed);
    const World& world() const { return world_; }
    const Pose& true_pose() const { return pose_; }
    /// The robot's start pose (on the circle, heading tangent to it).
    Pose start_pose() const;
    /// Moves the true robot one step; returns the odometry reading (with noise).
    Vec2 step();
    /// Noisy observations of the landmarks visible from the true pose.
    std::vector<Observation> observe();
    /// Noisy observations of every landmark, visible or not (the thesis's worst case).
    std::vector<Observation> observe_all();

private:
    Observation measure(int id);
    SimConfig config_;
    World world_;
    Pose pose_;
    std::mt19937_64 rng_;
    std::normal_distribution<double> gauss_{0.0, 1.0};
};

// ---- consistency ----------------------------------------------------------------------------

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
/// The statistics of runs of consecutive seeds, folded in the order given (seed order: the
/// order fixes every floating-point sum, so runs computed anywhere and folded here give the
/// same bits as monte_carlo()). `first` is the first seed's trace. Throws InputError for
/// no runs, runs of different lengths or a confidence outside (0, 1).
MonteCarlo fold_monte_carlo(const std::vector<RunErrors>& runs, RunTrace first, double confidence = 0.95);
/// run_simulation() of every seed, then fold_monte_carlo(). `progress` (may be empty) is
/// called after each run with (done, total).
MonteCarlo monte_carlo(const SimConfig& config, int runs, uint64_t first_seed, double confidence = 0.95,
                       const std::function<void(int, int)>& progress = {});

// ---- stereo landmarks and KITTI ---------------------------------------------------------

/// A 3-D landmark measured by a stereo pipeline in the left camera frame of one frame
/// (KITTI camera: x right, y down, z forward), with its covariance.
struct StereoLandmarkObs {
    Eigen::Vector3d p_cam = Eigen::Vector3d::Zero();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Identity();
    std::vector<uint8_t> descriptor;   ///< binary descriptor (Hamming); empty = not checked
    /// A track or point id from the pipeline; -1 = none. Association does not use it; when
    /// both an observation and the observation that created its landmark carry one, a
    /// match counts as agreeing (FrameStats::matched_agreeing) if they are equal.
    int id_hint = -1;
};
using StereoFrame = std::vector<StereoLandmarkObs>;

/// A range-bearing observation with its 2×2 covariance.
struct RangeBearing {
    Vec2 y = Vec2::Zero();
    Mat2 R = Mat2::Identity();
};
/// The top view of a camera-frame point: robot frame x = z_cam (forward), y = −x_cam
/// (left); y_cam (height) is dropped. R = Y_p·cov·Y_pᵀ with Y_p = ∂(range, bearing)/∂p_cam.
RangeBearing camera_to_range_bearing(const Eigen::Vector3d& p_cam, const Eigen::Matrix3d& cov,
                                     Eigen::Matrix<double, 2, 3>* Y_p = nullptr);

/// Reads a KITTI poses file (12 numbers a line: the 3×4 [R|t] of camera 0 in the first
/// camera's frame). Throws InputError naming the file and line when absent, unreadable,
/// malformed or empty.
std::vector<Mat34> read_kitti_poses(const std::filesystem::path& file);
/// The top view of a KITTI pose: (z, −x, yaw) with yaw = atan2(−R(0,2), R(2,2)).
Pose planar_pose(const Mat34& T);
/// A KITTI pose from a top-view pose (height 0, rotation about the camera's y axis).
Mat34 kitti_pose(const Pose& r);
/// Synthetic odometry on a real trajectory: the exact relative pose between consecutive
/// ground-truth poses (between()) with Gaussian noise of these standard deviations added.
struct SyntheticOdometry {
    double sigma_dx = 0.1;        ///< m per frame, forward
    double sigma_dy = 0.02;       ///< m per frame, sideways
    double sigma_dtheta = 0.002;  ///< rad per frame
    Mat3 covariance() const;
    void validate() const;        ///< InputError unless every σ is positive
};
/// between(truth[k-1], truth[k]) plus noise of `model` (seeded), one motion per step.
std::vector<Motion> noisy_odometry(const std::vector<Pose>& truth, const SyntheticOdometry& model, uint64_t seed);
/// Dead reckoning: the poses that compose() integrates from `start` with `motions`.
std::vector<Pose> dead_reckoning(const Pose& start, const std::vector<Motion>& motions);

/// Trajectory files: KITTI (12 numbers a line) and TUM ("t tx ty tz qx qy qz qw"), in
/// the KITTI camera frame (x right, y down, z forward), height 0.
std::string kitti_trajectory(const std::vector<Pose>& poses);
std::string tum_trajectory(const std::vector<Pose>& poses, const std::vector<double>& timestamps);
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
    double ape_percent() const { return path_length > 0 ? 100 * ape / path_length : 0; }
};
/// The metrics of `estimate` against `truth` (same length ≥ 1); `cov` (empty or one per pose)
/// gives the NEES. Throws std::invalid_argument on size mismatch.
TrajectoryMetrics score_trajectory(const std::vector<Pose>& estimate, const std::vector<Pose>& truth,
                                   const std::vector<Mat3>& cov = {});
/// The rigid motion (x, y, θ) that maps `estimate`'s positions onto `truth`'s with least
/// squares (Umeyama without scale, in 2-D). Throws std::invalid_argument on size mismatch.
Pose se2_alignment(const std::vector<Pose>& estimate, const std::vector<Pose>& truth);

/// How the observations of a frame are assigned to mapped landmarks.
enum class AssociationMethod {
    Jcbb,      ///< joint compatibility branch and bound (Neira & Tardós 2001) over the gated candidates
    Nearest,   ///< individual gating: pairs taken greedily by increasing Mahalanobis distance
};

/// Data association and map management for stereo landmark frames.
struct AssociationConfig {
    AssociationMethod method = AssociationMethod::Jcbb;
    double gate_probability = 0.99;   ///< individual gate: χ²(2) quantile of this probability
    double joint_probability = 0.99;  ///< JCBB's joint gate: χ²(2k) quantile for k pairings
    long max_nodes = 20000;           ///< JCBB: nodes searched at most (the best hypothesis so far is kept)
    /// Descriptor check: Hamming distance ≤ this fraction of the descriptor's bits.
    double max_hamming_fraction = 0.25;
    bool check_descriptor = true;
    int forget_after = 10;            ///< remove landmarks unseen for this many frames (0 = keep)
    double min_range = 1.0, max_range = 60.0;   ///< m: observations outside are ignored
    /// Observations used per frame (0 = all): the most precise ones (smallest det R), as
    /// each costs an O(n²) update or adds a landmark.
    int max_observations = 60;
    void validate() const;
};

/// The largest Hamming distance (bits) the check accepts for descriptors of `bytes` bytes:
/// floor(fraction · 8 · bytes).
int hamming_threshold(double fraction, size_t bytes);

/// Counts of one frame.
struct FrameStats {
    int observed = 0, matched = 0, added = 0, rejected_by_descriptor = 0, removed = 0, map_size = 0;
    int matched_with_hints = 0, matched_agreeing = 0;   ///< matches where both id hints are set / equal
    /// Scored against ground truth after the run (never used by it): matches whose observation
    /// and the landmark's first observation, placed in the world with the true poses, are
    /// farther apart than their covariances allow (χ²(2) 0.999).
    int matched_checked = 0, matched_wrong = 0;
    bool jcbb_complete = true;   ///< false when JCBB stopped at max_nodes
};

/// EKF-SLAM on stereo landmark frames: prediction with a 3-DoF motion and its covariance,
/// association of the frame's observations to mapped landmarks (individual Mahalanobis gate
/// and descriptor check give the candidates; JCBB or nearest neighbour picks among them),
/// correction with the matched ones, initialisation of the unmatched ones, removal of
/// landmarks unseen for `forget_after` frames.
class LandmarkSlam {
public:
    LandmarkSlam(const Pose& start, const AssociationConfig& association);
    /// The first frame: observations only (no motion before it).
    FrameStats first_frame(const StereoFrame& frame);
    /// A later frame: the motion from the previous frame and its covariance, then its observations.
    FrameStats next_frame(const Motion& u, const Mat3& Q, const StereoFrame& frame);
    const Ekf& filter() const { return ekf_; }
    /// The last frame's matches: (index of the observation in the frame, landmark id).
    const std::vector<std::pair<int, int>>& last_matches() const { return last_matches_; }
    /// Where landmark `id` was first observed: (frame number, index in that frame).
    std::pair<int, int> origin(int id) const { return origin_.at(id); }

private:
    FrameStats observe(const StereoFrame& frame);
    /// The landmarks each observation may be paired with: inside the individual gate, and the
    /// descriptor check passed; descriptor_failed[i] set when a gated landmark failed that check.
    std::vector<std::vector<int>> gate_candidates(const StereoFrame& frame, const std::vector<RangeBearing>& obs,
                                                  const std::vector<int>& src, std::vector<char>& descriptor_failed);
    /// Corrections with the observations paired with landmark[i] >= 0; the frame's matches and
    /// the id-hint counts of `st`.
    void correct_matched(const StereoFrame& frame, const std::vector<RangeBearing>& obs, const std::vector<int>& src,
                         const std::vector<int>& landmark, FrameStats& st);
    /// A new landmark for each unpaired observation (landmark[i] < 0).
    void add_unmatched(const StereoFrame& frame, const std::vector<RangeBearing>& obs, const std::vector<int>& src,
                       const std::vector<int>& landmark, const std::vector<char>& descriptor_failed, FrameStats& st);
    /// Removal of the landmarks unseen for forget_after frames.
    void forget_unseen(FrameStats& st);
    Ekf ekf_;
    AssociationConfig cfg_;
    double gate_;
    int frame_ = 0, next_id_ = 0;
    std::unordered_map<int, std::vector<uint8_t>> descriptors_;
    std::unordered_map<int, int> last_seen_, hints_;
    std::unordered_map<int, std::pair<int, int>> origin_;
    std::vector<std::pair<int, int>> last_matches_;
};

/// Number of differing bits; descriptors of different lengths differ in every extra bit.
int hamming_distance(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

/// A run on a sequence: the filter, and the same motions integrated alone (dead reckoning
/// of the odometry: synthetic odometry, or visual odometry alone).
struct SequenceRun {
    std::vector<Pose> truth, estimate, dead_reckoning;
    std::vector<Mat3> pose_cov;
    std::vector<FrameStats> frames;
    std::vector<Motion> odometry;
    std::vector<Mat3> odometry_cov;
    double ate_slam = 0, ate_dead_reckoning = 0;   ///< APE without alignment (m)
    TrajectoryMetrics slam_metrics, odometry_metrics;
    std::vector<Vec2> map;   ///< final landmark positions
    std::vector<Mat2> map_cov;
};
/// The filter over frames with the given motions (motions.size() == frames.size() − 1),
/// started at `start`, then scored against `truth` (one pose per frame; used only after the
/// run, for the metrics and the wrong-association counts). Throws InputError on size mismatch.
SequenceRun run_filter(const std::vector<StereoFrame>& frames, const std::vector<Motion>& motions,
                       const std::vector<Mat3>& motion_cov, const Pose& start, const AssociationConfig& association,
                       const std::vector<Pose>& truth);
/// Synthetic odometry on a real trajectory: run_filter over frames[k] seen at ground-truth
/// poses[k] (poses.size() == frames.size() ≥ 2) with noisy_odometry(truth, odometry, seed),
/// started at the first true pose. Throws InputError on a size mismatch or fewer than 2 poses.
SequenceRun run_sequence(const std::vector<Mat34>& poses, const std::vector<StereoFrame>& frames,
                         const SyntheticOdometry& odometry, const AssociationConfig& association, uint64_t seed);

/// The rig of the synthetic landmarks: KITTI's rectified cameras 0 and 1 (sequences 00-02):
/// fx = fy = 718.856 px, principal point (607.1928, 185.2157) px for both, the right camera
/// 0.5372 m to the right (tx1 = -fx * 0.5372), images 1241 x 376.
stereo::RectifiedRig synthetic_rig();
/// Synthetic stereo landmarks along a trajectory: `count` world points scattered on both
/// sides of the path (lateral 4..30 m, height -3..1 m in camera y), each with a random
/// 256-bit descriptor; frame k lists the points in front of camera k (z 2..60 m) that
/// project inside both images of `rig` (stereo::project), measured with `noise` (drawn on
/// u_l, v_l, u_r, v_r; a point whose noisy disparity is below 1 px is dropped), triangulated
/// (stereo::triangulate, with their first-order covariance under `noise`), and the descriptor
/// with `flip_bits` random bits flipped; id_hint = the world point's index (to score the
/// association, never used by it). Throws InputError when the rig has no image size.
std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const stereo::RectifiedRig& rig,
                                                  const stereo::PixelNoise& noise, int count, int flip_bits,
                                                  uint64_t seed);
/// A triangulated point (stereo::triangulate) as a filter observation: p_cam and cov (zero
/// when the disparity is not positive); no descriptor, no id hint.
StereoLandmarkObs to_observation(const stereo::Point3& t);

// ---- reports ------------------------------------------------------------------------------

/// Writes the Monte-Carlo report into `dir`: report.md, nees.csv, states.csv (the first
/// run), summary.json, trajectory.png (trajectory and map with 3σ ellipses), nees.png,
/// rmse.png. `command` is quoted in report.md. PNGs need gnuplot; without it they are
/// skipped with a note in the report. Files are written atomically.
void write_simulation_report(const std::filesystem::path& dir, const SimConfig& config, const MonteCarlo& mc,
                             const std::string& command);

/// Writes the sequence report: report.md (metrics of EKF-SLAM and of the odometry alone,
/// wrong associations against truth), states.csv (per frame, with the pose NEES),
/// summary.json, estimate_kitti.txt, estimate_tum.txt, dead_reckoning_kitti.txt (the
/// odometry alone), truth_kitti.txt, trajectory.png, map_size.png. `odometry_label` names
/// the odometry-alone trajectory ("visual odometry alone", "synthetic odometry alone").
void write_sequence_report(const std::filesystem::path& dir, const SequenceRun& run, const std::string& title,
                           const std::string& command, const std::string& odometry_label);
/// A Markdown table with one row per (sequence name, run).
std::string sequences_markdown(const std::vector<std::pair<std::string, SequenceRun>>& runs,
                               const std::string& odometry_label);

/// One point of the update timing: landmarks, milliseconds per step, per form.
struct TimingRow {
    int landmarks = 0;
    double structured_ms = 0, dense_kzk_ms = 0, dense_ms = 0;   ///< 0 = not measured
    /// dense_ms is k times one measured (I − KH)P update, not a measured step.
    bool dense_from_single_update = false;
};
/// Writes timing.csv and timing.png (log-log, with the thesis's Table 3 figures).
void write_timing_report(const std::filesystem::path& dir, const std::vector<TimingRow>& rows);

}  // namespace hc::slam

// Stereo visual odometry and joint-compatibility association: their own headers, part of
// this library's public interface.
#include "slam/association.hpp"
#include "slam/odometry.hpp"

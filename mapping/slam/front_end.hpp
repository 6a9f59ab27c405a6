// front_end.hpp: the stereo-landmark front end of the EKF-SLAM (slam.hpp): 3-D landmarks of
// a stereo pipeline as range-bearing observations, KITTI poses and trajectories, trajectory
// metrics, map management and data association (LandmarkSlam), runs over a sequence, and
// the synthetic landmarks seen through the rectified rig (mapping/landmarks/stereo.hpp).
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/landmarks/stereo.hpp"

#include <filesystem>
#include <functional>
#include <random>
#include <unordered_map>
#include <utility>

namespace hc::slam {

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

/// The noise covariance of observation o's (range, bearing) if the point were at q (robot
/// frame: x forward, y left) instead of where o was measured. The triangulation's covariance of
/// (x_cam, z_cam) is carried through (a, w) = (x_cam / z_cam, 1 / z_cam): a rectified rig
/// measures a = (u_l − cx) / fx and w = (u_l − u_r) / (fx · baseline) linearly in its pixels,
/// so their covariance is the same at every point, and the first-order covariance at q follows
/// from the one at the measurement without the rig: C_q = T C Tᵀ with T = ∂(x, z)/∂(a, w) at q
/// times ∂(a, w)/∂(x, z) at the measurement. q not in front (x ≤ 0): o's own covariance.
/// Exact in the camera's frame; in a levelled frame (odometry.hpp: levelled) the tilt mixes
/// the height into x and z, and the carried covariance is an approximation of the order of
/// the tilt.
Mat2 observation_noise_at(const StereoLandmarkObs& o, const Vec2& q);

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

/// Trajectory files: KITTI (12 numbers a line) and TUM ("t tx ty tz qx qy qz qw", qw ≥ 0) of
/// 6-DoF poses (camera 0 in the first camera's frame: x right, y down, z forward); a top-view
/// trajectory as KITTI poses at height 0 (kitti_pose).
std::string kitti_trajectory(const std::vector<Mat34>& poses);
std::string tum_trajectory(const std::vector<Mat34>& poses, const std::vector<double>& timestamps);
std::string kitti_trajectory(const std::vector<Pose>& poses);
/// One line of each: kitti_trajectory's and tum_trajectory's line of one pose (the same text).
std::string kitti_line(const Mat34& pose);
std::string tum_line(const Mat34& pose, double timestamp);
/// Reads a trajectory file of ground-truth poses of camera 0 in the first camera's frame (KITTI's
/// convention): KITTI (12 numbers a line, read_kitti_poses) or TUM ("t tx ty tz qx qy qz qw",
/// lines starting with '#' skipped), told apart by the count of numbers on its first pose line.
/// `times` given: receives a TUM file's timestamps, one per pose (left empty for a KITTI file,
/// which has none). Throws InputError naming the file and line when absent, malformed or empty.
std::vector<Mat34> read_trajectory_file(const std::filesystem::path& file, std::vector<double>* times = nullptr);
/// The ground-truth pose of each frame by timestamp: for frame k, the pose whose time is nearest
/// `frame_times[k]` (the earlier on a tie), when within `tolerance` (s). A frame without a pose
/// within it is an InputError naming `truth_name`, the frame and its time, unless `overlap`:
/// then the poses of the frames before the first such frame are returned (those frames are
/// scored). InputError when `tolerance` is not positive or the counts of poses and times differ.
std::vector<Mat34> truth_by_timestamp(const std::vector<Mat34>& poses, const std::vector<double>& pose_times,
                                      const std::vector<double>& frame_times, double tolerance,
                                      const std::string& truth_name, bool overlap);
/// Reads timestamps, one number (s) a line (KITTI's times.txt). InputError naming the file and
/// line when absent, malformed or empty.
std::vector<double> read_timestamps(const std::filesystem::path& file);
/// The 6-DoF poses of a top-view trajectory: rotation Y(θ)·tilt[k] (tilt_of's factors), position
/// (−y, height[k], x) in the camera frame. `tilt` and `height` empty: level, height 0 (kitti_pose).
/// Throws std::invalid_argument when a non-empty `tilt` or `height` is not one per pose.
std::vector<Mat34> spatial_poses(const std::vector<Pose>& planar, const std::vector<Mat3>& tilt = {},
                                 const std::vector<double>& height = {});
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
    /// true: an observation of a mapped landmark is gated, associated and corrected with its
    /// noise at the landmark's prediction (observation_noise_at; LandmarkSlam); false: at its
    /// measurement (the covariance the frame carries).
    bool noise_at_prediction = true;
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
/// landmarks unseen for `forget_after` frames. An observation of a mapped landmark is gated,
/// associated and corrected with its noise where the filter predicts the landmark
/// (observation_noise_at), not where it was measured: a stereo point's covariance grows with
/// its depth to the fourth power, so evaluated at the measurement it gives the points whose
/// noise put them too near the most weight, and the fused map and poses come out biased. A new
/// landmark is initialised with the covariance at its measurement (there is no prediction).
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
    /// The last frame's new landmarks: (index of the observation in the frame, landmark id).
    const std::vector<std::pair<int, int>>& last_added() const { return last_added_; }
    /// The landmarks the last frame removed (unseen for forget_after frames).
    const std::vector<int>& last_removed() const { return last_removed_; }

private:
    FrameStats observe(const StereoFrame& frame);
    /// The noise of observation o (rb, its range-bearing form) as a landmark the filter
    /// predicts at `at` (predicted_point): there with noise_at_prediction, else rb.R.
    Mat2 noise_of(const StereoLandmarkObs& o, const RangeBearing& rb, const Vec2& at) const;
    /// Where the filter predicts landmark `id`, in the robot's frame.
    Vec2 predicted_point(int id) const;
    /// The landmarks each observation may be paired with: inside the individual gate, and the
    /// descriptor check passed; descriptor_failed[i] set when a gated landmark failed that check.
    /// noise[i][c]: the noise of observation i paired with its c-th candidate (noise_of).
    /// Each landmark's prediction is computed once for all observations.
    std::vector<std::vector<int>> gate_candidates(const StereoFrame& frame, const std::vector<RangeBearing>& obs,
                                                  const std::vector<int>& src, std::vector<char>& descriptor_failed,
                                                  std::vector<std::vector<Mat2>>& noise);
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
    std::vector<std::pair<int, int>> last_matches_, last_added_;
    std::vector<int> last_removed_;
};

/// Number of differing bits; descriptors of different lengths differ in every extra bit.
int hamming_distance(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

/// One frame of a run as it comes (FilterRun): what states.csv and the trajectory files write of it.
struct FrameRecord {
    size_t frame = 0;
    const Pose* truth = nullptr;       ///< the frame's true pose; nullptr when the frame is not scored
    const Mat34* truth_3d = nullptr;   ///< its 3×4 pose, when the run has them (RunRecord::truth_3d)
    Pose estimate = Pose::Zero(), dead_reckoning = Pose::Zero();
    Mat3 pose_cov = Mat3::Zero();
    /// 6-DoF poses (spatial_poses of estimate and dead_reckoning with the frame's tilt and height).
    Mat34 estimate_3d = Mat34::Zero(), dead_reckoning_3d = Mat34::Zero();
    double nees_slam = 0, nees_odometry = 0;   ///< NaN when not scored or not defined
    double timestamp = 0;                      ///< TUM time (s), set by run_kitti_sequence's runs; else 0
    FrameStats stats;
};
using FrameSink = std::function<void(const FrameRecord&)>;
/// What a run gives besides its summary (SequenceRun): each frame's record as it comes, whether
/// SequenceRun keeps its per-frame vectors, and the truth's 3×4 poses for the 3-D APE.
struct RunRecord {
    FrameSink sink;                  ///< called once per frame, in order (may be empty)
    bool keep = true;                ///< false: SequenceRun's per-frame vectors stay empty
    std::vector<Mat34> truth_3d;     ///< the scored frames' 3×4 true poses (empty: no 3-D APE)
};
/// The counts of a run's frames, summed as frames come.
struct RunTotals {
    int matched = 0, observed = 0, peak = 0, final_map_size = 0, hinted = 0, agreeing = 0, checked = 0, wrong = 0,
        jcbb_cut = 0;
    void add(const FrameStats& f);
};

/// A run on a sequence: the filter, and the same motions integrated alone (dead reckoning
/// of the odometry: synthetic odometry, or visual odometry alone). `truth` holds the true poses
/// of the frames scored: one per frame, the first frames' only (the overlap of a shorter ground
/// truth), or none (no ground truth: every metric and the wrong-association counts stay 0).
/// The per-frame vectors (truth to disparity_offset, and the metrics' per-frame NEES) are kept
/// only with RunRecord::keep; the counts, totals, metrics and 3-D APE always (running sums).
struct SequenceRun {
    size_t frame_count = 0, scored_frames = 0;
    RunTotals totals;
    /// The disparity correction over the frames (with visual odometry estimating it): final, min, max.
    bool disparity_estimated = false;
    double disparity_final = 0, disparity_min = 0, disparity_max = 0;
    std::vector<Pose> truth, estimate, dead_reckoning;
    /// 6-DoF poses: the estimate and the odometry alone (top view of the filter or the odometry,
    /// height, roll and pitch of visual odometry's 6-DoF steps where it has them, else level at
    /// height 0: spatial_poses), and the truth's own 3×4 poses (the frames scored).
    std::vector<Mat34> estimate_3d, dead_reckoning_3d, truth_3d;
    /// 3-D APE (absolute_trajectory_error_3d) of estimate_3d and dead_reckoning_3d against
    /// truth_3d over its frames; 0 without it.
    double ape_3d_slam = 0, ape_3d_dead_reckoning = 0;
    /// true: estimate_3d's height, roll and pitch come from visual odometry's 6-DoF steps.
    bool spatial_from_odometry = false;
    /// TUM timestamps, one per frame (s), and where they come from (for the report).
    std::vector<double> timestamps;
    std::string timestamps_from;
    /// How the ground truth's poses were paired with the frames (for the report): in file order,
    /// or by timestamp; empty without a ground truth.
    std::string truth_pairing;
    std::vector<Mat3> pose_cov;
    std::vector<FrameStats> frames;
    std::vector<Motion> odometry;
    std::vector<Mat3> odometry_cov;
    double ate_slam = 0, ate_dead_reckoning = 0;   ///< APE without alignment (m)
    TrajectoryMetrics slam_metrics, odometry_metrics;
    std::vector<Vec2> map;   ///< final landmark positions
    std::vector<Mat2> map_cov;
    /// Visual odometry on pixels with the disparity correction estimated: the correction each
    /// frame was given (px, VisualOdometry::disparity_offset); empty otherwise.
    std::vector<double> disparity_offset;
    /// Visual odometry with noise_from_residuals: the factor every frame's covariance was scaled
    /// by (VisualOdometry::noise_scale); 1 otherwise.
    double noise_scale = 1;
};
/// Stereo frames in order: fills `frame` with the next one; false after the last.
using FrameSource = std::function<bool(StereoFrame& frame)>;
/// The frames of a vector, in order (they are referenced, not copied).
FrameSource frames_of(const std::vector<StereoFrame>& frames);

/// run_filter frame by frame: each frame is used as it comes and not kept; its record goes to
/// record.sink. Kept per frame only with record.keep: the poses, covariances, motions and counts
/// (SequenceRun's). The metrics against `truth` are running sums (TrajectoryScore) of the
/// filter's and the odometry alone's poses as frames come (the same bits as score_trajectory on
/// the run's vectors, the SE(2)-aligned APE to relative 1e-9), the counts too (RunTotals), and
/// the 3-D APE against record.truth_3d. The wrong-association check against `truth` is made as
/// frames come, with the world point of each landmark's first observation (under the true pose
/// of its frame) held while the landmark is mapped.
class FilterRun {
public:
    FilterRun(const Pose& start, const AssociationConfig& association, std::vector<Pose> truth, RunRecord record = {});
    /// The tilt and height (spatial_poses) of the frames given from now on; until it is called,
    /// the 6-DoF poses are kitti_pose's (level, height 0).
    void set_spatial(const Mat3& tilt, double height);
    void first_frame(const StereoFrame& frame);
    /// A later frame: the motion from the previous one, its covariance, the frame.
    void next_frame(const Motion& u, const Mat3& Q, const StereoFrame& frame);
    size_t frames() const { return run_.frame_count; }
    /// The run as run_filter returns it. InputError on fewer than 2 frames or a truth longer
    /// than the frames.
    SequenceRun finish();

private:
    void after_frame(const FrameStats& st, const StereoFrame& frame);
    void record_frame(FrameRecord& rec);
    LandmarkSlam slam_;
    std::vector<Pose> truth_;
    RunRecord record_;
    SequenceRun run_;
    Pose dead_reckoning_ = Pose::Zero();
    Mat3 tilt_ = Mat3::Identity();
    bool spatial_ = false;
    double height_ = 0, ape_3d_slam_ss_ = 0, ape_3d_odometry_ss_ = 0;
    size_t scored_3d_ = 0;
    double wrong_gate_;
    std::unordered_map<int, std::pair<Vec2, Mat2>> first_seen_;   // landmark id -> world point, covariance
    Mat3 dead_reckoning_cov_ = Mat3::Zero();   // the odometry alone's covariance, integrated
    TrajectoryScore slam_score_, odometry_score_;
    std::vector<double> slam_nees_, odometry_nees_;   // per frame scored, with record.keep
};

/// The filter over frames with the given motions (motions.size() == frames.size() − 1),
/// started at `start`, then scored against `truth` (used only after the run, for the metrics
/// and the wrong-association counts): one pose per frame, or fewer (the first truth.size()
/// frames are scored), or none (not scored). estimate_3d and dead_reckoning_3d are level at
/// height 0; no truth_3d nor 3-D APE (RunRecord::truth_3d is run_sequence's). Throws InputError
/// on a size mismatch of the motions or a truth longer than the frames.
SequenceRun run_filter(const std::vector<StereoFrame>& frames, const std::vector<Motion>& motions,
                       const std::vector<Mat3>& motion_cov, const Pose& start, const AssociationConfig& association,
                       const std::vector<Pose>& truth);
/// Synthetic odometry on a real trajectory: run_filter over frames[k] seen at ground-truth
/// poses[k] (poses.size() == frames.size() ≥ 2) with noisy_odometry(truth, odometry, seed),
/// started at the first true pose. Throws InputError on a size mismatch or fewer than 2 poses.
SequenceRun run_sequence(const std::vector<Mat34>& poses, const std::vector<StereoFrame>& frames,
                         const SyntheticOdometry& odometry, const AssociationConfig& association, uint64_t seed);
/// The same frame by frame (FilterRun, with `record`; its truth_3d is `poses`): InputError as
/// above, the count of frames checked when the source ends.
SequenceRun run_sequence(const std::vector<Mat34>& poses, const FrameSource& frames, const SyntheticOdometry& odometry,
                         const AssociationConfig& association, uint64_t seed, RunRecord record = {});

/// The rig of the synthetic landmarks: KITTI's rectified cameras 0 and 1 (sequences 00-02):
/// fx = fy = 718.856 px, principal point (607.1928, 185.2157) px for both, the right camera
/// 0.5372 m to the right (tx1 = -fx * 0.5372), images 1241 x 376.
landmarks::RectifiedRig synthetic_rig();
/// Synthetic stereo landmarks along a trajectory: `count` world points scattered on both
/// sides of the path (lateral 4..30 m, height -3..1 m in camera y), each with a random
/// 256-bit descriptor; frame k lists the points in front of camera k (z 2..60 m) that
/// project inside both images of `rig` (landmarks::project), measured with `noise` (drawn on
/// u_l, v_l, u_r, v_r; a point whose noisy disparity is below 1 px is dropped), triangulated
/// (landmarks::triangulate, with their first-order covariance under `noise`), and the descriptor
/// with `flip_bits` random bits flipped; id_hint = the world point's index (to score the
/// association, never used by it). Throws InputError when the rig has no image size.
std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const landmarks::RectifiedRig& rig,
                                                  const landmarks::PixelNoise& noise, int count, int flip_bits,
                                                  uint64_t seed);
/// synthesize_stereo_frames frame by frame (the same frames, drawn as they are asked for):
/// the world is laid out on construction (InputError as above), next() gives frame k of
/// poses[k].
class SyntheticFrames {
public:
    SyntheticFrames(std::vector<Mat34> poses, const landmarks::RectifiedRig& rig, const landmarks::PixelNoise& noise,
                    int count, int flip_bits, uint64_t seed);
    bool next(StereoFrame& frame);

private:
    std::vector<Mat34> poses_;
    landmarks::RectifiedRig rig_;
    landmarks::PixelNoise noise_;
    int flip_bits_;
    std::mt19937_64 rng_;
    std::vector<Eigen::Vector3d> world_;
    std::vector<std::vector<uint8_t>> desc_;
    size_t next_ = 0;
};
/// A triangulated point (landmarks::triangulate) as a filter observation: p_cam and cov (zero
/// when the disparity is not positive); no descriptor, no id hint.
StereoLandmarkObs to_observation(const landmarks::Point3& t);

}  // namespace hc::slam

// filter_run.hpp: runs of the landmark filter (landmark_slam.hpp) over a sequence (slam.hpp):
// each frame's record as it comes, the run's summary and metrics against ground truth
// (trajectory_metrics.hpp), frame sources, and the runs with given or synthetic odometry.
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/slam/landmark_slam.hpp"
#include "mapping/slam/observations.hpp"
#include "mapping/slam/synthetic.hpp"
#include "mapping/slam/trajectory_metrics.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hc::slam {

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
        jcbb_cut = 0, not_corrected = 0;
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

}  // namespace hc::slam

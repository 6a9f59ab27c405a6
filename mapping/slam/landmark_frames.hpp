// landmark_frames.hpp: the landmark pipeline of mapping/landmarks/ (corners, descriptors, the
// thesis's stereo matching, triangulation) as the filter's stereo frames: the one header of
// hc_slam that needs OpenCV (through mapping/landmarks/landmarks.hpp); slam.hpp needs none.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "io/frames/frames.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "mapping/slam/filter_run.hpp"
#include "mapping/slam/landmark_slam.hpp"
#include "mapping/slam/observations.hpp"
#include "mapping/slam/odometry.hpp"
#include "mapping/slam/synthetic.hpp"

namespace hc::slam {

/// One landmark of the pipeline as a filter observation (position, covariance, descriptor
/// bytes; no id hint: the pipeline has no track ids).
StereoLandmarkObs to_observation(const landmarks::Landmark& l);
/// The landmarks of every pair of `ds` (landmarks::acquire_dataset) as stereo frames.
std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o);
/// The same from the corners of every pair already detected (landmarks::detect_dataset's).
std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const std::vector<landmarks::PairKeypoints>& kp,
                                         const landmarks::PipelineOptions& o);

/// The landmark pipeline's stereo frames over `pairs` pairs loaded as they are reached
/// (`pair_at(k)`, in order), pair by pair: corners from the source's stream
/// (landmarks::PairCornerStream, a hardware source's threshold carried from pair to pair),
/// then description, matching and triangulation through `calib`; nothing of a pair is kept
/// once its frame is given out. `rig` set: the pairs are a user's rig's unrectified images and
/// their keypoints are rectified with it (landmarks::Dataset::rig), as landmark_frames does.
FrameSource landmark_stream(int pairs, landmarks::PairCornerStream::PairAt pair_at, const landmarks::RectifiedRig& calib,
                            const landmarks::PipelineOptions& o,
                            std::shared_ptr<const landmarks::Calibration> rig = nullptr);

/// One KITTI odometry sequence through the filter (`harris-cosim slam --sequences`): where the
/// landmarks come from, where the motion comes from, the association. Every default is the
/// owning struct's.
/// The landmark pipeline a KITTI run uses by default: landmarks::PipelineOptions's, with
/// BRIEF (the authors' box smoothing) as the descriptor. Chosen on Middlebury 2006, not on a
/// KITTI sequence (docs/slam.md, "How the defaults were chosen").
landmarks::PipelineOptions kitti_pipeline_defaults();

struct KittiRunOptions {
    /// true: the landmark pipeline on the sequence's stereo pairs (`pipeline`); false:
    /// synthetic landmarks along the ground-truth trajectory (synthesize_stereo_frames)
    bool stereo_landmarks = true;
    landmarks::PipelineOptions pipeline = kitti_pipeline_defaults();   ///< corners, descriptor (binary), grid, formats
    int synthetic_count = 1000;            ///< synthetic landmarks: world points
    int flip_bits = 8;                     ///< synthetic landmarks: bits flipped per observed descriptor
    /// true: stereo visual odometry from the frames (run_visual_sequence, no ground truth);
    /// false: the ground truth's relative poses plus `synthetic` noise (run_sequence)
    bool visual_odometry = true;
    VisualOdometryConfig vo;
    SyntheticOdometry synthetic;
    AssociationConfig association;
    std::uint64_t seed = 1;                ///< synthetic landmarks and synthetic odometry
    /// Ground truth: a KITTI or TUM trajectory file (read_trajectory_file); empty: a KITTI-layout
    /// sequence's poses/NN.txt when present, else none (the run is not scored).
    std::filesystem::path truth;
    /// A ground truth with another number of poses than frames: score the frames both cover
    /// (true), or refuse it (false: InputError naming both counts).
    bool score_overlap = false;
    /// TUM timestamps where the sequence has no times.txt (and on a rig): frame index × this (s).
    double frame_period = 0.1;
    /// A TUM ground truth on a sequence with a times.txt is paired with the stereo pairs by
    /// timestamp (truth_by_timestamp): the nearest pose within this (s; TUM's associate.py's
    /// default difference). A KITTI ground truth, or none of the frames' times: file order.
    double truth_time_tolerance = 0.02;
    /// The stereo pairs run, "a:b" (b excluded; util::parse_range's syntax, an open end runs to
    /// the last pair; empty: all): of the sequence, of a rig's --left/--right, or of the true
    /// poses of synthetic landmarks. The ground truth scored is the poses of these pairs.
    std::string pairs;
    std::function<void(const std::string&)> progress;   ///< one line per step (may be empty)
    /// Each frame's record as it comes, with its TUM timestamp (may be empty), and whether the
    /// run keeps its per-frame vectors (RunRecord; the command keeps none and writes the sink's rows).
    FrameSink sink;
    bool keep_frames = true;
};
struct KittiRun {
    SequenceRun run;
    VisualOdometry vo;   ///< with visual_odometry: the motions and how many estimates failed
};
/// Reads the ground truth (o.truth, else frames::kitti_poses_file when present; read only to
/// score, and for the synthetic odometry and landmarks, which are made from it), and runs the
/// filter frame by frame on the sequence's frames (its stereo pairs, their corners streamed
/// pair by pair by landmarks::PairCornerStream, or synthetic landmarks: one frame per true
/// pose, SyntheticFrames), none held once used (run_visual_stream, FilterRun, with o.sink and
/// o.keep_frames); TUM timestamps from the sequence's times.txt when present (read before the
/// run), else frame index × o.frame_period. A TUM ground truth is paired with the stereo pairs by timestamp when the
/// sequence has a times.txt (truth_by_timestamp, o.truth_time_tolerance: a pair without a pose
/// within it is an InputError unless o.score_overlap), else in file order; the run's
/// truth_pairing says which. InputError (slam's or landmarks') for fewer than 2 pairs, a ground truth
/// with another number of poses than stereo pairs (both counts named) unless o.score_overlap,
/// synthetic landmarks or odometry without a true pose per frame, a times.txt shorter than the
/// frames, a descriptor that is not binary, options out of range, or o.pairs past the pairs there are
/// (frames::pairs_within, naming --pairs and their count).
KittiRun run_kitti_sequence(const std::filesystem::path& kitti, const std::string& sequence, const KittiRunOptions& o);

/// A user's rig (frames::RigSource: --calib with --left and --right, opened by frames::open_rig):
/// unrectified stereo pairs and the calibration `harris-cosim calibrate` wrote (or a KITTI-style
/// calib.txt: pairs already rectified), keypoints rectified as `landmarks --calib` does
/// (landmarks::open_dataset).
/// run_kitti_sequence on a rig's pairs with the landmark pipeline (o.stereo_landmarks must be
/// set), pair by pair as a KITTI layout's (landmark_stream: each pair read when it is reached,
/// landmarks::rig_dataset's checks on it then): ground truth from o.truth only, timestamps frame
/// index × o.frame_period. InputError as run_kitti_sequence's and frames::open_rig's (before the
/// run), and rig_dataset's for a pair's image that is missing, unreadable or of another size
/// than the calibration's (when the pair is reached). o.pairs picks pairs of the lists (and
/// the poses of o.truth) as of a KITTI sequence.
KittiRun run_rig_sequence(const frames::RigSource& rig, const KittiRunOptions& o);

}  // namespace hc::slam

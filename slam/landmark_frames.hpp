// landmark_frames.hpp: the landmark pipeline of slam/landmarks/ (corners, descriptors, the
// thesis's stereo matching, triangulation) as the filter's stereo frames: the one header of
// hc_slam that needs OpenCV (through slam/landmarks/landmarks.hpp); slam.hpp needs none.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "slam/landmarks/landmarks.hpp"
#include "slam/slam.hpp"

namespace hc::slam {

/// One landmark of the pipeline as a filter observation (position, covariance, descriptor
/// bytes; no id hint: the pipeline has no track ids).
StereoLandmarkObs to_observation(const landmarks::Landmark& l);
/// The landmarks of every pair of `ds` (landmarks::acquire_dataset) as stereo frames.
std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o);
/// The same from the corners of every pair already detected (landmarks::detect_dataset's).
std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const std::vector<landmarks::PairKeypoints>& kp,
                                         const landmarks::PipelineOptions& o);

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
    std::function<void(const std::string&)> progress;   ///< one line per step (may be empty)
};
struct KittiRun {
    SequenceRun run;
    VisualOdometry vo;   ///< with visual_odometry: the motions and how many estimates failed
};
/// Reads the sequence's ground-truth poses (frames::kitti_poses_file; read only to score, and
/// for the synthetic odometry and landmarks, which are made from them), makes its frames and
/// runs the filter. A sequence with fewer stereo pairs than poses is cut to its pairs.
/// InputError (slam's or landmarks') for fewer than 2 poses or pairs, a descriptor that is not
/// binary, or options out of range.
KittiRun run_kitti_sequence(const std::filesystem::path& kitti, const std::string& sequence, const KittiRunOptions& o);

}  // namespace hc::slam

// landmark_frames.cpp: landmarks::Landmark -> slam::StereoLandmarkObs, and a KITTI sequence
// through the filter on the pipeline's or synthetic landmarks.
#include "slam/landmark_frames.hpp"

#include <algorithm>

#include "io/frames/frames.hpp"

namespace hc::slam {

landmarks::PipelineOptions kitti_pipeline_defaults() {
    landmarks::PipelineOptions o;
    o.descriptor = landmarks::Descriptor::brief;
    return o;
}

StereoLandmarkObs to_observation(const landmarks::Landmark& l) {
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(l.p_cam[0], l.p_cam[1], l.p_cam[2]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) o.cov(r, c) = l.cov(r, c);
    o.descriptor = l.descriptor;
    return o;
}

namespace {
std::vector<StereoFrame> as_frames(const std::vector<std::vector<landmarks::Landmark>>& landmarks) {
    std::vector<StereoFrame> frames;
    for (const auto& frame : landmarks) {
        StereoFrame f;
        f.reserve(frame.size());
        for (const auto& l : frame) f.push_back(to_observation(l));
        frames.push_back(std::move(f));
    }
    return frames;
}
}  // namespace

std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o) {
    return as_frames(landmarks::acquire_dataset(ds, o));
}

std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const std::vector<landmarks::PairKeypoints>& kp,
                                         const landmarks::PipelineOptions& o) {
    return as_frames(landmarks::acquire_dataset(ds, kp, o));
}

namespace {

/// The landmark pipeline on the sequence's first `poses` stereo pairs (fewer when it has fewer);
/// `rig`, the rig of the first pair.
std::vector<StereoFrame> stereo_frames(const std::filesystem::path& kitti, const std::string& sequence, size_t poses,
                                       const KittiRunOptions& o, stereo::RectifiedRig& rig) {
    const landmarks::PipelineOptions& po = o.pipeline;
    landmarks::validate(po.grid);
    landmarks::check_combination(po.descriptor, po.detector, landmarks::Norm::automatic);
    if (landmarks::make_descriptor(po.descriptor, po.grid)->descriptorType() != CV_8U)
        throw InputError("--descriptor " + landmarks::descriptor_name(po.descriptor) +
                         " is not binary: visual odometry and the association compare Hamming distances");
    const int pairs = std::min(static_cast<int>(poses), frames::open_kitti(kitti, sequence).pairs());
    if (pairs < 2) throw InputError("KITTI sequence " + sequence + " has fewer than 2 stereo pairs");
    if (o.progress)
        o.progress("landmarks of " + std::to_string(pairs) + " stereo pairs of " + sequence + " (" +
                   landmarks::detector_name(po.detector) + " corners, " + landmarks::descriptor_name(po.descriptor) +
                   " descriptor)");
    // The co-processor's sources stream the sequence as one (each frame's threshold comes from
    // the frame before), so they take it whole; the others detect image by image, and take
    // it kPairsAtOnce pairs at a time, so that the images held do not grow with its length.
    constexpr int kPairsAtOnce = 32;
    const int step = landmarks::is_hardware(po.detector) ? pairs : kPairsAtOnce;
    std::vector<StereoFrame> frames;
    frames.reserve(static_cast<size_t>(pairs));
    for (int first = 0; first < pairs; first += step) {
        const auto ds = landmarks::kitti_dataset(kitti, sequence, {first, std::min(first + step, pairs)});
        if (first == 0) rig = ds.calib.front();
        for (auto& f : landmark_frames(ds, po)) frames.push_back(std::move(f));
    }
    return frames;
}

}  // namespace

KittiRun run_kitti_sequence(const std::filesystem::path& kitti, const std::string& sequence, const KittiRunOptions& o) {
    auto poses = read_kitti_poses(frames::kitti_poses_file(kitti, sequence));
    if (poses.size() < 2) throw InputError("sequence " + sequence + " has fewer than 2 poses");
    o.association.validate();
    // the frames' rig, for visual odometry on pixel residuals: synthetic_rig() for synthetic
    // landmarks, the first pair's rig for the pipeline's (set by stereo_frames)
    VisualOdometryConfig vo = o.vo;
    vo.rig = synthetic_rig();
    vo.validate();
    if (!o.visual_odometry) o.synthetic.validate();
    std::vector<StereoFrame> frames;
    if (o.stereo_landmarks) {
        frames = stereo_frames(kitti, sequence, poses.size(), o, *vo.rig);
        poses.resize(frames.size());
    } else {
        if (o.flip_bits < 0) throw InputError("--flip-bits must not be negative");
        frames = synthesize_stereo_frames(poses, *vo.rig, {}, o.synthetic_count, o.flip_bits, o.seed);
    }
    std::vector<Pose> truth;
    for (const auto& T : poses) truth.push_back(planar_pose(T));
    KittiRun r;
    r.run = o.visual_odometry ? run_visual_sequence(frames, truth, vo, o.association, &r.vo)
                              : run_sequence(poses, frames, o.synthetic, o.association, o.seed);
    return r;
}

}  // namespace hc::slam

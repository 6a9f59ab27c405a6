// landmark_frames.cpp: landmarks::Landmark -> slam::StereoLandmarkObs.
#include "slam/landmark_frames.hpp"

namespace hc::slam {

StereoLandmarkObs to_observation(const landmarks::Landmark& l) {
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(l.p_cam[0], l.p_cam[1], l.p_cam[2]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) o.cov(r, c) = l.cov(r, c);
    o.descriptor = l.descriptor;
    return o;
}

std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o) {
    std::vector<StereoFrame> frames;
    for (const auto& frame : landmarks::acquire_dataset(ds, o)) {
        StereoFrame f;
        f.reserve(frame.size());
        for (const auto& l : frame) f.push_back(to_observation(l));
        frames.push_back(std::move(f));
    }
    return frames;
}

}  // namespace hc::slam

// landmark_frames.hpp: the landmark pipeline of slam/landmarks/ (corners, descriptors, the
// thesis's stereo matching, triangulation) as the filter's stereo frames. A separate target
// (hc_slam_landmarks) so that hc_slam itself needs no OpenCV.
#pragma once

#include "slam/landmarks/landmarks.hpp"
#include "slam/slam.hpp"

namespace hc::slam {

/// One landmark of the pipeline as a filter observation (position, covariance, descriptor
/// bytes; no id hint: the pipeline has no track ids).
StereoLandmarkObs to_observation(const landmarks::Landmark& l);
/// The landmarks of every pair of `ds` (landmarks::acquire_dataset) as stereo frames.
std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o);

}  // namespace hc::slam

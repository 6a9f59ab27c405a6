// observations.hpp: the stereo landmarks the filter observes (slam.hpp): 3-D points of a
// stereo pipeline in the left camera's frame with their covariance and descriptor, their
// top-view range-bearing form, the noise of an observation carried to another point, and a
// triangulated point (mapping/landmarks/stereo.hpp) as an observation.
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/landmarks/stereo.hpp"

#include <cstdint>
#include <vector>

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
    /// Set by the visual-odometry run: an inlier of the motion into this observation's frame
    /// (AssociationConfig::correct_with_odometry_inliers).
    bool odometry_inlier = false;
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

/// A triangulated point (landmarks::triangulate) as a filter observation: p_cam and cov (zero
/// when the disparity is not positive); no descriptor, no id hint.
StereoLandmarkObs to_observation(const landmarks::Point3& t);

}  // namespace hc::slam

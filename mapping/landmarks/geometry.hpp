// geometry.hpp: from a stereo match to a landmark (part of mapping/landmarks/landmarks.hpp): the
// Middlebury rig, the pixel-noise model, the landmark and its files, depth errors against ground truth.
#pragma once

#include "mapping/landmarks/matching.hpp"
#include "mapping/landmarks/stereo.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hc::landmarks {

// ---- geometry ---------------------------------------------------------------------------

// The rig of a pair is landmarks::RectifiedRig and its triangulation landmarks::triangulate
// (stereo.hpp): the rig of KITTI's calib.txt is landmarks::read_kitti_calib(file).rectified.

/// The Middlebury 2006 rig at image scale s: focal length 3740 px and baseline 160 mm at full
/// size (the dataset's description), principal point at the image centre, the right
/// camera's cx at cx + dmin * s so that Z = b f s / (x_l - x_r + dmin s). Units: metres.
landmarks::RectifiedRig middlebury_calib(double scale, double dmin_full, cv::Size image);

/// The pixel-noise model (sigma_px on each of x_l, y_l, x_r, y_r): the landmark chain's, shared
/// with the EKF-SLAM side's synthetic measurements.

/// The four image coordinates of a stereo match (left, right) as landmarks::triangulate takes them.
inline landmarks::StereoPixels pixels(cv::Point2f left, cv::Point2f right) { return {left.x, left.y, right.x, right.y}; }

/// A landmark as an EKF-SLAM front end consumes it.
struct Landmark {
    cv::Vec3d p_cam;                      ///< position in the left rectified camera (metres)
    cv::Matx33d cov;                      ///< 3x3 covariance of p_cam (m^2)
    std::vector<std::uint8_t> descriptor; ///< the descriptor's bytes (SIFT: 128 floats, raw bytes)
    cv::Point2f left, right;              ///< image coordinates (pixels)
    float match_distance = 0;             ///< descriptor distance of the stereo match
};

/// Landmark files: CSV (one landmark a line, header names the columns) and ASCII PLY.
std::string landmarks_csv(const std::vector<Landmark>& l);
std::string landmarks_ply(const std::vector<Landmark>& l);

/// Depth error of matches against a ground-truth disparity map: relative |Z - Z_gt| / Z_gt
/// of every correct (thesis) match with a known disparity.
struct DepthError {
    long n = 0;
    double median = 0, mean = 0, p90 = 0;   ///< relative errors
};
DepthError depth_error(const PairResult& r, const cv::Mat& disparity, const landmarks::RectifiedRig& calib);

}  // namespace hc::landmarks

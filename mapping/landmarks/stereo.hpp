// stereo.hpp: the rectified stereo rig, triangulation through it and the pixel-noise model, a
// section of the landmark chain (mapping/landmarks/landmarks.hpp includes it). The project's one
// rig type and one triangulation: the calibration (calib.hpp: calibrated, or read from KITTI's
// calib.txt or OpenCV storage), the landmark pipeline (landmarks.hpp) and the EKF-SLAM front end
// (mapping/slam/slam.hpp) all hold a RectifiedRig and call triangulate(). Plain doubles: no OpenCV or
// Eigen type, so the filter's code needs neither.
//
// Model (thesis 4.3, Eq. 4.6 generalised to two projection matrices): the rectified left and
// right cameras project with
//   P0 = [fx 0 cx0 tx0; 0 fy cy ty; 0 0 1 0],   P1 = [fx 0 cx1 tx1; 0 fy cy ty; 0 0 1 0]
// (KITTI calib.txt P0, P1; OpenCV stereoRectify's P1, P2), so a point (X, Y, Z) of the left
// rectified camera's frame (x right, y down, z forward) is seen at
//   u_l = (fx X + cx0 Z + tx0) / Z,   u_r = (fx X + cx1 Z + tx1) / Z,   v = (fy Y + cy Z + ty) / Z.
// With the effective disparity D = u_l - u_r - (cx0 - cx1) and B = tx0 - tx1 (= fx * baseline):
//   Z = B / D,   X = ((u_l - cx0) Z - tx0) / fx,   Y = ((v - cy) Z - ty) / fy,   v = (v_l + v_r) / 2.
//
// Pixel-noise model (PixelNoise): the one the landmark pipeline and the SLAM side's synthetic
// measurements use for a point's covariance and its noise.
//
// Errors: a rig that is not a rectified pair throws hc::InputError (model/util/errors.hpp) naming why.
#pragma once

#include <random>
#include <string>

namespace hc::landmarks {

/// A rectified stereo rig: the entries of the two rectified projections above, and the
/// images' size.
struct RectifiedRig {
    double fx = 1, fy = 1;     ///< focal lengths (px), shared by both cameras
    double cx0 = 0, cx1 = 0;   ///< principal points' columns, left and right (px)
    double cy = 0;             ///< principal point's row (px), shared
    double tx0 = 0, tx1 = 0;   ///< P0[0][3], P1[0][3]: fx times each camera's x offset
    double ty = 0;             ///< P0[1][3] = P1[1][3]
    int width = 0, height = 0; ///< image size (px); 0 x 0 when unknown (a calib.txt does not say)

    /// The right camera's offset to the right of the left one, (tx0 - tx1) / fx, in the unit of
    /// the calibration (metres for KITTI and Middlebury).
    double baseline() const { return (tx0 - tx1) / fx; }
    /// Throws InputError ("stereo calibration: ...") when a focal length is not positive or the
    /// right camera is not to the right of the left one (tx0 <= tx1).
    void validate() const;
    /// The rectified projections P0 (left) and P1 (right), row-major 3 x 4.
    void projections(double P0[12], double P1[12]) const;
};

/// The rig of two rectified projection matrices (row-major 3 x 4: KITTI calib.txt's P0 and P1,
/// OpenCV stereoRectify's P1 and P2), images of `width` x `height` (0: unknown). Throws
/// InputError ("stereo calibration: ...") when they are not of the form above (skew, a third
/// row other than (0 0 1 0), different fx, fy, cy or ty) or the rig fails validate().
RectifiedRig rig_from_projections(const double P0[12], const double P1[12], int width = 0, int height = 0);

/// The four measured image coordinates of one point: left (u_l, v_l), right (u_r, v_r), pixels.
struct StereoPixels {
    double u_l = 0, v_l = 0, u_r = 0, v_r = 0;
};

/// A triangulated point, its Jacobian with respect to the four measured coordinates and its
/// covariance under a pixel-noise model.
struct Point3 {
    double p[3] = {0, 0, 0};    ///< X, Y, Z in the left rectified camera's frame
    double J[3][4] = {};        ///< d(X, Y, Z) / d(u_l, v_l, u_r, v_r)
    double cov[3][3] = {};      ///< sigma^2 J J^T (PixelNoise::covariance)
    bool valid = false;         ///< D > 0: in front of both cameras (else p, J and cov are zero)
};

/// Pixel-noise model: each measured corner coordinate (u_l, v_l, u_r, v_r) carries
/// independent zero-mean Gaussian noise of standard deviation sigma_px (corner localisation
/// noise). v enters the point through the mean of v_l and v_r, so in (u = u_l, v,
/// d = u_l - u_r) the covariance is sigma^2 [[1, 0, 1], [0, 1/2, 0], [1, 0, 2]]. The point's
/// covariance is first-order propagation, sigma^2 J J^T with J = Point3::J. The default
/// 0.5 px is an assumed value, not a measured one; it is not the rounding of integer corner
/// positions (a uniform error in [-0.5, 0.5) px has sigma 1/sqrt(12) = 0.289 px).
struct PixelNoise {
    double sigma_px = 0.5;
    /// sigma^2 J J^T of a valid point (row-major 3x3, J J^T summed over the four coordinates
    /// in order, then scaled by sigma^2).
    void covariance(const Point3& t, double cov[3][3]) const;
    /// `exact` with this model's noise: one standard normal draw from `rng` per coordinate,
    /// in the order u_l, v_l, u_r, v_r, times sigma_px.
    StereoPixels perturb(const StereoPixels& exact, std::mt19937_64& rng) const;
};

/// The point seen at m (rectified pixels), with its Jacobian and its covariance under `noise`.
/// Invalid when the effective disparity D is not positive (at or beyond infinity).
Point3 triangulate(const RectifiedRig& rig, const StereoPixels& m, const PixelNoise& noise = {});

/// Where the rig sees the point p = (X, Y, Z) of the left rectified camera's frame (Z > 0):
/// the projections above, v_l = v_r = v (triangulate's inverse).
StereoPixels project(const RectifiedRig& rig, const double p[3]);

}  // namespace hc::landmarks

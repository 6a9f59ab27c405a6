// odometry.hpp: stereo visual odometry. The landmarks of two consecutive stereo frames are
// matched by descriptor (mutual nearest neighbours under a Hamming threshold that is a
// fraction of the descriptor's length); RANSAC finds the inliers and weighted Gauss-Newton on
// them gives the motion (dx, dy, dθ) and its covariance (the inverse of the Fisher information
// of the residuals, each weighted by both points' covariances), by one of two residuals:
//  - pixels (OdometryResidual::pixels): 6-DoF. A previous point moved into the current camera
//    and projected through the rig, against where the current frame saw it, (u_l, v, u_r) in
//    pixels; its covariance is both points' covariances carried into those pixels. RANSAC
//    over triples of matches (the closed-form 3-D rigid alignment of the triple, Umeyama);
//    the motion is the top view of the 6-DoF estimate, its covariance carried there.
//  - top view (OdometryResidual::top_view): 3-DoF. The top-view points of the two frames
//    aligned in the plane; RANSAC over pairs of matches (the closed-form 2-D alignment).
// Deterministic: RANSAC draws from a generator of fixed seed.
#pragma once

#include "slam/slam.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace hc::slam {

/// What visual odometry's residuals measure (header comment).
enum class OdometryResidual { pixels, top_view };

struct VisualOdometryConfig {
    OdometryResidual residual = OdometryResidual::pixels;
    /// The rig the frames were triangulated through; required by OdometryResidual::pixels.
    std::optional<stereo::RectifiedRig> rig;
    double max_hamming_fraction = 0.25;   ///< temporal matches: Hamming ≤ this fraction of the bits
    double min_range = 1.0, max_range = 60.0;   ///< m: top-view range of the points used
    int ransac_iterations = 300;
    double inlier_probability = 0.99;     ///< inlier gate: χ² quantile (2 dof top view, 3 pixels) of the Mahalanobis residual
    int min_inliers = 8;                  ///< fewer: the estimate is marked failed
    double max_step = 5.0;                ///< m: hypotheses moving farther in one frame are rejected
    /// The motion used when the estimate fails: the previous motion with this covariance
    /// (diagonal standard deviations dx, dy m and dθ rad).
    double fail_sigma_xy = 1.0, fail_sigma_theta = 0.1;
    void validate() const;   ///< InputError naming the first bad value
};

/// One frame-to-frame motion estimate.
struct MotionEstimate {
    Motion u = Motion::Zero();       ///< pose of the current frame in the previous one
    Mat3 cov = Mat3::Identity();     ///< its covariance
    int candidates = 0;              ///< descriptor matches before RANSAC
    int inliers = 0;
    bool ok = false;                 ///< false: fewer than min_inliers inliers (u, cov undefined)
    std::vector<std::pair<int, int>> matches;   ///< inliers: (index in previous, index in current)
};

/// The top view of a camera-frame point (x = z_cam forward, y = −x_cam left) and its 2×2
/// covariance.
std::pair<Vec2, Mat2> top_view(const StereoLandmarkObs& o);

/// The motion between two stereo frames from their landmarks alone.
MotionEstimate estimate_motion(const StereoFrame& previous, const StereoFrame& current,
                               const VisualOdometryConfig& config = {});

/// Visual odometry over a sequence: one estimate per consecutive pair; a failed one is
/// replaced by the previous motion (zero at the start) with the failure covariance.
struct VisualOdometry {
    std::vector<Motion> motions;
    std::vector<Mat3> covariances;
    std::vector<MotionEstimate> estimates;   ///< as estimated (ok, inliers, candidates)
    int failures = 0;
};
VisualOdometry visual_odometry(const std::vector<StereoFrame>& frames, const VisualOdometryConfig& config = {});

/// Visual odometry and EKF-SLAM on stereo frames alone, started at the origin (KITTI's
/// first pose is the identity); `truth` (one pose per frame) is read after the run only, to
/// score. Throws InputError on fewer than 2 frames or a truth of another length.
SequenceRun run_visual_sequence(const std::vector<StereoFrame>& frames, const std::vector<Pose>& truth,
                                const VisualOdometryConfig& vo, const AssociationConfig& association,
                                VisualOdometry* odometry = nullptr);

}  // namespace hc::slam

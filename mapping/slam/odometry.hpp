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
//    With estimate_disparity_offset, a disparity correction c (px) common to both frames'
//    measurements is estimated with the motion: a rig whose disparities are all off by the
//    same amount (a principal-point or rectification error) scales every motion; c is
//    observable because a point's optical flow gives Z_prev / Z_cur independently of its
//    disparity. c is estimated recursively over the sequence (each step's estimate has the one
//    before as its prior); once it is significant (a 3σ test) the motions are computed, and
//    the filter's frames corrected, at the estimate so far. With offset_uncertainty, each
//    motion's covariance also carries the uncertainty of the correction it was computed at:
//    σ_c² s sᵀ, s the motion's sensitivity to the correction (MotionEstimate::offset_variance).
//  - top view (OdometryResidual::top_view): 3-DoF. The top-view points of the two frames
//    aligned in the plane; RANSAC over pairs of matches (the closed-form 2-D alignment).
// Deterministic: RANSAC draws from a generator of fixed seed.
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/slam/filter_run.hpp"
#include "mapping/slam/landmark_slam.hpp"
#include "mapping/slam/observations.hpp"
#include "mapping/landmarks/stereo.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace hc::slam {

/// What visual odometry's residuals measure (header comment).
enum class OdometryResidual { pixels, top_view };

struct VisualOdometryConfig {
    OdometryResidual residual = OdometryResidual::pixels;
    /// The rig the frames were triangulated through; required by OdometryResidual::pixels.
    std::optional<landmarks::RectifiedRig> rig;
    /// Pixels only: estimate the disparity correction c with each motion (header comment).
    bool estimate_disparity_offset = true;
    /// The correction is applied (to the motions and the filter's frames) once its estimate
    /// differs from 0 by more than this many standard deviations (a 3σ test).
    double disparity_offset_significance = 3.0;
    /// Pixels, with estimate_disparity_offset: each motion's covariance also carries the
    /// uncertainty of the correction it was computed at, σ_c² s sᵀ (s = ∂u/∂c, σ_c² the mean
    /// square of the correction's error; MotionEstimate::offset_variance).
    bool offset_uncertainty = true;
    /// Pixels only: the motions and the filter's frames are taken in the levelled frame of each
    /// camera (VisualOdometry::tilt), so that a camera that pitches and rolls relative to the
    /// first one still moves and sees in one plane; false: in each camera's own frame.
    bool level = true;
    /// Pixels only: the final motion is refined jointly with every inlier's point, estimated
    /// from its pixels in both frames, each frame's pixels under their own covariance (a
    /// two-view bundle adjustment; the points eliminated by their Schur complement); false: the
    /// previous frame's triangulated point is taken as given and its covariance carried into
    /// the current frame's pixels (the residual RANSAC and the inlier gate use).
    bool two_view_points = false;
    /// Every frame's covariance is scaled by the variance factor of the run's own inlier
    /// residuals (residual_variance_factor), re-estimated on the scaled frames until it is within
    /// noise_tolerance of 1 (at most noise_rounds rounds): the pixel noise measured on the run
    /// instead of the one the frames were triangulated with. Both the odometry and the filter
    /// see the scaled frames (run_visual_sequence).
    bool noise_from_residuals = false;
    double noise_tolerance = 0.01;
    int noise_rounds = 10;
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
    /// With estimate_disparity_offset: the disparity correction c (px) estimated with u, and
    /// its standard deviation; 0 and 0 without.
    double disparity_offset = 0, disparity_offset_sigma = 0;
    /// The inliers' squared Mahalanobis residuals at the estimate, summed, under the frames'
    /// own covariances, and their degrees of freedom (residuals minus the motion's parameters:
    /// 3n − 6 on pixels, 2n − 3 on the top view).
    double residual_chi2 = 0;
    int residual_dof = 0;
    /// Pixels, with estimate_disparity_offset: the correction c_used (px) the motion was
    /// computed at (0 until the correction is applied), the motion's sensitivity to it,
    /// ∂(ω, δt)/∂c of the 6-DoF motion and ∂u/∂c of its top view (the final refinement solved
    /// again at c_used ± h), and σ_c², the mean square of c − c_used under what is known of c
    /// when the motion is computed: the estimate of the earlier steps N(m, σ²) (the prior), or
    /// this step's own estimate when there is none: (m − c_used)² + σ². Applied, that is σ²;
    /// not applied yet, the motion errs by s·c, and σ_c² is the mean square of c itself. With
    /// offset_uncertainty, σ_c² s sᵀ is added to cov6 (and so to cov); else all are computed
    /// and nothing is added. 0 without the correction estimated (a rig taken as exact).
    double offset_used = 0, offset_variance = 0;
    Eigen::Matrix<double, 6, 1> offset_sensitivity6 = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Vector3d offset_sensitivity = Eigen::Vector3d::Zero();
    std::vector<std::pair<int, int>> matches;   ///< inliers: (index in previous, index in current)
    /// Pixels: the 6-DoF motion, X_prev = rotation · X_cur + translation, and the covariance of
    /// its perturbation (ω, δt) (rotation · Exp(ω), translation + δt); u is its top view in the
    /// previous camera's frame. Top view: identity, zero, zero.
    Mat3 rotation = Mat3::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, 6, 6> cov6 = Eigen::Matrix<double, 6, 6>::Zero();
};

/// The top view of a camera-frame point (x = z_cam forward, y = −x_cam left) and its 2×2
/// covariance.
std::pair<Vec2, Mat2> top_view(const StereoLandmarkObs& o);

/// What earlier steps know of the disparity correction c: its mean and standard deviation
/// (px); sigma 0: nothing (c is estimated from the step's matches alone).
struct DisparityPrior {
    double mean = 0, sigma = 0;
};

/// The motion between two stereo frames from their landmarks alone; with the disparity
/// correction estimated, `prior` is its estimate so far (hypotheses start from its mean).
MotionEstimate estimate_motion(const StereoFrame& previous, const StereoFrame& current,
                               const VisualOdometryConfig& config = {}, const DisparityPrior& prior = {});

/// The tilt of a camera orientation M (camera axes in the first camera's frame): the rotation
/// A with M = Y(ψ) · A, Y(ψ) the rotation about the first camera's y axis by the heading
/// ψ = atan2(−M(0,2), M(2,2)) (planar_pose's), so that A's optical axis has no x component.
/// A carries camera coordinates into the camera's levelled frame: the frame of heading ψ whose
/// x-z plane is the first camera's, where the 2-D filter's top view belongs.
Mat3 tilt_of(const Mat3& M);
/// The top-view motion of the 6-DoF step (rotation R, translation t: X_prev = R X_cur + t) taken
/// from a camera of tilt A: planar_pose of A · [R | t], the step between the two cameras'
/// levelled frames; with `cov6` (of the perturbation (ω, δt), MotionEstimate::cov6) its covariance
/// into `cov`.
Motion levelled_motion(const Mat3& A, const Mat3& R, const Eigen::Vector3d& t,
                       const Eigen::Matrix<double, 6, 6>& cov6, Mat3* cov = nullptr);
/// `frame` in the levelled frame of a camera of tilt A: every p_cam ← A p_cam, cov ← A cov Aᵀ.
StereoFrame levelled(const StereoFrame& frame, const Mat3& A);

/// Visual odometry over a sequence: one estimate per consecutive pair; a failed one is
/// replaced by the previous motion (zero at the start) with the failure covariance.
/// On pixel residuals, the camera's tilt is tracked through the 6-DoF steps (the first camera
/// level), and each motion is the step between levelled frames (levelled_motion).
struct VisualOdometry {
    std::vector<Motion> motions;
    std::vector<Mat3> covariances;
    std::vector<MotionEstimate> estimates;   ///< as estimated (ok, inliers, candidates)
    int failures = 0;
    /// Per frame, the disparity correction the filter's frame is given: the estimate after the
    /// last step up to max(k, 1) that succeeded, each step's estimate taking the one before as
    /// its prior (a recursive estimate of one constant), when significant; else 0.
    std::vector<double> disparity_offset;
    /// Per frame, the camera's tilt (tilt_of) after the 6-DoF steps so far: identity for frame 0,
    /// on the top view and without levelling; a failed step keeps the tilt before it.
    std::vector<Mat3> tilt;
    /// With noise_from_residuals: the factor every frame's covariance was scaled by (the pixel
    /// noise's variance relative to the frames' own); 1 without.
    double noise_scale = 1;
};
VisualOdometry visual_odometry(const std::vector<StereoFrame>& frames, const VisualOdometryConfig& config = {});

/// visual_odometry step by step: step(previous, current) for each pair of consecutive frames
/// extends odometry() by one motion (and after the first step, frame 0's and frame 1's
/// disparity correction and tilt; after step k, frame k's). With `keep` false, odometry() keeps
/// the failures only (no per-step vectors); the last step is in motion(), covariance() and
/// estimate(), the current frame's correction and tilt in disparity_offset() and tilt().
class VisualOdometryStream {
public:
    explicit VisualOdometryStream(const VisualOdometryConfig& config, bool keep = true);   ///< InputError as validate()
    void step(const StereoFrame& previous, const StereoFrame& current);
    const VisualOdometry& odometry() const { return vo_; }
    VisualOdometry take() { return std::move(vo_); }
    const Motion& motion() const { return last_; }
    const Mat3& covariance() const { return last_cov_; }
    const MotionEstimate& estimate() const { return last_estimate_; }
    double disparity_offset() const { return frame_offset_; }
    const Mat3& tilt() const { return tilt_; }

private:
    VisualOdometryConfig cfg_;
    bool keep_;
    VisualOdometry vo_;
    MotionEstimate last_estimate_;
    Mat3 last_cov_ = Mat3::Zero();
    double frame_offset_ = 0;
    Motion last_ = Motion::Zero();
    Mat3 fail_;
    DisparityPrior offset_;        // the posterior of the last step that estimated c
    bool level_;
    Mat3 tilt_ = Mat3::Identity();   // the tilt of the camera before the step
};

/// The variance factor of the odometry's residuals: the inliers' squared Mahalanobis residuals
/// summed over the steps that succeeded, over their degrees of freedom, divided by what one
/// residual of dimension d (3 on pixels, 2 on the top view) averages per dimension when it is
/// χ²(d) truncated at the inlier gate g: F_{d+2}(g) / F_d(g). 1 when no step succeeded.
double residual_variance_factor(const VisualOdometry& vo, const VisualOdometryConfig& config);
/// `frame` with every point's covariance multiplied by `factor` (> 0).
StereoFrame with_noise_scaled(const StereoFrame& frame, double factor);
/// What visual odometry's 6-DoF steps say of the camera beyond the top view, per frame: its
/// tilt (tilt_of) and height (camera y, m) after the steps so far integrated (pose of frame k =
/// pose of frame k−1 · [rotation | translation] of step k); frame 0 level at height 0. A failed
/// step and a step on the top view move neither.
struct SpatialTrack {
    std::vector<Mat3> tilt;
    std::vector<double> height;
};
SpatialTrack spatial_track(const VisualOdometry& vo);
/// spatial_track step by step (the same bits): frame 0 level at height 0, then one step per
/// estimate.
class SpatialTracker {
public:
    void step(const MotionEstimate& e);
    Mat3 tilt() const;
    double height() const { return p_.y(); }

private:
    Mat3 M_ = Mat3::Identity();   // the camera's orientation and position in the first camera's frame
    Eigen::Vector3d p_ = Eigen::Vector3d::Zero();
    bool stepped_ = false;   // frame 0's tilt is M_ itself (the identity), as spatial_track's
};

/// `frame` with every disparity made `c` px larger: each point re-triangulated through `rig` at
/// (u_l, v, u_r − c), its covariance carried by the Jacobian of that map. Points whose
/// disparity does not stay positive are dropped; descriptors and id hints are kept.
StereoFrame with_disparity_offset(const StereoFrame& frame, const landmarks::RectifiedRig& rig, double c);

/// Visual odometry and EKF-SLAM on stereo frames alone, started at the origin (KITTI's
/// first pose is the identity); `truth` (one pose per frame) is read after the run only, to
/// score (as run_filter's: one per frame, the first frames', or none). With the disparity
/// correction estimated, the filter sees each frame corrected by
/// VisualOdometry::disparity_offset; with levelling, in the camera's levelled frame
/// (VisualOdometry::tilt). On pixel residuals, estimate_3d and dead_reckoning_3d take their
/// height, roll and pitch from spatial_track. Throws InputError on fewer than 2 frames or a
/// truth longer than the frames.
SequenceRun run_visual_sequence(const std::vector<StereoFrame>& frames, const std::vector<Pose>& truth,
                                const VisualOdometryConfig& vo, const AssociationConfig& association,
                                VisualOdometry* odometry = nullptr);
/// The same frame by frame: each frame is read once, its odometry step taken with the frame
/// before it, and given to the filter (FilterRun) with the correction and tilt of that step;
/// frame 0 waits for step 1 (it takes step 1's correction). Held: two frames. With
/// noise_from_residuals the whole sequence is read first and held (the noise is measured on
/// the run's own residuals before the filter starts: run_visual_sequence on it). `record` is
/// the filter's (FilterRun); without record.keep the odometry keeps no per-step vectors either
/// (`odometry` gets its failures only). InputError as run_visual_sequence, the counts checked
/// when the source ends.
SequenceRun run_visual_stream(const FrameSource& frames, const std::vector<Pose>& truth, const VisualOdometryConfig& vo,
                              const AssociationConfig& association, VisualOdometry* odometry = nullptr,
                              RunRecord record = {});

}  // namespace hc::slam

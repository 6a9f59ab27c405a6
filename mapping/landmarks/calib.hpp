// calib.hpp: stereo calibration of a user's own rig from chessboard pairs, the calibration
// files (a KITTI-style calib.txt with the rectified projections, and an OpenCV YAML/JSON with
// the distortion model and Q), and the rectification of keypoint positions.
//
// The camera model is OpenCV's (thesis 4.2: pinhole, radial k1 k2 k3, tangential p1 p2); the
// calibration is Zhang's planar method as OpenCV implements it (thesis 4.3): each camera
// alone (cv::calibrateCamera), then both together (cv::stereoCalibrate), then the rectifying
// rotations and projections (cv::stereoRectify). As in the thesis (5.1.5), images are never
// warped: the pipeline moves only keypoint positions, with cv::undistortPoints and the
// rectifying rotation R1/R2 and projection P1/P2, so that rectified matches share a row and
// x_l - x_r is the disparity.
//
// Conventions (OpenCV's): camera 1 is the left (reference) camera; R, T take a point from the
// left camera's frame to the right camera's (X_r = R X_l + T); P2(0,3) = Tx' f with Tx' the
// rectified right camera's x offset (negative for a right camera on the right), so the
// baseline is -P2(0,3) / P2(0,0); Q maps (x, y, x_l - x_r, 1) to homogeneous 3D.
#pragma once

#include "mapping/landmarks/stereo.hpp"
#include "model/util/errors.hpp"
#include <opencv2/core.hpp>

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hc::landmarks {

/// A chessboard: its inner corners per row and per column, and the side of one square in the
/// unit the translation T and the baseline are wanted in (metres, millimetres, or squares).
struct Board {
    cv::Size inner{9, 6};   ///< inner corners: width = per row, height = per column
    double square = 1.0;    ///< side of a square
};

/// Parses "WxH" (inner corners, each 2..100) with the square side `square` (> 0). Throws
/// InputError naming the specification otherwise.
Board parse_board(const std::string& spec, double square);


/// The board's inner corners in `grey` (8-bit, one channel), row by row, refined to
/// sub-pixel accuracy by cv::cornerSubPix with a (2 subpix_half + 1)^2 window, or empty when
/// the board is not found in full. subpix_half = 0 chooses it per image: a third of the
/// smallest distance between adjacent corners, within [2, 11] px, so that the window stays
/// inside the four squares around a corner (OpenCV's samples use 11 whatever the board's
/// size; docs/calibration.md measures both). The half side used is stored in *used_half
/// when given.
std::vector<cv::Point2f> find_board(const cv::Mat& grey, const Board& board, int subpix_half = 0,
                                    int* used_half = nullptr);

/// One stereo pair in which both images show the whole board.
struct StereoView {
    std::string name;                                ///< "left01.jpg + right01.jpg"
    std::vector<cv::Point2f> left, right;            ///< corners, same order in both
    int window_left = 0, window_right = 0;           ///< sub-pixel half windows used, px
    std::filesystem::path left_file, right_file;     ///< the images
};

/// The boards found over a list of stereo pairs.
struct Detection {
    cv::Size image_size;                   ///< of the images of every used pair (all must agree)
    std::vector<StereoView> views;         ///< pairs with the board in both images
    std::vector<std::string> skipped;      ///< "name: board not found in the right image"
};

/// Called with one line per pair: found, or skipped with a warning.
using Progress = std::function<void(const std::string&)>;

/// Options of the board detection.
struct DetectOptions {
    int min_views = 5;     ///< fewest pairs with the board in both images
    int subpix_half = 0;   ///< find_board's sub-pixel half window, px (0: per image)
};

/// Finds the board in every pair left[i], right[i]. A pair without the whole board in both
/// images is skipped (reported through `progress` as "warning: skipping NAME: ..."). Throws
/// InputError when an option is out of range (min_views < 0, subpix_half outside 0..50), the
/// lists differ in length, an image is missing or unreadable, the two images of a pair differ
/// in size, a used pair's size differs from the first used pair's (a skipped pair sets no
/// size and may be of any size), or fewer than opt.min_views pairs show the board (the
/// message lists the skipped pairs).
Detection detect_boards(const std::vector<std::filesystem::path>& left,
                        const std::vector<std::filesystem::path>& right, const Board& board,
                        const DetectOptions& opt = {}, const Progress& progress = {});

/// A calibrated stereo rig and its rectification. Matrices are CV_64F.
struct Calibration {
    cv::Mat K1, D1, K2, D2;    ///< intrinsics 3x3; distortion 1x5 (k1 k2 p1 p2 k3)
    cv::Mat R, T;              ///< right from left: X_r = R X_l + T (3x3, 3x1)
    cv::Mat R1, R2;            ///< rectifying rotations (3x3)
    /// The rectified pair: stereoRectify's P1 and P2 (calib.txt's P0 and P1) and the images'
    /// size (0x0 when unknown: a KITTI calib.txt does not say).
    landmarks::RectifiedRig rectified;
    cv::Mat Q;                 ///< disparity-to-depth (4x4)
    double rms = 0;            ///< stereo reprojection RMS, px (0 when not calibrated here)
    /// Standard deviations of fx, fy, cx, cy from each camera's own calibration
    /// (cv::calibrateCamera's estimate, px); zero when not calibrated here.
    cv::Vec4d sigma1, sigma2;
    std::vector<cv::Vec2d> per_view_errors;   ///< RMS per view, left and right, px
    std::vector<std::string> view_names;      ///< parallel to per_view_errors
    /// True when the images are already rectified and undistorted (a KITTI calib.txt):
    /// rectify_points returns its input unchanged.
    bool rectified_input = false;
};

/// The images' size of a calibration (0x0 when unknown).
inline cv::Size image_size(const Calibration& c) { return {c.rectified.width, c.rectified.height}; }

/// Options of the calibration.
struct CalibOptions {
    /// stereoRectify's alpha: 0 keeps only valid pixels in the rectified view (as KITTI's
    /// cropped images), 1 keeps every source pixel, -1 OpenCV's default scaling.
    double alpha = 0;
    /// Refine both cameras' intrinsics in the stereo optimisation (after each camera's own
    /// calibration); false keeps each camera's own intrinsics fixed (CALIB_FIX_INTRINSIC).
    bool refine_intrinsics = true;
};

/// Calibrates each camera, then the pair, then rectifies: the RMS is stereoCalibrate's
/// (over both images of every view). Throws InputError when `d` holds fewer than 3 views,
/// when OpenCV's optimisation fails on them, or for a vertical rig.
Calibration calibrate(const Detection& d, const Board& board, const CalibOptions& opt = {});

/// Which camera a point comes from.
enum class Side { left, right };

/// Rectified pixel positions of `pts` seen by the camera `side`: cv::undistortPoints with
/// that camera's K, D, rectifying rotation and rectified projection (iterated to 1e-10 in
/// normalised coordinates, at most 100 steps). Points only, no image is warped. For a rig
/// whose images are already rectified (rectified_input) the points are returned unchanged.
std::vector<cv::Point2f> rectify_points(const Calibration& c, Side side,
                                        const std::vector<cv::Point2f>& pts);

/// Rectified rows of the board corners of every view: mean and largest |y_l - y_r| over all
/// corner pairs after rectify_points.
struct RectificationCheck {
    double mean_abs_dy = 0, max_abs_dy = 0;
    std::size_t corners = 0;
};
RectificationCheck check_rectification(const Calibration& c, const Detection& d);
/// Above this mean |y_l - y_r| (px) a calibration is reported as not usable: the thesis's
/// epipolar test (|dy| < 5 px) would then reject good matches. A good one measures 0.1 px
/// (docs/calibration.md).
inline constexpr double kUsableMeanDy = 1.0;

/// A picture for the eye, not for the pipeline: `left` and `right` (8-bit grey) rectified by
/// warping (cv::initUndistortRectifyMap, cv::remap) side by side, with the board corners of
/// `view` moved by rectify_points drawn on them (green left, red right) and a horizontal
/// line every 20 px: on a good calibration every corner pair sits on one row. BGR, 2W x H.
/// Throws InputError when the images are not of the calibration's size.
cv::Mat rectified_pair_figure(const Calibration& c, const cv::Mat& left, const cv::Mat& right,
                              const StereoView& view);

/// A rectified camera's projection as OpenCV takes it (3x4, CV_64F): the rig's P0 for the
/// left camera, P1 for the right (stereoRectify's P1, P2). The focal length of the pair is
/// rig.fx, its baseline in the board's unit rig.baseline().
cv::Mat projection(const landmarks::RectifiedRig& rig, Side side);

/// The KITTI-style calib.txt: two rows "P0: " and "P1: " of the 12 numbers of the rectified
/// pair's projections, row-major, each in the shortest scientific form that reads back to the same double.
std::string to_kitti_calib(const Calibration& c);
/// Reads a KITTI calib.txt: the rows P0 and P1 (12 numbers each) are required; other rows
/// (P2, P3, Tr, ...) are ignored. The result is a rectified rig: `rectified` from P0 and P1
/// (landmarks::rig_from_projections), K1, K2 the left 3x3 of P0, P1; no distortion; identity
/// rotations; T = (P1[3]/P1[0] - P0[3]/P0[0], 0, 0), which is -baseline for KITTI's P0
/// (P0[3] = 0); Q from the rig; rectified_input = true. Throws InputError naming `name` (and
/// the row) when a row is malformed, P0/P1 is missing, or P0 and P1 are not a rectified pair
/// with the right camera to the right.
Calibration parse_kitti_calib(const std::string& text, const std::string& name);
/// Reads the file `p` with parse_kitti_calib; InputError naming it when it cannot be read.
Calibration read_kitti_calib(const std::filesystem::path& p);

/// The whole calibration as OpenCV FileStorage text: YAML when `json` is false, else JSON.
/// Keys: image_width, image_height, distortion_model, K1, D1, K2, D2, R, T, R1, R2, P1, P2,
/// Q, rms, per_view_errors, view_names, sigma1, sigma2 (1x4: fx fy cx cy), rectified_input.
std::string to_opencv_storage(const Calibration& c, bool json);
/// Reads a file written by to_opencv_storage (.yml, .yaml, .json). Throws InputError naming
/// it when it is missing, unreadable or lacks a key.
Calibration read_opencv_storage(const std::filesystem::path& p);

/// The disparity-to-depth matrix of a rectified rig (stereoRectify's Q with
/// CALIB_ZERO_DISPARITY semantics): (x, y, x_l - x_r, 1) -> (X, Y, Z, W).
cv::Mat disparity_to_depth(const landmarks::RectifiedRig& rig);

/// A Markdown report of a calibration: RMS, per-view errors, intrinsics, distortion,
/// extrinsics, rectified projections, Q, the rectification check and the skipped pairs;
/// with `figure` (a PNG file name beside the report, of rectified_pair_figure for the view
/// named `figure_view`), a link to it.
std::string report_markdown(const Calibration& c, const Detection& d, const Board& board,
                            const RectificationCheck& check, const std::string& figure = {},
                            const std::string& figure_view = {});

}  // namespace hc::landmarks

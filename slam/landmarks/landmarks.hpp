// landmarks.hpp: landmark acquisition downstream of the Harris co-processor (Schulz 2015,
// Figure 1, sections 4.3, 5.1, 6.1, 6.4): corners from any source -> descriptor -> stereo
// correspondence -> 3D landmarks with covariance, and the descriptor comparison of the
// thesis's Tables 6-10 scored, beyond the thesis, against ground-truth disparity.
//
// Purpose: one typed API for the `landmarks` command, the sweep (score a bit-width
// configuration by correct stereo matches) and an EKF-SLAM front end (acquire() per frame).
//
//   corners      detect_pairs(): OpenCV's Harris reference (docs/metrics.md), OpenCV's
//                SIFT (all points, or the 512 strongest), ORB, BRISK, and the co-processor
//                as `spec` (frame model), `cycle` (HarrisTop through the host driver) and
//                `rtl` (the GHDL-synthesised netlist under Verilator) for any Formats.
//   descriptors  make_descriptor(): grid (thesis or corrected), sift, orb, brisk, brief, freak
//                (hc::features for grid, brief, freak; OpenCV for the others).
//   matching     hc::features::match_stereo (cross-check, 2-NN ratio, epipolar |y_r - y_l| < 5).
//   scoring      a match is "correct (thesis)" when it passes all three tests; "correct
//                (ground truth)" when besides |x_l - x_r - d(x_l, y_l)| <= 1 px with d the
//                dataset's disparity at the left keypoint's pixel (0 = unknown: excluded)
//                and |y_r - y_l| <= 1 px (the x-only count is kept beside it).
//   geometry     stereo::triangulate() through the pair's stereo::RectifiedRig (KITTI
//                calib.txt's P0, P1, a calibrated rig's rectified pair, or Middlebury's focal
//                length, baseline and offset), covariance by Jacobian propagation of an
//                isotropic pixel noise.
//
// Errors: bad input (missing files, sizes, impossible combinations, out-of-range parameters)
// throws landmarks::InputError naming the input; the CLI maps it to exit status 2.
#pragma once

#include "io/util/errors.hpp"
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "slam/landmarks/calib.hpp"
#include "slam/landmarks/descriptors.hpp"
#include "model/harris/harris_pkg.hpp"
#include "slam/landmarks/stereo.hpp"

namespace hc::landmarks {

/// Bad user input (files, sizes, parameter ranges, impossible combinations).
struct InputError : hc::InputError {
    using hc::InputError::InputError;
};

// ---- corner sources -------------------------------------------------------------------

enum class Detector {
    opencv,    ///< OpenCV Harris reference: hc::spec::opencv_corners (docs/metrics.md)
    sift,      ///< cv::SIFT detector, all points
    sift512,   ///< cv::SIFT detector, the 512 strongest points by response (thesis 6.4.1)
    orb,       ///< cv::ORB detector (nfeatures = CornerOptions::orb_features)
    brisk,     ///< cv::BRISK detector
    spec,      ///< co-processor, frame-level spec model (hc::spec::SpecModel)
    cycle,     ///< co-processor, cycle model hc::HarrisTop through the host driver
    rtl,       ///< co-processor, Verilator netlist of rtl/ (GHDL synthesis), after its gate
};
Detector parse_detector(const std::string& s);   ///< "opencv", "sift", "sift512", ...; InputError
std::string detector_name(Detector d);
bool is_hardware(Detector d);                    ///< spec, cycle, rtl
std::vector<Detector> all_detectors();

struct CornerOptions {
    Formats formats{};          ///< bit widths of spec/cycle/rtl (thesis defaults)
    float keypoint_size = 7.f;  ///< cv::KeyPoint::size given to Harris and hardware corners
                                ///< (the 7x7 window a co-processor corner is decided on)
    int orb_features = 2000;    ///< cv::ORB nfeatures
    bool progress = false;      ///< progress lines on stderr for cycle/rtl
};

/// The corners of one image, with where they come from. Each point's `pt` is the pixel
/// (x = column, y = row; integer for Harris and hardware sources), `class_id` the frame.
struct FrameKeypoints {
    Detector source = Detector::opencv;
    int frame = 0;                       ///< index of the image in the caller's stream
    std::string name;                    ///< e.g. "Aloe/L" or "01/L000003"
    std::vector<cv::KeyPoint> points;
};

struct StereoImages {
    cv::Mat left, right;   ///< 8-bit grey, same size
    std::string name;
};

struct PairKeypoints {
    FrameKeypoints left, right;
};

/// Corners of each stereo pair. All pairs must have one size for the hardware sources, whose
/// threshold comes from the previous frame's maximum: they stream the first pair once more
/// in front as a seed (not returned), and cycle/rtl append the last pair once more as a
/// flush (its windows come back only while later pixels are written), as docs/metrics.md's
/// protocol does. Frame numbers are 2k (left) and 2k+1 (right) of pair k.
std::vector<PairKeypoints> detect_pairs(Detector d, const std::vector<StereoImages>& pairs,
                                        const CornerOptions& o = {});

// ---- descriptors and matching ----------------------------------------------------------

/// `sift`: SIFT matched at ratio 0.8, Lowe's recommendation (Lowe 2004), which the thesis uses
/// for its SIFT reference (section 6.4.1); `sift_ratio1`: the same descriptor matched at ratio
/// 1, the test the thesis applies to the grid descriptor (6.4.1, appendix F).
/// `brief`: BRIEF with the authors' 9 x 9 box smoothing over an integral image (their code, as
/// OpenCV contrib's); `brief_gaussian`: the paper's 9 x 9 Gaussian (features::BriefSmoothing).
enum class Descriptor { grid, grid_corrected, sift, sift_ratio1, orb, brisk, brief, brief_gaussian, freak };
Descriptor parse_descriptor(const std::string& s);   ///< "grid", "grid-corrected", "sift-ratio1", ...; InputError
std::string descriptor_name(Descriptor d);
/// grid sift sift-ratio1 orb brisk brief brief-gaussian freak
std::vector<Descriptor> comparison_descriptors();
/// The 2-NN ratio a descriptor is matched at when MatchParams::ratio <= 0: 0.8 for `sift` (the
/// thesis's SIFT reference, Lowe's value), 1 for every other (the thesis's test of the grid,
/// which on Hamming distances removes nothing).
double default_ratio(Descriptor d);

struct GridParams {
    int g = 16;   ///< grid side (cells)
    int h = 3;    ///< resolution reduction 2^h
};
/// Throws InputError when g or h is outside hc::features' ranges (features::check_grid_params).
void validate(const GridParams& p);

/// The OpenCV Feature2D that computes `d` (g, h used by grid only).
cv::Ptr<cv::Feature2D> make_descriptor(Descriptor d, const GridParams& p = {});

enum class Norm { automatic, hamming, l2 };
Norm parse_norm(const std::string& s);   ///< "auto", "hamming", "l2"; InputError

/// Throws InputError when the pair cannot work: a float descriptor (SIFT) under a Hamming
/// matcher or a binary descriptor under L2.
void check_combination(Descriptor d, Detector det, Norm n);

struct MatchParams {
    Norm norm = Norm::automatic;
    /// 2-NN ratio for every descriptor; <= 0: by descriptor (default_ratio: 1, a printed test
    /// that drops ratio > 1, never on Hamming, see docs/landmarks.md; 0.8 for `sift`).
    double ratio = 0;
    bool drop_ties = false;    ///< the evidently intended ratio test: also drop d0 == d1
    double epipolar_px = 5;    ///< |y_r - y_l| < epipolar_px
};

/// One match of a stereo pair with everything the scoring and the landmark need.
struct StereoMatch {
    cv::Point2f left, right;
    float distance = 0;
    int left_index = 0, right_index = 0;   ///< into the described keypoints
    bool epipolar = false;                 ///< passes |y_r - y_l| < epipolar_px
    int truth = -1;                        ///< truth_unknown, truth_wrong, truth_right or truth_x_only
};
/// StereoMatch::truth against a ground-truth disparity d at the left keypoint's pixel.
inline constexpr int truth_unknown = -1;   ///< d unknown (0 in disp1.png) or no ground truth
inline constexpr int truth_wrong = 0;      ///< |x_l - x_r - d| > 1 px
inline constexpr int truth_right = 1;      ///< |x_l - x_r - d| <= 1 px and |y_r - y_l| <= 1 px
inline constexpr int truth_x_only = 2;     ///< |x_l - x_r - d| <= 1 px but |y_r - y_l| > 1 px

struct PairResult {
    std::string name;
    int keypoints_left = 0, keypoints_right = 0;     ///< described (after the descriptor's border)
    std::vector<StereoMatch> matches;                ///< pass cross-check and ratio
    long all() const { return static_cast<long>(matches.size()); }
    long correct() const;          ///< thesis: all tests incl. epipolar
    long truth_known() const;      ///< correct, with a known ground-truth disparity
    long truth_correct() const;    ///< correct, within 1 px of the ground truth in x and |y_r - y_l| <= 1
    long truth_correct_x() const;  ///< correct, within 1 px of the ground truth in x (y not checked)
    bool has_truth = false;        ///< scored against a ground-truth disparity map
    int descriptor_bytes = 0;
    double seconds = 0;            ///< extraction (both images) + matching, this thread
    cv::Mat desc_left;             ///< descriptors of the described keypoints (rows)
    std::vector<cv::KeyPoint> kp_left, kp_right;
};

/// Describes and matches one pair on given keypoints, timed on the calling thread (set
/// cv::setNumThreads(1) for one-thread figures). `disparity` (CV_32F, left image's size,
/// <= 0 unknown) scores the ground truth when non-empty.
/// `rig`, when given, is the calibration of an unrectified pair (a user's own rig): each
/// keypoint is moved to its undistorted, rectified position by calib::rectify_points (no
/// image is warped). Descriptors that read the image are computed at the raw positions on the
/// raw images; the grid, which reads only positions, on the rectified ones. The epipolar test,
/// the matches' coordinates (and so triangulation and overlays) use the rectified positions.
PairResult match_pair(const StereoImages& img, const PairKeypoints& kp, Descriptor d, const GridParams& gp,
                      const MatchParams& mp, const cv::Mat& disparity = {}, const calib::Calibration* rig = nullptr);

// ---- datasets -------------------------------------------------------------------------

/// A Middlebury 2006 scene folder: view1.png (left), view5.png (right), disp1.png (ground
/// truth of the left view), dmin.txt (full-size disparity offset).
struct MiddleburyScene {
    std::string name;
    StereoImages images;        ///< grey
    cv::Mat disparity;          ///< CV_32F disparity in this image's pixels, 0 = unknown
    double scale = 0.5;         ///< image size / full size
    double dmin_full = 0;       ///< dmin.txt
};
/// How disp1.png encodes disparity: the 2006 set stores the disparity of the image's own
/// size times the reduction factor (full 1, half 2, third 3), so d = value * scale; 0 unknown.
float middlebury_disparity(std::uint8_t value, double scale);
/// The scale of a Middlebury 2006 folder from its height (1110 full, 555 half, 370 third).
double middlebury_scale(int height);
/// Loads a scene; throws InputError naming the missing file (e.g. disp1.png) or the size
/// mismatch. `need_truth` false reads no disp1.png (disparity left empty).
MiddleburyScene load_middlebury(const std::filesystem::path& dir, bool need_truth = true);
/// The scene folders under `root` (sorted; those holding view1.png).
std::vector<std::filesystem::path> middlebury_scenes(const std::filesystem::path& root);

// ---- geometry ---------------------------------------------------------------------------

// The rig of a pair is stereo::RectifiedRig and its triangulation stereo::triangulate
// (stereo.hpp): the rig of KITTI's calib.txt is calib::read_kitti_calib(file).rectified.

/// The Middlebury 2006 rig at image scale s: focal length 3740 px and baseline 160 mm at full
/// size (the dataset's description), principal point at the image centre, the right
/// camera's cx at cx + dmin * s so that Z = b f s / (x_l - x_r + dmin s). Units: metres.
stereo::RectifiedRig middlebury_calib(double scale, double dmin_full, cv::Size image);

/// The pixel-noise model (sigma_px on each of x_l, y_l, x_r, y_r): hc::stereo's, shared
/// with the EKF-SLAM side's synthetic measurements.
using PixelNoise = stereo::PixelNoise;

/// The four image coordinates of a stereo match (left, right) as stereo::triangulate takes them.
inline stereo::StereoPixels pixels(cv::Point2f left, cv::Point2f right) { return {left.x, left.y, right.x, right.y}; }

/// A landmark as an EKF-SLAM front end consumes it.
struct Landmark {
    cv::Vec3d p_cam;                      ///< position in the left rectified camera (metres)
    cv::Matx33d cov;                      ///< 3x3 covariance of p_cam (m^2)
    std::vector<std::uint8_t> descriptor; ///< the descriptor's bytes (SIFT: 128 floats, raw bytes)
    cv::Point2f left, right;              ///< image coordinates (pixels)
    float match_distance = 0;             ///< descriptor distance of the stereo match
};

struct PipelineOptions {
    Detector detector = Detector::opencv;
    Descriptor descriptor = Descriptor::grid;
    GridParams grid{};
    MatchParams match{};
    CornerOptions corners{};
    PixelNoise noise{};
    double min_disparity = 0.5;   ///< px; closer to 0 the point is dropped (depth unbounded)
};

/// One stereo frame to landmarks: corners, description, matching (all three tests), and
/// triangulation of each correct match. Throws InputError for images of different sizes or
/// not 8-bit. (Hardware sources stream the pair with a seed and a flush, see detect_pairs.)
std::vector<Landmark> acquire(const cv::Mat& left, const cv::Mat& right, const stereo::RectifiedRig& calib,
                              const PipelineOptions& o);
/// The same from matches already computed (the command's path, which also scores them).
std::vector<Landmark> landmarks_from(const PairResult& r, const stereo::RectifiedRig& calib, const PipelineOptions& o);

/// Landmark files: CSV (one landmark a line, header names the columns) and ASCII PLY.
std::string landmarks_csv(const std::vector<Landmark>& l);
std::string landmarks_ply(const std::vector<Landmark>& l);

/// Depth error of matches against a ground-truth disparity map: relative |Z - Z_gt| / Z_gt
/// of every correct (thesis) match with a known disparity.
struct DepthError {
    long n = 0;
    double median = 0, mean = 0, p90 = 0;   ///< relative errors
};
DepthError depth_error(const PairResult& r, const cv::Mat& disparity, const stereo::RectifiedRig& calib);
struct Dataset;
struct ComparisonRow;
/// The same over all pairs of a comparison row (pairs without ground truth skipped).
DepthError depth_error(const ComparisonRow& row, const Dataset& ds);

// ---- evaluation: comparison and the g x h study ------------------------------------------

struct Totals {
    long all = 0, correct = 0, truth_known = 0, truth_correct = 0;
    long truth_correct_x = 0;   ///< x within 1 px, y not checked (PairResult::truth_correct_x)
    long keypoints = 0;
    double seconds = 0;
    int pairs = 0;
    void add(const PairResult& r);
};

/// Summed counts of one descriptor on one detector's corners over a set of pairs.
struct ComparisonRow {
    Descriptor descriptor = Descriptor::grid;
    Detector detector = Detector::opencv;
    GridParams grid{};
    int descriptor_bytes = 0;
    Totals totals;
    std::vector<PairResult> pairs;   ///< per pair (matches kept for overlays and landmarks)
};

/// A dataset: stereo pairs with optional ground truth and a calibration per pair.
struct Dataset {
    std::string name;                    ///< "middlebury-half", "kitti-01", "rig"
    std::vector<StereoImages> pairs;
    std::vector<cv::Mat> disparity;      ///< per pair, empty if unknown
    std::vector<stereo::RectifiedRig> calib;   ///< per pair: the rectified rig
    /// Set when the pairs are a user's rig's unrectified images: every step that matches them
    /// (compare, study, acquire_dataset, score_formats) rectifies keypoints with it (match_pair).
    std::shared_ptr<const calib::Calibration> rig;
};
/// All scenes under `root`; InputError for a scene without disp1.png unless `need_truth` is
/// false (then its ground-truth columns stay empty).
Dataset middlebury_dataset(const std::filesystem::path& root, bool need_truth = true);
/// KITTI odometry pairs [first, last) of a sequence (calib.txt of the sequence).
Dataset kitti_dataset(const std::filesystem::path& kitti_root, const std::string& sequence, int first, int last);
/// A calibration file of a user's rig: `harris-cosim calibrate`'s OpenCV storage (.yml, .yaml,
/// .json: intrinsics, distortion, rectifying rotations and projections) or a KITTI-style
/// calib.txt (any other name: images already rectified). Throws calib::InputError naming it.
calib::Calibration read_rig_calibration(const std::filesystem::path& file);
/// Stereo pairs left[i], right[i] of a user's rig (unrectified images, read as grey), with
/// `rig` to rectify their keypoints. InputError naming an image that is missing, unreadable or
/// of another size than the calibration's, or when the lists differ in length or are empty.
Dataset rig_dataset(const std::vector<std::filesystem::path>& left, const std::vector<std::filesystem::path>& right,
                    const calib::Calibration& rig);

/// Landmarks of every pair of a dataset, pair by pair: the corners of all pairs first (a
/// hardware source streams them once, carrying its state from frame to frame as the
/// co-processor does, see detect_dataset), then description, matching and triangulation of
/// each pair with its own calibration.
std::vector<std::vector<Landmark>> acquire_dataset(const Dataset& ds, const PipelineOptions& o);

struct ComparisonOptions {
    std::vector<Detector> detectors{Detector::sift512, Detector::sift, Detector::opencv};
    std::vector<Descriptor> descriptors = comparison_descriptors();
    GridParams grid{16, 3};
    MatchParams match{};
    CornerOptions corners{};
    std::function<void(const std::string&)> progress;   ///< one line per finished row
    int threads = 0;   ///< workers over (descriptor, pair) tasks, each on one thread (0: all cores)
};
/// Corners of every pair of a dataset. Hardware sources stream the pairs of one size together
/// (seed and flush as detect_pairs), and a dataset of several sizes scene by scene.
std::vector<PairKeypoints> detect_dataset(const Dataset& ds, Detector d, const CornerOptions& o = {});

/// Corners once per detector, then every descriptor on them; each pair's extraction and
/// matching on one thread (cv::setNumThreads(1)), `threads` pairs at once. `keypoints`, when given, receives the corners
/// of each detector (o.detectors order) for reuse, e.g. by study().
std::vector<ComparisonRow> compare(const Dataset& ds, const ComparisonOptions& o,
                                   std::vector<std::vector<PairKeypoints>>* keypoints = nullptr);

/// Correct matches (thesis and ground truth) of the grid descriptor over g x h.
struct StudyCell {
    int g = 0, h = 0;
    long all = 0, correct = 0, truth_correct = 0;
    long truth_correct_x = 0;                 ///< x within 1 px, y not checked
    std::vector<long> pair_correct, pair_truth_correct;   ///< per pair of the dataset
};
struct StudyResult {
    Detector detector = Detector::opencv;
    std::vector<StudyCell> cells;   ///< g-major
    StudyCell best_correct() const;         ///< most thesis-correct matches (ties: smaller g, h)
    StudyCell best_truth() const;           ///< most ground-truth-correct matches
    /// The same study restricted to the pairs `pairs` (indices into the dataset): every cell's
    /// correct and truth_correct summed over those pairs only (all, truth_correct_x: 0).
    StudyResult on_pairs(const std::vector<size_t>& pairs) const;
};

/// (g, h) chosen on some pairs and scored on others: the cell with the most ground-truth-correct
/// matches over `choose` (`by_truth`; else thesis-correct), its counts over `report`, and for
/// comparison the best cell of `report` itself (what choosing on the scored pairs would claim).
struct HeldOutChoice {
    StudyCell chosen;        ///< counts over `choose`
    StudyCell on_report;     ///< the chosen (g, h), counts over `report`
    StudyCell report_best;   ///< the best cell of `report` by the same criterion
};
HeldOutChoice held_out_choice(const StudyResult& s, const std::vector<size_t>& choose,
                              const std::vector<size_t>& report, bool by_truth);
struct StudyOptions {
    int g_min = 4, g_max = 32, h_min = 0, h_max = 5;
    bool corrected = false;                 ///< the corrected g x g grid instead of the thesis's
    MatchParams match{};
    CornerOptions corners{};
    int threads = 0;                        ///< 0: all cores (cells in parallel)
};
StudyResult study(const Dataset& ds, Detector d, const StudyOptions& o);
/// The same on keypoints already detected (one entry per pair of ds).
StudyResult study(const Dataset& ds, Detector d, const std::vector<PairKeypoints>& kp, const StudyOptions& o);

/// Scoring a bit-width configuration downstream (for the sweep): the co-processor's corners
/// (spec model, or cycle) with `formats` on a dataset, grid descriptor (g, h), matched with the
/// thesis's tests. Returns the summed totals (correct = thesis, truth_correct = ground truth).
Totals score_formats(const Dataset& ds, const Formats& formats, Detector source = Detector::spec,
                     const GridParams& gp = {16, 3}, const MatchParams& mp = {});

// ---- re-observations between consecutive frames --------------------------------------------

/// How much a descriptor changes between consecutive frames of one camera (the left images of
/// a dataset's pairs, e.g. a KITTI sequence driving forward), measured without descriptors:
/// corners of frame k tracked into frame k+1 by pyramidal Lucas-Kanade optical flow (21 x 21
/// window, 3 levels), kept when the backward track comes back within `max_fb_px` and a corner
/// of frame k+1 lies within `max_corner_px` of the tracked point (a corner claimed by two
/// tracks is dropped). No ground truth is used.
struct ReobservationOptions {
    Detector detector = Detector::opencv;
    std::vector<Descriptor> descriptors{Descriptor::grid, Descriptor::grid_corrected, Descriptor::orb,
                                        Descriptor::brisk, Descriptor::brief, Descriptor::freak};
    GridParams grid{16, 3};
    double max_fb_px = 0.5;
    double max_corner_px = 1.0;
    std::uint64_t seed = 1;   ///< random pairs
    CornerOptions corners{};
};
/// Per descriptor: Hamming distances (as a fraction of the descriptor's bits) between the two
/// descriptors of each re-observed corner, against a random pair per re-observation (the same
/// corner of frame k and a random other corner of frame k+1).
struct ReobservationRow {
    Descriptor descriptor = Descriptor::grid;
    int bits = 0;
    long frames = 0;               ///< consecutive frame pairs with re-observations
    long reobservations = 0;       ///< re-observed corners described in both frames
    double same_median = 0, same_mean = 0;       ///< re-observations
    double random_median = 0, random_mean = 0;   ///< random pairs
    long below_random_median = 0;  ///< re-observations closer than the random pairs' median
    long nearest = 0;              ///< re-observations whose nearest frame-(k+1) descriptor is their own
};
/// Indices (i into ka, j into kb) of the corners of image a re-observed in image b.
std::vector<std::pair<int, int>> track_corners(const cv::Mat& a, const cv::Mat& b, const std::vector<cv::KeyPoint>& ka,
                                               const std::vector<cv::KeyPoint>& kb, const ReobservationOptions& o);
/// The rows above over the consecutive left images of `ds`; InputError for fewer than two
/// frames or a float descriptor (SIFT).
std::vector<ReobservationRow> reobservation_study(const Dataset& ds, const ReobservationOptions& o);

// ---- reports -----------------------------------------------------------------------------

/// Writes `bytes` to `target` through a temporary beside it and a rename (never half a file).
void write_atomic(const std::filesystem::path& target, const std::string& bytes);
/// Left and right images side by side, each match a line: green when correct (within 1 px of
/// the ground truth, or without ground truth passing the epipolar test), red when wrong,
/// yellow when the ground truth is unknown at the left pixel. Unmatched keypoints grey.
cv::Mat match_overlay(const StereoImages& img, const PairResult& r);
void write_png(const std::filesystem::path& target, const cv::Mat& img);   ///< atomic

/// The comparison as CSV (one row per detector x descriptor, summed over pairs; plus the
/// SURF row marked unavailable), Markdown and JSON (per pair as well).
std::string comparison_csv(const std::string& dataset, const std::vector<ComparisonRow>& rows);
std::string comparison_markdown(const std::vector<ComparisonRow>& rows);
std::string comparison_json(const std::string& dataset, const std::vector<ComparisonRow>& rows);

std::string study_csv(const std::string& dataset, const StudyResult& s);
/// Correct matches over g, one curve per h (as the thesis's Figures 29-34), `reference` a
/// dashed line (e.g. the SIFT descriptor's count on the same corners; < 0: none), through
/// gnuplot (false when gnuplot is not installed). `truth` plots ground-truth-correct counts.
bool plot_study(const StudyResult& s, bool truth, double reference, const std::string& title,
                const std::filesystem::path& png);

}  // namespace hc::landmarks

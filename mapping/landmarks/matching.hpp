// matching.hpp: descriptors and stereo matching of one pair (part of mapping/landmarks/landmarks.hpp):
// the descriptor names, the OpenCV Feature2D of each, the matcher's parameters and one pair's
// matches with their scoring against ground truth.
#pragma once

#include "mapping/landmarks/calib.hpp"
#include "mapping/landmarks/corners.hpp"
#include "mapping/landmarks/descriptors.hpp"

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

namespace hc::landmarks {

// ---- descriptors and matching ----------------------------------------------------------

/// The descriptors. Each has one row in the descriptor table (descriptor_table.cpp), which is
/// the one list of them: names, the factories, the properties the pipelines ask, the help
/// texts and the docs' list are made from it (docs/architecture.md, "Adding a descriptor").
/// `sift`: SIFT matched at ratio 0.8, Lowe's recommendation (Lowe 2004), which the thesis uses
/// for its SIFT reference (section 6.4.1); `sift_ratio1`: the same descriptor matched at ratio
/// 1, the test the thesis applies to the grid descriptor (6.4.1, appendix F).
/// `brief`: BRIEF with the authors' 9 x 9 box smoothing over an integral image (their code, as
/// OpenCV contrib's); `brief_gaussian`: the paper's 9 x 9 Gaussian (landmarks::BriefSmoothing).
enum class Descriptor { grid, grid_corrected, sift, sift_ratio1, orb, brisk, brief, brief_gaussian, freak };

struct GridParams {
    int g = 16;   ///< grid side (cells)
    int h = 3;    ///< resolution reduction 2^h
};
/// Throws InputError when g or h is outside the grid's ranges (landmarks::check_grid_params).
void validate(const GridParams& p);

/// One row of the descriptor table.
struct DescriptorInfo {
    Descriptor id;
    const char* name;        ///< the flag value and the reports' name
    const char* help;        ///< what the help text says of it after its name ("": nothing)
    bool compared;           ///< in the thesis's comparison (comparison_descriptors, `landmarks --compare`)
    bool reobserved;         ///< in the re-observation study's default list (binary ones only)
    double ratio;            ///< the 2-NN ratio it is matched at when MatchParams::ratio <= 0
    /// reads keypoint positions only, with GridParams g and h (the grid descriptor): described at
    /// the rectified positions of a calibrated rig's keypoints; the others read the raw image
    bool grid;
    /// it reads cv::KeyPoint::octave in its own encoding (OpenCV's SIFT and ORB): keypoints of a
    /// detector not in `own_keypoints` enter at octave 0 (keypoints_for)
    bool reads_octave;
    std::vector<Detector> own_keypoints;
    /// the OpenCV Feature2D that computes it (`p` read by the grid only); its defaultNorm()
    /// says how it is matched (descriptor_norm)
    cv::Ptr<cv::Feature2D> (*make)(const GridParams& p);
};
/// Every descriptor, in the order of the enum.
const std::vector<DescriptorInfo>& descriptor_table();
const DescriptorInfo& descriptor_info(Descriptor d);
Descriptor parse_descriptor(const std::string& s);   ///< a table name; InputError naming the known ones
std::string descriptor_name(Descriptor d);
/// The names joined by ", " (with_help: each followed by its help in parentheses, where it has
/// one), of every descriptor or of those `keep` accepts: for help texts and messages.
std::string descriptor_list(bool with_help = false, bool (*keep)(const DescriptorInfo&) = nullptr);
/// The rows with `compared` (the thesis's comparison), in table order.
std::vector<Descriptor> comparison_descriptors();
/// The rows with `reobserved`, in table order.
std::vector<Descriptor> reobservation_descriptors();
/// The table's `ratio`.
double default_ratio(Descriptor d);
/// The OpenCV Feature2D that computes `d` (g, h used by grid only; InputError when out of range).
cv::Ptr<cv::Feature2D> make_descriptor(Descriptor d, const GridParams& p = {});
/// The norm `d` is matched by: its Feature2D's defaultNorm() (cv::NORM_HAMMING for the binary
/// descriptors, cv::NORM_L2 for SIFT).
int descriptor_norm(Descriptor d);
/// descriptor_norm is a Hamming norm (NORM_HAMMING or NORM_HAMMING2): compared bit by bit.
bool is_binary(Descriptor d);
/// `kp` of detector `det` as descriptor `d` reads them (DescriptorInfo::reads_octave).
std::vector<cv::KeyPoint> keypoints_for(Descriptor d, Detector det, const std::vector<cv::KeyPoint>& kp);

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
/// A pair's result as JSON, everything it holds (a match and a keypoint as an array of its
/// fields, the descriptor matrix as hex) and back; InputError for a matrix whose hex does not
/// fit its size (results_json.cpp).
void to_json(nlohmann::json& j, const PairResult& r);
void from_json(const nlohmann::json& j, PairResult& r);

/// Describes and matches one pair on given keypoints, timed on the calling thread (set
/// cv::setNumThreads(1) for one-thread figures). `disparity` (CV_32F, left image's size,
/// <= 0 unknown) scores the ground truth when non-empty.
/// `rig`, when given, is the calibration of an unrectified pair (a user's own rig): each
/// keypoint is moved to its undistorted, rectified position by landmarks::rectify_points (no
/// image is warped). Descriptors that read the image are computed at the raw positions on the
/// raw images; the grid, which reads only positions, on the rectified ones. The epipolar test,
/// the matches' coordinates (and so triangulation and overlays) use the rectified positions.
PairResult match_pair(const StereoImages& img, const PairKeypoints& kp, Descriptor d, const GridParams& gp,
                      const MatchParams& mp, const cv::Mat& disparity = {}, const landmarks::Calibration* rig = nullptr);

}  // namespace hc::landmarks

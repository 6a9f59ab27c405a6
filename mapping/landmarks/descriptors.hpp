// descriptors.hpp: the star-ID grid, BRIEF and FREAK descriptors and the stereo matcher of
// the landmark chain (namespace hc::landmarks; included by mapping/landmarks/landmarks.hpp).
//
// Purpose: binary descriptors for stereo landmark acquisition and the stereo matcher that
// pairs them (thesis sections 5.3.2, 6.1, 6.4; appendices E and F).
//
//  - GridDescriptor: the thesis's simplified star-ID grid descriptor (appendix E), in the
//    `thesis` variant (bit-exact with the printed listing, quirks included) and a
//    `corrected` variant (a true g x g grid). docs/landmarks.md, "Grid descriptor quirks".
//  - BriefDescriptor: BRIEF (Calonder et al. 2010), 256 intensity tests on a smoothed
//    48 x 48 patch, 32 bytes.
//  - FreakDescriptor: FREAK (Alahi et al. 2012), 43 receptive fields, 512 pairs, 64 bytes.
//  - match_stereo: appendix F's brute-force 2-NN matching both ways, ratio, symmetry and
//    epipolar tests, each test's removals counted.
//
// All three descriptors are cv::Feature2D, so cv::BFMatcher and any OpenCV code take them.
// Bad input (out-of-range parameters, a descriptor type that cannot go with a norm, keypoint
// and descriptor counts that disagree) throws hc::InputError.
#pragma once

#include "model/util/errors.hpp"
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace hc::landmarks {

// ---- Grid descriptor (thesis 5.3.2, appendix E) -----------------------------------------

/// `thesis`: appendix E as printed. Cells X, Y in [0, g] (g + 1 per axis) with bit g*Y + X,
///   so cell (g, Y) and cell (0, Y + 1) share a bit; (g(g+1) >> 3) + 1 bytes (35 at g = 16);
///   the keypoint sits in cell centre = g/2 + 1 (integer division); a neighbour's cell is the
///   int conversion (truncation toward zero) of the single-precision sum
///   p_j / 2^h + (centre - p_i / 2^h), so sums in (-1, 0) land in cell 0 with those in
///   [0, 1): cell 0 is two cells wide and the reach is (-g/2 - 2, g - g/2) cells. For
///   coordinates >= 0 the keypoint's own sum is exactly centre; a negative sub-pixel one can
///   round one cell low.
/// `corrected`: a true g x g grid: X = floor((x_j - x_i) / 2^h) + g/2 in [0, g), bit g*Y + X,
///   ceil(g^2 / 8) bytes (32 at g = 16); every cell is 2^h pixels wide; no shared bits.
/// Both set the keypoint's own (centre) bit and use every keypoint of the set as neighbour.
enum class GridVariant { thesis, corrected };

/// Valid parameter ranges (inclusive). g in [grid_g_min, grid_g_max], h in [0, grid_h_max].
inline constexpr int grid_g_min = 2;
inline constexpr int grid_g_max = 256;
inline constexpr int grid_h_max = 16;

/// Throws InputError naming g or h when out of range.
void check_grid_params(int g, int h);

/// Descriptor length in bytes: (g(g+1) >> 3) + 1 for `thesis`, ceil(g^2 / 8) for `corrected`.
int grid_descriptor_bytes(int g, GridVariant v);

/// The descriptors of every keypoint of `keypoints`, each against all keypoints of the set
/// (its neighbours are the keypoints within the grid's reach). One CV_8U row per keypoint,
/// in input order; bit b of a row is byte b >> 3, bit b & 7 (LSB first), as appendix E.
/// Cost O(n (g + k)) with k neighbours per keypoint: keypoints are bucketed by scaled pixel
/// (p / 2^h), so each descriptor reads only the bucket rows within its grid's reach.
/// Throws InputError for out-of-range g/h or non-finite / huge (|p| >= 2^24) coordinates.
cv::Mat grid_describe(const std::vector<cv::KeyPoint>& keypoints, int g, int h, GridVariant v);

/// The cell (X, Y) keypoint `p` falls in on the grid of keypoint `ref` (either variant), or
/// nothing when outside (`inside` false; corrected x/y then clamped to [-1, g]); and the bit
/// that cell sets. Exposes the per-pair rule for tests and the quirk measurements.
struct GridCell {
    bool inside = false;
    int x = 0;
    int y = 0;
    int bit = 0;
};
GridCell grid_cell(cv::Point2f ref, cv::Point2f p, int g, int h, GridVariant v);

/// Measured consequences of appendix E's quirks on one keypoint set (docs/landmarks.md).
struct GridQuirkStats {
    long long keypoints = 0;
    long long neighbour_hits = 0;        ///< (i, j != i) pairs that set a bit (thesis variant)
    long long shared_bit_hits = 0;       ///< of those, hits in a shared cell (X == g, or X == 0 with Y >= 1)
    long long shared_bit_collisions = 0; ///< (descriptor, shared bit) with both of its cells occupied
    long long descriptors_with_collision = 0; ///< descriptors with at least one such collision
    long long truncation_hits = 0;       ///< hits whose cell coordinate sum lies in (-1, 0), cell 0 by truncation
    long long self_bit_off_centre = 0;   ///< keypoints whose own bit is not at (centre, centre)
    long long neighbours_thesis_only = 0;    ///< (i, j) pairs in the thesis grid's reach only
    long long neighbours_corrected_only = 0; ///< (i, j) pairs in the corrected grid's reach only
    long long relative_cell_differs = 0;     ///< pairs in both reaches whose cell offset from the centre differs
    long long descriptors_differing = 0; ///< keypoints whose (neighbour, cell offset) set differs between variants
    long long bits_set_thesis = 0;       ///< total bits set over all descriptors (thesis)
    long long bits_set_corrected = 0;    ///< total bits set over all descriptors (corrected)
    long long empty_neighbourhood_thesis = 0;    ///< descriptors with only the centre bit (thesis)
    long long empty_neighbourhood_corrected = 0; ///< descriptors with only the centre bit (corrected)
};
GridQuirkStats grid_quirk_stats(const std::vector<cv::KeyPoint>& keypoints, int g, int h);

/// A binary descriptor of this library as a cv::Feature2D (the grid, BRIEF and FREAK below):
/// bytes (CV_8U) compared by cv::NORM_HAMMING.
class BinaryDescriptor : public cv::Feature2D {
public:
    int descriptorType() const override { return CV_8U; }
    int defaultNorm() const override { return cv::NORM_HAMMING; }
};

/// The grid descriptor as a cv::Feature2D. Descriptor only: call compute() (or
/// detectAndCompute with useProvidedKeypoints = true). The image is not read (the descriptor
/// depends on keypoint positions only), but OpenCV's compute() returns an empty result for
/// an empty image, so pass the image the keypoints come from. Keypoints are never removed.
class GridDescriptor : public BinaryDescriptor {
public:
    /// Throws InputError when g or h is out of range.
    static cv::Ptr<GridDescriptor> create(int g = 16, int h = 2,
                                          GridVariant v = GridVariant::thesis);
    GridDescriptor(int g, int h, GridVariant v);

    void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                          std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                          bool useProvidedKeypoints = false) override;
    int descriptorSize() const override;  ///< grid_descriptor_bytes(g, variant)
    cv::String getDefaultName() const override;  ///< "hc.features.GridDescriptor"

    int g() const { return g_; }
    int h() const { return h_; }
    GridVariant variant() const { return variant_; }

private:
    int g_;
    int h_;
    GridVariant variant_;
};

// ---- BRIEF and FREAK ----------------------------------------------------------------------

/// What a descriptor does with keypoints whose pattern leaves the image.
/// `drop`: remove them from the keypoint vector (OpenCV's convention and the authors'
/// implementations); `pad`: keep them, reading the image reflected at its border
/// (cv::BORDER_REFLECT_101), so every keypoint gets a descriptor.
enum class BorderPolicy { drop, pad };

/// How BRIEF smooths before its intensity tests.
/// `box`: the authors' code and OpenCV contrib's BriefDescriptorExtractor: each test point's
///   value is the sum of the 9 x 9 box around it, read from an integral image (only the test
///   points are smoothed, 4 reads each). `gaussian`: the paper's text: the whole image
///   smoothed by a 9 x 9 Gaussian of sigma 2 (cv::GaussianBlur), then single pixels compared.
enum class BriefSmoothing { box, gaussian };

/// BRIEF (Calonder, Lepetit, Strecha, Fua, ECCV 2010): 256 tests I(p + x_k) < I(p + y_k) on a
/// 48 x 48 patch around the rounded keypoint pixel of the smoothed image (BriefSmoothing);
/// (x_k, y_k) drawn once from the paper's isotropic Gaussian G II (sigma^2 = S^2 / 25, S = 48),
/// clamped to the patch, by a fixed-seed generator of this library (platform independent).
/// 32 bytes, NORM_HAMMING, bit k is bit k & 7 of byte k >> 3. No orientation, one scale.
class BriefDescriptor : public BinaryDescriptor {
public:
    static cv::Ptr<BriefDescriptor> create(BorderPolicy border = BorderPolicy::drop,
                                           BriefSmoothing smoothing = BriefSmoothing::box);
    BriefDescriptor(BorderPolicy border, BriefSmoothing smoothing);

    void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                          std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                          bool useProvidedKeypoints = false) override;
    int descriptorSize() const override;  ///< 32
    cv::String getDefaultName() const override;  ///< "hc.features.BriefDescriptor"

    /// Patch side (48), smoothing kernel side (9) and the test offsets (x1, y1, x2, y2)
    /// relative to the keypoint pixel.
    static constexpr int patch_size = 48;
    static constexpr int kernel_size = 9;
    static const std::vector<cv::Vec4i>& pattern();
    BriefSmoothing smoothing() const { return smoothing_; }

private:
    BorderPolicy border_;
    BriefSmoothing smoothing_;
};

/// FREAK (Alahi, Ortiz, Vandergheynst, CVPR 2012): 43 overlapping receptive fields on 7
/// rings of 6 plus the centre, each field's mean intensity over a box of side ~2 sigma
/// (integral image), and 512 bits I(field a) > I(field b) over a fixed coarse-to-fine
/// choice of 512 of the 903 field pairs. 64 bytes, NORM_HAMMING. `pattern_scale` is the
/// pattern's reach in pixels (outer ring radius + its field's sigma), one scale for all
/// keypoints. With `orientation`, the pattern is rotated by the angle of the mean local
/// gradient measured on pairs of fields of the same ring and keypoint.angle is set.
class FreakDescriptor : public BinaryDescriptor {
public:
    static cv::Ptr<FreakDescriptor> create(bool orientation = false, float pattern_scale = 22.f,
                                           BorderPolicy border = BorderPolicy::drop);
    FreakDescriptor(bool orientation, float pattern_scale, BorderPolicy border);

    void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                          std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                          bool useProvidedKeypoints = false) override;
    int descriptorSize() const override;  ///< 64
    cv::String getDefaultName() const override;  ///< "hc.features.FreakDescriptor"

    /// Field centres (x, y) in units of pattern_scale, and field sigmas in the same units.
    struct Field {
        float x;
        float y;
        float sigma;
    };
    static const std::vector<Field>& fields();            ///< 43 fields, ring by ring, outer first
    static const std::vector<cv::Vec2i>& pairs();         ///< 512 (a, b) field indices

private:
    bool orientation_;
    float scale_;
    BorderPolicy border_;
};

// ---- Stereo matcher (thesis 6.1, appendix F) ---------------------------------------------

/// 2-NN ratio test on d0 <= d1, the distances to the best and second-best neighbour.
/// `none`: no test. `printed`: appendix F: ratio = d0 / d1 (float division), the match is
///   removed when ratio > max_ratio. With max_ratio = 1 it never removes anything (d0 <= d1);
///   0 / 0 is NaN and NaN > max_ratio is false, so the match is kept.
/// `drop_ties`: the evidently intended test: kept only when d0 < max_ratio * d1, so with
///   max_ratio = 1 ties d0 == d1 (0 == 0 included) are removed.
/// A query with a single neighbour (the other side has one descriptor) passes both tests
/// (the printed code would throw std::out_of_range there).
enum class RatioTest { none, printed, drop_ties };

struct MatchOptions {
    int norm = cv::NORM_HAMMING;         ///< NORM_HAMMING(2) for CV_8U, NORM_L1/L2/L2SQR for CV_32F
    bool symmetry = true;                ///< keep i->j only when j's best match is i
    RatioTest ratio = RatioTest::printed;
    double max_ratio = 1.0;              ///< the thesis's maxRatio
    bool epipolar = true;                ///< keep only |y_r - y_l| < max_dy (rectified pairs)
    double max_dy = 5.0;
};

/// How many matches each test removed, in pipeline order: ratio test on left->right and on
/// right->left 2-NN lists, symmetry test on the left survivors, epipolar test.
/// Invariant: left_queries - ratio_left - symmetry - epipolar == kept (ratio_right removals
/// show up in `symmetry` when their left partner loses its reverse match).
struct MatchCounts {
    int left_queries = 0;    ///< left descriptors with at least one neighbour
    int right_queries = 0;   ///< right descriptors with at least one neighbour (0 without symmetry)
    int ratio_left = 0;      ///< left 2-NN lists removed by the ratio test
    int ratio_right = 0;     ///< right 2-NN lists removed by the ratio test
    int ratio_nan_left = 0;  ///< left lists with d0 = d1 = 0 (ratio NaN), removed or not
    int ratio_nan_right = 0;
    int ratio_ties_left = 0; ///< left lists with d0 == d1 (NaN cases included)
    int ratio_ties_right = 0;
    int symmetry = 0;        ///< left survivors removed by the symmetry test
    int epipolar = 0;        ///< removed by the epipolar test
    int kept = 0;            ///< matches returned
};

/// True when descriptors of OpenCV type `descriptor_type` can be compared with `norm`:
/// Hamming norms need CV_8U (binary descriptors), L1/L2/L2SQR need CV_32F (e.g. SIFT).
bool descriptor_norm_valid(int descriptor_type, int norm);

/// Throws InputError naming `what` when descriptor_norm_valid fails.
void require_descriptor_norm(int descriptor_type, int norm, const std::string& what);

/// The 2 nearest `train` rows of every `query` row (fewer when train has fewer rows), best
/// first, ties broken by the lower train index, as cv::BFMatcher::knnMatch(k = 2) does.
std::vector<std::vector<cv::DMatch>> knn2(const cv::Mat& query, const cv::Mat& train, int norm);

/// Appendix F's stereo matching: 2-NN both ways, ratio test (both ways), symmetry test,
/// epipolar test, each optional. queryIdx indexes kp_l/desc_l, trainIdx kp_r/desc_r; matches
/// in increasing queryIdx. Throws InputError for an invalid descriptor/norm pair, descriptor
/// widths or types that differ, or keypoint counts that differ from descriptor rows.
std::vector<cv::DMatch> match_stereo(const cv::Mat& desc_l, const std::vector<cv::KeyPoint>& kp_l,
                                     const cv::Mat& desc_r, const std::vector<cv::KeyPoint>& kp_r,
                                     const MatchOptions& options, MatchCounts* counts = nullptr);

}  // namespace hc::landmarks

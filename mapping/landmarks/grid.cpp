// Purpose: the simplified star-ID grid descriptor of thesis section 5.3.2 / appendix E, in
// the printed (`thesis`) variant and a `corrected` g x g variant, with keypoints bucketed by
// grid cell so that a descriptor reads only the keypoints within its grid's reach.
//
// Appendix E, reconstructed (the PDF split the listing in two blocks and dropped the
// indentation of the second; docs/landmarks.md records each reconstruction):
//   center = g/2 + 1;  needed_bytes = ((g*(g+1)) >> 3) + 1;
//   every keypoint scaled: x / (1 << h), y / (1 << h)          (float / int: float division)
//   for each keypoint i: dsc = 0; lx = center - x_i; ly = center - y_i;   (float)
//     for each keypoint j (i included): X = x_j + lx; Y = y_j + ly;  (float sum, int truncation)
//       if (X >= 0 && Y >= 0 && X <= g && Y <= g) set bit g*Y + X of dsc
//     row i = dsc
#include "mapping/landmarks/descriptors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>

namespace hc::landmarks {
namespace {

/// The thesis's grid centre: g/2 + 1 (integer division; 9 at g = 16).
int thesis_centre(int g) { return g / 2 + 1; }

/// The corrected grid's centre: g/2, so a g x g grid spans offsets [-g/2, g - g/2) cells.
int corrected_centre(int g) { return g / 2; }

/// Appendix E's scaling `pt / (1 << h)`: single-precision division by 2^h (exact).
float scaled(float p, int h) { return p / static_cast<float>(1 << h); }

/// Appendix E's cell coordinate: `int X = x_j + lx` with `float lx = center - x_i`, both
/// operands scaled; the float sum is converted to int by truncation toward zero.
int thesis_coordinate(float scaled_ref, float scaled_p, int centre) {
    const float l = static_cast<float>(centre) - scaled_ref;
    const float sum = scaled_p + l;
    return static_cast<int>(sum);
}

/// True when the float sum of thesis_coordinate lies in (-1, 0): cell 0 by truncation.
bool thesis_truncated_negative(float scaled_ref, float scaled_p, int centre) {
    const float l = static_cast<float>(centre) - scaled_ref;
    const float sum = scaled_p + l;
    return sum < 0.f && sum > -1.f;
}

/// The corrected cell coordinate: floor of the offset in cells, plus the centre.
/// Computed in double: the difference of two floats and the division by 2^h are exact.
/// 2^-h, the corrected grid's cells per pixel.
double inv_cell(int h) { return 1.0 / double(1 << h); }

/// `cells_per_pixel` = inv_cell(h) (a product by 2^-h is exact, and cheaper than a division).
long long corrected_coordinate(float ref, float p, double cells_per_pixel, int centre) {
    const double cells = (static_cast<double>(p) - static_cast<double>(ref)) * cells_per_pixel;
    const auto t = static_cast<long long>(cells);           // toward zero (|cells| < 2^26)
    return t - static_cast<long long>(cells < double(t)) + centre;  // floor
}

void check_coordinates(const std::vector<cv::KeyPoint>& kps) {
    constexpr float limit = 16777216.f;  // 2^24: beyond, float steps exceed one pixel
    for (size_t i = 0; i < kps.size(); ++i) {
        const cv::Point2f p = kps[i].pt;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::fabs(p.x) >= limit ||
            std::fabs(p.y) >= limit)
            throw InputError("grid descriptor: keypoint " + std::to_string(i) + " at (" +
                             std::to_string(p.x) + ", " + std::to_string(p.y) +
                             ") is not finite or |coordinate| >= 2^24");
    }
}

/// Keypoints sorted into square buckets of `side` scaled units, row-major, so that the
/// keypoints of one bucket row between two bucket columns are one contiguous range.
class Buckets {
public:
    Buckets(const std::vector<float>& sx, const std::vector<float>& sy, size_t max_buckets) {
        const size_t n = sx.size();
        if (n == 0) return;
        auto [x0, x1] = std::minmax_element(sx.begin(), sx.end());
        auto [y0, y1] = std::minmax_element(sy.begin(), sy.end());
        min_x_ = std::floor(*x0);
        min_y_ = std::floor(*y0);
        const double span_x = std::floor(*x1) - min_x_ + 1;
        const double span_y = std::floor(*y1) - min_y_ + 1;
        side_ = 1;
        while ((span_x / side_ + 1) * (span_y / side_ + 1) > double(max_buckets)) side_ *= 2;
        cols_ = static_cast<long long>(span_x / side_) + 1;
        rows_ = static_cast<long long>(span_y / side_) + 1;
        start_.assign(static_cast<size_t>(cols_ * rows_ + 1), 0);
        std::vector<long long> key(n);
        for (size_t j = 0; j < n; ++j) {
            key[j] = row(sy[j]) * cols_ + col(sx[j]);
            ++start_[static_cast<size_t>(key[j]) + 1];
        }
        for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
        index_.resize(n);
        std::vector<int> fill(start_.begin(), start_.end() - 1);
        for (size_t j = 0; j < n; ++j) index_[static_cast<size_t>(fill[key[j]]++)] = static_cast<int>(j);
    }

    /// Calls f(b, e) for each range [b, e) of bucket order positions whose keypoints' scaled
    /// positions may lie in [lo_x, hi_x] x [lo_y, hi_y] (a superset: whole buckets), one
    /// range per bucket row.
    template <class F>
    void for_each_range(double lo_x, double hi_x, double lo_y, double hi_y, F&& f) const {
        if (index_.empty()) return;
        const long long c0 = std::max(0LL, col(lo_x)), c1 = std::min(cols_ - 1, col(hi_x));
        const long long r0 = std::max(0LL, row(lo_y)), r1 = std::min(rows_ - 1, row(hi_y));
        if (c0 > c1) return;
        for (long long r = r0; r <= r1; ++r)
            f(start_[static_cast<size_t>(r * cols_ + c0)], start_[static_cast<size_t>(r * cols_ + c1 + 1)]);
    }

    /// Calls f(j) for every keypoint j of for_each_range.
    template <class F>
    void for_each_in(double lo_x, double hi_x, double lo_y, double hi_y, F&& f) const {
        for_each_range(lo_x, hi_x, lo_y, hi_y, [&](int b, int e) {
            for (int k = b; k < e; ++k) f(index_[static_cast<size_t>(k)]);
        });
    }

    /// The keypoint at bucket order position k.
    int index(int k) const { return index_[static_cast<size_t>(k)]; }
    size_t size() const { return index_.size(); }

private:
    long long col(double x) const { return static_cast<long long>(std::floor((std::floor(x) - min_x_) / side_)); }
    long long row(double y) const { return static_cast<long long>(std::floor((std::floor(y) - min_y_) / side_)); }

    double min_x_ = 0, min_y_ = 0, side_ = 1;
    long long cols_ = 0, rows_ = 0;
    std::vector<int> start_;
    std::vector<int> index_;
};

/// At most this many buckets (or 4 per keypoint when more): coarser buckets beyond.
size_t bucket_budget(size_t n) { return std::max<size_t>(size_t{1} << 20, 4 * n); }

struct Scaled {
    std::vector<float> x, y;
};

Scaled scale_all(const std::vector<cv::KeyPoint>& kps, int h) {
    Scaled s;
    s.x.resize(kps.size());
    s.y.resize(kps.size());
    for (size_t j = 0; j < kps.size(); ++j) {
        s.x[j] = scaled(kps[j].pt.x, h);
        s.y[j] = scaled(kps[j].pt.y, h);
    }
    return s;
}

/// The scaled window that holds keypoint i's grid of either variant: thesis reach x_j in
/// (x_i - centre - 1, x_i - centre + g + 1) = (x_i - g/2 - 2, x_i + g - g/2), corrected
/// reach [x_i - g/2, x_i + g - g/2) (exact), widened by the float rounding of the thesis's
/// sum: a few units in the last place of the largest operand (2^-21 relative, and 1e-3).
struct Reach {
    double lo_x, hi_x, lo_y, hi_y;
};
Reach reach_of(const Scaled& s, size_t i, int g) {
    const auto margin = [&](float v) { return 1e-3 + (std::fabs(double(v)) + 2.0 * g + 4.0) * 0x1p-21; };
    const double lo = -double(thesis_centre(g)) - 1.0, hi = double(g - g / 2);
    const double mx = margin(s.x[i]), my = margin(s.y[i]);
    return {s.x[i] + lo - mx, s.x[i] + hi + mx, s.y[i] + lo - my, s.y[i] + hi + my};
}

/// Visits every j whose scaled position may fall on keypoint i's grid of either variant.
template <class F>
void for_each_candidate(const Buckets& b, const Scaled& s, size_t i, int g, F&& f) {
    const Reach r = reach_of(s, i, g);
    b.for_each_in(r.lo_x, r.hi_x, r.lo_y, r.hi_y, f);
}

/// `v` permuted into the buckets' order, so a bucket row's keypoints are read sequentially.
std::vector<float> in_bucket_order(const std::vector<float>& v, const Buckets& b) {
    std::vector<float> o(b.size());
    for (size_t k = 0; k < o.size(); ++k) o[k] = v[static_cast<size_t>(b.index(static_cast<int>(k)))];
    return o;
}

inline void set_bit(uchar* row, int bit) { row[bit >> 3] = static_cast<uchar>(row[bit >> 3] | (1 << (bit & 7))); }

}  // namespace

void check_grid_params(int g, int h) {
    if (g < grid_g_min || g > grid_g_max)
        throw InputError("grid descriptor: g = " + std::to_string(g) + " is out of range [" +
                         std::to_string(grid_g_min) + ", " + std::to_string(grid_g_max) + "]");
    if (h < 0 || h > grid_h_max)
        throw InputError("grid descriptor: h = " + std::to_string(h) + " is out of range [0, " +
                         std::to_string(grid_h_max) + "]");
}

int grid_descriptor_bytes(int g, GridVariant v) {
    check_grid_params(g, 0);
    if (v == GridVariant::thesis) return ((g * (g + 1)) >> 3) + 1;  // appendix E: 35 at g = 16
    return (g * g + 7) / 8;                                          // ceil(g^2 / 8): 32 at g = 16
}

GridCell grid_cell(cv::Point2f ref, cv::Point2f p, int g, int h, GridVariant v) {
    check_grid_params(g, h);
    GridCell c;
    if (v == GridVariant::thesis) {
        const int centre = thesis_centre(g);
        c.x = thesis_coordinate(scaled(ref.x, h), scaled(p.x, h), centre);
        c.y = thesis_coordinate(scaled(ref.y, h), scaled(p.y, h), centre);
        c.inside = c.x >= 0 && c.y >= 0 && c.x <= g && c.y <= g;
    } else {
        const int centre = corrected_centre(g);
        const long long x = corrected_coordinate(ref.x, p.x, inv_cell(h), centre);
        const long long y = corrected_coordinate(ref.y, p.y, inv_cell(h), centre);
        c.inside = x >= 0 && y >= 0 && x < g && y < g;
        c.x = static_cast<int>(std::clamp<long long>(x, -1, g));
        c.y = static_cast<int>(std::clamp<long long>(y, -1, g));
    }
    c.bit = c.inside ? g * c.y + c.x : 0;
    return c;
}

cv::Mat grid_describe(const std::vector<cv::KeyPoint>& keypoints, int g, int h, GridVariant v) {
    check_grid_params(g, h);
    check_coordinates(keypoints);
    const int bytes = grid_descriptor_bytes(g, v);
    cv::Mat dp = cv::Mat::zeros(static_cast<int>(keypoints.size()), bytes, CV_8U);
    if (keypoints.empty()) return dp;
    const Scaled s = scale_all(keypoints, h);
    const Buckets buckets(s.x, s.y, bucket_budget(keypoints.size()));
    // coordinates in bucket order: scaled for the thesis variant, pixels for the corrected one
    Scaled px;
    if (v == GridVariant::corrected) {
        px.x.resize(keypoints.size());
        px.y.resize(keypoints.size());
        for (size_t j = 0; j < keypoints.size(); ++j) {
            px.x[j] = keypoints[j].pt.x;
            px.y[j] = keypoints[j].pt.y;
        }
    }
    const Scaled& src = v == GridVariant::thesis ? s : px;
    const std::vector<float> ox = in_bucket_order(src.x, buckets), oy = in_bucket_order(src.y, buckets);
    for (size_t i = 0; i < keypoints.size(); ++i) {
        uchar* row = dp.ptr<uchar>(static_cast<int>(i));
        const Reach r = reach_of(s, i, g);
        if (v == GridVariant::thesis) {
            const int centre = thesis_centre(g);
            buckets.for_each_range(r.lo_x, r.hi_x, r.lo_y, r.hi_y, [&](int b, int e) {
                for (size_t k = static_cast<size_t>(b); k < static_cast<size_t>(e); ++k) {
                    const int X = thesis_coordinate(s.x[i], ox[k], centre);
                    const int Y = thesis_coordinate(s.y[i], oy[k], centre);
                    // X >= 0 && Y >= 0 && X <= g && Y <= g, without branches (most
                    // candidates of a bucket row fall outside: branches mispredict)
                    const unsigned in = unsigned(unsigned(X) <= unsigned(g)) & unsigned(unsigned(Y) <= unsigned(g));
                    const int bit = in ? g * Y + X : 0;
                    row[bit >> 3] = static_cast<uchar>(row[bit >> 3] | (in << (bit & 7)));
                }
            });
        } else {
            const int centre = corrected_centre(g);
            const double inv = inv_cell(h);
            const cv::Point2f ref = keypoints[i].pt;
            buckets.for_each_range(r.lo_x, r.hi_x, r.lo_y, r.hi_y, [&](int b, int e) {
                for (size_t k = static_cast<size_t>(b); k < static_cast<size_t>(e); ++k) {
                    const long long X = corrected_coordinate(ref.x, ox[k], inv, centre);
                    const long long Y = corrected_coordinate(ref.y, oy[k], inv, centre);
                    // X, Y in [0, g), without branches (as the thesis variant)
                    const unsigned in = unsigned((unsigned long long)X < (unsigned long long)g) &
                                        unsigned((unsigned long long)Y < (unsigned long long)g);
                    const int bit = in ? static_cast<int>(g * Y + X) : 0;
                    row[bit >> 3] = static_cast<uchar>(row[bit >> 3] | (in << (bit & 7)));
                }
            });
        }
    }
    return dp;
}

GridQuirkStats grid_quirk_stats(const std::vector<cv::KeyPoint>& keypoints, int g, int h) {
    check_grid_params(g, h);
    check_coordinates(keypoints);
    GridQuirkStats st;
    st.keypoints = static_cast<long long>(keypoints.size());
    if (keypoints.empty()) return st;
    const Scaled s = scale_all(keypoints, h);
    const Buckets buckets(s.x, s.y, bucket_budget(keypoints.size()));
    const int tc = thesis_centre(g), cc = corrected_centre(g);
    const cv::Mat dt = grid_describe(keypoints, g, h, GridVariant::thesis);
    const cv::Mat dc = grid_describe(keypoints, g, h, GridVariant::corrected);
    std::vector<uchar> occupied(static_cast<size_t>((g + 1) * (g + 1)));
    struct Rel {
        int j, x, y;
        bool operator<(const Rel& o) const { return std::tie(j, x, y) < std::tie(o.j, o.x, o.y); }
        bool operator==(const Rel& o) const { return j == o.j && x == o.x && y == o.y; }
    };
    std::vector<Rel> rel_t, rel_c;
    for (size_t i = 0; i < keypoints.size(); ++i) {
        std::fill(occupied.begin(), occupied.end(), uchar{0});
        rel_t.clear();
        rel_c.clear();
        const int self_x = thesis_coordinate(s.x[i], s.x[i], tc);
        const int self_y = thesis_coordinate(s.y[i], s.y[i], tc);
        if (self_x != tc || self_y != tc) ++st.self_bit_off_centre;
        for_each_candidate(buckets, s, i, g, [&](int jj) {
            const size_t j = static_cast<size_t>(jj);
            const int X = thesis_coordinate(s.x[i], s.x[j], tc);
            const int Y = thesis_coordinate(s.y[i], s.y[j], tc);
            const bool in_t = X >= 0 && Y >= 0 && X <= g && Y <= g;
            if (in_t) {
                occupied[static_cast<size_t>(Y * (g + 1) + X)] = 1;
                rel_t.push_back({jj, X - tc, Y - tc});
                if (j != i) {
                    ++st.neighbour_hits;
                    if ((X == g && Y < g) || (X == 0 && Y >= 1)) ++st.shared_bit_hits;
                    if (thesis_truncated_negative(s.x[i], s.x[j], tc) ||
                        thesis_truncated_negative(s.y[i], s.y[j], tc))
                        ++st.truncation_hits;
                }
            }
            const long long cx = corrected_coordinate(keypoints[i].pt.x, keypoints[j].pt.x, inv_cell(h), cc);
            const long long cy = corrected_coordinate(keypoints[i].pt.y, keypoints[j].pt.y, inv_cell(h), cc);
            const bool in_c = cx >= 0 && cy >= 0 && cx < g && cy < g;
            if (in_c) rel_c.push_back({jj, static_cast<int>(cx - cc), static_cast<int>(cy - cc)});
            if (j != i && in_t && !in_c) ++st.neighbours_thesis_only;
            if (j != i && !in_t && in_c) ++st.neighbours_corrected_only;
            if (j != i && in_t && in_c && (X - tc != cx - cc || Y - tc != cy - cc))
                ++st.relative_cell_differs;
        });
        int collisions = 0;
        for (int Y = 0; Y < g; ++Y)
            if (occupied[static_cast<size_t>(Y * (g + 1) + g)] &&
                occupied[static_cast<size_t>((Y + 1) * (g + 1))])
                ++collisions;
        st.shared_bit_collisions += collisions;
        if (collisions > 0) ++st.descriptors_with_collision;
        std::sort(rel_t.begin(), rel_t.end());
        std::sort(rel_c.begin(), rel_c.end());
        if (rel_t != rel_c) ++st.descriptors_differing;
        const int bt = static_cast<int>(cv::norm(dt.row(static_cast<int>(i)), cv::NORM_HAMMING));
        const int bc = static_cast<int>(cv::norm(dc.row(static_cast<int>(i)), cv::NORM_HAMMING));
        st.bits_set_thesis += bt;
        st.bits_set_corrected += bc;
        if (bt <= 1) ++st.empty_neighbourhood_thesis;
        if (bc <= 1) ++st.empty_neighbourhood_corrected;
    }
    return st;
}

// ---- cv::Feature2D ------------------------------------------------------------------------

cv::Ptr<GridDescriptor> GridDescriptor::create(int g, int h, GridVariant v) {
    return cv::makePtr<GridDescriptor>(g, h, v);
}

GridDescriptor::GridDescriptor(int g, int h, GridVariant v) : g_(g), h_(h), variant_(v) {
    check_grid_params(g, h);
}

void GridDescriptor::detectAndCompute(cv::InputArray, cv::InputArray,
                                      std::vector<cv::KeyPoint>& keypoints,
                                      cv::OutputArray descriptors, bool useProvidedKeypoints) {
    if (!useProvidedKeypoints)
        throw InputError("grid descriptor: it describes given keypoints and detects none "
                         "(call compute, or detectAndCompute with useProvidedKeypoints)");
    grid_describe(keypoints, g_, h_, variant_).copyTo(descriptors);
}

int GridDescriptor::descriptorSize() const { return grid_descriptor_bytes(g_, variant_); }
cv::String GridDescriptor::getDefaultName() const { return "hc.features.GridDescriptor"; }

}  // namespace hc::landmarks

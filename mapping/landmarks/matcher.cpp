// Purpose: the stereo matcher of thesis section 6.1 / appendix F: brute-force 2-NN both ways,
// the 2-NN ratio test (as printed, or dropping ties), the symmetry (cross-check) test and the
// epipolar test for rectified pairs, in appendix F's order: ratio test on both 2-NN lists,
// symmetry test on what remains (a list emptied by the ratio test fails it), epipolar test.
#include "mapping/landmarks/descriptors.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace hc::landmarks {
namespace {

bool is_hamming(int norm) { return norm == cv::NORM_HAMMING || norm == cv::NORM_HAMMING2; }
bool is_metric(int norm) { return norm == cv::NORM_L1 || norm == cv::NORM_L2 || norm == cv::NORM_L2SQR; }

std::string norm_name(int norm) {
    switch (norm) {
    case cv::NORM_HAMMING: return "NORM_HAMMING";
    case cv::NORM_HAMMING2: return "NORM_HAMMING2";
    case cv::NORM_L1: return "NORM_L1";
    case cv::NORM_L2: return "NORM_L2";
    case cv::NORM_L2SQR: return "NORM_L2SQR";
    default: return "norm " + std::to_string(norm);
    }
}

/// Best and second best (distance, index) with OpenCV's tie rule: a candidate replaces a
/// kept one only when strictly closer, so among equal distances the lower index ranks first.
template <class D>
struct Best2T {
    D d0 = std::numeric_limits<D>::max(), d1 = d0;
    int i0 = -1, i1 = -1;
    void offer(D d, int i) {
        if (d < d0) {
            d1 = d0; i1 = i0;
            d0 = d; i0 = i;
        } else if (d < d1) {
            d1 = d; i1 = i;
        }
    }
};
using Best2 = Best2T<float>;

/// Integer Hamming lists as float lists (distances below 2^24 are exact in float).
void to_float(const std::vector<Best2T<int>>& in, std::vector<Best2>& out) {
    out.assign(in.size(), Best2{});
    for (size_t k = 0; k < in.size(); ++k) {
        out[k].i0 = in[k].i0;
        out[k].i1 = in[k].i1;
        if (in[k].i0 >= 0) out[k].d0 = static_cast<float>(in[k].d0);
        if (in[k].i1 >= 0) out[k].d1 = static_cast<float>(in[k].d1);
    }
}

/// Binary descriptors as rows of 64-bit words, zero-padded (zero bytes add no distance).
struct Packed {
    int rows = 0;
    int words = 0;
    std::vector<std::uint64_t> w;
    const std::uint64_t* row(int r) const { return w.data() + static_cast<size_t>(r) * words; }
};

Packed pack(const cv::Mat& m) {
    Packed p;
    p.rows = m.rows;
    p.words = (m.cols + 7) / 8;
    p.w.assign(static_cast<size_t>(p.rows) * p.words, 0);
    for (int r = 0; r < m.rows; ++r)
        std::memcpy(p.w.data() + static_cast<size_t>(r) * p.words, m.ptr<uchar>(r), static_cast<size_t>(m.cols));
    return p;
}

/// Distances of every row of `a` to every row of `b`, fed to both directions' 2-NN lists.
/// `Words` > 0: the word count known at compile time (unrolled); 0: `a.words` at run time.
template <int Words>
[[gnu::always_inline]] inline void hamming_rows(const Packed& a, const Packed& b, std::vector<Best2T<int>>& ab,
                                                std::vector<Best2T<int>>& ba) {
    const int words = Words > 0 ? Words : a.words;
    // tiles of `tile` columns, so that their descriptors and lists stay in the L1 cache;
    // each list still receives its offers in increasing index order (OpenCV's tie rule)
    constexpr int tile = 256;
    for (int c0 = 0; c0 < b.rows; c0 += tile) {
        const int c1 = std::min(b.rows, c0 + tile);
        for (int r = 0; r < a.rows; ++r) {
            const std::uint64_t* x = a.row(r);
            Best2T<int>& row_best = ab[static_cast<size_t>(r)];
            for (int c = c0; c < c1; ++c) {
                const std::uint64_t* y = b.row(c);
                int d = 0;
                for (int k = 0; k < words; ++k) d += std::popcount(x[k] ^ y[k]);
                row_best.offer(d, c);
                ba[static_cast<size_t>(c)].offer(d, r);
            }
        }
    }
}

#if defined(__GNUC__) && defined(__x86_64__)
/// NORM_HAMMING both ways with AVX-512 (VPOPCNTDQ): `b`'s rows are transposed in blocks of
/// 8 (word k of rows 8j..8j+7 is one 512-bit vector), so one XOR + VPOPCNTQ per word gives a
/// row of `a` against 8 rows of `b`. Block by block (outer) and row by row (inner), every
/// list still receives its offers in increasing index order; an offer is made only for a
/// distance below the list's second best, which is exactly when offer() would change the
/// list, so the lists are those of the scalar loop, ties included.
template <int Words>
__attribute__((target("avx512f,avx512vpopcntdq"))) void hamming_avx512(const Packed& a, const Packed& b,
                                                                        std::vector<Best2T<int>>& ab,
                                                                        std::vector<Best2T<int>>& ba) {
    const int words = Words > 0 ? Words : a.words;
    const int blocks = (b.rows + 7) / 8;
    std::vector<std::uint64_t> bt(static_cast<size_t>(blocks) * words * 8, 0);
    for (int c = 0; c < b.rows; ++c)
        for (int k = 0; k < words; ++k) bt[(static_cast<size_t>(c / 8) * words + k) * 8 + c % 8] = b.row(c)[k];
    alignas(64) long long dist[8], col_d1[8];
    constexpr int kept = Words > 0 ? Words : 1;
    __m512i B[kept];
    for (int j = 0; j < blocks; ++j) {
        const std::uint64_t* bj = bt.data() + static_cast<size_t>(j) * words * 8;
        if constexpr (Words > 0)
            for (int k = 0; k < Words; ++k) B[k] = _mm512_loadu_si512(bj + 8 * k);
        const int c0 = 8 * j, lanes = std::min(8, b.rows - c0);
        const __mmask8 valid = static_cast<__mmask8>((1u << lanes) - 1);
        // a padded lane's threshold is -1: no distance is below it
        for (int l = 0; l < 8; ++l) col_d1[l] = l < lanes ? ba[static_cast<size_t>(c0 + l)].d1 : -1;
        __m512i cd1 = _mm512_load_si512(col_d1);
        for (int r = 0; r < a.rows; ++r) {
            const std::uint64_t* x = a.row(r);
            __m512i d = _mm512_setzero_si512();
            for (int k = 0; k < words; ++k) {
                const __m512i y = Words > 0 ? B[k] : _mm512_loadu_si512(bj + 8 * k);
                d = _mm512_add_epi64(d, _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_set1_epi64(static_cast<long long>(x[k])), y)));
            }
            Best2T<int>& row_best = ab[static_cast<size_t>(r)];
            const __mmask8 to_row = _mm512_mask_cmplt_epi64_mask(valid, d, _mm512_set1_epi64(row_best.d1));
            const __mmask8 to_col = _mm512_cmplt_epi64_mask(d, cd1);
            if ((to_row | to_col) == 0) continue;
            _mm512_store_si512(dist, d);
            for (unsigned m = to_row; m; m &= m - 1) {
                const int l = __builtin_ctz(m);
                row_best.offer(static_cast<int>(dist[l]), c0 + l);
            }
            if (to_col) {
                for (unsigned m = to_col; m; m &= m - 1) {
                    const int l = __builtin_ctz(m);
                    Best2T<int>& col_best = ba[static_cast<size_t>(c0 + l)];
                    col_best.offer(static_cast<int>(dist[l]), r);
                    col_d1[l] = col_best.d1;
                }
                cd1 = _mm512_load_si512(col_d1);
            }
        }
    }
}

/// The kernel for `a.words` words: unrolled up to 18 words (the thesis grid at g = 33), else
/// the word count at run time.
template <int W = 1>
void hamming_avx512_dispatch(const Packed& a, const Packed& b, std::vector<Best2T<int>>& ab,
                             std::vector<Best2T<int>>& ba) {
    if constexpr (W <= 18) {
        if (a.words == W) return hamming_avx512<W>(a, b, ab, ba);
        return hamming_avx512_dispatch<W + 1>(a, b, ab, ba);
    } else {
        return hamming_avx512<0>(a, b, ab, ba);
    }
}

/// The AVX-512 path is taken when the CPU has it, unless $HC_MATCHER_NO_AVX512 is set (not
/// empty, not "0"): the tests run the word-wise path that way on any CPU.
bool has_avx512_popcount() {
    static const bool yes = [] {
        const char* off = std::getenv("HC_MATCHER_NO_AVX512");
        if (off && *off && std::string(off) != "0") return false;
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vpopcntdq");
    }();
    return yes;
}
#endif

/// NORM_HAMMING both ways: on a CPU with AVX-512 VPOPCNTDQ hamming_avx512 (8 rows of `b` at
/// once); else XOR and popcount on 64-bit words (the same distances as cv::batchDistance;
/// compiled also for the popcnt instruction and picked at load time),
/// unrolled for descriptors of 4 words (32 bytes: BRIEF, ORB, the corrected grid at
/// g = 16), 5 (the thesis grid's 35 bytes at g = 16) and 8 (FREAK, BRISK).
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target_clones("popcnt", "default")))
#endif
void hamming_both_ways(const Packed& a, const Packed& b, std::vector<Best2T<int>>& ab,
                       std::vector<Best2T<int>>& ba) {
#if defined(__GNUC__) && defined(__x86_64__)
    if (has_avx512_popcount()) return hamming_avx512_dispatch(a, b, ab, ba);
#endif
    switch (a.words) {
    case 4: hamming_rows<4>(a, b, ab, ba); break;
    case 5: hamming_rows<5>(a, b, ab, ba); break;
    case 8: hamming_rows<8>(a, b, ab, ba); break;
    default: hamming_rows<0>(a, b, ab, ba); break;
    }
}

/// Rows of query x rows of train distances, in blocks of query rows, feeding both directions'
/// 2-NN lists (one distance computation serves both).
void both_ways(const cv::Mat& a, const cv::Mat& b, int norm, std::vector<Best2>& ab,
               std::vector<Best2>& ba) {
    ab.assign(static_cast<size_t>(a.rows), Best2{});
    ba.assign(static_cast<size_t>(b.rows), Best2{});
    if (a.rows == 0 || b.rows == 0) return;
    if (norm == cv::NORM_HAMMING) {
        std::vector<Best2T<int>> iab(ab.size()), iba(ba.size());
        hamming_both_ways(pack(a), pack(b), iab, iba);
        to_float(iab, ab);
        to_float(iba, ba);
        return;
    }
    const int dtype = is_hamming(norm) ? CV_32S : CV_32F;
    constexpr int block = 256;
    cv::Mat dist;
    for (int r0 = 0; r0 < a.rows; r0 += block) {
        const int r1 = std::min(a.rows, r0 + block);
        cv::batchDistance(a.rowRange(r0, r1), b, dist, dtype, cv::noArray(), norm);
        for (int r = r0; r < r1; ++r) {
            Best2& row_best = ab[static_cast<size_t>(r)];
            if (dtype == CV_32S) {
                const int* d = dist.ptr<int>(r - r0);
                for (int c = 0; c < b.rows; ++c) {
                    row_best.offer(static_cast<float>(d[c]), c);
                    ba[static_cast<size_t>(c)].offer(static_cast<float>(d[c]), r);
                }
            } else {
                const float* d = dist.ptr<float>(r - r0);
                for (int c = 0; c < b.rows; ++c) {
                    row_best.offer(d[c], c);
                    ba[static_cast<size_t>(c)].offer(d[c], r);
                }
            }
        }
    }
}

std::vector<cv::DMatch> as_list(const Best2& b, int query) {
    std::vector<cv::DMatch> m;
    if (b.i0 >= 0) m.emplace_back(query, b.i0, b.d0);
    if (b.i1 >= 0) m.emplace_back(query, b.i1, b.d1);
    return m;
}

void check_descriptors(const cv::Mat& d, const std::string& what) {
    if (d.dims > 2 || d.channels() != 1)
        throw InputError(what + ": descriptors must be a single-channel matrix");
    if (!d.empty() && d.depth() != CV_8U && d.depth() != CV_32F)
        throw InputError(what + ": descriptor type must be CV_8U or CV_32F");
}

/// Whether the ratio test removes a 2-NN list with distances d0 <= d1 (the list has two).
bool ratio_removes(RatioTest t, float d0, float d1, double max_ratio) {
    switch (t) {
    case RatioTest::none: return false;
    case RatioTest::printed: {
        // appendix F: double ratio = distance0 / distance1 (float division); ratio > maxRatio.
        const double ratio = d0 / d1;
        return ratio > max_ratio;  // NaN (0/0) compares false: kept
    }
    case RatioTest::drop_ties: return !(double(d0) < max_ratio * double(d1));
    }
    return false;
}

}  // namespace

bool descriptor_norm_valid(int descriptor_type, int norm) {
    const int depth = CV_MAT_DEPTH(descriptor_type);
    if (CV_MAT_CN(descriptor_type) != 1) return false;
    if (is_hamming(norm)) return depth == CV_8U;
    if (is_metric(norm)) return depth == CV_32F;
    return false;
}

void require_descriptor_norm(int descriptor_type, int norm, const std::string& what) {
    if (descriptor_norm_valid(descriptor_type, norm)) return;
    throw InputError(what + ": " + norm_name(norm) + " cannot compare descriptors of type " +
                     cv::typeToString(descriptor_type) +
                     " (Hamming norms need binary CV_8U descriptors, L1/L2 need CV_32F ones "
                     "such as SIFT)");
}

std::vector<std::vector<cv::DMatch>> knn2(const cv::Mat& query, const cv::Mat& train, int norm) {
    check_descriptors(query, "query");
    check_descriptors(train, "train");
    if (!query.empty()) require_descriptor_norm(query.type(), norm, "query descriptors");
    if (!train.empty()) require_descriptor_norm(train.type(), norm, "train descriptors");
    if (!query.empty() && !train.empty() && (query.cols != train.cols || query.type() != train.type()))
        throw InputError("knn2: query and train descriptors differ in width or type");
    std::vector<Best2> qt, tq;
    both_ways(query, train, norm, qt, tq);
    std::vector<std::vector<cv::DMatch>> out(static_cast<size_t>(query.rows));
    for (int q = 0; q < query.rows; ++q) out[static_cast<size_t>(q)] = as_list(qt[static_cast<size_t>(q)], q);
    return out;
}

std::vector<cv::DMatch> match_stereo(const cv::Mat& desc_l, const std::vector<cv::KeyPoint>& kp_l,
                                     const cv::Mat& desc_r, const std::vector<cv::KeyPoint>& kp_r,
                                     const MatchOptions& o, MatchCounts* counts) {
    check_descriptors(desc_l, "left descriptors");
    check_descriptors(desc_r, "right descriptors");
    if (!desc_l.empty()) require_descriptor_norm(desc_l.type(), o.norm, "left descriptors");
    if (!desc_r.empty()) require_descriptor_norm(desc_r.type(), o.norm, "right descriptors");
    if (!desc_l.empty() && !desc_r.empty() &&
        (desc_l.cols != desc_r.cols || desc_l.type() != desc_r.type()))
        throw InputError("match_stereo: left descriptors (" + std::to_string(desc_l.cols) + " x " +
                         cv::typeToString(desc_l.type()) + ") and right descriptors (" +
                         std::to_string(desc_r.cols) + " x " + cv::typeToString(desc_r.type()) +
                         ") differ");
    if (static_cast<size_t>(desc_l.rows) != kp_l.size())
        throw InputError("match_stereo: " + std::to_string(kp_l.size()) + " left keypoints but " +
                         std::to_string(desc_l.rows) + " left descriptors");
    if (static_cast<size_t>(desc_r.rows) != kp_r.size())
        throw InputError("match_stereo: " + std::to_string(kp_r.size()) + " right keypoints but " +
                         std::to_string(desc_r.rows) + " right descriptors");
    if (!(o.max_ratio >= 0) || !(o.max_dy >= 0))
        throw InputError("match_stereo: max_ratio and max_dy must be >= 0");

    MatchCounts c;
    std::vector<Best2> lr, rl;
    both_ways(desc_l, desc_r, o.norm, lr, rl);

    // Ratio test on both 2-NN lists; `alive` = the list was not cleared.
    auto ratio_pass = [&](std::vector<Best2>& lists, int& queries, int& removed, int& nans,
                          int& ties) {
        std::vector<char> alive(lists.size(), 0);
        for (size_t q = 0; q < lists.size(); ++q) {
            const Best2& b = lists[q];
            if (b.i0 < 0) continue;
            ++queries;
            alive[q] = 1;
            if (b.i1 < 0) continue;  // a single neighbour: nothing to compare
            if (b.d0 == b.d1) ++ties;
            if (b.d0 == 0 && b.d1 == 0) ++nans;
            if (ratio_removes(o.ratio, b.d0, b.d1, o.max_ratio)) {
                alive[q] = 0;
                ++removed;
            }
        }
        return alive;
    };
    const std::vector<char> alive_l =
        ratio_pass(lr, c.left_queries, c.ratio_left, c.ratio_nan_left, c.ratio_ties_left);
    std::vector<char> alive_r(rl.size(), 1);
    if (o.symmetry)
        alive_r = ratio_pass(rl, c.right_queries, c.ratio_right, c.ratio_nan_right, c.ratio_ties_right);

    std::vector<cv::DMatch> out;
    for (size_t q = 0; q < lr.size(); ++q) {
        if (!alive_l[q]) continue;
        const Best2& b = lr[q];
        if (o.symmetry) {
            const size_t t = static_cast<size_t>(b.i0);
            if (!alive_r[t] || rl[t].i0 != static_cast<int>(q)) {
                ++c.symmetry;
                continue;
            }
        }
        if (o.epipolar) {
            // appendix F: fabsf(y_r - y_l) < 5, in single precision
            const float dy = std::fabs(kp_r[static_cast<size_t>(b.i0)].pt.y - kp_l[q].pt.y);
            if (!(double(dy) < o.max_dy)) {
                ++c.epipolar;
                continue;
            }
        }
        out.emplace_back(static_cast<int>(q), b.i0, b.d0);
    }
    c.kept = static_cast<int>(out.size());
    if (counts) *counts = c;
    return out;
}

}  // namespace hc::landmarks

// overflow.hpp: the overflow audit of a configuration: at every narrowing of the datapath,
// does the hardware's value (numeric_std resize/slice/wrapping add) differ from the exact
// integer it stands for?
//
// Purpose: a too-narrow width does not fail loudly in hardware, it wraps. Accuracy figures
// of a wrapping configuration describe only the data they were measured on, so the sweep
// counts the wraps per stage on the same dataset and marks such configurations.
//
// Per stage, on the stage's own (already narrowed) inputs, with the exact value computed
// in 64-bit integers and the narrowed one by the shared stage functions (LeanWord):
//   sobel      ix, iy             vs the exact 3x3 Sobel sum (sobel_x.hpp / sobel_y.hpp)
//   m_resize   resize(ix*iy, m_prod_w) vs ix*iy (m_products.hpp; the LSB drop is a floor,
//              not an overflow, and is not counted)
//   block_sum  the bf_sum_w-bit sum of nine M values, LSBs dropped, vs floor(exact sum / 2^bf_drop)
//   k_term     ktr2 in ktr_w bits vs floor(tr^2/2^k_shift1) + floor(tr^2/2^k_shift2)
//   response   resize(ac) - resize(bb) - resize(ktr2) in resp_w bits vs ac - bb - ktr2
// A value "loses its sign" when the narrowed and exact values have different signs.
// The threshold (floor(max/2^a) + floor(max/2^b) in resp_w bits) cannot overflow: the sum
// is at most max*(2^-a + 2^-b) <= max for a, b >= 1, and both terms keep max's sign.
// Pixels: every position of each pass (Sobel on the image's interior, block sum and
// response wherever the 3x3 M neighbourhood exists), as the spec model's Border::window.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc::sweep {

enum Stage { sobel, m_resize, block_sum, k_term, response, stage_count };
inline constexpr std::array<const char*, stage_count> kStageNames{"sobel", "m_resize", "block_sum", "k_term",
                                                                   "response"};

struct OverflowCounts {
    std::array<std::uint64_t, stage_count> wrapped{};     ///< narrowed != exact
    std::array<std::uint64_t, stage_count> sign_lost{};   ///< ... and of different sign
    std::array<std::uint64_t, stage_count> values{};      ///< values checked
    void add(const OverflowCounts& o);
    std::uint64_t total_wrapped() const;
    /// "" when nothing wrapped, else e.g. "sobel 1234 (sign 12), response 5"
    std::string summary() const;
};

/// The audit of one frame.
OverflowCounts count_overflows(const Image& img, const Formats& f);
/// The audit of many frames, in parallel (threads <= 0: all cores).
OverflowCounts count_overflows(const std::vector<const Image*>& frames, const Formats& f, int threads);

}  // namespace hc::sweep

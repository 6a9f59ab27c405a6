// block_filter.hpp: model of rtl/block_filter.vhd (combinational part).
//
// The nine M coefficients, each resized (sign-extended) to bf_sum_w, summed in bf_sum_w
// bits, then bits bf_sum_w-1 .. bf_drop kept: 20 -> 16 bits, floor(sum / 16).
// Template over the number type T (Word or LeanWord).
#pragma once

#include "harris/harris_pkg.hpp"
#include "harris/types.hpp"

namespace hc {

template <class T>
inline T block_filter(const std::array<std::array<T, 3>, 3>& a, const Formats& f) {
    T sum = T::sgn(0, f.bf_sum_w);
    for (const auto& row : a)
        for (const T& x : row) sum = sum + resize(x, f.bf_sum_w);
    return slice(sum, f.bf_sum_w - 1, f.bf_drop);   // 20 -> 16 bits: drop 4 LSBs
}

}  // namespace hc

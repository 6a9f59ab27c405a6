// block_filter.hpp: model of rtl/block_filter.vhd (combinational part).
//
// The nine M coefficients, each resized (sign-extended) to bf_sum_w, summed in bf_sum_w
// bits (in the VHDL's order: block_filter; by columns: block_column_sum, then
// block_filter_of_columns), then bits bf_sum_w-1 .. bf_drop kept: floor(sum / 2^bf_drop)
// in bf_sum_w - bf_drop bits (thesis: 20 -> 16 bits, floor(sum / 16)).
// Template over the number type T (Word or LeanWord).
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// The sum of one column of the 3x3 (three coefficients, each resized to bf_sum_w), in
/// bf_sum_w bits. Sums in bf_sum_w bits wrap modulo 2^bf_sum_w, so the order in which the
/// nine are added does not change a bit of the result: the frame-level model sums columns
/// once and reuses each for three windows (model/spec/spec_model.cpp).
template <class T>
inline T block_column_sum(const T& a0, const T& a1, const T& a2, const Formats& f) {
    return resize(a0, f.bf_sum_w) + resize(a1, f.bf_sum_w) + resize(a2, f.bf_sum_w);
}

/// The block filter's output from its three column sums (bf_sum_w-bit words, as
/// block_column_sum returns them): their sum in bf_sum_w bits, then bits
/// bf_sum_w-1 .. bf_drop.
template <class T>
inline T block_filter_of_columns(const T& c0, const T& c1, const T& c2, const Formats& f) {
    const T sum = c0 + c1 + c2;   // same widths: the sum wraps to bf_sum_w bits
    return slice(sum, f.bf_sum_w - 1, f.bf_drop);   // drop bf_drop LSBs: bf_sum_w -> bf_w() bits
}

/// The block filter's output: the nine resized to bf_sum_w and summed in the VHDL's order
/// (row by row, left to right), then bits bf_sum_w-1 .. bf_drop. The same bits as the column
/// sums above; the same order keeps a solver's term of it the netlist's term.
template <class T>
inline T block_filter(const std::array<std::array<T, 3>, 3>& a, const Formats& f) {
    const int w = f.bf_sum_w;
    const T sum = resize(a[0][0], w) + resize(a[0][1], w) + resize(a[0][2], w) + resize(a[1][0], w) + resize(a[1][1], w) +
                  resize(a[1][2], w) + resize(a[2][0], w) + resize(a[2][1], w) + resize(a[2][2], w);
    return slice(sum, f.bf_sum_w - 1, f.bf_drop);   // drop bf_drop LSBs: bf_sum_w -> bf_w() bits
}

}  // namespace hc

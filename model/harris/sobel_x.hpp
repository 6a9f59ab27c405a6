// sobel_x.hpp: model of rtl/sobel_x.vhd (combinational part; the register is in harris_top).
//
// ix = [-1 0 +1; -2 0 +2; -1 0 +1] * a. Each pixel becomes a 9-bit signed (a 10-bit one for
// the doubled middle row), every term is resized to sobel_w and the six are added in
// sobel_w bits, exactly as the VHDL does.
// Templates over the number type T: Word (cycle model), LeanWord (spec model, with the
// same numeric_std semantics) or RangeWord (range analysis: T::uns takes a pixel interval);
// T defaults to Word. The 3x3 pixel matrix P is Pixels3, or a matrix of whatever T::uns takes.
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// +-p widened like signed(resize(p, w)) with an optional negation and doubling.
template <class T = Word, class Px = Pixel>
inline T pixel_term(const Px& p, int width, bool negate, bool doubled) {
    const T x = as_signed(resize(T::uns(p, 8), width));   // zero-extend, read as signed
    T t = doubled ? (negate ? -x - x : x + x) : (negate ? -x : x);
    return t;
}

template <class T = Word, class P = Pixels3>
inline T sobel_x(const P& a, const Formats& f) {
    const int w = f.sobel_w;
    const T p11 = pixel_term<T>(a[0][0], 9, true, false);
    const T p21 = pixel_term<T>(a[1][0], 10, true, true);
    const T p31 = pixel_term<T>(a[2][0], 9, true, false);
    const T p13 = pixel_term<T>(a[0][2], 9, false, false);
    const T p23 = pixel_term<T>(a[1][2], 10, false, true);
    const T p33 = pixel_term<T>(a[2][2], 9, false, false);
    return resize(p11, w) + resize(p13, w) + resize(p21, w) + resize(p23, w) + resize(p31, w) +
           resize(p33, w);
}

}  // namespace hc

// sobel_y.hpp: model of rtl/sobel_y.vhd (combinational part).
//
// iy = [+1 +2 +1; 0 0 0; -1 -2 -1] * a: top row minus bottom row (see the RTL's note on
// the sign), every term resized to sobel_w and added in sobel_w bits.
// Templates over the number type T (Word by default) and the pixel matrix P, as sobel_x.
#pragma once

#include "model/harris/sobel_x.hpp"

namespace hc {

template <class T = Word, class P = Pixels3>
inline T sobel_y(const P& a, const Formats& f) {
    const int w = f.sobel_w;
    const T p11 = pixel_term<T>(a[0][0], 9, false, false);
    const T p12 = pixel_term<T>(a[0][1], 10, false, true);
    const T p13 = pixel_term<T>(a[0][2], 9, false, false);
    const T p31 = pixel_term<T>(a[2][0], 9, true, false);
    const T p32 = pixel_term<T>(a[2][1], 10, true, true);
    const T p33 = pixel_term<T>(a[2][2], 9, true, false);
    return resize(p11, w) + resize(p12, w) + resize(p13, w) + resize(p31, w) + resize(p32, w) +
           resize(p33, w);
}

}  // namespace hc

// sobel_y.hpp: model of rtl/sobel_y.vhd (combinational part).
//
// iy = [+1 +2 +1; 0 0 0; -1 -2 -1] * a: top row minus bottom row (see the RTL's note on
// the sign), every term resized to sobel_w and added in sobel_w bits.
#pragma once

#include "harris/sobel_x.hpp"

namespace hc {

inline Word sobel_y(const Pixels3& a, const Formats& f) {
    const int w = f.sobel_w;
    const Word p11 = pixel_term(a[0][0], 9, false, false);
    const Word p12 = pixel_term(a[0][1], 10, false, true);
    const Word p13 = pixel_term(a[0][2], 9, false, false);
    const Word p31 = pixel_term(a[2][0], 9, true, false);
    const Word p32 = pixel_term(a[2][1], 10, true, true);
    const Word p33 = pixel_term(a[2][2], 9, true, false);
    return resize(p11, w) + resize(p12, w) + resize(p13, w) + resize(p31, w) + resize(p32, w) +
           resize(p33, w);
}

}  // namespace hc

// input_converter.hpp: model of rtl/input_converter.vhd.
//
// On a write, row i (1..7) of the window shifts one place left and the pixel enters its
// rightmost column; seven writes add one column.
// Template over the window W (a 7x7 matrix of pixels: Window7, or of the proofs' symbolic
// word, sweep/smt_word.hpp) and the pixel P.
#pragma once

#include "model/harris/types.hpp"

namespace hc {

template <class W, class P>
inline void input_converter_shift(W& win, int i, const P& p) {
    auto& row = win[i - 1];
    for (int col = 0; col < 6; ++col) row[col] = row[col + 1];
    row[6] = p;
}

}  // namespace hc

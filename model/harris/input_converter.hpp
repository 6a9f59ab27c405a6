// input_converter.hpp: model of rtl/input_converter.vhd.
//
// On a write, row i (1..7) of the window shifts one place left and the pixel enters its
// rightmost column; seven writes add one column.
#pragma once

#include "model/harris/types.hpp"

namespace hc {

inline void input_converter_shift(Window7& win, int i, Pixel p) {
    auto& row = win[i - 1];
    for (int col = 0; col < 6; ++col) row[col] = row[col + 1];
    row[6] = p;
}

}  // namespace hc

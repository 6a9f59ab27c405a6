// windows.hpp: pixel windows for the Sobel stages' tests (sobel_x_test, sobel_y_test).
#pragma once

#include <initializer_list>

#include "model/harris/types.hpp"

namespace hc::test {

/// The 3x3 window of nine pixels given row by row.
inline Pixels3 px(std::initializer_list<int> v) {
    Pixels3 p{};
    int k = 0;
    for (int x : v) p[k / 3][k % 3] = static_cast<Pixel>(x), ++k;
    return p;
}

}  // namespace hc::test

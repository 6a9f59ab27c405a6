// sobel_y_test.cpp: unit tests of model/harris/sobel_y.hpp (rtl/sobel_y.vhd).
//
// iy = [+1 +2 +1; 0 0 0; -1 -2 -1] * a (appendix A's Sy: the top row is positive).
// Appendix A: +1020 at {255,255,255; 0,0,0; 0,0,0}, -1020 at the bottom-row twin.
#include <catch2/catch.hpp>

#include "tests/model/windows.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"

using namespace hc;
using hc::test::px;

TEST_CASE("sobel_y of the appendix A argmax window (bright top row) is +1020", "[model][sobel_y]") {
    const Word iy = sobel_y(px({255, 255, 255, 0, 0, 0, 0, 0, 0}), Formats{});
    CHECK(iy.value() == 1020);
    CHECK(iy.width() == 11);
}

TEST_CASE("sobel_y of the appendix A argmin window (bright bottom row) is -1020", "[model][sobel_y]") {
    CHECK(sobel_y(px({0, 0, 0, 0, 0, 0, 255, 255, 255}), Formats{}).value() == -1020);
}

TEST_CASE("sobel_y of a worked example is top row minus bottom row, centre doubled", "[model][sobel_y]") {
    // a = {10 20 30; 40 50 60; 70 80 90}: (10 + 40 + 30) - (70 + 160 + 90) = 80 - 320 = -240
    CHECK(sobel_y(px({10, 20, 30, 40, 50, 60, 70, 80, 90}), Formats{}).value() == -240);
    // the middle row does not matter
    CHECK(sobel_y(px({10, 20, 30, 255, 255, 255, 70, 80, 90}), Formats{}).value() == -240);
}

TEST_CASE("sobel_y of a window is minus sobel_x of its transpose", "[model][sobel_y]") {
    // transposing swaps rows and columns; the x kernel is right minus left, the y kernel top
    // minus bottom, so iy(a) = -ix(a^T). Checked on a few windows with distinct pixels.
    for (int seed = 0; seed < 20; ++seed) {
        Pixels3 a{}, at{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) a[i][j] = static_cast<Pixel>((seed * 37 + i * 91 + j * 53) % 256);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) at[i][j] = a[j][i];
        INFO("seed " << seed);
        CHECK(sobel_y(a, Formats{}).value() == -sobel_x(at, Formats{}).value());
    }
}

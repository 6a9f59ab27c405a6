// sobel_x_test.cpp: unit tests of model/harris/sobel_x.hpp (rtl/sobel_x.vhd).
//
// ix = [-1 0 +1; -2 0 +2; -1 0 +1] * a, every term RESIZEd to sobel_w and summed in sobel_w
// bits. Extreme values from the thesis, appendix A (Mathematica ArgMax/ArgMin over 8-bit
// pixels): +1020 at {0,0,255; 0,0,255; 0,0,255} and -1020 at its mirror, hence 11 bits.
#include <catch2/catch.hpp>

#include "tests/model/windows.hpp"
#include "model/harris/sobel_x.hpp"

using namespace hc;
using hc::test::px;

namespace {
Formats with_sobel_w(int w) {
    Formats f;
    f.sobel_w = w;
    return f;
}
}  // namespace

TEST_CASE("sobel_x of the appendix A argmax window is +1020 in 11 signed bits", "[model][sobel_x]") {
    // (255 - 0) + 2*(255 - 0) + (255 - 0) = 4*255 = 1020
    const Word ix = sobel_x(px({0, 0, 255, 0, 0, 255, 0, 0, 255}), Formats{});
    CHECK(ix.value() == 1020);
    CHECK(ix.width() == 11);
    CHECK(ix.is_signed());
}

TEST_CASE("sobel_x of the appendix A argmin window is -1020", "[model][sobel_x]") {
    const Word ix = sobel_x(px({255, 0, 0, 255, 0, 0, 255, 0, 0}), Formats{});
    CHECK(ix.value() == -1020);
}

TEST_CASE("sobel_x of a worked example ignores the middle column and doubles the middle row",
          "[model][sobel_x]") {
    // a = {10 20 30; 40 50 60; 70 80 90}: (30-10) + 2*(60-40) + (90-70) = 20 + 40 + 20 = 80
    CHECK(sobel_x(px({10, 20, 30, 40, 50, 60, 70, 80, 90}), Formats{}).value() == 80);
    // the middle column (20, 50, 80) does not matter: set it to 255
    CHECK(sobel_x(px({10, 255, 30, 40, 255, 60, 70, 255, 90}), Formats{}).value() == 80);
    // a flat window has no gradient
    CHECK(sobel_x(px({77, 77, 77, 77, 77, 77, 77, 77, 77}), Formats{}).value() == 0);
}

TEST_CASE("sobel_x in 10 bits wraps +1020 to -4 (why appendix A needs 11)", "[model][sobel_x]") {
    // terms 255 (9 bits), 510 (10 bits), 255 all grow to 10 bits unchanged; 1020 mod 1024
    // read as signed = 1020 - 1024 = -4
    CHECK(sobel_x(px({0, 0, 255, 0, 0, 255, 0, 0, 255}), with_sobel_w(10)).value() == -4);
}

TEST_CASE("sobel_x in 8 bits shrinks each term with RESIZE's sign-keeping rule, not modulo 256",
          "[model][sobel_x]") {
    // 255 as 9 bits = 0_1111_1111: RESIZE to 8 keeps sign 0 and the 7 LSBs -> 127
    // 510 as 10 bits = 01_1111_1110: sign 0, 7 LSBs 111_1110 -> 126
    // 127 + 126 + 127 = 380 = 124 mod 256 -> +124 (a plain 1020 mod 256 would give -4)
    CHECK(sobel_x(px({0, 0, 255, 0, 0, 255, 0, 0, 255}), with_sobel_w(8)).value() == 124);
}

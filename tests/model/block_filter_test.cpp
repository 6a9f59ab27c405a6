// block_filter_test.cpp: unit tests of model/harris/block_filter.hpp (rtl/block_filter.vhd).
//
// Nine 16-bit M values sign-extended to 20 bits, summed, bits 19..4 kept (floor of /16).
// Appendix A: max1 = 9 * ceil(1,040,400 / 2^5) = 9 * 32,513 = 292,617 -> 20 bits; then
// ceil(292,617 / 16) = 18,289 bounds a, b, c. In the hardware 292,617 is reached in
// magnitude by b = -32,513 in all nine places; the largest positive M value is 32,512.
#include <catch2/catch.hpp>

#include "model/harris/block_filter.hpp"

using namespace hc;

namespace {
Matrix3 all(int v, int w = 16) { return filled<3>(Word::sgn(v, w)); }
}  // namespace

TEST_CASE("block_filter of nine -32,513 sums -292,617 in 20 bits and keeps floor(/16) = -18,289",
          "[model][block_filter]") {
    // -292,617 / 16 = -18,288.56 -> -18,289 (appendix A's 18,289 bound, with a minus sign)
    const Word s = block_filter(all(-32513), Formats{});
    CHECK(s.value() == -18289);
    CHECK(s.width() == 16);
}

TEST_CASE("block_filter of nine 32,512 gives floor(292,608 / 16) = 18,288", "[model][block_filter]") {
    CHECK(block_filter(all(32512), Formats{}).value() == 18288);
}

TEST_CASE("block_filter of a worked example sums 1..9 = 45 and divides by 16, not 9", "[model][block_filter]") {
    Matrix3 m;
    for (int k = 0; k < 9; ++k) m[k / 3][k % 3] = Word::sgn(k + 1, 16);
    CHECK(block_filter(m, Formats{}).value() == 2);   // 45 / 16 = 2.81 -> 2
    CHECK(block_filter(all(-1), Formats{}).value() == -1);   // -9 / 16 = -0.56 -> -1 (floor)
    CHECK(block_filter(all(0), Formats{}).value() == 0);
}

TEST_CASE("block_filter with a 19-bit sum wraps 292,608 negative (why appendix A needs 20)",
          "[model][block_filter]") {
    // 292,608 - 2^19 = -231,680; with bf_drop = 3 (still 16 output bits): floor(/8) = -28,960
    Formats f;
    f.bf_sum_w = 19;
    f.bf_drop = 3;
    CHECK(block_filter(all(32512), f).value() == -28960);
}

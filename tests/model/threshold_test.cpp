// threshold_test.cpp: unit tests of model/harris/threshold.hpp (rtl/threshold.vhd and the
// thr assignment in rtl/harris_top.vhd).
//
// thr = floor(max/128) + floor(max/512) in 32 bits; a response below thr becomes 0, one equal
// to thr is kept.
#include <catch2/catch.hpp>

#include "model/harris/threshold.hpp"

using namespace hc;

TEST_CASE("threshold_value of appendix A's maximum 282,223,846 is 2,756,091", "[model][threshold]") {
    // 282,223,846 / 128 = 2,204,873.8 -> 2,204,873; / 512 = 551,218.4 -> 551,218; sum 2,756,091
    const Word thr = threshold_value(Word::sgn(282223846, 32), Formats{});
    CHECK(thr.value() == 2756091);
    CHECK(thr.width() == 32);
}

TEST_CASE("threshold_value of the find-max reset value (most negative) is -20,971,520", "[model][threshold]") {
    // -2^31 / 128 = -16,777,216; -2^31 / 512 = -4,194,304
    CHECK(threshold_value(Word::most_negative(32), Formats{}).value() == -20971520);
    // floor, not truncation: max = -1 gives -1 + -1 = -2
    CHECK(threshold_value(Word::sgn(-1, 32), Formats{}).value() == -2);
    CHECK(threshold_value(Word::sgn(0, 32), Formats{}).value() == 0);
}

TEST_CASE("threshold keeps a response equal to thr and zeroes one just below", "[model][threshold]") {
    const Word thr = Word::sgn(2756091, 32);
    CHECK(threshold(Word::sgn(2756091, 32), thr).value() == 2756091);
    CHECK(threshold(Word::sgn(2756090, 32), thr).value() == 0);
    CHECK(threshold(Word::sgn(282223846, 32), thr).value() == 282223846);
    CHECK(threshold(Word::sgn(-5, 32), thr).value() == 0);
    CHECK(threshold(Word::sgn(-5, 32), thr).width() == 32);
}

TEST_CASE("threshold with a negative thr keeps negative responses above it", "[model][threshold]") {
    const Word thr = Word::sgn(-20971520, 32);
    CHECK(threshold(Word::sgn(-39062, 32), thr).value() == -39062);
    CHECK(threshold(Word::sgn(-668975042, 32), thr).value() == 0);
}

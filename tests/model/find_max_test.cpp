// find_max_test.cpp: unit tests of model/harris/find_max.hpp (rtl/find_max.vhd).
//
// Tracks the largest response over find_max_period = (h/2-3)*(w/2+3)*4 enabled steps, then
// publishes it and restarts from the most negative value; the response of the step that
// ends a period is not counted. Only `max` is reset.
#include <catch2/catch.hpp>

#include "model/harris/find_max.hpp"

using namespace hc;

namespace {
Word r32(long v) { return Word::sgn(v, 32); }
}  // namespace

TEST_CASE("find_max publishes the largest of the first period-1 responses after period steps", "[model][find_max]") {
    const Geometry g{10, 8};   // period = (8/2-3)*(10/2+3)*4 = 1*8*4 = 32
    const Formats f;
    REQUIRE(g.find_max_period() == 32);
    FindMax fm(f);
    CHECK(fm.max == Word::most_negative(32));   // the reset value: -2^31
    for (int n = 1; n <= 31; ++n) {
        fm = fm.next(r32(n == 7 ? 1000 : n), g);
        CHECK(fm.max == Word::most_negative(32));   // nothing published before the period ends
    }
    fm = fm.next(r32(5000), g);   // step 32 ends the period: 5000 is not counted
    CHECK(fm.max.value() == 1000);
    CHECK(fm.running == Word::most_negative(32));
    CHECK(fm.count == 1);
}

TEST_CASE("find_max restarts from the most negative value, so an all-negative period publishes its maximum",
          "[model][find_max]") {
    const Geometry g{10, 8};
    const Formats f;
    FindMax fm(f);
    for (int n = 1; n <= 32; ++n) fm = fm.next(r32(1000), g);
    for (int n = 1; n <= 32; ++n) fm = fm.next(r32(-100 - n), g);
    CHECK(fm.max.value() == -101);
}

TEST_CASE("find_max reset clears only the published maximum", "[model][find_max]") {
    const Geometry g{10, 8};
    const Formats f;
    FindMax fm(f);
    for (int n = 1; n <= 40; ++n) fm = fm.next(r32(n), g);
    REQUIRE(fm.max.value() == 31);
    fm.reset(f);
    CHECK(fm.max == Word::most_negative(32));
    CHECK(fm.count == 9);                 // 40 - 32 + 1: the counter kept its value
    CHECK(fm.running.value() == 40);      // and so did the running maximum
}

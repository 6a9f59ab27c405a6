// harris_response_test.cpp: unit tests of model/harris/harris_response.hpp
// (rtl/harris_response.vhd).
//
// r = a*c - b*b - (floor(tr^2/32) + floor(tr^2/128)), tr = a + c, in 32 bits.
// Appendix A (a, b, c in +-18,289, k = 1/32 + 1/128): max 282,223,846 at {-18289, 0, -18289}
// (30 bits) and min -668,975,042 at {-18289, -18289, 18289} (31 bits).
#include <catch2/catch.hpp>

#include "model/harris/harris_response.hpp"

using namespace hc;

namespace {
Word response(int a, int b, int c, ResponseTerms* terms = nullptr) {
    const Formats f;
    const ResponseTerms t = harris_response_terms(Word::sgn(a, 16), Word::sgn(b, 16), Word::sgn(c, 16), f);
    if (terms) *terms = t;
    return harris_response(t, f);
}
}  // namespace

TEST_CASE("harris_response at appendix A's argmax {-18289, 0, -18289} is 282,223,846", "[model][harris_response]") {
    // ac = 18,289^2 = 334,487,521; tr = -36,578; tr^2 = 1,337,950,084
    // floor(tr^2/32) = 41,810,940 (.125 dropped); floor(tr^2/128) = 10,452,735 (.03 dropped)
    // ktr2 = 52,263,675; r = 334,487,521 - 0 - 52,263,675 = 282,223,846
    ResponseTerms t;
    const Word r = response(-18289, 0, -18289, &t);
    CHECK(t.ac.value() == 334487521);
    CHECK(t.bb.value() == 0);
    CHECK(t.ktr2.value() == 52263675);
    CHECK(r.value() == 282223846);
    CHECK(r.width() == 32);
}

TEST_CASE("harris_response at appendix A's argmin {-18289, -18289, 18289} is -668,975,042",
          "[model][harris_response]") {
    // ac = -334,487,521; bb = 334,487,521; tr = 0 -> ktr2 = 0; r = -668,975,042
    ResponseTerms t;
    CHECK(response(-18289, -18289, 18289, &t).value() == -668975042);
    CHECK(t.ktr2.value() == 0);
}

TEST_CASE("harris_response of the largest positive block sums {18288, 0, 18288} is 282,192,984",
          "[model][harris_response]") {
    // ac = 334,450,944; tr^2 = 36,576^2 = 1,337,803,776 -> 41,806,368 + 10,451,592 = 52,257,960
    CHECK(response(18288, 0, 18288).value() == 282192984);
}

TEST_CASE("harris_response of a worked example floors each k term separately", "[model][harris_response]") {
    // a=100 b=50 c=200: ac = 20,000; bb = 2,500; tr^2 = 90,000 -> 2,812 (2,812.5) + 703 (703.1)
    // = 3,515 (the real k*tr^2 is 3,515.625); r = 20,000 - 2,500 - 3,515 = 13,985
    ResponseTerms t;
    CHECK(response(100, 50, 200, &t).value() == 13985);
    CHECK(t.ktr2.value() == 3515);
    CHECK(t.ktr2.width() == 30);
    CHECK(t.ac.width() == 32);
}

TEST_CASE("harris_response of an edge (a only) is negative and of a flat region zero", "[model][harris_response]") {
    // a = 1000: ac = 0; tr^2 = 1,000,000 -> 31,250 + 7,812 = 39,062; r = -39,062
    CHECK(response(1000, 0, 0).value() == -39062);
    CHECK(response(0, 0, 0).value() == 0);
}

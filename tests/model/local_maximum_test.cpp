// local_maximum_test.cpp: unit tests of model/harris/local_maximum.hpp (rtl/local_maximum.vhd).
//
// A corner when the centre is strictly greater than all 8 neighbours: ties suppress.
#include <catch2/catch.hpp>

#include "model/harris/local_maximum.hpp"

using namespace hc;

namespace {
Matrix3 m3(std::initializer_list<long> v) {
    Matrix3 m;
    int k = 0;
    for (long x : v) m[k / 3][k % 3] = Word::sgn(x, 32), ++k;
    return m;
}
}  // namespace

TEST_CASE("local_maximum is true for a centre strictly above all 8 neighbours", "[model][local_maximum]") {
    CHECK(local_maximum(m3({1, 2, 3, 4, 9, 5, 6, 7, 8})));
    CHECK(local_maximum(m3({-6, -6, -6, -6, -5, -6, -6, -6, -6})));   // negative values compare by value
}

TEST_CASE("local_maximum is false when any one neighbour ties the centre", "[model][local_maximum]") {
    for (int k = 0; k < 9; ++k) {
        if (k == 4) continue;
        Matrix3 m = m3({1, 1, 1, 1, 9, 1, 1, 1, 1});
        m[k / 3][k % 3] = Word::sgn(9, 32);
        INFO("tie at neighbour (" << k / 3 << "," << k % 3 << ")");
        CHECK_FALSE(local_maximum(m));
    }
}

TEST_CASE("local_maximum is false when a neighbour is larger or everything is zero", "[model][local_maximum]") {
    CHECK_FALSE(local_maximum(m3({1, 1, 1, 1, 9, 1, 1, 1, 10})));
    CHECK_FALSE(local_maximum(m3({0, 0, 0, 0, 0, 0, 0, 0, 0})));
}

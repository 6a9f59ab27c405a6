// corner_shift_register_test.cpp: unit tests of model/harris/corner_shift_register.hpp
// (rtl/corner_shift_register.vhd): a 6-bit shift of the corner bit on every write; the
// host reads bits 5..2.
#include <catch2/catch.hpp>

#include "model/harris/corner_shift_register.hpp"

using namespace hc;

TEST_CASE("corner_shift_register shows a corner bit from 3 to 6 writes after it entered, bit 0 to bit 3",
          "[model][corner_shift_register]") {
    CornerShiftRegister c;
    c = c.next(true);
    const unsigned expect[] = {0, 0, 1, 2, 4, 8, 0};   // out after writes 1..7
    for (int n = 0; n < 7; ++n) {
        INFO("after write " << n + 1 << " c = " << static_cast<int>(c.c));
        CHECK(c.out() == expect[n]);
        c = c.next(false);
    }
}

TEST_CASE("corner_shift_register reads four consecutive corner bits with the oldest in bit 3",
          "[model][corner_shift_register]") {
    // bits entered q0=1, q1=0, q2=1, q3=1, then two more writes: out = c(5..2) = 1011
    CornerShiftRegister c;
    for (bool b : {true, false, true, true, false, false}) c = c.next(b);
    CHECK(c.out() == 0b1011);
    c.reset();
    CHECK(c.out() == 0);
}

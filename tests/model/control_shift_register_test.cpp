// control_shift_register_test.cpp: unit tests of model/harris/control_shift_register.hpp
// (rtl/control_shift_register.vhd): t = the last six values of ready, t(0) the newest.
#include <catch2/catch.hpp>

#include "model/harris/control_shift_register.hpp"

using namespace hc;

TEST_CASE("control_shift_register enables stage k exactly k+1 writes after ready", "[model][control_shift_register]") {
    ControlShiftRegister c;
    c = c.next(true);    // ready on write 1 only
    for (int k = 0; k < 6; ++k) {
        INFO("after write " << k + 1 << " t = " << static_cast<int>(c.t));
        for (int j = 0; j < 6; ++j) CHECK(c.en(j) == (j == k));
        c = c.next(false);
    }
    CHECK(c.t == 0);     // shifted out after 6 more writes: only 6 bits
}

TEST_CASE("control_shift_register keeps 6 bits and resets to zero", "[model][control_shift_register]") {
    ControlShiftRegister c;
    for (int n = 0; n < 10; ++n) c = c.next(true);
    CHECK(c.t == 0x3F);
    c = c.next(false);
    CHECK(c.t == 0x3E);
    c.reset();
    CHECK(c.t == 0);
}

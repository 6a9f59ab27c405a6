// m_products_test.cpp: unit tests of model/harris/m_products.hpp (rtl/m_products.vhd).
//
// a = ix*ix, b = ix*iy, c = iy*iy: the 22-bit product RESIZEd to 21 bits, bits 20..5 kept
// (floor of /32). Appendix A: |products| <= 1020^2 = 1,040,400 < 2^20, so 21 signed bits;
// a's argmax {-1020, 0}, b's argmax {-1020, -1020} and argmin {-1020, 1020}.
#include <catch2/catch.hpp>

#include "model/harris/m_products.hpp"

using namespace hc;

namespace {
MProducts m(int ix, int iy, const Formats& f = Formats{}) {
    return m_products(Word::sgn(ix, f.sobel_w), Word::sgn(iy, f.sobel_w), f);
}
}  // namespace

TEST_CASE("m_products of appendix A's a-argmax {-1020, 0} gives a = floor(1,040,400 / 32) = 32,512",
          "[model][m_products]") {
    const MProducts r = m(-1020, 0);
    CHECK(r.a.value() == 32512);   // 1,040,400 / 32 = 32,512.5 -> 32,512
    CHECK(r.b.value() == 0);
    CHECK(r.c.value() == 0);
    CHECK(r.a.width() == 16);
}

TEST_CASE("m_products of appendix A's b extremes gives +32,512 and -32,513 (floor, not truncation)",
          "[model][m_products]") {
    CHECK(m(-1020, -1020).b.value() == 32512);    // +1,040,400 / 32 = 32,512.5 -> 32,512
    CHECK(m(-1020, 1020).b.value() == -32513);    // -1,040,400 / 32 = -32,512.5 -> -32,513
    CHECK(m(-1020, 1020).a.value() == 32512);
    CHECK(m(-1020, 1020).c.value() == 32512);
    CHECK(m(0, -1020).c.value() == 32512);        // c's argmax {0, -1020}
}

TEST_CASE("m_products of worked small gradients floors each product divided by 32", "[model][m_products]") {
    // ix = 100, iy = 7: a = 10,000/32 = 312.5 -> 312; b = 700/32 = 21.875 -> 21; c = 49/32 -> 1
    const MProducts r = m(100, 7);
    CHECK(r.a.value() == 312);
    CHECK(r.b.value() == 21);
    CHECK(r.c.value() == 1);
    // ix = 3, iy = -5: b = -15/32 = -0.47 -> -1 (floor); a = 9/32 -> 0; c = 25/32 -> 0
    const MProducts s = m(3, -5);
    CHECK(s.a.value() == 0);
    CHECK(s.b.value() == -1);
    CHECK(s.c.value() == 0);
}

TEST_CASE("m_products with a 20-bit product width loses 1,040,400's bit 19 (why appendix A needs 21)",
          "[model][m_products]") {
    // 1,040,400 = 0b0_1111_1110_0000_0001_0000 (22 bits); RESIZE to 20 keeps sign 0 and the
    // 19 LSBs: 1,040,400 - 2^19 = 516,112; bits 19..5 -> floor(516,112 / 32) = 16,128
    Formats f;
    f.m_prod_w = 20;
    CHECK(m(-1020, 0, f).a.value() == 16128);
    CHECK(m(-1020, 0, f).a.width() == 15);
}

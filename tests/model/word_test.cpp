#include <catch2/catch.hpp>

#include "model/fixed/word.hpp"

using hc::Word;

TEST_CASE("resize of a signed word keeps the sign bit and the low bits when shrinking", "[model][word]") {
    // numeric_std RESIZE(-1024 as 22 bits -> 21 bits) = -1024; 2^20 (22 bits) -> 21 bits: sign 0, low 20 bits 0
    CHECK(resize(Word::sgn(1 << 20, 22), 21).value() == 0);
    CHECK(resize(Word::sgn(-(1 << 20) - 1, 22), 21).value() == -1);
    CHECK(resize(Word::sgn(-5, 8), 4).value() == -5);
    CHECK(resize(Word::sgn(-9, 8), 4).value() == -1);   // 1111_0111 -> sign 1, low 3 bits 111
    CHECK(resize(Word::sgn(9, 8), 4).value() == 1);     // 0000_1001 -> sign 0, low 3 bits 001
    CHECK(resize(Word::sgn(-3, 4), 10).value() == -3);
}

TEST_CASE("resize of an unsigned word keeps the low bits", "[model][word]") {
    CHECK(resize(Word::uns(0x1FF, 9), 8).value() == 0xFF);
    CHECK(resize(Word::uns(200, 8), 10).value() == 200);
}

TEST_CASE("a slice of a signed word reads its top bit as the sign", "[model][word]") {
    const Word x = Word::sgn(-100, 32);
    CHECK(slice(x, 31, 7).width() == 25);
    CHECK(slice(x, 31, 7).value() == -1);       // floor(-100 / 128)
    CHECK(slice(Word::sgn(1000, 32), 31, 5).value() == 31);
    CHECK(slice(Word::sgn(0b1011, 4), 2, 1).value() == 1);   // bits 01
    CHECK(slice(Word::sgn(0b1101, 4), 3, 2).value() == -1);  // bits 11
}

TEST_CASE("addition wraps to the wider operand and multiplication is exact", "[model][word]") {
    CHECK((Word::sgn(127, 8) + Word::sgn(1, 8)).value() == -128);
    CHECK((Word::sgn(-1020, 11) * Word::sgn(-1020, 11)).width() == 22);
    CHECK((Word::sgn(-1020, 11) * Word::sgn(-1020, 11)).value() == 1040400);
    CHECK((-Word::sgn(-128, 8)).value() == -128);
    CHECK(Word::most_negative(32).value() == -2147483648LL);
    CHECK(Word::from_bits(0x80000000U, 32, true).value() == -2147483648LL);
}

// corner_shift_register.hpp: model of rtl/corner_shift_register.vhd.
//
// A 6-bit shift register of the corner bit on every write; the output is bits 5..2.
// Template over the bits B (6 bits: std::uint8_t, or the proofs' symbolic word) and the
// corner bit C (bool, or a symbolic condition); shift_in(c, bit) is the shift (this file's
// overload, and sweep/smt_word.hpp's).
#pragma once

#include <cstdint>

namespace hc {

/// The 6-bit register c shifted left by one, `bit` entering bit 0.
inline std::uint8_t shift_in(std::uint8_t c, bool bit) {
    return static_cast<std::uint8_t>(((c << 1) | (bit ? 1U : 0U)) & 0x3FU);
}

template <class B, class C>
struct CornerShiftRegisterT {
    B c{};   ///< bits 5..0

    void reset() { c = 0; }
    std::uint8_t out() const { return static_cast<std::uint8_t>((c >> 2) & 0xFU); }
    CornerShiftRegisterT next(const C& corner) const { return {shift_in(c, corner)}; }
};
using CornerShiftRegister = CornerShiftRegisterT<std::uint8_t, bool>;

}  // namespace hc

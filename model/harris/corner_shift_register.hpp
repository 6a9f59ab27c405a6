// corner_shift_register.hpp: model of rtl/corner_shift_register.vhd.
//
// A 6-bit shift register of the corner bit on every write; the output is bits 5..2.
#pragma once

#include <cstdint>

namespace hc {

struct CornerShiftRegister {
    std::uint8_t c = 0;   ///< bits 5..0

    void reset() { c = 0; }
    std::uint8_t out() const { return static_cast<std::uint8_t>((c >> 2) & 0xFU); }
    CornerShiftRegister next(bool corner) const {
        return {static_cast<std::uint8_t>(((c << 1) | (corner ? 1U : 0U)) & 0x3FU)};
    }
};

}  // namespace hc

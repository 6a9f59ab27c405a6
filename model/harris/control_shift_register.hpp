// control_shift_register.hpp: model of rtl/control_shift_register.vhd.
//
// t = the last six values of ready, t(0) the newest: the stage enables.
#pragma once

#include <cstdint>

namespace hc {

struct ControlShiftRegister {
    std::uint8_t t = 0;   ///< bits 5..0

    void reset() { t = 0; }
    bool en(int k) const { return (t >> k) & 1U; }
    ControlShiftRegister next(bool ready) const {
        return {static_cast<std::uint8_t>(((t << 1) | (ready ? 1U : 0U)) & 0x3FU)};
    }
};

}  // namespace hc

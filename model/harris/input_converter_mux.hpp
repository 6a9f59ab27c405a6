// input_converter_mux.hpp: model of rtl/input_converter_mux.vhd.
//
// Four converters; quadrant q sees the write's byte q and the row counter delayed by q
// writes. The output register takes window i-1 on a write with i = 1..4, else zeros;
// ready = (i in 2..5) and not load. Only i is reset; the delays and the output register
// keep their values (the output is undefined until the first write).
#pragma once

#include <array>
#include <cstdint>

#include "model/harris/input_converter.hpp"

namespace hc {

struct InputConverterMux {
    int i = 1;                                   ///< row counter, 1..7
    std::array<int, 3> i_dly{1, 1, 1};           ///< i delayed by 1, 2, 3 writes (no reset)
    std::array<std::uint32_t, 3> data_dly{};     ///< data delayed by 1, 2, 3 writes (no reset)
    std::array<Window7, 4> win{};                ///< the four converters' windows
    Window7 a{};                                 ///< output register
    bool a_defined = false;                      ///< false until the first write ('U')

    void reset() {
        i = 1;
        for (auto& w : win) w = Window7{};
    }

    bool ready(bool load) const { return i > 1 && i <= 5 && !load; }

    /// One write: every register takes its value after the clock edge (each new value from
    /// the old ones: the shifts read the delays before they move on).
    void advance(std::uint32_t data) {
        const int i0 = i;
        const std::array<int, 3> i_dly0 = i_dly;
        const std::array<std::uint32_t, 3> data_dly0 = data_dly;
        a = i0 <= 4 ? win[i0 - 1] : Window7{};   // the windows before this write's shift
        a_defined = true;
        i = i0 < 7 ? i0 + 1 : 1;
        i_dly = {i0, i_dly0[0], i_dly0[1]};
        data_dly = {data, data_dly0[0], data_dly0[1]};
        input_converter_shift(win[0], i0, static_cast<Pixel>(data & 0xFFU));
        for (int q = 1; q < 4; ++q)
            input_converter_shift(win[q], i_dly0[q - 1], static_cast<Pixel>((data_dly0[q - 1] >> (8 * q)) & 0xFFU));
    }
    InputConverterMux next(std::uint32_t data) const {
        InputConverterMux n = *this;
        n.advance(data);
        return n;
    }
};

}  // namespace hc

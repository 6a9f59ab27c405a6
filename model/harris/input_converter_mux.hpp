// input_converter_mux.hpp: model of rtl/input_converter_mux.vhd.
//
// Four converters; quadrant q sees the write's byte q and the row counter delayed by q
// writes. The output register takes window i-1 on a write with i = 1..4, else zeros;
// ready = (i in 2..5) and not load. Only i is reset; the delays and the output register
// keep their values (the output is undefined until the first write).
// Template over the pixel numbers N: N::Pixel, N::Data (the written word), N::pixel(v) (a
// constant pixel), N::data(v) (a constant word) and N::byte(data, q) (byte q of a word).
// PixelNumbers is the cycle model's (8-bit pixels, 32-bit words); the whole-design proof
// runs it on the symbolic word (sweep/datapath_induction.cpp). The row counters are plain
// integers in both.
#pragma once

#include <array>
#include <cstdint>

#include "model/harris/input_converter.hpp"

namespace hc {

/// 8-bit pixels and 32-bit bus words.
struct PixelNumbers {
    using Pixel = hc::Pixel;
    using Data = std::uint32_t;
    static Pixel pixel(int v) { return static_cast<Pixel>(v); }
    static Pixel byte(Data d, int q) { return static_cast<Pixel>((d >> (8 * q)) & 0xFFU); }
    static Data data(std::uint32_t v) { return v; }
};

template <class N>
struct InputConverterMuxT {
    using Px = typename N::Pixel;
    using Window = std::array<std::array<Px, 7>, 7>;
    int i = 1;                                   ///< row counter, 1..7
    std::array<int, 3> i_dly{1, 1, 1};           ///< i delayed by 1, 2, 3 writes (no reset)
    /// data delayed by 1, 2, 3 writes (no reset; initial value 0)
    std::array<typename N::Data, 3> data_dly{N::data(0), N::data(0), N::data(0)};
    std::array<Window, 4> win{};                 ///< the four converters' windows
    Window a{};                                  ///< output register
    bool a_defined = false;                      ///< false until the first write ('U')

    static Window zeros() {
        Window z;
        for (auto& row : z) row.fill(N::pixel(0));
        return z;
    }

    void reset() {
        i = 1;
        win.fill(zeros());
    }

    bool ready(bool load) const { return i > 1 && i <= 5 && !load; }

    /// One write: every register takes its value after the clock edge (each new value from
    /// the old ones: the shifts read the delays before they move on).
    void advance(const typename N::Data& data) {
        const int i0 = i;
        const std::array<int, 3> i_dly0 = i_dly;
        const std::array<typename N::Data, 3> data_dly0 = data_dly;
        a = i0 <= 4 ? win[i0 - 1] : zeros();   // the windows before this write's shift
        a_defined = true;
        i = i0 < 7 ? i0 + 1 : 1;
        i_dly = {i0, i_dly0[0], i_dly0[1]};
        data_dly = {data, data_dly0[0], data_dly0[1]};
        input_converter_shift(win[0], i0, N::byte(data, 0));
        for (int q = 1; q < 4; ++q) input_converter_shift(win[q], i_dly0[q - 1], N::byte(data_dly0[q - 1], q));
    }
    InputConverterMuxT next(const typename N::Data& data) const {
        InputConverterMuxT n = *this;
        n.advance(data);
        return n;
    }
};
using InputConverterMux = InputConverterMuxT<PixelNumbers>;

}  // namespace hc

// input_converter_mux_test.cpp: unit tests of model/harris/input_converter_mux.hpp and
// input_converter.hpp (rtl/input_converter_mux.vhd, rtl/input_converter.vhd).
//
// Writes carry 4 pixels; quadrant q's converter sees byte q and the row counter delayed by
// q writes. The output register takes window i-1 on a write with i = 1..4, else zeros;
// ready = i in 2..5 and not load.
#include <catch2/catch.hpp>

#include "model/harris/input_converter_mux.hpp"

using namespace hc;

namespace {
/// The pixel of quadrant q at window row r (0..6), column c (0..6): distinct for all four.
Pixel pix(int q, int r, int c) { return static_cast<Pixel>(q * 64 + r * 8 + c + 1); }
/// Word k of column c: row k of each quadrant.
std::uint32_t word(int c, int k) {
    std::uint32_t d = 0;
    for (int q = 0; q < 4; ++q) d |= static_cast<std::uint32_t>(pix(q, k, c)) << (8 * q);
    return d;
}
}  // namespace

TEST_CASE("input_converter_shift moves row i left and puts the pixel in column 7", "[model][input_converter_mux]") {
    Window7 w{};
    for (int c = 0; c < 7; ++c) w[2][c] = static_cast<Pixel>(c + 1);   // row 3: 1..7
    input_converter_shift(w, 3, 99);
    CHECK(w[2] == std::array<Pixel, 7>{2, 3, 4, 5, 6, 7, 99});
    CHECK(w[1] == std::array<Pixel, 7>{});   // other rows unchanged
}

TEST_CASE("input_converter_mux outputs quadrant q's complete window on write 50+q after 7 columns",
          "[model][input_converter_mux]") {
    InputConverterMux m;
    m.reset();
    CHECK_FALSE(m.a_defined);
    // 7 columns x 7 rows = 49 writes, then 7 more writes of an 8th column (their data is
    // still arriving in quadrants 1..3 through the delays)
    for (int c = 0; c < 7; ++c)
        for (int k = 0; k < 7; ++k) m = m.next(word(c, k));
    for (int k = 0; k < 7; ++k) {
        m = m.next(word(7, k));
        // after write 50+k the register holds window k (k < 4) or zeros
        for (int r = 0; r < 7; ++r)
            for (int c = 0; c < 7; ++c) {
                const int expect = k < 4 ? pix(k, r, c) : 0;
                INFO("write " << 50 + k << " window row " << r << " col " << c);
                REQUIRE(static_cast<int>(m.a[r][c]) == expect);
            }
    }
    CHECK(m.a_defined);
}

TEST_CASE("input_converter_mux is ready on 4 writes of 7 (i = 2..5) and never while load is high",
          "[model][input_converter_mux]") {
    InputConverterMux m;
    std::string pattern, with_load;
    for (int n = 0; n < 14; ++n) {
        pattern += m.ready(false) ? '1' : '0';
        with_load += m.ready(true) ? '1' : '0';
        m = m.next(0);
    }
    CHECK(pattern == "01111000111100");
    CHECK(with_load == std::string(14, '0'));
}

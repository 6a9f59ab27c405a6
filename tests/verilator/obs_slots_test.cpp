// obs_slots_test: the decoder of the verilated obs port (cosim/verilator/lockstep.cpp).
//
// GHDL turns the VHDL port obs(0 to N-1) into Verilog [N-1:0] with obs(0) as bit N-1, and
// Verilator stores bit b in word b/32. These tests pin that mapping down without a
// simulator, so that a decoding error cannot hide behind a netlist that happens to agree.
#include <catch2/catch.hpp>

#include "model/harris/observation.hpp"
#include "cosim/verilator/lockstep.hpp"

using namespace hc;
using namespace hc::vl;

namespace {
// Puts `value` (width bits) at VHDL obs index p.. (MSB first) into Verilator words.
void put(std::vector<std::uint32_t>& words, int nbits, int p, int width, std::uint64_t value) {
    for (int k = 0; k < width; ++k) {
        const int vhdl = p + k;                 // bit k from the MSB
        const int verilog = nbits - 1 - vhdl;
        const bool b = (value >> (width - 1 - k)) & 1U;
        if (b) words[static_cast<std::size_t>(verilog / 32)] |= 1U << (verilog % 32);
    }
}
}  // namespace

TEST_CASE("obs slots cover the port once, in layout order, obs(0) = load at the top bit", "[verilator][obs]") {
    const Formats f;
    const int n = obs_width(f);
    const auto slots = obs_slots(f, n);
    REQUIRE(slots.front().field == 0);            // load
    CHECK(slots.front().lsb == n - 1);
    CHECK(slots.front().width == 1);
    CHECK(slots.back().lsb == 0);                 // corner(31 downto 0) ends at bit 0
    CHECK(slots.back().width == 32);
    long covered = 0;
    for (std::size_t k = 1; k < slots.size(); ++k) CHECK(slots[k].lsb + slots[k].width == slots[k - 1].lsb);
    for (const auto& s : slots) covered += s.width;
    CHECK(covered == n);
}

TEST_CASE("obs_value reads every element back, across 32-bit word boundaries", "[verilator][obs]") {
    const Formats f;
    const int n = obs_width(f);
    const auto slots = obs_slots(f, n);
    std::vector<std::uint32_t> words(static_cast<std::size_t>((n + 31) / 32), 0);
    // a distinct, width-filling pattern per element: alternating bits rotated by index
    std::vector<std::uint64_t> want;
    int p = 0;
    for (std::size_t k = 0; k < slots.size(); ++k) {
        const int w = slots[k].width;
        const std::uint64_t mask = w >= 64 ? ~0ULL : (1ULL << w) - 1;
        const std::uint64_t v = (0x9E3779B97F4A7C15ULL * (k + 1)) & mask;
        want.push_back(v);
        put(words, n, p, w, v);
        p += w;
    }
    for (std::size_t k = 0; k < slots.size(); ++k) {
        INFO("element " << k << " width " << slots[k].width << " lsb " << slots[k].lsb);
        CHECK(obs_value(words, slots[k]) == want[k]);
    }
}

TEST_CASE("obs_slots refuses a port whose width is not the layout's", "[verilator][obs]") {
    const Formats f;
    CHECK_THROWS_WITH(obs_slots(f, 1), Catch::Contains("OBSERVE = false"));
}

// sweep_cache_test.cpp: the synthesis cache of tools/sweep/cost.cpp against the real tools:
// a first call synthesises (GHDL + yosys), the second reads the cache. Exit 77 (skipped)
// without ghdl or yosys. Label slow: one synthesis takes ~20-30 s.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "cosim/cosim.hpp"
#include "sweep/cost.hpp"

namespace fs = std::filesystem;
using namespace hc;
using namespace hc::sweep;

TEST_CASE("a second synthesis of the same configuration is a cache hit with the same counts", "[slow][synth]") {
    const fs::path cache = fs::temp_directory_path() / ("hc-sweep-cache-test-" + std::to_string(::getpid()));
    fs::remove_all(cache);
    CostOptions o;
    o.rtl_sources = cosim::rtl_sources();
    o.cache_dir = cache;
    o.geometry = {16, 12};   // counters only; the datapath is the full design
    const CostContext ctx(o);
    Formats f;
    f.sobel_w = 10;
    Cost c;
    CHECK_FALSE(cached_cost(ctx, f, Variant::signed_mul, c));
    const Cost first = synth_cost(ctx, f, Variant::signed_mul);
    CHECK_FALSE(first.cached);
    CHECK(first.dsps == 102);   // 75 M products + 27 response products, one DSP48E1 each
    CHECK(first.luts > 1000);
    const auto t0 = std::chrono::steady_clock::now();
    const Cost second = synth_cost(ctx, f, Variant::signed_mul);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);
    CHECK(second.cached);
    CHECK(second.key == first.key);
    CHECK(second.cells == first.cells);
    // another configuration is another key
    Formats g = f;
    g.m_drop = 6;
    CHECK(cost_key(ctx, g, Variant::signed_mul) != first.key);
    CHECK(cost_key(ctx, f, Variant::ghdl) != first.key);
    fs::remove_all(cache);
}

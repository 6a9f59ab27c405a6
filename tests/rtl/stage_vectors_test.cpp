// stage_vectors_test.cpp: checks of the entity benches' C++ side without a simulator.
//
// Purpose: the benches claim to contain the appendix A extreme vectors (Schulz 2015) and to
// schedule the registers as the RTL headers describe. These tests drive a Bench the way the
// testbench does (next() until the vector of interest completes) and assert the inputs and
// the model's expected outputs: Sobel +-1020 at the appendix A windows, the response extremes
// 282223846 and -668975042 at appendix A's argmax/argmin, the reset value 0 on the first cycle,
// and the run's vector counts.
#include <catch2/catch.hpp>

#include "tests/rtl/stage_bench.hpp"
#include "tests/rtl/stage_bridge.h"

using hc::Formats;
using hc::Word;
using hc::stage::Bench;
using hc::stage::make_bench;

namespace {

/// Runs `b` until vector `index` completes; returns the inputs applied on that cycle.
std::vector<std::int32_t> run_to(Bench& b, long index) {
    std::vector<std::int32_t> in;
    while (b.next(in))
        if (b.completes_vector() && b.expected().vector == index) return in;
    FAIL("vector " << index << " never completed");
    return in;
}

std::vector<std::int64_t> values(const std::vector<Word>& v) {
    std::vector<std::int64_t> out;
    for (const Word& w : v) out.push_back(w.value());
    return out;
}

}  // namespace

TEST_CASE("sobel benches start with appendix A's argmax and argmin windows, +-1020", "[entity]") {
    const Formats f;
    auto x = make_bench(STAGE_SOBEL_X, f, 0, 1);
    auto y = make_bench(STAGE_SOBEL_Y, f, 0, 1);
    const std::int64_t ix[4] = {1020, -1020, 0, 0}, iy[4] = {0, 0, 1020, -1020};
    for (long k = 0; k < 4; ++k) {
        run_to(*x, k);
        run_to(*y, k);
        CHECK(x->expected().out[0].value() == ix[k]);
        CHECK(y->expected().out[0].value() == iy[k]);
    }
}

TEST_CASE("the first cycle of a registered bench is a hold check of the reset value 0", "[entity]") {
    auto b = make_bench(STAGE_M_PRODUCTS, Formats{}, 10, 1);
    std::vector<std::int32_t> in;
    REQUIRE(b->next(in));
    CHECK(in[0] == 0);                       // write = '0'
    CHECK_FALSE(b->completes_vector());
    CHECK(values(b->expected().out) == std::vector<std::int64_t>{0, 0, 0});
}

TEST_CASE("m_products extremes reach the most negative SOBEL_W value, outside a Sobel's range",
          "[entity]") {
    auto b = make_bench(STAGE_M_PRODUCTS, Formats{}, 0, 1);
    const auto in = run_to(*b, 0);
    CHECK(in[2] == -1024);   // ix: 11-bit most negative
    CHECK(in[3] == -1024);   // iy
    // (-1024)^2 = 2^20 needs 22 bits signed; numeric_std's resize to 21 bits keeps the sign
    // bit (0) and the 20 LSBs (all 0), so the product wraps to 0 (not 2^20 / 32 = 32768):
    // the wrap the RTL must show too
    CHECK(values(b->expected().out) == std::vector<std::int64_t>{0, 0, 0});
}

TEST_CASE("harris_response bench reaches appendix A's response extremes through its pipeline",
          "[entity]") {
    const Formats f;
    auto b = make_bench(STAGE_HARRIS_RESPONSE, f, 0, 1);
    bool max_seen = false, min_seen = false;
    std::vector<std::int32_t> in;
    while (b->next(in)) {
        if (!b->completes_vector()) continue;
        const auto abc = values(b->expected().inputs);
        if (abc == std::vector<std::int64_t>{-18289, 0, -18289}) {   // appendix A argmax r
            CHECK(b->expected().out[0].value() == 282223846);
            max_seen = true;
        }
        if (abc == std::vector<std::int64_t>{-18289, -18289, 18289}) {   // argmin r
            CHECK(b->expected().out[0].value() == -668975042);
            min_seen = true;
        }
    }
    CHECK(max_seen);
    CHECK(min_seen);
    CHECK(b->counts().extremes == 9 * 9 * 9);
}

TEST_CASE("every bench completes each of its vectors exactly once", "[entity]") {
    for (int id = STAGE_SOBEL_X; id <= STAGE_LOCAL_MAXIMUM; ++id) {
        auto b = make_bench(id, Formats{}, 1000, 7);
        long completed = 0, next_index = 0;
        std::vector<std::int32_t> in;
        while (b->next(in))
            if (b->completes_vector()) {
                CHECK(b->expected().vector == next_index);
                ++next_index;
                ++completed;
            }
        INFO(b->name());
        CHECK(completed == b->counts().extremes + 1000);
    }
}

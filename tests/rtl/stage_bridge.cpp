// stage_bridge.cpp: the VHPIDIRECT entry points of stage_bridge.h and the comparison.
//
// Purpose: holds one run (one entity, one set of generics): collects the generics the
// testbench hands over, builds hc::Formats from them (so the model computes at the widths
// GHDL elaborated), asks the entity's Bench (stage_benches.cpp) for each cycle's inputs and
// expected outputs, compares the outputs bit by bit and counts mismatches. A bit that is
// neither '0' nor '1' makes the cycle a *metavalue* mismatch, counted apart from value
// mismatches. The first kMaxReports failures are printed in full (entity, cycle from 0 after
// reset, cycle kind, vector index, inputs, expected, actual); the summary line gives the
// totals and the measured vectors per second.
#include "tests/rtl/stage_bridge.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "tests/rtl/stage_bench.hpp"

namespace {

using hc::Word;
using hc::stage::Bench;

constexpr long kMaxReports = 10;
constexpr const char* kStdUlogic = "UX01ZWLH-";   // std_ulogic'pos order

const char* const kGenericNames[STAGE_G_COUNT] = {
    "SOBEL_W", "M_PROD_W", "M_DROP", "IN_W", "BF_SUM_W", "BF_DROP", "BF_W",
    "RESP_W",  "KTR_W",    "K_SHIFT1", "K_SHIFT2", "RANDOM_VECTORS", "SEED"};

/// The generics each testbench must hand over (its entity's, plus the run parameters).
std::vector<int> required_generics(int entity) {
    std::vector<int> g;
    switch (entity) {
        case STAGE_SOBEL_X:
        case STAGE_SOBEL_Y: g = {STAGE_G_SOBEL_W}; break;
        case STAGE_M_PRODUCTS: g = {STAGE_G_SOBEL_W, STAGE_G_M_PROD_W, STAGE_G_M_DROP}; break;
        case STAGE_BLOCK_FILTER: g = {STAGE_G_IN_W, STAGE_G_BF_SUM_W, STAGE_G_BF_DROP}; break;
        case STAGE_HARRIS_RESPONSE:
            g = {STAGE_G_BF_W, STAGE_G_RESP_W, STAGE_G_KTR_W, STAGE_G_K_SHIFT1, STAGE_G_K_SHIFT2};
            break;
        case STAGE_THRESHOLD:
        case STAGE_LOCAL_MAXIMUM: g = {STAGE_G_RESP_W}; break;
        default: break;
    }
    g.push_back(STAGE_G_RANDOM_VECTORS);
    g.push_back(STAGE_G_SEED);
    return g;
}

struct Run {
    int generic[STAGE_G_COUNT] = {};
    bool given[STAGE_G_COUNT] = {};
    std::unique_ptr<Bench> bench;
    std::string generics_text;          // "SOBEL_W=11 ..." for the summary
    std::vector<std::int32_t> in;       // the current cycle's inputs
    long cycles = 0, vectors = 0, holds = 0;
    long value_mismatches = 0, meta_mismatches = 0;
    bool error = false;
    long flip_vector = -1;              // $STAGE_FLIP_VECTOR: expect a wrong LSB there
    std::chrono::steady_clock::time_point start;
};

Run& run() {
    static Run r;
    return r;
}

void fail(const std::string& what) {
    run().error = true;
    std::fprintf(stderr, "stage_bridge: error: %s\n", what.c_str());
    std::fflush(stderr);
}

/// The formats the entity was elaborated with: defaults of model/harris/harris_pkg.hpp,
/// overridden by the generics handed over. IN_W and BF_W (block_filter's and
/// harris_response's input widths) are derived widths in Formats, so the cut widths are
/// set to give them: m_w() = IN_W, bf_w() = BF_W.
hc::Formats formats_of(const Run& r) {
    hc::Formats f;
    auto set = [&](int g, int& field) {
        if (r.given[g]) field = r.generic[g];
    };
    set(STAGE_G_SOBEL_W, f.sobel_w);
    set(STAGE_G_M_PROD_W, f.m_prod_w);
    set(STAGE_G_M_DROP, f.m_drop);
    set(STAGE_G_BF_SUM_W, f.bf_sum_w);
    set(STAGE_G_BF_DROP, f.bf_drop);
    set(STAGE_G_RESP_W, f.resp_w);
    set(STAGE_G_KTR_W, f.ktr_w);
    set(STAGE_G_K_SHIFT1, f.k_shift1);
    set(STAGE_G_K_SHIFT2, f.k_shift2);
    if (r.given[STAGE_G_IN_W]) f.m_prod_w = r.generic[STAGE_G_IN_W] + f.m_drop;
    if (r.given[STAGE_G_BF_W]) f.bf_sum_w = r.generic[STAGE_G_BF_W] + f.bf_drop;
    f.validate();
    return f;
}

/// Bits of one output port as the testbench delivered them; `meta` is set when any bit is
/// neither '0' nor '1'.
struct Actual {
    std::string text;
    bool meta = false;
    std::uint64_t bits = 0;
};

Actual read_port(const std::uint8_t* out, int pos, int width, bool is_signed) {
    Actual a;
    for (int i = 0; i < width; ++i) {
        const std::uint8_t code = out[pos + i];
        a.text += code < 9 ? kStdUlogic[code] : '?';
        if (code == 2 || code == 3) a.bits = (a.bits << 1) | (code == 3 ? 1U : 0U);
        else a.meta = true;
    }
    if (!a.meta) a.text = std::to_string(Word::from_bits(a.bits, width, is_signed).value());
    return a;
}

void report(const Run& r, const std::vector<Word>& expected, const std::vector<Actual>& actual, bool meta) {
    const Bench& b = *r.bench;
    const hc::stage::Expected& e = b.expected();
    std::string msg = std::string(b.name()) + ": " + (meta ? "METAVALUE" : "MISMATCH") + " at cycle " +
                      std::to_string(r.cycles) + " (" + b.cycle_kind() + "): ";
    if (e.vector >= 0) {
        const long n_ext = b.counts().extremes;
        msg += "vector " + std::to_string(e.vector) +
               (e.vector < n_ext ? " (extreme #" + std::to_string(e.vector)
                                 : " (random #" + std::to_string(e.vector - n_ext)) +
               "): " + b.describe(e.inputs);
    } else {
        msg += std::string("no vector (") + e.note + ")";
    }
    const auto names = b.output_names();
    msg += "; expected";
    for (std::size_t k = 0; k < names.size(); ++k) msg += " " + names[k] + "=" + std::to_string(expected[k].value());
    msg += ", actual";
    for (std::size_t k = 0; k < names.size(); ++k) msg += " " + names[k] + "=" + actual[k].text;
    std::fprintf(stderr, "%s\n", msg.c_str());
    std::fflush(stderr);
}

int32_t check(const std::uint8_t* out) {
    Run& r = run();
    const Bench& b = *r.bench;
    std::vector<Word> exp = b.expected().out;
    if (b.completes_vector() && b.expected().vector == r.flip_vector)   // test of the test
        exp[0] = Word::from_bits(exp[0].bits() ^ 1U, exp[0].width(), exp[0].is_signed());
    std::vector<Actual> actual;
    bool meta = false, differ = false;
    int pos = 0;
    for (const Word& w : exp) {
        actual.push_back(read_port(out, pos, w.width(), w.is_signed()));
        pos += w.width();
        meta = meta || actual.back().meta;
        differ = differ || actual.back().meta || actual.back().bits != w.bits();
    }
    if (b.completes_vector()) ++r.vectors;
    if (differ) {
        (meta ? r.meta_mismatches : r.value_mismatches) += 1;
        if (r.value_mismatches + r.meta_mismatches <= kMaxReports) report(r, exp, actual, meta);
    }
    ++r.cycles;
    return 0;
}

// f()'s value, or `on_error` when it threw: the exception reported as `where`'s (fail).
template <class F>
int32_t guarded(const char* where, int32_t on_error, F f) {
    try {
        return f();
    } catch (const std::exception& e) {
        fail(std::string(where) + ": " + e.what());
    } catch (...) {
        fail(std::string(where) + ": exception");
    }
    return on_error;
}

}  // namespace

extern "C" {

int32_t stage_generic(int32_t index, int32_t value) {
    try {
        if (index < 0 || index >= STAGE_G_COUNT) {
            fail("stage_generic: unknown generic index " + std::to_string(index));
            return 0;
        }
        run().generic[index] = value;
        run().given[index] = true;
    } catch (...) {
        fail("stage_generic: exception");
    }
    return 0;
}

int32_t stage_open(int32_t entity, int32_t out_w) {
    return guarded("stage_open", 1, [&]() -> int32_t {
        Run& r = run();
        for (int g : required_generics(entity)) {
            if (!r.given[g]) {
                fail(std::string("stage_open: the testbench did not hand over ") + kGenericNames[g]);
                return 1;
            }
            if (g != STAGE_G_RANDOM_VECTORS && g != STAGE_G_SEED)
                r.generics_text += std::string(r.generics_text.empty() ? "" : " ") + kGenericNames[g] + "=" +
                                   std::to_string(r.generic[g]);
        }
        if (r.generic[STAGE_G_RANDOM_VECTORS] < 0) {
            fail("stage_open: RANDOM_VECTORS must not be negative");
            return 1;
        }
        const hc::Formats f = formats_of(r);
        r.bench = hc::stage::make_bench(entity, f, r.generic[STAGE_G_RANDOM_VECTORS],
                                        static_cast<std::uint64_t>(r.generic[STAGE_G_SEED]));
        if (r.bench->out_width() != out_w) {
            fail(std::string(r.bench->name()) + ": the testbench packs " + std::to_string(out_w) +
                 " output bits, the model produces " + std::to_string(r.bench->out_width()));
            return 1;
        }
        if (r.bench->out_width() > STAGE_OUT_MAX || r.bench->widest_input() > 32) {
            fail(std::string(r.bench->name()) + ": ports wider than 32 bits (inputs) or " +
                 std::to_string(STAGE_OUT_MAX) + " bits (packed outputs) do not pass the bridge");
            return 1;
        }
        // Test of the test: with STAGE_FLIP_VECTOR=n the bench expects bit 0 of the first
        // output of vector n inverted, so a correct entity must fail there (tests/rtl CTest
        // entity_*_reports_an_injected_mismatch).
        if (const char* flip = std::getenv("STAGE_FLIP_VECTOR")) {
            r.flip_vector = std::stol(flip);
            std::printf("%s: STAGE_FLIP_VECTOR=%ld: expecting a wrong bit 0 at that vector\n",
                        r.bench->name(), r.flip_vector);
        }
        r.start = std::chrono::steady_clock::now();
        return 0;
    });
}

int32_t stage_next(void) {
    return guarded("stage_next", 0, []() -> int32_t {
        Run& r = run();
        if (!r.bench || r.error) return 0;
        return r.bench->next(r.in) ? 1 : 0;
    });
}

int32_t stage_input(int32_t k) {
    try {
        Run& r = run();
        if (k >= 0 && static_cast<std::size_t>(k) < r.in.size()) return r.in[k];
        fail("stage_input: input " + std::to_string(k) + " of " + std::to_string(r.in.size()));
    } catch (...) {
        fail("stage_input: exception");
    }
    return 0;
}

int32_t stage_check(const uint8_t* out) {
    return guarded("stage_check", 1, [&]() -> int32_t {
        if (!run().bench) return 1;
        return check(out);
    });
}

int32_t stage_close(void) {
    try {
        Run& r = run();
        if (!r.bench) {
            fail("stage_close: no bench was opened");
            return 2;
        }
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
        const hc::stage::Counts& c = r.bench->counts();
        const long expected_vectors = c.extremes + c.random;
        if (r.vectors != expected_vectors)
            fail("stage_close: " + std::to_string(r.vectors) + " vectors checked, " +
                 std::to_string(expected_vectors) + " scheduled (the run ended early)");
        std::printf(
            "%s: %ld vectors (%ld extreme + %ld random, seed %d), %ld hold checks, %ld cycles; "
            "mismatches: %ld value, %ld metavalue; %s; %.2f s, %.0f vectors/s\n",
            r.bench->name(), r.vectors, c.extremes, c.random, r.generic[STAGE_G_SEED], c.holds, r.cycles,
            r.value_mismatches, r.meta_mismatches, r.generics_text.c_str(), s, s > 0 ? r.vectors / s : 0.0);
        std::fflush(stdout);
        if (r.error) return 2;
        return r.value_mismatches + r.meta_mismatches > 0 ? 1 : 0;
    } catch (...) {
        std::fprintf(stderr, "stage_bridge: error: stage_close: exception\n");
        return 2;
    }
}

}  // extern "C"

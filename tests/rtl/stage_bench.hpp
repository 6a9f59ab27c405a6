// stage_bench.hpp: the C++ side of one entity-level bench: vectors, control schedule, and
// the outputs the model's stage function says the entity must show after each cycle.
//
// Purpose: stage_bridge.cpp (the VHPIDIRECT entry points) is generic; everything that is
// specific to one entity lives behind `Bench`: which inputs it has and in which order the
// testbench reads them, its extreme vectors, how random vectors are drawn, how the entity's
// registers and enables are sequenced (the single register of the Sobel, M-product and
// block-filter stages, the two steps of harris_response, the one-write delay of threshold,
// the combinational local_maximum), and which model function predicts the outputs.
//
// A *vector* is one set of input port values whose result the model predicts and the bench
// compares (counted once). A *hold check* is a cycle in which the entity must not take its
// inputs (write = '0', or an enable low) and the outputs must keep, or for threshold clear,
// their value; hold checks are extra cycles, not counted as vectors.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "model/fixed/word.hpp"
#include "model/harris/harris_pkg.hpp"

namespace hc::stage {

/// Deterministic random port values. std::mt19937_64's sequence is fixed by the C++
/// standard, and the draws below avoid the library-defined distributions, so a seed gives the
/// same vectors with any compiler.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : g_(seed) {}
    /// Uniform over every value of a `width`-bit signed port: the top `width` bits of a draw.
    Word any_signed(int width) { return Word::from_bits(g_() >> (64 - width), width, true); }
    /// Uniform over every value of a `width`-bit unsigned port.
    Word any_unsigned(int width) { return Word::from_bits(g_() >> (64 - width), width, false); }
    /// An integer in [lo, hi] (small ranges only: the modulo bias is then negligible).
    std::int64_t in_range(std::int64_t lo, std::int64_t hi) {
        return lo + static_cast<std::int64_t>(g_() % static_cast<std::uint64_t>(hi - lo + 1));
    }
    /// One element of `set`, uniformly.
    template <class T>
    const T& pick(const std::vector<T>& set) { return set[g_() % set.size()]; }

private:
    std::mt19937_64 g_;
};

/// The extreme values of a `width`-bit signed port: most negative, most negative + 1, -1,
/// 0, 1, most positive - 1, most positive, plus `extra` values that fit (e.g. the appendix A
/// bounds). Duplicates removed, ascending.
std::vector<std::int64_t> signed_edges(int width, const std::vector<std::int64_t>& extra = {});

/// What the outputs must be after the current cycle, and which vector produced them.
struct Expected {
    std::vector<Word> out;     ///< output ports in the testbench's packing order
    long vector = -1;          ///< index of the producing vector; -1: the reset value
    std::vector<Word> inputs;  ///< that vector's input port values (for messages)
    const char* note = "reset value";   ///< where the value comes from when vector < 0
};

/// Per-run counters a bench keeps.
struct Counts {
    long extremes = 0;   ///< extreme vectors in the run
    long random = 0;     ///< random vectors in the run
    long holds = 0;      ///< hold checks (cycles whose inputs the entity must not take)
};

/// One entity's bench.
class Bench {
public:
    virtual ~Bench() = default;
    /// The entity stem, as in rtl/<stem>.vhd.
    virtual const char* name() const = 0;
    /// Packed output width: the sum of the output port widths.
    virtual int out_width() const = 0;
    /// Output port names, in packing order.
    virtual std::vector<std::string> output_names() const = 0;
    /// The inputs of a vector as the failure message prints them.
    virtual std::string describe(const std::vector<Word>& inputs) const = 0;
    /// Prepares the next cycle: fills `in` (the values the testbench applies, in the
    /// entity's input order) and advances the model's registers. False when the run is over.
    virtual bool next(std::vector<std::int32_t>& in) = 0;

    /// The outputs after the cycle prepared by the last next().
    const Expected& expected() const { return expected_; }
    /// True when that cycle completes a vector for the first time (count it as checked).
    bool completes_vector() const { return completes_; }
    /// What the cycle prepared by the last next() checks, for messages ("vector check", "hold
    /// check with write = '0'", ...).
    const char* cycle_kind() const { return kind_; }
    const Counts& counts() const { return counts_; }
    /// Largest port width the bench passes through a VHDL integer.
    virtual int widest_input() const = 0;

protected:
    Expected expected_;
    bool completes_ = false;
    const char* kind_ = "vector check";
    Counts counts_;
};

/// The bench of entity `id` (STAGE_* of stage_bridge.h) for formats `f`: its extreme
/// vectors, then `random` random vectors drawn from `seed`. Throws std::invalid_argument for
/// an unknown entity.
std::unique_ptr<Bench> make_bench(int id, const Formats& f, long random, std::uint64_t seed);

}  // namespace hc::stage

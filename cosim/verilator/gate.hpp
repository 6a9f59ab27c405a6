// gate.hpp: the three-way gate that must pass before a Verilator result counts.
//
// Purpose: GHDL's Verilog back end is a second implementation of VHDL's semantics, and it
// has known defects (GHDL 2.0 writes shift_right on `signed` as a logical `>>`). So the
// same small-frame regression set runs through
//   GHDL   (simulation of the VHDL itself: cosim/verilator/ghdl_replay_tb.vhd),
//   Verilator (the GHDL-synthesised netlist, as in the real run), and
//   the cycle model (hc::HarrisTop),
// and every read - and every observed register, when the netlist keeps the obs port -
// must agree three ways. The verdict separates the faults:
//   translation fault: GHDL != Verilator (the netlist does not mean what the VHDL means);
//   RTL fault:         GHDL == Verilator != model (the design and the model disagree).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"
#include "cosim/verilator/netlist.hpp"

namespace hc::vl {

/// One regression case: `frames` chained frames of a synthetic pattern at a small size.
struct GateCase {
    std::string name;
    Geometry g;
    Pattern pattern;
    int frames;
};
/// The regression set: the smallest size the host driver can chain (two window rows),
/// odd sizes, and larger sizes, each over 3 chained frames (so find-max publishes a real maximum).
std::vector<GateCase> gate_cases();

enum class GateVerdict { pass, translation_fault, rtl_fault };
const char* verdict_name(GateVerdict v);

struct GateResult {
    GateVerdict verdict = GateVerdict::pass;
    long writes = 0, reads = 0;        ///< over all cases
    long obs_compared = 0;             ///< writes whose obs port was compared
    std::string first;                 ///< the first disagreement, in words
    std::vector<std::string> per_case; ///< one line per case
};

/// Runs the gate for formats `f` and VHDL `variants`: the cases in order, up to the first
/// case that shows a fault. GHDL's analysis and each netlist go to `cache_dir`.
GateResult run_gate(const Formats& f, const std::vector<std::filesystem::path>& variants,
                    const std::filesystem::path& cache_dir, std::ostream& log);

/// run_gate, remembered: a passing gate is recorded in cache_dir under a key over the
/// sources, formats and harness, so later runs of the same design skip it.
GateResult run_gate_cached(const Formats& f, const std::vector<std::filesystem::path>& variants,
                           const std::filesystem::path& cache_dir, std::ostream& log, bool* from_cache);

}  // namespace hc::vl

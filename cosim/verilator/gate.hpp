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

/// One regression case: one frame size (one netlist), one frame per pattern, chained.
struct GateCase {
    std::string name;
    Geometry g;
    std::vector<Pattern> patterns;   ///< frame k is make_pattern(patterns[k], ..., k, 7)
};
/// The regression set: the smallest size the host driver can chain (two window rows) and an
/// odd size with several window rows, each over four chained frames of the four textured
/// patterns (so find-max publishes real maxima and the threshold is exercised). Two sizes
/// mean two netlists per configuration; the patterns share each one.
std::vector<GateCase> gate_cases();

enum class GateVerdict { pass, translation_fault, rtl_fault };
const char* verdict_name(GateVerdict v);

struct GateResult {
    GateVerdict verdict = GateVerdict::pass;
    long writes = 0, reads = 0;        ///< over all cases
    long obs_compared = 0;             ///< writes whose obs port was compared
    std::string first;                 ///< the first disagreement, in words
    std::vector<std::string> per_case; ///< one line per case
    double seconds = 0;                ///< wall time of the run that gave the verdict (a cached one's)
};

/// Runs the gate for formats `f` and VHDL `variants`: the cases in order, up to the first
/// case that shows a fault. GHDL's analysis (one per set of sources, shared by every
/// configuration: the formats are generics given at elaboration) and each netlist (built
/// unoptimised: the gate's streams are a few thousand writes, so compile time dominates)
/// go to `cache_dir`.
GateResult run_gate(const Formats& f, const std::vector<std::filesystem::path>& variants,
                    const std::filesystem::path& cache_dir, std::ostream& log);

/// run_gate, remembered: a passing gate is recorded in cache_dir under gate_key(), so later
/// runs of the same design skip it. Only a pass is recorded; a verdict is reused only when
/// the formats, every VHDL source, the harness, the cases and the tool versions are the
/// same, so an edited RTL file is gated again, never passed from the cache.
/// The key of a recorded verdict: a hash over every netlist key of the cases (formats hash,
/// sources' contents, Verilator harness, tool versions), the GHDL replay testbench and the
/// cases themselves.
std::string gate_key(const Formats& f, const std::vector<std::filesystem::path>& variants);

GateResult run_gate_cached(const Formats& f, const std::vector<std::filesystem::path>& variants,
                           const std::filesystem::path& cache_dir, std::ostream& log, bool* from_cache);

}  // namespace hc::vl

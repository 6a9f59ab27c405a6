// verilate.hpp: the Verilator flow as one C++ call: the three-way gate (gate.hpp), the
// netlist for the frames' size (netlist.hpp), and the lock-step run against the cycle model
// (lockstep.hpp). `harris-cosim verilate` and the sweep's RTL checks call it.
//
// Errors: InputError (a missing variant file, no GHDL/Verilator), SimulatorError (a tool
// step failed). The verdicts (gate fault, mismatches) are in the result, not exceptions.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/verilator/gate.hpp"
#include "cosim/verilator/lockstep.hpp"
#include "cosim/verilator/netlist.hpp"

namespace hc::vl {

struct VerilateRun {
    std::vector<Image> frames;                      ///< may be empty with gate_only / no frames
    std::vector<std::string> frame_names;
    Formats formats;
    std::vector<std::filesystem::path> variants;    ///< test-only VHDL files (netlist.hpp)
    std::filesystem::path cache;                    ///< empty: default_cache_dir()
    bool gate = true;                               ///< run the three-way gate first
    bool gate_only = false;
    bool build_only = false;                        ///< build the netlist for the frames' size, stop
    bool observe = false;                           ///< compare every observed register (OBSERVE netlist)
    bool keep_going = false;
    std::vector<std::string>* read_rows = nullptr;  ///< every read: write,frame,x,y,value
    std::function<void(const FrameStats&)> on_frame;
};

struct VerilateResult {
    std::optional<GateResult> gate;   ///< absent when skipped
    bool gate_cached = false;
    std::string netlist_key;          ///< empty when no netlist was needed
    std::filesystem::path netlist;
    std::optional<RunResult> run;     ///< absent with gate_only, build_only or a failed gate
    long writes_in_stream = 0;
    /// "pass", "mismatch", "translation_fault", "rtl_fault" (gate), "built" (build_only)
    std::string status() const;
};

/// Streams of at most this many writes run on a netlist compiled without optimisation
/// (NetlistConfig::optimise): its build is several times quicker and the run takes well
/// under a second either way; the gate's small frames use the same builds.
inline constexpr long kUnoptimisedWrites = 100000;

/// The flow; progress lines go to `log`.
VerilateResult run_verilate(const VerilateRun& r, std::ostream& log);

/// The counts of a lock-step run both verilate summaries give: complete, writes, reads,
/// corners, read_mismatches.
nlohmann::json run_counts_json(const RunResult& r);

/// A mismatch as the summaries give it: kind, write, frame, x, y, quadrant, signal, stage,
/// expected, actual.
nlohmann::json mismatch_json(const Mismatch& m);

/// The summary of one flow (`harris-cosim verilate --json`): command, simulator, formats; the
/// gate (verdict, whether recorded earlier, writes, reads, cases, the first fault) or
/// "skipped"; the netlist (key, library, observe); the lock-step run (geometry, per-frame
/// rows, counts, mismatches with the first one described, timings; the fields of
/// `harris-cosim rtl --json` where they apply); status. `wall_seconds_including_build` is
/// the caller's clock over the whole flow.
nlohmann::json summary_json(const VerilateRun& run, const VerilateResult& res, double wall_seconds_including_build);

}  // namespace hc::vl

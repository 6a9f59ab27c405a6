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

/// How far a netlist's Verilator results stand for its VHDL: what `verilate` reports of its own
/// run, and the sweep's Verilator trust column of each configuration.
enum class NetlistTrust {
    not_run,        ///< no gate and no Verilator run
    failed,         ///< the gate or a Verilator run failed
    samples,        ///< passed on the streams it ran (the gate's lock step against GHDL and the model); no stage proof
    stages_proven,  ///< passed, and every datapath stage of the netlist proven equal to the model for every input
};
/// The trust of results whose gate and runs did or did not run and fail; `stages_proven`:
/// every stage of the configuration's netlist is proven (sweep/stage_equivalence.hpp).
NetlistTrust netlist_trust(bool ran, bool failed, bool stages_proven);
/// "-", "failed", "samples only", "stages proven" (the value in CSV and JSON)
const char* netlist_trust_name(NetlistTrust t);
/// A run's own trust: `verilate` proves no stage, so at best "samples only" (the gate, or a
/// lock-step run with --no-gate, passed); "-" when neither ran (--build-only).
NetlistTrust netlist_trust(const VerilateResult& res);

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

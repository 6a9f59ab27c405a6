// sweep.hpp: the bit-width sweep: per configuration the overflow audit, the accuracy
// against OpenCV (spec model, thesis protocol), the synthesis cost; the Pareto front of
// cost against accuracy; every Pareto point checked on the RTL (GHDL co-simulation of the
// regression set, verilate's three-way gate, Verilator on KITTI frames). Reports:
// sweep_report.hpp.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "eval/eval.hpp"
#include "sweep/cost.hpp"
#include "sweep/overflow.hpp"
#include "sweep/sweep_config.hpp"

namespace hc::sweep {

/// One RTL check of a configuration (several runs of one simulator).
struct TrustResult {
    bool ran = false;
    int runs = 0;              ///< simulator runs
    int failed = 0;            ///< runs that did not pass (mismatch or error)
    long mismatches = 0;       ///< mismatching cycles (GHDL) or writes (Verilator), summed
    long reads = 0;            ///< corner reads compared
    double seconds = 0;
    bool cached = false;
    std::string detail;        ///< e.g. "10/10 streams pass" or the first failure
};

struct PointResult {
    Config config;
    OverflowCounts overflow;
    eval::Confusion accuracy;          ///< summed over the scored frames
    Cost cost;                         ///< variant signed (what the Pareto front uses)
    Cost cost_ghdl;                    ///< variant ghdl (thesis configuration only)
    bool has_cost_ghdl = false;
    long register_bits = 0;            ///< datapath_register_bits
    bool wraps = false;                ///< overflow.total_wrapped() > 0
    bool pareto = false;
    bool verify = false;               ///< RTL-checked: Pareto point, thesis, or a finding (sweep_report.hpp)
    double eval_seconds = 0, overflow_seconds = 0;
    TrustResult rtl, verilator;
    /// verilate's three-way gate (GHDL / Verilator / model on small frames) for these formats:
    /// runs 1, failed 1 on a translation or RTL fault; seconds: the gate's own run (also
    /// when the verdict comes from the cache); detail: the verdict
    TrustResult gate;
};

struct SweepOptions {
    std::filesystem::path spec_file;
    std::filesystem::path out;
    std::filesystem::path cache;       ///< synthesis + trust cache
    std::filesystem::path kitti;       ///< KITTI root (holds sequences/NN)
    std::filesystem::path regression_set;   ///< golden/regression-set.txt: the GHDL checks' streams
    std::string ghdl_backend = "gcc";  ///< GHDL back end of the RTL checks (cosim::run_ghdl)
    int threads = 0;                   ///< accuracy / overflow threads (0: all cores)
    int jobs = 2;                      ///< synthesis and GHDL processes at once (Verilator runs one at a time)
    bool trust = true;                 ///< run the RTL checks of the Pareto points
    bool progress = true;
};

struct SweepResult {
    SweepSpec spec;
    std::vector<PointResult> points;
    std::string stream;                ///< what the accuracy was measured on
    int scored_frames = 0;
    double seconds_load = 0, seconds_reference = 0, seconds_cost = 0, seconds_accuracy = 0,
           seconds_trust = 0, seconds_total = 0;
    int synthesised = 0, synth_cached = 0;
    int gates_run = 0, gates_cached = 0;
    double gate_seconds_sum = 0;       ///< wall time of the gates run now (cached ones: 0)
    double synth_seconds_sum = 0;      ///< sum of synthesis times of the runs made now
    std::string command;
};

/// Pareto front: minimise LUTs and DSPs, maximise F1; only configurations that do not wrap.
void mark_pareto(std::vector<PointResult>& pts);
/// The points whose RTL is checked: the Pareto front, the thesis configuration and the
/// findings' points (findings() in sweep_report.hpp), which need not be Pareto-optimal.
void mark_verify(SweepResult& r);

/// The whole sweep (throws InputError on bad input, SimulatorError on a tool failure).
/// The RTL checks call cosim::run_ghdl and vl::run_verilate. Progress on stderr.
SweepResult run_sweep(const SweepOptions& o);

}  // namespace hc::sweep

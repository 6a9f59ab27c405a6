// stage_equivalence.hpp: the model's stage functions proven equal to the RTL's entities,
// for every input, at a configuration's generics.
//
// For one datapath entity and one Formats: GHDL synthesises the entity at the configuration's
// generics (a constant wider than 32 bits, which GHDL writes as a quoted bit string, read as a
// sized literal), yosys ties its write, enable and reset ports to their active and inactive levels,
// turns every register into an input (its current value, <reg>.q) and an output (its next
// value, <reg>.d) (`expose -evert-dff`) and writes the transition as SMT-LIB. The model's
// stage function (model/harris/*.hpp) runs on SmtWord over the same inputs and current
// registers; the miter asks z3 (resource limit, not time) for an input where one next
// register differs:
//   unsat: proven equal for every input (within the stage's input domain where one is
//          assumed, see below), then asked again of a second solver (cvc5) on the same file;
//   sat:   a counterexample (the inputs), checked concretely on the model's Word arithmetic;
//          asked again with every signed resize to fewer bits written as a plain truncation
//          (what GHDL 2.0's synthesis makes of numeric_std's resize): unsat there means the
//          netlist differs from the VHDL because such a shrink overflows, not an RTL fault.
//          Where the overflow lies outside the stage's input domain (the interval bound of the
//          registers that feed it, proven where the bound fits), the proof is asked again on
//          that domain, and holds for the VHDL because the shrink cannot overflow there;
//   unknown: open (z3's resource limit reached).
// Stages: sobel_x, sobel_y, m_products, block_filter, harris_response (both steps together:
// the products and the k-term from a, b, c; the response from the current step-1 registers,
// which hold step 1's values of the block sums of the write before, a_prev, b_prev, c_prev,
// free or in their domain as a, b, c are), threshold (r0_delay and r1 from r0, thr and the
// current r0_delay, enable high), find_max (count, running and max from the centre response
// and the current registers, enable high, at the geometry's period), local_maximum (the
// corner bit from the 3x3 thresholded responses; combinational, so its output is compared
// rather than a next register).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "model/harris/harris_pkg.hpp"

namespace hc::sweep {

enum class EqStage { sobel_x, sobel_y, m_products, block_filter, harris_response, threshold, find_max, local_maximum, count };
inline constexpr int kEqStageCount = static_cast<int>(EqStage::count);
inline constexpr std::array<const char*, kEqStageCount> kEqStageNames{
    "sobel_x", "sobel_y", "m_products", "block_filter", "harris_response", "threshold", "find_max", "local_maximum"};
/// The stage named `name`; InputError naming it otherwise.
EqStage eq_stage(const std::string& name);
/// The name of the Sobel stages' input pixel (i, j) of the 3x3 window (row i, column j, from 0)
/// in their queries and counterexamples: "p_<i>_<j>".
std::string pixel_input(int i, int j);

enum class EqVerdict { equal, counterexample, netlist_differs, open };
/// "proven equal", "counterexample", "netlist differs from the VHDL", "open"
const char* eq_verdict_name(EqVerdict v);

struct StageProof {
    EqStage stage = EqStage::sobel_x;
    EqVerdict verdict = EqVerdict::open;
    std::string solver = "z3";          ///< the solver that decided it
    std::int64_t rlimit = 0;            ///< z3's resource units spent (every query of the stage)
    double seconds = 0;                 ///< wall time of the stage: synthesis, queries, second solver
    std::string assumed;                ///< the input domain the proof assumes ("" : every input)
    std::string recheck;                ///< the second solver's answer: "cvc5: unsat", "cvc5: unknown (...)", ...
    bool rechecked = false;             ///< the second solver proved it too (unsat)
    std::map<std::string, std::int64_t> counterexample;   ///< input (and current register) values, by name
    std::string detail;                 ///< the differing output (model and netlist values), the shrink, the note
    std::string command;                ///< the one command that reruns the proof
    /// a counterexample written as a co-simulation stimulus (stage_stimulus.hpp): its
    /// regression-set file, "" where there is none (no counterexample, no options dir, or
    /// inputs no pixel window gives)
    std::string stimulus;
};

struct StageOptions {
    /// z3's resource limit per query; on this project's machine z3 spends about 5 million
    /// units per second of CPU, so 300 million is about 60 s
    std::int64_t rlimit = 300'000'000;
    /// cvc5's limit for the second proof, wall-clock (its resource limit does not stop it in
    /// time on these queries): the second proof's answer may depend on the machine, z3's does not
    int recheck_seconds = 20;
    bool recheck = true;                       ///< ask cvc5 again where z3 proves
    /// keep the netlist, the yosys script and the queries here (one folder per stage; the
    /// rerun commands name them); empty: a scratch directory, and the command names files gone
    std::filesystem::path dir;
    std::filesystem::path rtl_dir;             ///< the VHDL (empty: the project's rtl/)
    /// the image size find_max's period is built for (its IMG_WIDTH, IMG_HEIGHT generics)
    Geometry geometry;
    /// the configuration's name: a counterexample's stimulus is written (when `dir` is set) as
    /// <dir>/stimulus/<config>_<stage>.pgm with its regression-set file and golden files
    std::string config = "thesis";
};

/// The ports yosys's write_smt2 declares in `smt` (`; yosys-smt2-input|output NAME W`): their
/// widths by name.
std::map<std::string, int> yosys_smt2_ports(const std::string& smt);

/// The proof of one stage at formats `f`. SimulatorError when GHDL or yosys fails; a
/// counterexample that does not hold in the model is std::logic_error.
StageProof prove_stage(EqStage s, const Formats& f, const StageOptions& o = {});

struct StageEquivalence {
    Formats formats;
    std::vector<StageProof> stages;
    double seconds = 0;
    bool cached = false;   ///< read from cached_stage_equivalence's cache, not proven by this call
    /// "8 proven equal" or "7 proven equal, harris_response: netlist differs from the VHDL"
    std::string summary() const;
    /// The sweep's column: "8/8 proven", or the proven count and the others by verdict,
    /// "7 proven, 1 netlist differs (harris_response)"
    std::string column() const;
    /// Every stage proven equal, each for every input of its domain (a signed shrink that
    /// overflows only outside the domain included): the datapath stages of the netlist are
    /// GHDL's synthesis of the VHDL the model agrees with, for every input. Not control,
    /// load control or the shift registers, which no stage proof covers.
    bool all_proven() const;
};
/// Every stage (in EqStage order) at formats `f`, each in o.dir/<stage> when o.dir is set.
StageEquivalence stage_equivalence(const Formats& f, const StageOptions& o = {});
/// stage_equivalence(f, o), remembered in cache_dir/<key>.json: `key` is the sweep's synthesis
/// key (cost_key: the RTL's contents, the generics of formats and geometry, GHDL's and yosys's
/// versions, how GHDL's Verilog is read), and the entry also records the options that can change
/// a verdict (resource limit, second solver and its time, geometry, rtl_dir); an entry made
/// under other options, or unreadable, is proven again and overwritten. The result's `cached`
/// says which. Only a run that finished is recorded.
StageEquivalence cached_stage_equivalence(const Formats& f, const std::string& key, const std::filesystem::path& cache_dir,
                                          const StageOptions& o = {});

/// One row per stage: verdict, solvers, seconds, assumptions, the command that reruns it.
std::string stage_equivalence_markdown(const std::string& config, const StageEquivalence& r);

nlohmann::json stage_equivalence_to_json(const StageEquivalence& r);
StageEquivalence stage_equivalence_from_json(const nlohmann::json& j);   ///< throws on a malformed document

}  // namespace hc::sweep

// control_induction.hpp: harris_top's control registers proven to follow the cycle model's
// from reset, for every input sequence, on GHDL's netlist of the whole design.
//
// The control registers (load control's row, col and load; input_converter_mux's row counter
// i and its delays i_dly; the stage enables t; find_max's period counter count) move on each
// write by the number of writes alone. Their frame part (all but find_max's counter) repeats
// every frame; the whole state only after P / gcd(P, E) frames (P find_max's period, E the
// writes of a frame that enable it), too many states to ask one by one at large sizes. So the
// counter is kept symbolic. The cycle model (HarrisTopT, model/harris/harris_top_t.hpp) is run
// concretely from reset (HarrisTopT::control() after each write): its distinct frame parts
// c_0 ... c_{prefix+period-1} until one repeats, then once more until its whole control state
// repeats, checking at every write that the next frame part is c_{k+1} (c_prefix after the
// last) and that each state k moves the counter by one rule: unchanged, or +1 but for one wrap
// value (the rule f_k and the counter's range [lo, hi] are read off this run, and past it the
// model repeats itself).
//
// The netlist: GHDL synthesises harris_top at the geometry and formats (OBSERVE false), yosys
// ties rst high and write high, flattens it, turns every register into an input (its current
// value) and an output (its next value) (`expose -evert-dff`) and writes the transition as
// SMT-LIB, cut to the cone of the control registers' next values (every register stays an
// input, free unless a query fixes it). One query per frame part k: with the netlist's frame
// part at c_k, its counter any value in [lo, hi], and every other register (every datapath
// register, the windows, the delays of the pixels) and the written word free, is a next
// frame-part register other than c_{k+1}, or the next counter other than f_k(counter)? All
// unsat, and the netlist's reset state (the reset value of a register the reset sets, the
// declared initial value of one it does not: i_dly, count) equal to the model's, is the
// induction: after any number of writes n, of any pixels, the netlist's control registers hold
// the model's (by induction on n, the model's counter in [lo, hi] at every n). Each query is
// preceded by a check of the state alone, which must be sat (the netlist's constraints admit
// it, so its unsat is not vacuous). The control state's ready, which the co-simulation
// compares, is the next t(0), so it is covered as well. z3 answers the queries (one file, two
// checks per state); cvc5 answers them again, in parts run side by side.
//
// Not covered: the datapath registers (the stage proofs, stage_equivalence.hpp, prove each
// stage's next registers equal to the model's for every input; that the whole design's
// datapath registers equal the model's at every write is not proven here).
#pragma once

#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "sweep/stage_equivalence.hpp"

namespace hc::sweep {

struct ControlInductionOptions {
    /// keep the netlist, the yosys script and the query here; empty: a scratch directory
    std::filesystem::path dir;
    std::filesystem::path rtl_dir;     ///< the VHDL (empty: the project's rtl/)
    /// at most this many distinct control states are asked (more: the verdict is open)
    long max_states = 500'000;
    /// the model's run that checks the counter's rule stops here if its whole control state has
    /// not repeated by then (the verdict is then open)
    long max_writes = 1'000'000'000;
    bool recheck = true;               ///< cvc5 answers the same checks again
    int recheck_seconds = 300;         ///< cvc5's time for each part of 20,000 states (wall clock)
    int recheck_jobs = 0;              ///< cvc5's parts run at once (0: one per core)
};

/// The proof at one image size.
struct ControlInduction {
    Geometry geometry;
    EqVerdict verdict = EqVerdict::open;   ///< equal: every query unsat and the reset state is c_0
    long prefix = 0;                       ///< writes before the control states repeat
    long period = 0;                       ///< the control states' period from there
    long queries = 0;                      ///< one per distinct control state (prefix + period)
    long model_writes = 0;                 ///< writes of the model's run until its whole control state repeated
    std::pair<long, long> count_range{};   ///< find_max's counter's values in that run
    std::vector<std::string> registers;    ///< "lc.col = u.lc.col (6 bits)": model register = netlist flop
    std::string solver = "z3";
    std::string recheck;                   ///< "cvc5: 62 unsat of 62", or why not
    bool rechecked = false;                ///< cvc5 answered unsat to every query too
    double seconds = 0;                    ///< wall time: synthesis, the model's run, both solvers
    std::string detail;                    ///< the first differing state and register, or why it is open
    std::string command;                   ///< the one command that reruns the queries
};

/// How the netlist of harris_top is made for a proof: the wrapper module `top` (top.v), the
/// yosys script (top.ys, which reads harris_top.v and top.v and writes top.smt2) and the lines
/// of commands.txt after GHDL's.
struct HarrisTopScript {
    std::string top_v, script, commands;
};
struct HarrisTopNetlist {
    std::string verilog;   ///< GHDL's Verilog of harris_top (harris_top.v)
    std::string smt;       ///< yosys's SMT-LIB (top.smt2)
};
/// GHDL's synthesis of harris_top at `g` and `f` (OBSERVE false) in `dir`, then the script;
/// commands.txt rebuilds both. SimulatorError when GHDL or yosys fails.
HarrisTopNetlist synthesise_harris_top(const Formats& f, const Geometry& g, const std::filesystem::path& dir,
                                       const std::filesystem::path& rtl_dir, const HarrisTopScript& s);

/// A solver's answers in its output file, in order ("sat", "unsat" or "unknown"; nothing for
/// a missing file).
std::vector<std::string> solver_answers(const std::filesystem::path& file);

/// The proof at geometry `g` and formats `f`. SimulatorError when GHDL or yosys fails;
/// std::logic_error when a control register is not found on the netlist.
ControlInduction prove_control_from_reset(const Formats& f, const Geometry& g, const ControlInductionOptions& o = {});

/// One row per size: verdict, prefix, period, queries, second solver, seconds, command.
std::string control_induction_markdown(const std::string& config, const std::vector<ControlInduction>& r);

}  // namespace hc::sweep

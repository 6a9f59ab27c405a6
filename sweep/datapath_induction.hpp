// datapath_induction.hpp: every register of GHDL's netlist of harris_top proven to hold the
// cycle model's value after every write from reset, for every input sequence.
//
// The relation: each register of the model (HarrisCycle, model/harris/harris_top_t.hpp: the
// windows, the pixel delays, icm, the gradients, M coefficients, block sums, step 1's terms,
// responses, delayed and thresholded responses, find_max's counter, running and published
// maximum, the corner shift register) equals a named signal of the netlist (u.sxm element
// (i, j), u.rows3_n1_cols3_n1_hr.ac, ...), except icm before the first write and step 1's
// terms before its first enable, which the VHDL leaves undefined and the model marks so. The
// model runs on the symbolic word (SmtNumbers, sweep/smt_word.hpp), its registers being the
// netlist's signals in the current state, so each query is one clock edge of both.
//
// The control registers move by the number of writes alone (control_induction.hpp proves
// the netlist's follow the model's), and the model's datapath processes read of them only
// load, the row counter i and its delays, the stage enables t and find_max's counter (the
// code of HarrisCycle). So one query per distinct class of those values the model reaches
// from reset (with icm's and step 1's definedness), found by running the model until its
// frame part and both flags repeat, covers every reachable state: with the reset high, the
// netlist's control signals at the class's values, find_max's counter any value in 1 .. its
// period, every datapath register equal to the model's and the written word free, is a next
// register other than the model's? All unsat (each hypothesis alone sat), and the netlist one
// clock edge after power-up (its declared initial values) with the reset low, then high,
// equal to the model's reset state, is the induction: after every write, every register of
// the netlist holds the model's, for every input sequence. The queries are files after one
// head (yosys's transition system instantiated at two states as plain bit-vector logic),
// answered side by side by z3, then by cvc5.
//
// Where a signed resize to fewer bits could overflow, GHDL 2.0's netlist truncates where
// numeric_std keeps the sign (docs/stage-equivalence.md): the relation then carries the
// registers' proven ranges (docs/derived-ranges.md) as invariants, and every signed resize of
// the model's write is a side condition (it does not overflow) that the step query assumes.
// Both are proven on the model alone with the current registers free: the invariants in the
// next state under each class's hypothesis, each distinct resize once under the invariants of
// the current state (without overflow); so the proof is about the VHDL's semantics wherever
// the netlist's could differ.
#pragma once

// the control registers' proof, on which this one builds (its geometry, formats, verdicts)
#include "sweep/control_induction.hpp"

namespace hc::sweep {

struct DatapathInductionOptions {
    /// keep the netlist, the yosys script and the queries here; empty: a scratch directory
    std::filesystem::path dir;
    std::filesystem::path rtl_dir;   ///< the VHDL (empty: the project's rtl/)
    /// the model's run that finds the control classes stops here if its frame part has not
    /// repeated (the verdict is then open)
    long max_writes = 50'000'000;
    bool recheck = true;             ///< cvc5 answers the same queries again
    int seconds = 600;               ///< each solver's time for one query
    int jobs = 0;                    ///< queries solved side by side (0: every core)
};

/// The proof at one image size.
struct DatapathInduction {
    Geometry geometry;
    EqVerdict verdict = EqVerdict::open;   ///< equal: the base and every class's step unsat
    long model_writes = 0;                 ///< writes of the model's run until its control classes repeated
    long classes = 0;                      ///< distinct control classes: one step query each
    std::vector<std::string> registers;    ///< "sxm(1,1) = u.sxm[274:264]": model register = netlist signal
    std::vector<std::string> invariants;   ///< the ranges carried with the relation
    /// the model's signed resizes to fewer bits over every class, each proven not to overflow
    /// where the class's hypothesis holds (side conditions the step queries assume)
    long side_conditions = 0;
    long distinct_side_conditions = 0;     ///< of those, the distinct ones (each proven once)
    std::string solver = "z3";
    std::string recheck;                   ///< "cvc5: 34 unsat of 34": every query and side check
    bool rechecked = false;
    double seconds = 0;                    ///< wall time: synthesis, the model's run, both solvers
    std::string detail;                    ///< the first differing class and register, or why it is open
    std::string command;                   ///< the one command that reruns the queries
};

/// The proof at geometry `g` and formats `f`. SimulatorError when GHDL or yosys fails;
/// std::logic_error when a register has no signal of its width on the netlist.
DatapathInduction prove_datapath_from_reset(const Formats& f, const Geometry& g, const DatapathInductionOptions& o = {});

/// One row per size: verdict, classes, model writes, invariants, side conditions, second
/// solver, seconds, command.
std::string datapath_induction_markdown(const std::string& config, const std::vector<DatapathInduction>& r);

}  // namespace hc::sweep

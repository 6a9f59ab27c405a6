// sweep_report.hpp: the outputs of `harris-cosim sweep`, each written atomically into the
// output directory: sweep.csv (one row per configuration), sweep.md (table, Pareto front,
// findings), sweep.json (everything), pareto.png (gnuplot: F1, recall, precision against
// LUTs and against DSPs; Pareto points marked, wrapping points crossed out).
#pragma once

#include <filesystem>
#include <string>

#include "cosim/verilator/verilate.hpp"
#include "sweep/sweep.hpp"

namespace hc::sweep {

std::string to_csv(const SweepResult& r);
std::string to_markdown(const SweepResult& r);
std::string to_json(const SweepResult& r);
/// Renders pareto.png with gnuplot (a subprocess); returns "" or why it could not.
std::string write_plot(const SweepResult& r, const std::filesystem::path& dir);
/// All of the above into `dir`.
void write_reports(const SweepResult& r, const std::filesystem::path& dir);

/// Index of the thesis configuration (always present), of the cheapest configuration with
/// recall and precision >= the thesis's (by LUTs, then DSPs; -1 if none but the thesis),
/// and of the most accurate (F1) whose LUTs and DSPs are <= the thesis's.
struct Findings {
    int thesis = -1, cheapest_as_good = -1, best_at_thesis_cost = -1;
};
Findings findings(const SweepResult& r);

/// How far a point's Verilator results stand for its VHDL (the Verilator trust column): the
/// gate's and Verilator runs' verdicts with the point's stage proofs (vl::netlist_trust).
using VerilatorTrust = vl::NetlistTrust;
VerilatorTrust verilator_trust(const PointResult& p);

}  // namespace hc::sweep

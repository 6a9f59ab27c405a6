// ghdl_verilog.hpp: GHDL's synthesised Verilog (`ghdl --synth --out=verilog`) as a Verilog
// tool must read it. Every reader of GHDL's Verilog reads it through this file: the Verilator
// netlist (cosim/verilator, sized_bit_literals() after its logged GHDL step), and through
// synth_verilog() the synthesis cost, the ranges' netlist route and the stage proofs (sweep/)
// and the mutation campaign's proofs (mutation/).
//
// GHDL 2.0 writes a constant wider than 32 bits as a quoted string of its bits ("1000...0"),
// which Verilog (Verilator, yosys read_verilog) reads as text, 8 bits per character: at a
// response wider than 32 bits, find_max's most negative value is such a string, and the tools
// read another constant. sized_bit_literals() writes each such string as the sized binary
// literal GHDL means (38'b1000...0).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/util/util.hpp"

namespace hc::cosim {

/// Every quoted string of 0s and 1s in `verilog` as a sized binary literal: "101" -> 3'b101.
/// Other quoted strings (empty, or with another character) are kept as they are.
std::string sized_bit_literals(const std::string& verilog);

/// The same rewrite as a shell filter (stdin to stdout), for the rerun commands the proofs
/// write beside their files: `ghdl --synth ... | <filter> > entity.v`.
extern const char* const kSizedBitLiteralsFilter;

/// What the readers' caches must key on besides GHDL's version and the VHDL: how GHDL's
/// Verilog is rewritten before a tool reads it (a changed rewrite makes other netlists).
extern const char* const kVerilogReading;

/// Runs `argv` (a `ghdl --synth ... --out=verilog ... -e ENTITY` command) with its stdout to
/// `verilog`, then rewrites that file by sized_bit_literals(). Returns GHDL's exit status (the
/// file is rewritten only when it is 0); `opt.stdout_file` is replaced by `verilog`.
int synth_verilog(const std::vector<std::string>& argv, const std::filesystem::path& verilog, util::ProcessOptions opt = {});

}  // namespace hc::cosim

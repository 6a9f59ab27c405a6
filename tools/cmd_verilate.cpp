// cmd_verilate.cpp: the flags of `harris-cosim verilate` (cosim/verilator/verilate_command.hpp),
// full-frame RTL verification on Verilator; they follow `harris-cosim rtl` where they apply.
#include "cosim/verilator/verilate_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_verilate_command(CLI::App& app) {
    const auto [c, a] = add_command<Sharded<vl::VerilateCommand>>(app, "verilate",
        "Full-frame RTL verification on Verilator: the GHDL-synthesised netlist against the cycle model,\n"
        "after a three-way gate (GHDL / Verilator / model on small frames) has passed.\n"
        "Exit status: 0 all agree, 1 mismatch, 2 bad input, 3 a tool failed, 4 translation fault.");
    add_frame_source_options(c, a->src);
    c->add_option("--config", a->config, "JSON file of bit widths and shifts (default: the thesis's)");
    c->add_flag("--keep-going", a->keep_going, "Count all mismatches instead of stopping at the first");
    c->add_flag("--obs", a->obs,
                "Also compare every observed inter-stage register after every write (OBSERVE netlist, slower)");
    c->add_option("--json", a->json_path, "Write the JSON summary here");
    c->add_option("--reads", a->reads_path, "Write every read as CSV: write,frame,x,y,value");
    c->add_option("--cache", a->cache, "Netlist cache directory (else $HARRIS_COSIM_VL_CACHE or the build tree)");
    c->add_option("--variant", a->variants,
                  "Test-only VHDL file replacing the rtl/ file of the entity it declares (e.g. tests/rtl/*.vhd)");
    c->add_flag("--no-gate", a->no_gate, "Skip the three-way gate (results are then marked untrusted)");
    c->add_flag("--gate-only", a->gate_only, "Run the gate only");
    c->add_flag("--build-only", a->build_only, "Build (or find) the netlist for the frames' size and stop");
    c->add_option("--sequences", a->sequences,
                  "KITTI sequences, each from its own reset: a range 00-21 or a list 00,01,05 (one shard per "
                  "sequence; --pairs applies to each; --json gets per-sequence rows and totals)");
    add_runner_flags(c, a->runner);
    c->callback([a, c] { vl::run_verilate_command(*a, job_runner(c, a->runner)); });
}

}  // namespace hc::tools

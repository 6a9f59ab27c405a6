// cmd_rtl.cpp: the flags of `harris-cosim rtl` and `harris-cosim model` (cosim/cosim_command.hpp).
#include "cosim/cosim_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_rtl_command(CLI::App& app) {
    const auto [cmd, o] = add_command<cosim::RtlCommand>(app, "rtl",
        "Co-simulate the VHDL co-processor in GHDL against the cycle-accurate model, comparing every\n"
        "inter-stage register after every write. Exit status: 0 all equal, 1 mismatch, 2 bad input,\n"
        "3 simulator failure (including a simulator older than the RTL: rebuild).");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--backend", o->backend, "GHDL back end: gcc, llvm or mcode")->capture_default_str();
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--sim-dir", o->sim_dir,
                    "gcc/llvm: directory holding another build of harris_top_tb_<backend> (e.g. the coverage build of "
                    "tools/rtl-coverage.sh); refused when older than rtl/");
    cmd->add_option("--compare", o->compare,
                    "all: every inter-stage register after every cycle; reads: only the corner bits the host reads")
        ->capture_default_str();
    cmd->add_flag("--keep-going", o->keep_going, "count every mismatch per stage instead of stopping at the first");
    cmd->add_option("--vcd", o->vcd, "VCD of the cycles around the first mismatch (RTL and model side by side)")
        ->capture_default_str();
    cmd->add_option("--wave", o->wave, "GHW waveform of the whole run (GHDL --wave; large for big frames)");
    cmd->add_option("--json", o->json_out, "write the JSON summary here");
    cmd->add_option("--reads", o->reads_out, "write every read as CSV: write,frame,x,y,value");
    cmd->add_option("--expect-reads", o->expect_reads, "fail unless the RTL's reads equal this golden CSV");
    cmd->add_option("--idle-every", o->idle_every, "insert an idle cycle (write='0') after every N writes")
        ->check(whole_number(0));
    cmd->add_option("--max-writes", o->max_writes, "stop after N writes")->check(whole_number(0));
    cmd->add_flag("--quiet", o->quiet, "no progress lines");
    cmd->callback([o] { cosim::run_rtl_command(*o); });
}

void add_model_command(CLI::App& app) {
    const auto [cmd, o] = add_command<cosim::ModelCommand>(app,
        "model", "Run the cycle-accurate model alone through the host driver's write order (no simulator).");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--reads", o->reads_out, "write every read as CSV: write,frame,x,y,value");
    cmd->add_option("--json", o->json_out, "write a JSON summary here");
    cmd->callback([o] { cosim::run_model_command(*o); });
}

}  // namespace hc::tools

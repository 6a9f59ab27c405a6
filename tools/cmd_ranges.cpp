// cmd_ranges.cpp: the flags of `harris-cosim ranges` (sweep/ranges_command.hpp): the derived
// range of every datapath register for every input.
#include "sweep/ranges_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_ranges_command(CLI::App& app) {
    const auto [cmd, o] = add_command<sweep::RangesCommand>(app, "ranges",
        "Derived ranges of every datapath register for every input: an interval bound through the model's\n"
        "stage functions; where it does not fit, a search for a pixel window that wraps the register, then z3\n"
        "on the model's arithmetic; and every register of the stage chain asked by z3 on GHDL's netlist.\n"
        "Each register is proven (cannot wrap), wraps (witness window) or open (bound, best value reached).\n"
        "z3 is limited by its resource limit (rlimit), so verdicts do not depend on the machine's speed.");
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--spec", o->spec, "sweep spec (sweep/configs/bit-widths.json): every configuration in it");
    cmd->add_option("--witnesses", o->witnesses, "write each witness window as a PGM stimulus and its --config file here");
    cmd->add_option("--set-dir", o->set_dir, "print the witnesses' regression-set lines relative to this directory (default: golden)")
        ->capture_default_str();
    cmd->add_option("--json", o->json, "the reports as JSON");
    cmd->add_option("--out", o->out, "the reports as Markdown (default: stdout)");
    cmd->add_option("--pixel-max", o->pixel_max, "pixels in [0, N]")->capture_default_str()->check(whole_number(1));
    cmd->add_option("--search-windows", o->ro.search_windows, "windows the witness search scores per register and side, at most")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--solver-rlimit", o->ro.solver_rlimit, "z3 resource units for the model route, per configuration (0: none)")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    cmd->add_option("--query-rlimit", o->ro.query_rlimit, "z3 resource units per query of the model route")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--netlist-budget", o->ro.netlist_budget, "z3 resource units for the netlist route, per configuration")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    cmd->add_option("--netlist-query-rlimit", o->ro.netlist_query_rlimit, "z3 resource units per query of the netlist route")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_flag("--no-netlist", o->no_netlist, "skip the netlist route (GHDL, yosys, z3 on the synthesised stage chain)");
    cmd->add_option("--netlist-dir", o->netlist_dir,
                    "keep the netlists (GHDL's Verilog, the yosys scripts, the SMT-LIB) here, one folder per configuration");
    cmd->add_option("--propose", o->propose,
                    "write the narrowest widths the report proves safe (drops and shifts unchanged) as a --config\n"
                    "file here, and add a section to the report: each width, base and proposed, the register and range\n"
                    "that set it (one configuration: not with --spec)");
    cmd->add_option("--stages", o->stages,
                    "also prove each stage entity's netlist equal to the model's stage function (z3, then cvc5), keeping\n"
                    "the netlists and queries under DIR/<configuration>/<stage> (the report prints the command that reruns each)");
    cmd->add_option("--rtl", o->rtl,
                    "the VHDL the stage proofs (--stages) synthesise, a directory with rtl/'s files (default: the project's\n"
                    "rtl/), e.g. a mutant's copy; the derived ranges' netlist route keeps rtl/");
    cmd->add_option("--control-induction", o->control_induction,
                    "also prove the control registers of harris_top's netlist (load control, icmux's row counter and its\n"
                    "delays, the stage enables, find_max's period counter) equal to the cycle model's from reset for every\n"
                    "input sequence, one query per state of a frame with find_max's counter symbolic (z3, then cvc5 in parts on\n"
                    "every core), keeping the files under DIR/<configuration>/<WxH>; the thesis's 640x360 takes minutes");
    cmd->add_option("--datapath-induction", o->datapath_induction,
                    "also prove every register of harris_top's netlist (the windows, pixel delays, gradients, M\n"
                    "coefficients, block sums, response terms, responses, thresholded responses, find_max's maximum, the\n"
                    "corner shift register) equal to the cycle model's from reset for every input sequence, one query per\n"
                    "control class a frame reaches (z3, then cvc5, side by side on every core), keeping the files under\n"
                    "DIR/<configuration>/<WxH>; about 6 min on 2 cores at 10x8");
    cmd->add_option("--control-sizes", o->control_sizes, "the image sizes of --control-induction and --datapath-induction, WxH")
        ->delimiter(',')->capture_default_str();
    cmd->callback([o] { sweep::run_ranges_command(*o); });
}

}  // namespace hc::tools

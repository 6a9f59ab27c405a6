// cmd_mutate.cpp: the flags of `harris-cosim mutate` (mutation/mutate_command.hpp): the
// hand-written smoke list, or with --generate every generated mutant of rtl/.
#include "mutation/mutate_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

namespace {

/// The generated campaign's flags (an option group of their own).
void add_generated_flags(CLI::App* cmd, mutation::MutateCommand& f) {
    const std::string g = "Generated mutants";
    cmd->add_flag("--generate", f.generate,
                  "run the generated mutants of rtl/ (mutation/vhdl_mutants.hpp) instead of the hand-written list:\n"
                  "kill each by co-simulation or prove it equivalent with yosys")->group(g);
    cmd->add_flag("--list", f.list_only, "with --generate: list the selected mutants' names and stop")->group(g);
    cmd->add_option("--class", f.classes, "with --generate: only these classes (arith, rel, logic, negate, literal, "
                                          "slice, resize, shift, stuck, enable)")->delimiter(',')->group(g);
    cmd->add_option("--file", f.files, "with --generate: only the mutants of these rtl/ files (e.g. sobel_x.vhd)")
        ->delimiter(',')->group(g);
    cmd->add_option("--data", f.data, "data directory for the KITTI crop stimulus (else $HARRIS_COSIM_DATA, ../shared/data)")->group(g);
    cmd->add_flag("--quick-only", f.quick_only, "with --generate: only the quick stimulus, no longer ones, no proofs")->group(g);
    cmd->add_flag("--no-prove", f.no_prove, "with --generate: report the survivors without proof attempts")->group(g);
    cmd->add_option("--proof-timeout", f.proof_timeout, "seconds per yosys proof attempt")
        ->check(CLI::Range(1, 86400))->capture_default_str()->group(g);
    cmd->add_option("--per-shard", f.per_shard, "mutants per shard (when --shards is not given)")
        ->check(CLI::Range(1, 100000))->capture_default_str()->group(g);
    cmd->add_flag("--render", f.render, "with --generate: render the report from the finished shards of the run in --run-dir "
                                        "(default <report folder>/run) without running any (marked partial when shards are missing)")->group(g);
    cmd->add_option("--reuse-verdicts", f.reuse,
                    "with --generate: a verdict CSV of an earlier run on the same rtl/ (checked by its rtl_hash):\n"
                    "its killed, stillborn and unconditionally proven verdicts stand; its surviving mutants and those\n"
                    "proven under assumptions are proven again under proven assumptions (no co-simulation runs:\n"
                    "they passed every stimulus on this rtl/); the report says which were reused")->group(g);
}

}  // namespace

void add_mutate_command(CLI::App& app) {
    const auto [cmd, o] = add_command<Sharded<mutation::MutateCommand>>(app, "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass), 1 otherwise.\n"
        "With " + cluster::sharding_flags_named() + " the mutants run in shards (run directory --run-dir, default <folder of --report>/run).\n"
        "With --generate: every generated mutant of rtl/ is killed by co-simulation or proven equivalent\n"
        "with yosys; exit status 1 when one survives.");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-smoke.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id (with --generate: names or name prefixes, "
                                       "e.g. 'sobel_x.vhd:30:', repeatable)");
    add_generated_flags(cmd, *o);
    add_runner_flags(cmd, o->runner);
    // the generated campaign always runs in shards, --jobs of them at once
    cmd->callback([o, cmd] { run_quoting_command_line(cmd, *o, mutation::run_mutate_command, o->generate); });
}

}  // namespace hc::tools

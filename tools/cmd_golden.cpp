// cmd_golden.cpp: the flags of `harris-cosim golden` (golden/golden.hpp: run_golden_command).
#include "golden/golden.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_golden_command(CLI::App& app) {
    struct Settings {
        std::string out = "golden", set;
        bool check = false;
    };
    const auto [cmd, o] = add_command<Settings>(app, "golden",
        "Regenerate the golden reference results from the cycle model (a deliberate act: review the diff),\n"
        "or with --check compare the model with the committed files (exit status 1 on any difference).");
    cmd->add_option("--out", o->out, "golden directory")->capture_default_str();
    cmd->add_option("--set", o->set, "regression-set file (default <out>/regression-set.txt)");
    cmd->add_flag("--check", o->check, "compare instead of writing; exit 1 on any difference");
    cmd->callback([o] { golden::run_golden_command(o->out, o->set, o->check); });
}

}  // namespace hc::tools

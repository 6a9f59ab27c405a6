// cmd_mutate.cpp: `harris-cosim mutate`: the mutation campaign (mutate/mutate.hpp); prints
// or writes its Markdown table (docs/mutation-smoke.md).
#include <cstdio>

#include "mutate/mutate.hpp"
#include "tools/cmd_mutants.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_mutate_command(CLI::App& app) {
    struct Opts {
        std::string list = std::string(HC_SOURCE_DIR) + "/mutate/mutations.json";
        std::string report;
        std::vector<std::string> only;
        GeneratedFlags gen;
    };
    auto o = std::make_shared<Opts>();
    CLI::App* cmd = app.add_subcommand(
        "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass), 1 otherwise.\n"
        "With --generate: every generated mutant of rtl/ is killed by co-simulation or proven equivalent\n"
        "with yosys; exit status 1 when one survives.");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-smoke.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id (with --generate: names or name prefixes, "
                                       "e.g. 'sobel_x.vhd:30:', repeatable)");
    add_generated_flags(cmd, o->gen);
    cmd->callback([o]() {
        if (o->gen.generate) {
            GeneratedFlags g = o->gen;
            g.only = o->only;
            g.report = o->report;
            run_generated(g);
            return;
        }
        if (o->only.size() > 1) throw InputError("--only takes one mutant id of the hand-written list");
        const mutate::Campaign c = mutate::load_campaign(o->list);
        const mutate::CampaignResult r =
            mutate::run_campaign(c, o->only.empty() ? "" : o->only.front(), [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); });
        const std::string md = mutate::markdown(c, r, "mutate/mutations.json");
        if (!o->report.empty()) util::write_file_atomic(o->report, md);
        else std::printf("%s", md.c_str());
        std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", r.caught, r.total, r.problems);
        if (r.problems) throw MismatchError(std::to_string(r.problems) + " mutant(s) not caught or not localised");
    });
}

}  // namespace hc::tools

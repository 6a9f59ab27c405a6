// cmd_mutate.cpp: `harris-cosim mutate`: the mutation campaign (mutate/mutate.hpp); prints
// or writes its Markdown table (docs/mutation-campaign.md).
#include <cstdio>

#include "mutate/mutate.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_mutate_command(CLI::App& app) {
    struct Opts {
        std::string list = std::string(HC_SOURCE_DIR) + "/mutate/mutations.json";
        std::string report;
        std::string only;
    };
    auto o = std::make_shared<Opts>();
    CLI::App* cmd = app.add_subcommand(
        "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass), 1 otherwise.");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-campaign.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id");
    cmd->callback([o]() {
        const mutate::Campaign c = mutate::load_campaign(o->list);
        const mutate::CampaignResult r =
            mutate::run_campaign(c, o->only, [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); });
        const std::string md = mutate::markdown(c, r, "mutate/mutations.json");
        if (!o->report.empty()) util::write_file_atomic(o->report, md);
        else std::printf("%s", md.c_str());
        std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", r.caught, r.total, r.problems);
        if (r.problems) throw MismatchError(std::to_string(r.problems) + " mutant(s) not caught or not localised");
    });
}

}  // namespace hc::tools

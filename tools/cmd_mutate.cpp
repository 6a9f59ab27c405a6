// cmd_mutate.cpp: `harris-cosim mutate`: the mutation campaign (mutate/mutate.hpp); prints
// or writes its Markdown table (docs/mutation-campaign.md).
#include <cstdio>

#include "jobs/jobs.hpp"
#include "mutate/mutate.hpp"
#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"

namespace hc::tools {

void add_mutate_command(CLI::App& app) {
    struct Opts {
        std::string list = std::string(HC_SOURCE_DIR) + "/mutate/mutations.json";
        std::string report;
        std::string only;
        RunnerFlags runner;
    };
    auto o = std::make_shared<Opts>();
    CLI::App* cmd = app.add_subcommand(
        "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass), 1 otherwise.\n"
        "With --runner or --shards the mutants run in shards (run directory --run-dir, default ./mutate-run).");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-campaign.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id");
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd]() {
        const mutate::Campaign c = mutate::load_campaign(o->list);
        mutate::CampaignResult r;
        if (cmd->count("--runner") + cmd->count("--shards") > 0) {
            const cluster::Manifest m = jobs::mutate_manifest({o->list, o->only, o->runner.shards});
            const std::filesystem::path dir = o->runner.run_dir.empty() ? std::filesystem::path("mutate-run") : std::filesystem::path(o->runner.run_dir);
            r = jobs::mutate_result(m, jobs::run_and_merge(dir, m, run_options(o->runner, dir)));
        } else {
            r = mutate::run_campaign(c, o->only, [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); });
        }
        const std::string md = mutate::markdown(c, r, "mutate/mutations.json");
        if (!o->report.empty()) util::write_file_atomic(o->report, md);
        else std::printf("%s", md.c_str());
        std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", r.caught, r.total, r.problems);
        if (r.problems) throw MismatchError(std::to_string(r.problems) + " mutant(s) not caught or not localised");
    });
}

}  // namespace hc::tools

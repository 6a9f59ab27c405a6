// cmd_mutate.cpp: `harris-cosim mutate`: the mutation campaign (mutation/smoke.hpp); prints
// or writes its Markdown table (docs/mutation-smoke.md).
#include <cstdio>

#include "mutation/mutate_job.hpp"
#include "mutation/mutation.hpp"
#include "tools/cmd_mutants.hpp"
#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"

namespace hc::tools {

void add_mutate_command(CLI::App& app) {
    struct Opts {
        std::string list = std::string(HC_SOURCE_DIR) + "/mutation/mutations.json";
        std::string report;
        std::vector<std::string> only;
        GeneratedFlags gen;   ///< gen.runner: the sharding flags of both campaigns
    };
    const auto [cmd, o] = add_command<Opts>(app, "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass), 1 otherwise.\n"
        "With " + sharding_flags_named() + " the mutants run in shards (run directory --run-dir, default <folder of --report>/run).\n"
        "With --generate: every generated mutant of rtl/ is killed by co-simulation or proven equivalent\n"
        "with yosys; exit status 1 when one survives.");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-smoke.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id (with --generate: names or name prefixes, "
                                       "e.g. 'sobel_x.vhd:30:', repeatable)");
    add_generated_flags(cmd, o->gen);
    cmd->callback([o, cmd]() {
        if (o->gen.generate) {
            GeneratedFlags g = o->gen;
            g.only = o->only;
            g.report = o->report;
            run_generated(g);
            return;
        }
        if (o->only.size() > 1) throw InputError("--only takes one mutant id of the hand-written list");
        const std::string only = o->only.empty() ? "" : o->only.front();
        const mutation::SmokeList c = mutation::load_smoke_list(o->list);
        mutation::SmokeResult r;
        const RunnerFlags& rf = o->gen.runner;
        if (sharded(cmd)) {
            const cluster::Manifest m = mutation::mutate_manifest({o->list, only, rf.shards});
            const std::filesystem::path dir = run_dir(rf, folder_of(o->report));
            const auto merged = run_sharded(dir, m, rf);
            if (!merged) return;
            r = mutation::mutate_result(m, *merged);
        } else {
            r = mutation::run_smoke_list(c, only, [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); });
        }
        const std::string md = mutation::smoke_markdown(c, r, "mutation/mutations.json");
        if (!o->report.empty()) util::write_file_atomic(o->report, md);
        else std::printf("%s", md.c_str());
        std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", r.caught, r.total, r.problems);
        if (r.problems) throw MismatchError(std::to_string(r.problems) + " mutant(s) not caught or not localised");
    });
}

}  // namespace hc::tools

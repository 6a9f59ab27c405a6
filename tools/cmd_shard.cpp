// cmd_shard.cpp: `harris-cosim shard`: the worker and merge ends of a sharded run (what the
// local runner's processes and the Slurm array tasks execute), and a status view.
#include "tools/commands.hpp"
#include "tools/registry.hpp"

namespace hc::tools {

void add_shard_command(CLI::App& app) {
    struct Settings {
        std::string dir;
        std::size_t index = 0;
    };
    const auto [cmd, o] = add_command<Settings>(app, "shard",
        "The ends of a sharded run (see --runner on eval, verilate, sweep, mutate, landmarks, slam):\n"
        "`run DIR INDEX` computes one shard, `merge DIR` folds all results into DIR/merged.json,\n"
        "`status DIR` lists the shards still without a result.");
    cmd->require_subcommand(1);
    CLI::App* run = cmd->add_subcommand("run", "compute shard INDEX of the run in DIR and write its result file");
    run->add_option("dir", o->dir, "run directory")->required();
    run->add_option("index", o->index, "shard index")->required();
    run->callback([o, run] { job_runner(run, {}).run_worker(o->dir, o->index); });
    CLI::App* merge = cmd->add_subcommand("merge", "fold every shard result of DIR into DIR/merged.json");
    merge->add_option("dir", o->dir, "run directory")->required();
    merge->callback([o] {
        cluster::merge_run(registry(), o->dir);
        std::printf("harris-cosim shard merge: wrote %s\n", cluster::merged_path(o->dir).c_str());
    });
    CLI::App* status = cmd->add_subcommand("status", "list the shards of DIR without a result");
    status->add_option("dir", o->dir, "run directory")->required();
    status->callback([o] { std::fputs(cluster::status_text(o->dir).c_str(), stdout); });
}

}  // namespace hc::tools

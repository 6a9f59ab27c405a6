// runner_flags.hpp: the flags every sharded command shares (--runner, --jobs, --shards,
// --run-dir, --resume, Slurm pass-through) and their translation into cluster::RunOptions.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include "io/cluster/cluster.hpp"

namespace hc::tools {

struct RunnerFlags {
    std::string runner = "local";   ///< local | slurm
    int jobs = 1;                   ///< local: worker processes at once
    int shards = 0;                 ///< 0: the command's default split
    int retries = 1;                ///< local: extra attempts of a failed shard
    std::string run_dir;            ///< where the manifest, shard results and logs live
    bool resume = false;            ///< reuse an existing run directory of the same manifest
    std::string partition, account, time, mem;
    bool no_wait = false;           ///< slurm: submit and return
};

/// Adds the flags to `cmd` (in an option group "Sharding").
void add_runner_flags(CLI::App* cmd, RunnerFlags& f);

/// The flags that make a command run in shards (sharded()).
inline constexpr std::array<const char*, 4> kShardingFlags{"--runner", "--shards", "--run-dir", "--resume"};
/// "the sharding flags (--runner, --shards, --run-dir, --resume)", as messages and help name them.
std::string sharding_flags_named();

/// The one sharding rule of every command: it runs in shards when --runner, --shards,
/// --run-dir or --resume is given on `cmd`, in one process otherwise. --jobs is how many
/// processes run at once: a sharded run's shards, or those a command's single run starts
/// itself (`single_jobs`: the sweep's syntheses and GHDL runs, the generated campaign's
/// pool). A command whose single run starts none refuses --jobs without a sharding flag
/// (InputError), so that no flag is silently ignored.
bool sharded(const CLI::App* cmd, bool single_jobs = false);

/// The one default run directory: --run-dir, else `<out>/run`, where `out` is the directory
/// the command writes to (its --out, the folder of its --report or --json file; the working
/// directory when it only prints).
std::filesystem::path run_dir(const RunnerFlags& f, const std::filesystem::path& out);
/// The folder of an output file as run_dir takes it ("" for a file in the working directory
/// or no file: the working directory).
std::filesystem::path folder_of(const std::string& file);

/// Sets the path of this executable (main's argv[0], resolved) for the workers it starts.
void set_program_path(const char* argv0);
/// The path set above.
const std::filesystem::path& program_path();

/// The runner options: workers are `harris-cosim shard run DIR INDEX`, the Slurm merge job
/// `harris-cosim shard merge DIR`; progress (shards done/total, ETA) printed to stderr.
/// A run directory that already holds results is refused unless --resume is given, so an
/// earlier run's results are never silently reused (InputError naming the directory).
cluster::RunOptions run_options(const RunnerFlags& f, const std::filesystem::path& dir);

/// Runs the manifest's shards in `dir` and returns the merged result (cluster::run_and_merge).
/// With --runner slurm --no-wait it submits the array and the merge job, prints their ids
/// and how to render the report once they are done (the same command with --resume), and
/// returns nothing: the caller writes no report. When every shard already has its result,
/// it merges them instead, with or without --no-wait. `fork`: the local runner forks its
/// workers (fork_workers).
std::optional<nlohmann::json> run_sharded(const std::filesystem::path& dir, const cluster::Manifest& m,
                                          const RunnerFlags& f, bool fork = false);
/// The worker's body, `harris-cosim shard run DIR INDEX` without starting the program.
void run_worker(const std::filesystem::path& dir, std::size_t index);
/// Local runner: each shard in a forked copy of this process running run_worker
/// (cluster::RunOptions::fork_worker) while this process runs no other thread, else the
/// worker program is started.
void fork_workers(cluster::RunOptions& o);

}  // namespace hc::tools

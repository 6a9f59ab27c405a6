// runner.hpp: how every command runs its job: in this process, or in shards by the local or
// Slurm runner (cluster.hpp), with one rule for "sharded", one default run directory and
// one worker program. The command line fills RunnerSettings from its sharding flags; the
// libraries' commands take a JobRunner and never ask how it was configured.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "io/cluster/cluster.hpp"

namespace hc::cluster {

/// The flags that make a command run in shards.
inline constexpr std::array<const char*, 4> kShardingFlags{"--runner", "--shards", "--run-dir", "--resume"};
/// "the sharding flags (--runner, --shards, --run-dir, --resume)", as messages and help name them.
std::string sharding_flags_named();

/// The sharding flags' values, shared by every command.
struct RunnerSettings {
    std::string runner = "local";   ///< local | slurm
    int jobs = 1;                   ///< local: worker processes at once
    int shards = 0;                 ///< 0: the command's default split
    int retries = 1;                ///< local: extra attempts of a failed shard
    std::string run_dir;            ///< where the manifest, shard results and logs live
    bool resume = false;            ///< reuse an existing run directory of the same manifest
    std::string partition, account, time, mem;
    bool no_wait = false;           ///< slurm: submit and return
    bool sharded = false;           ///< one of kShardingFlags was given: the job runs in shards
};

/// The folder of an output file as a run directory's default takes it ("" for a file in the
/// working directory or no file: the working directory).
fs::path folder_of(const std::string& file);

/// The absolute path of the program `argv0` names (through $PATH when it has no folder).
fs::path resolve_program(const char* argv0);

/// The state of the run in `dir`, as `harris-cosim shard status DIR` prints it: its job kind,
/// the shards done, and each shard still without a result (missing, with its log, or damaged,
/// with why).
std::string status_text(const fs::path& dir);

/// Runs a command's manifests: every shard in this process (cluster::run_in_process) when
/// not sharded, else by the runner the settings name, with the workers `program shard run
/// DIR INDEX` and the Slurm merge job `program shard merge DIR`, progress on stderr.
class JobRunner {
public:
    JobRunner(const JobRegistry& reg, RunnerSettings s, fs::path program, std::string version)
        : reg_(&reg), s_(std::move(s)), program_(std::move(program)), version_(std::move(version)) {}

    const RunnerSettings& settings() const { return s_; }
    bool sharded() const { return s_.sharded; }
    const JobRegistry& registry() const { return *reg_; }

    /// The one default run directory: --run-dir, else `<out>/run`, where `out` is the folder
    /// the command writes to (its --out, the folder of its --report or --json file; the
    /// working directory when empty).
    fs::path run_dir(const fs::path& out) const;

    /// The manifest's merged data: in this process when not sharded, else in shards in
    /// run_dir(out). Nothing when a Slurm run was submitted without waiting (--no-wait): the
    /// caller then writes no report. `fork`: the local runner forks its workers.
    std::optional<json> run(const Manifest& m, const fs::path& out, bool fork = false) const;
    /// The manifest's shards in the run directory `dir` itself (e.g. a second run beside the
    /// first), with the same runner. A directory that already holds results is refused
    /// unless --resume was given (InputError naming it); when every shard already has its
    /// result, they are merged, with or without --no-wait.
    std::optional<json> run_in(const fs::path& dir, const Manifest& m, bool fork = false) const;

    /// The worker's body, `program shard run DIR INDEX`.
    void run_worker(const fs::path& dir, std::size_t index) const;

private:
    RunOptions options(const fs::path& dir, bool fork) const;
    const JobRegistry* reg_;
    RunnerSettings s_;
    fs::path program_;
    std::string version_;
};

}  // namespace hc::cluster

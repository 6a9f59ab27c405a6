// cluster.hpp: long jobs split into shards, run by a pool of local processes or a Slurm job
// array, and merged from the shards' result files.
//
// A run lives in one directory:
//   DIR/manifest.json          the job kind, its common parameters and one entry per shard
//   DIR/shards/NNNNN.json      one self-describing result per finished shard (written
//                              atomically: a shard killed half-way leaves no file), with a
//                              digest of its own content; one damaged from outside (a
//                              truncated copy, a bad disk) is set aside by the next run as
//                              NNNNN.json.damaged-K and its shard runs again
//   DIR/logs/NNNNN.log         the shard's stdout/stderr (local runner) or Slurm's output
//   DIR/slurm/                 the sbatch scripts and job ids (slurm runner)
// A shard is run by a worker command (argv + "DIR" + "INDEX"), which computes the shard's
// data and calls write_result(). A merge reads every result (all must be present and belong
// to this manifest) and folds them with the job kind's merge function. Nothing in this
// library knows a job kind: those register a ShardJob (see JobRegistry).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/util/errors.hpp"

namespace hc::cluster {

namespace fs = std::filesystem;
using nlohmann::json;

/// A shard or the scheduler failed (after the retries): status 3.
struct ClusterRunError : hc::SimulatorError {
    using hc::SimulatorError::SimulatorError;
};

/// What a run computes: a job kind, parameters every shard shares, one entry per shard.
struct Manifest {
    std::string job;
    json common = json::object();
    std::vector<json> shards;

    /// FNV-1a 64 of the manifest's canonical JSON (hex): results carry it so that a merge
    /// never takes a result of another manifest.
    std::string hash() const;
    json to_json() const;
    static Manifest from_json(const json& j, const std::string& what);
};

fs::path manifest_path(const fs::path& dir);
fs::path result_path(const fs::path& dir, std::size_t index);
fs::path log_path(const fs::path& dir, std::size_t index);

/// Creates DIR (and its subfolders) and writes the manifest. If DIR already holds a manifest
/// it must be the same one (a resumed run); a different one is hc::InputError, so an
/// existing run's results are never mixed with another's.
void prepare_run(const fs::path& dir, const Manifest& m);
/// Reads DIR/manifest.json; hc::InputError naming the file when absent or corrupt.
Manifest read_manifest(const fs::path& dir);

/// A finished shard's self-description and data.
struct ShardResult {
    std::string job;
    std::size_t index = 0;
    std::string manifest_hash;
    json provenance = json::object();   ///< tool versions, input hashes, host, CPU seconds
    json data;                          ///< what the job kind's merge folds
};

/// Writes DIR/shards/NNNNN.json atomically (temporary file in the same folder, then rename),
/// with "digest": FNV-1a 64 (hex) of the result's compact JSON without that key.
void write_result(const fs::path& dir, const ShardResult& r);

/// What a shard's result file holds.
enum class ResultState {
    absent,    ///< no file
    valid,     ///< parses, its digest matches its content, and it belongs to the manifest
    damaged,   ///< does not parse, is not a shard result, or its digest does not match
};
struct ResultCheck {
    ResultState state = ResultState::absent;
    std::optional<ShardResult> result;   ///< when valid
    std::string why;                     ///< when damaged: what is wrong with it
};
/// Reads and checks the result of shard `index`. A file that is intact but belongs to
/// another run (job, index or manifest hash differ) is hc::InputError: it is not damage
/// but a mix-up of run directories, which no rerun should hide.
ResultCheck check_result(const fs::path& dir, const Manifest& m, std::size_t index);
/// The result of shard `index` if it is present, intact and belongs to `m`; nullopt when
/// absent. A damaged file (check_result) or a foreign one is hc::InputError naming it.
std::optional<ShardResult> read_result(const fs::path& dir, const Manifest& m, std::size_t index);
/// Indices of the shards without a valid result (absent or damaged), ascending.
std::vector<std::size_t> missing_shards(const fs::path& dir, const Manifest& m);

/// A damaged result moved out of the way.
struct SetAside {
    std::size_t index = 0;
    fs::path kept;      ///< where the damaged file is now (DIR/shards/NNNNN.json.damaged-K)
    std::string why;
};
/// Renames every damaged result of DIR to NNNNN.json.damaged-K (K: the first number not
/// taken), so that its shard counts as missing and the file stays for inspection; appends a
/// line naming it to the shard's log. Returns what it moved, in shard order.
std::vector<SetAside> set_aside_damaged(const fs::path& dir, const Manifest& m);

/// Progress of a run, as reported to the callback after each shard.
struct Progress {
    std::size_t done = 0, total = 0, failed = 0;
    double elapsed_s = 0, eta_s = 0;   ///< eta from the mean time per finished shard
};
using ProgressFn = std::function<void(const Progress&)>;

enum class RunnerKind { local, slurm };

struct SlurmOptions {
    std::string partition, account, time, mem;   ///< passed through when not empty
    int cpus_per_task = 1;
    int max_parallel = 0;                        ///< %N throttle of the array (0: none)
    bool wait = true;                            ///< block until the array and merge finish
    double poll_s = 1.0;                         ///< squeue polling period while waiting
    std::vector<std::string> extra;              ///< further sbatch arguments
};

struct RunOptions {
    RunnerKind runner = RunnerKind::local;
    int jobs = 1;        ///< local: processes at once
    int retries = 1;     ///< local: extra attempts of a failed shard
    std::vector<std::string> worker;   ///< argv of the worker; DIR and INDEX are appended
    /// local: when set, each shard runs in a forked copy of this process calling it with DIR
    /// and INDEX instead of starting `worker`, so no shard loads the program again (dynamic
    /// libraries, static initialisation); stdout and stderr go to the shard's log as a
    /// started worker's do, and an exception is a failed shard. Used only while this process
    /// runs no other thread (fork copies the calling thread only); else `worker` is started.
    std::function<void(const fs::path& dir, std::size_t index)> fork_worker;
    std::vector<std::string> merger;   ///< slurm: argv of the dependent merge job (DIR appended); empty: none
    SlurmOptions slurm;
    ProgressFn progress;
    /// Called with one line per damaged result set aside before the shards run (empty: none).
    std::function<void(const std::string&)> notice;
};

struct RunSummary {
    std::size_t shards = 0, ran = 0, skipped = 0;   ///< skipped: already had a result
    std::vector<std::size_t> failed;                ///< still without a result
    std::vector<SetAside> set_aside;                ///< damaged results moved away first
    std::string slurm_array_job, slurm_merge_job;   ///< job ids (slurm runner)
};

/// Runs every shard of DIR's manifest that has no valid result yet (so a second call resumes
/// an interrupted or failed run); damaged results are set aside first (set_aside_damaged,
/// each reported through `notice`) and their shards run again. Local: up to `jobs` worker processes at once, a failed
/// shard retried `retries` times. Slurm: one sbatch job array over the missing shards and,
/// if `merger` is set, a merge job depending on it (afterok); with `wait` it polls squeue
/// until both have left the queue. Returns which shards are still missing.
RunSummary run(const fs::path& dir, const RunOptions& o);

/// One job kind: how to compute a shard and how to fold the shards' data.
struct ShardJob {
    std::string name;
    /// Computes shard `index` of a manifest (its common parameters and its own entry).
    std::function<json(const json& common, const json& shard, std::size_t index)> run;
    /// Folds the shards' data, given in shard order, into the job's result.
    std::function<json(const json& common, const std::vector<json>& data)> merge;
};

class JobRegistry {
public:
    void add(ShardJob j);
    const ShardJob& at(const std::string& name) const;   ///< hc::InputError if unknown
    std::vector<std::string> names() const;

private:
    std::map<std::string, ShardJob> jobs_;
};

/// The worker's body: runs shard `index` of DIR's manifest with the registered job kind and
/// writes its result with provenance (the given tool versions, host, CPU seconds).
void run_shard(const JobRegistry& reg, const fs::path& dir, std::size_t index,
               const json& tool_versions = json::object());

/// Reads every shard's result (hc::InputError naming the missing ones) and folds them.
json merge(const JobRegistry& reg, const fs::path& dir);

/// The data of a single-process run of the same manifest: every shard computed in this
/// process, in order, then folded. Sharded runs must equal it exactly.
json run_in_process(const JobRegistry& reg, const Manifest& m);

/// `a:b` of [0, n) split into `k` contiguous parts as equal as possible, as (first, last).
std::vector<std::pair<long, long>> split_range(long first, long last, int k);
/// [first, last) of `n` items in `k` groups (k <= 0 or > n: one per item; n <= 0: none).
std::vector<std::pair<long, long>> split_items(long n, int k);

/// The file a merge writes its folded data to: DIR/merged.json.
fs::path merged_path(const fs::path& dir);

/// Folds DIR's shard results with `reg` and writes DIR/merged.json atomically.
/// hc::InputError (status 2) names missing or foreign results.
json merge_run(const JobRegistry& reg, const fs::path& dir);

/// Prepares DIR for manifest `m` (or checks it is the same run: resume), runs the shards
/// still missing through `o`'s runner, and merges them with `reg`. ClusterRunError when
/// shards are still missing after the runner's retries; the message names them and says
/// that running the same command again resumes.
json run_and_merge(const JobRegistry& reg, const fs::path& dir, const Manifest& m, const RunOptions& o);

}  // namespace hc::cluster

// jobs.hpp: the project's long jobs as shard kinds of hc::cluster. Each kind (eval,
// verilate, sweep, mutate, landmarks, slam, ...) has a function here that builds its
// manifest from typed parameters and one that adds its ShardJob to a registry; registry()
// holds every kind, so that a worker (`harris-cosim shard run DIR INDEX`) and a merge
// (`harris-cosim shard merge DIR`) can run any manifest.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "cluster/cluster.hpp"
#include "eval/report.hpp"
#include "model/harris/harris_pkg.hpp"
#include "util/util.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();
/// Each kind's registration (registry() calls them).
void add_eval_job(cluster::JobRegistry& r);
void add_verilate_job(cluster::JobRegistry& r);

/// The file a merge writes its folded data to: DIR/merged.json.
fs::path merged_path(const fs::path& dir);

/// Folds DIR's shard results with the registry and writes DIR/merged.json atomically.
/// ClusterInputError (status 2) names missing or foreign results.
json merge_run(const fs::path& dir);

/// Prepares DIR for manifest `m` (or checks it is the same run: resume), runs the shards
/// still missing through `o`'s runner, and merges them. ClusterRunError when shards are
/// still missing after the runner's retries; the message names them and says that running
/// the same command again resumes.
json run_and_merge(const fs::path& dir, const cluster::Manifest& m, const cluster::RunOptions& o);

// ---- eval (jobs/eval_job.cpp) ---------------------------------------------------------

/// `harris-cosim eval` over KITTI-layout sequences, each streamed from its own reset.
struct EvalJob {
    std::string source = "spec";          ///< spec, cycle or rtl
    fs::path kitti;                       ///< KITTI root holding sequences/
    std::vector<std::string> sequences;
    util::Range pairs{0, 1 << 30};        ///< stereo pairs of each sequence (an open end: all)
    std::string pairs_flag = "--frames";  ///< how the range is named in errors
    bool ablation = true;
    /// shards in all: at least one per sequence; spec and cycle split sequences further
    /// (by pairs, in proportion to their length), rtl never does (0: one per sequence)
    int shards = 0;
    int threads = 1;                      ///< threads of each shard (0: all cores)
};
/// The manifest of an eval run. For the cycle source split within a sequence it runs the
/// serial pre-pass: the cycle model's checkpoint at every part's first frame goes into its
/// shard entry. InputError naming missing sequences or ranges without two pairs.
cluster::Manifest eval_manifest(const EvalJob& j);
/// The report of a merged eval run (merged.json's data), without timings.
eval::Report eval_report(const json& merged);

// ---- verilate (jobs/verilate_job.cpp) -------------------------------------------------

/// `harris-cosim verilate` over KITTI-layout sequences: one shard per sequence (the netlist
/// cannot start half-way through a stream), each from its own reset.
struct VerilateJob {
    fs::path kitti;
    std::vector<std::string> sequences;
    util::Range pairs{0, 1 << 30};
    std::string pairs_flag = "--pairs";
    Formats formats;
    fs::path cache;                       ///< netlist cache (empty: the default), shared by all shards
    bool keep_going = false;
};
cluster::Manifest verilate_manifest(const VerilateJob& j);

/// Before the shards of an eval (rtl source) or verilate run start: the gate and the netlist
/// for every geometry of the manifest, so that shards find them in the cache instead of
/// building the same files at once. Progress to stderr; throws as vl::run_verilate.
void prepare_rtl(const cluster::Manifest& m);

}  // namespace hc::jobs

// jobs.hpp: the project's long jobs as shard kinds of hc::cluster. Each kind (eval,
// verilate, sweep, mutate, landmarks, slam, ...) has a function here that builds its
// manifest from typed parameters and one that adds its ShardJob to a registry; registry()
// holds every kind, so that a worker (`harris-cosim shard run DIR INDEX`) and a merge
// (`harris-cosim shard merge DIR`) can run any manifest.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "cluster/cluster.hpp"
#include "mutants/mutants.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();

/// The generated-mutants campaign (kind "mutants", jobs/mutants_job.cpp): the named mutants of
/// mutants::generate_all(), `per_shard` to a shard, each judged by mutants::run_mutant; the
/// merge lists every result in the mutants' order ({"results": [...]}). The manifest carries
/// a hash of rtl/, so a run is never resumed or merged against other RTL.
struct MutantsJob {
    std::vector<std::string> names;      ///< mutant names, in generate_all() order
    mutants::Stimulus quick = mutants::quick_stimulus();
    std::vector<mutants::Stimulus> longer;
    bool prove = true;
    int proof_timeout_s = 120;
    int per_shard = 8;                   ///< mutants per shard (ignored when shards > 0)
    int shards = 0;                      ///< number of shards (0: from per_shard)
};
cluster::Manifest mutants_manifest(const MutantsJob& p);
/// The merged data's results, in order.
std::vector<mutants::Result> mutants_results(const json& merged);
void add_mutants_job(cluster::JobRegistry& r);

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

}  // namespace hc::jobs

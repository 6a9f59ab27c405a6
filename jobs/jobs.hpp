// jobs.hpp: the project's long jobs as shard kinds of hc::cluster. Each kind (eval,
// verilate, sweep, mutate, landmarks, slam, ...) has a function here that builds its
// manifest from typed parameters and one that adds its ShardJob to a registry; registry()
// holds every kind, so that a worker (`harris-cosim shard run DIR INDEX`) and a merge
// (`harris-cosim shard merge DIR`) can run any manifest.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "cluster/cluster.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();

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

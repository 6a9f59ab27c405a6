// jobs.hpp: the project's long jobs as shard kinds of hc::cluster. Each kind (eval,
// verilate, sweep, mutate, landmarks, slam, ...) has a function here that builds its
// manifest from typed parameters and one that adds its ShardJob to a registry; registry()
// holds every kind, so that a worker (`harris-cosim shard run DIR INDEX`) and a merge
// (`harris-cosim shard merge DIR`, cluster::merge_run) can run any manifest.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "cosim/verilator/verilate_job.hpp"
#include "eval/eval_job.hpp"
#include "slam/landmarks/landmarks_job.hpp"
#include "model/harris/harris_pkg.hpp"
#include "mutation/mutants_job.hpp"
#include "mutation/mutate_job.hpp"
#include "slam/slam_job.hpp"
#include "sweep/sweep_job.hpp"
#include "io/util/util.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();

}  // namespace hc::jobs

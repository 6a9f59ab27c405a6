// slam_job.hpp: the job kind "slam" of hc::cluster, Monte-Carlo seeds of the simulator in
// shards (slam_job.cpp): a shard simulates a range of seeds (run_simulation, run_errors); the
// merge folds the runs in seed order (fold_monte_carlo), so the statistics equal
// monte_carlo's bit for bit.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "mapping/slam/consistency.hpp"

namespace hc::slam {

struct SlamJob {
    SimConfig config;
    int runs = 50;
    std::uint64_t first_seed = 1;
    double confidence = 0.95;
    int shards = 0;               ///< 0: one per seed
};
/// InputError (slam's) for a bad configuration or run count.
cluster::Manifest slam_manifest(const SlamJob& p);
MonteCarlo slam_result(const cluster::Manifest& m, const nlohmann::json& merged);
/// Adds the kind "slam" to `r`.
void add_slam_job(cluster::JobRegistry& r);

}  // namespace hc::slam

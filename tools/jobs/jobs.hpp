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
#include "slam/landmarks/landmarks.hpp"
#include "model/harris/harris_pkg.hpp"
#include "mutation/mutants_job.hpp"
#include "mutation/mutate_job.hpp"
#include "slam/slam.hpp"
#include "sweep/sweep_job.hpp"
#include "io/util/util.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();

// ---- landmarks (tools/jobs/landmarks_job.cpp) ------------------------------------------------
// The descriptor comparison: a shard computes, for one detector and a range of the
// dataset's pairs, every descriptor's matches (landmarks::match_pair). Hardware detectors
// carry state from pair to pair, so their shards span the whole dataset.

struct LandmarksShards {
    std::string dataset = "middlebury";   ///< middlebury or kitti
    fs::path root;                        ///< Middlebury folder of scenes, or the KITTI root
    bool need_truth = true;               ///< Middlebury: require disp1.png
    std::string sequence = "01";          ///< KITTI
    int first = 0, last = 0;              ///< KITTI stereo pairs [first, last)
    landmarks::ComparisonOptions options; ///< detectors, descriptors, grid, match, corners
    std::size_t pairs = 0;                ///< pairs of the dataset (to split them)
    int shards = 0;                       ///< 0: one per detector and pair
};
/// InputError (landmarks') for an impossible detector/descriptor combination.
cluster::Manifest landmarks_manifest(const LandmarksShards& p);
/// The rows of the comparison (detectors x descriptors, in the options' order), each pair's
/// result as match_pair returned it (its time included).
std::vector<landmarks::ComparisonRow> landmarks_rows(const json& merged);

// ---- slam (tools/jobs/slam_job.cpp) ----------------------------------------------------------
// A shard simulates a range of Monte-Carlo seeds (slam::run_simulation, slam::run_errors);
// the merge folds the runs in seed order (slam::fold_monte_carlo), so the statistics equal
// slam::monte_carlo's bit for bit.

struct SlamShards {
    slam::SimConfig config;
    int runs = 50;
    std::uint64_t first_seed = 1;
    double confidence = 0.95;
    int shards = 0;               ///< 0: one per seed
};
/// InputError (slam's) for a bad configuration or run count.
cluster::Manifest slam_manifest(const SlamShards& p);
slam::MonteCarlo slam_result(const cluster::Manifest& m, const json& merged);

namespace detail {
/// Registration of each kind (tools/jobs/<kind>_job.cpp).
cluster::ShardJob landmarks_job();
cluster::ShardJob slam_job();
}  // namespace detail

}  // namespace hc::jobs

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
#include "mutation/mutation.hpp"
#include "slam/slam.hpp"
#include "sweep/sweep.hpp"
#include "io/util/util.hpp"

namespace hc::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every job kind of the project.
const cluster::JobRegistry& registry();

/// The generated-mutants campaign (kind "mutants", tools/jobs/mutants_job.cpp): the named mutants of
/// mutation::generate_all(), `per_shard` to a shard, each judged by mutation::run_mutant; the
/// merge lists every result in the mutants' order ({"results": [...]}). The manifest carries
/// a hash of rtl/, so a run is never resumed or merged against other RTL.
struct MutantsJob {
    std::vector<std::string> names;      ///< mutant names, in generate_all() order
    mutation::Stimulus quick = mutation::quick_stimulus();
    std::vector<mutation::Stimulus> longer;
    bool prove = true;
    int proof_timeout_s = 120;
    int per_shard = 8;                   ///< mutants per shard (ignored when shards > 0)
    int shards = 0;                      ///< number of shards (0: from per_shard)
};
cluster::Manifest mutants_manifest(const MutantsJob& p);
/// The merged data's results, in order.
std::vector<mutation::Result> mutants_results(const json& merged);
void add_mutants_job(cluster::JobRegistry& r);
/// The finished shards of the mutants run in `dir` (`mutate --generate --render`): their
/// results in the generator's order, the manifest's stimuli and shard count, and the seconds
/// from the manifest's writing to the last finished result. InputError when `dir` holds a
/// run of another kind.
struct MutantsProgress {
    std::vector<mutation::Result> results;
    mutation::Stimulus quick;
    std::vector<mutation::Stimulus> longer;
    std::size_t shards = 0;
    double wall_seconds = 0;
};
MutantsProgress mutants_finished(const fs::path& dir);

// ---- sweep (tools/jobs/sweep_job.cpp) --------------------------------------------------------
// A shard evaluates a group of configurations (sweep::evaluate_points: synthesis cost,
// overflow audit, accuracy); the merge lists the points in spec order. The RTL checks of
// the Pareto points need the whole front: they are a second run of their own kind,
// "sweep-check", planned from the merged points (sweep::plan_checks), one shard per check.

struct SweepShards {
    std::string spec_text;        ///< the spec file's contents (the manifest carries them)
    std::string spec_name;        ///< the spec file, for messages
    fs::path kitti, cache;        ///< as sweep::SweepOptions
    fs::path middlebury;          ///< as sweep::SweepOptions ("": no landmark column)
    int threads = 1;              ///< accuracy threads per shard
    int jobs = 1;                 ///< synthesis processes per shard
    int shards = 0;               ///< 0: one per configuration
};
/// InputError (sweep's) for a bad spec.
cluster::Manifest sweep_manifest(const SweepShards& p);
/// The merged points as a result: spec, points in spec order, stream, Pareto front and the
/// points to verify marked, synthesis counts, the phases' times summed over the shards; no
/// RTL checks run.
sweep::SweepResult sweep_result(const cluster::Manifest& m, const json& merged);

/// The RTL checks of a merged sweep (kind "sweep-check"): a shard per check of `plan` (one
/// GHDL stream, the gate or the Verilator run of a point), run by sweep::CheckRunner with
/// `o`'s out, cache, KITTI root, GHDL back end and threads; the merge lists the outcomes in
/// the plan's order ({"outcomes": [...]}). The manifest carries the spec, the points'
/// formats, the trust cache keys and the regression streams: a worker reads nothing else.
cluster::Manifest sweep_check_manifest(const std::string& spec_text, const std::string& spec_name,
                                       const sweep::SweepResult& r, const sweep::CheckPlan& plan,
                                       const sweep::SweepOptions& o);
/// Folds the merged outcomes into `r` in the plan's order (sweep::apply_check, then
/// sweep::finish_checks), as sweep::check_points does. ClusterInputError when they do not
/// answer the plan's checks one for one.
void apply_sweep_checks(sweep::SweepResult& r, const sweep::CheckPlan& plan, const json& merged,
                        const sweep::SweepOptions& o);

// ---- mutate (tools/jobs/mutate_job.cpp) ------------------------------------------------------
// A shard co-simulates a group of the list's mutants (mutation::run_smoke_mutant); the first shard
// also the unmutated baseline. The manifest carries the list file's path and hash and the
// hash of rtl/: a shard refuses a list or RTL that changed since.

struct MutateShards {
    fs::path list;                ///< the mutation list (mutation/mutations.json)
    std::string only;             ///< only this mutant id ("" all)
    int shards = 0;               ///< 0: one per mutant (the baseline with the first)
};
cluster::Manifest mutate_manifest(const MutateShards& p);
/// The campaign the manifest ran (the list file read again and checked against its hash).
mutation::SmokeList mutate_campaign(const cluster::Manifest& m);
/// The verdicts in list order and the counts (mutation::tally_smoke).
mutation::SmokeResult mutate_result(const cluster::Manifest& m, const json& merged);

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
cluster::ShardJob sweep_job();
cluster::ShardJob sweep_check_job();
cluster::ShardJob mutate_job();
cluster::ShardJob landmarks_job();
cluster::ShardJob slam_job();
}  // namespace detail

}  // namespace hc::jobs

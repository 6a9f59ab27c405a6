// sweep_job.hpp: the job kinds "sweep" and "sweep-check" of hc::cluster (sweep_job.cpp). A
// "sweep" shard evaluates a group of configurations (evaluate_points: synthesis cost,
// overflow audit, accuracy); the merge lists the points in spec order. The RTL checks of
// the Pareto points need the whole front: they are a second run of their own kind,
// "sweep-check", planned from the merged points (plan_checks), one shard per check.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "sweep/sweep.hpp"

namespace hc::sweep {

struct SweepJob {
    std::string spec_text;        ///< the spec file's contents (the manifest carries them)
    std::string spec_name;        ///< the spec file, for messages
    std::filesystem::path kitti, cache;   ///< as SweepOptions
    std::filesystem::path middlebury;     ///< as SweepOptions ("": no landmark column)
    int threads = 1;              ///< accuracy threads per shard
    int jobs = 1;                 ///< synthesis processes per shard
    bool stage_proofs = false;    ///< as SweepOptions
    int shards = 0;               ///< 0: one per configuration
};
/// InputError (sweep's) for a bad spec.
cluster::Manifest sweep_manifest(const SweepJob& p);
/// The merged points as a result: spec, points in spec order, stream, Pareto front and the
/// points to verify marked, synthesis counts, the phases' times summed over the shards; no
/// RTL checks run.
SweepResult sweep_result(const cluster::Manifest& m, const nlohmann::json& merged);
/// Adds the kind "sweep" to `r`.
void add_sweep_job(cluster::JobRegistry& r);

/// The RTL checks of a merged sweep (kind "sweep-check"): a shard per check of `plan` (one
/// GHDL stream, the gate or the Verilator run of a point), run by CheckRunner with `o`'s out,
/// cache, KITTI root, GHDL back end and threads; the merge lists the outcomes in the plan's
/// order ({"outcomes": [...]}). The manifest carries the spec, the points' formats, the trust
/// cache keys and the regression streams: a worker reads nothing else.
cluster::Manifest sweep_check_manifest(const std::string& spec_text, const std::string& spec_name,
                                       const SweepResult& r, const CheckPlan& plan, const SweepOptions& o);
/// Folds the merged outcomes into `r` in the plan's order (apply_check, then finish_checks),
/// as check_points does. hc::InputError when they do not answer the plan's checks one for
/// one.
void apply_sweep_checks(SweepResult& r, const CheckPlan& plan, const nlohmann::json& merged, const SweepOptions& o);
/// Adds the kind "sweep-check" to `r`.
void add_sweep_check_job(cluster::JobRegistry& r);

}  // namespace hc::sweep

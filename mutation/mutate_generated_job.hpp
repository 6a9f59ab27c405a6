// mutate_generated_job.hpp: the job kind "mutate-generated" of hc::cluster, the generated campaign in shards
// (mutate_generated_job.cpp): the named mutants of generate_all(), `per_shard` to a shard, each judged
// by run_mutant; the merge lists every result in the mutants' order ({"results": [...]}).
// The manifest carries a hash of rtl/, so a run is never resumed or merged against other RTL.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "mutation/campaign.hpp"

namespace hc::mutation {

struct MutantsJob {
    std::vector<std::string> names;      ///< mutant names, in generate_all() order
    Stimulus quick = quick_stimulus();
    std::vector<Stimulus> longer;
    bool prove = true;
    int proof_timeout_s = 120;
    int per_shard = 8;                   ///< mutants per shard (ignored when shards > 0)
    int shards = 0;                      ///< number of shards (0: from per_shard)
};
cluster::Manifest mutants_manifest(const MutantsJob& p);
/// The merged data's results, in order.
std::vector<Result> mutants_results(const nlohmann::json& merged);
/// Adds the kind "mutate-generated" to `r`.
void add_mutate_generated_job(cluster::JobRegistry& r);

/// The finished shards of the mutants run in `dir` (`mutate --generate --render`): their
/// results in the generator's order, the manifest's stimuli and shard count, and the seconds
/// from the manifest's writing to the last finished result. InputError when `dir` holds a
/// run of another kind.
struct MutantsProgress {
    std::vector<Result> results;
    Stimulus quick;
    std::vector<Stimulus> longer;
    std::size_t shards = 0;
    double wall_seconds = 0;
};
MutantsProgress mutants_finished(const std::filesystem::path& dir);

}  // namespace hc::mutation

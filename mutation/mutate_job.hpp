// mutate_job.hpp: the job kind "mutate" of hc::cluster, the hand-written smoke list in shards
// (mutate_job.cpp). A shard co-simulates a group of the list's mutants (run_smoke_mutant) in
// a scratch copy of rtl/; the first shard also the unmutated baseline. The manifest carries
// the list file's path and hash and the hash of rtl/: a shard refuses a list or RTL that
// changed since.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "mutation/smoke.hpp"

namespace hc::mutation {

struct MutateJob {
    std::filesystem::path list;   ///< the mutation list (mutation/mutations.json)
    std::string only;             ///< only this mutant id ("" all)
    int shards = 0;               ///< 0: one per mutant (the baseline with the first)
};
cluster::Manifest mutate_manifest(const MutateJob& p);
/// The campaign the manifest ran (the list file read again and checked against its hash).
SmokeList mutate_campaign(const cluster::Manifest& m);
/// The verdicts in list order and the counts (tally_smoke).
SmokeResult mutate_result(const cluster::Manifest& m, const nlohmann::json& merged);
/// Adds the kind "mutate" to `r`.
void add_mutate_job(cluster::JobRegistry& r);

}  // namespace hc::mutation

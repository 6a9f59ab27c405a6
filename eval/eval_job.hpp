// eval_job.hpp: the job kind "eval" of hc::cluster: an evaluation over KITTI-layout
// sequences in parts (sequences.hpp), whole sequences or ranges of stereo pairs, the cycle
// source's parts starting at checkpoints of a serial pre-pass; the merge folds the parts per
// sequence (eval_job.cpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/report.hpp"
#include "io/cluster/cluster.hpp"
#include "model/util/util.hpp"

namespace hc::eval {

/// `harris-cosim eval` over KITTI-layout sequences, each streamed from its own reset.
struct EvalJob {
    std::string source = "spec";          ///< spec, cycle or rtl
    std::filesystem::path kitti;          ///< KITTI root holding sequences/
    std::vector<std::string> sequences;
    util::Range pairs{0, 1 << 30};        ///< stereo pairs of each sequence (an open end: all)
    std::string pairs_flag = "--pairs";   ///< how the range is named in errors
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
Report eval_report(const nlohmann::json& merged);
/// Adds the kind "eval" to `r`.
void add_eval_job(cluster::JobRegistry& r);

}  // namespace hc::eval

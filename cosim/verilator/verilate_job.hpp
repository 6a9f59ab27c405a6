// verilate_job.hpp: the job kind "verilate" of hc::cluster: the netlist against the cycle
// model in lock step over KITTI-layout sequences, one shard per sequence from its own reset;
// the merge lists the sequences and adds their counts (verilate_job.cpp). Also the RTL
// preparation before the shards of a run on the netlist (verilate, or eval's rtl source).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/cluster/cluster.hpp"
#include "model/util/util.hpp"
#include "model/harris/harris_pkg.hpp"

namespace hc::vl {

/// `harris-cosim verilate` over KITTI-layout sequences: one shard per sequence (the netlist
/// cannot start half-way through a stream), each from its own reset.
struct VerilateJob {
    std::filesystem::path kitti;
    std::vector<std::string> sequences;
    util::Range pairs{0, 1 << 30};
    std::string pairs_flag = "--pairs";
    Formats formats;
    std::filesystem::path cache;          ///< netlist cache (empty: the default), shared by all shards
    bool keep_going = false;
};
cluster::Manifest verilate_manifest(const VerilateJob& j);
/// Adds the kind "verilate" to `r`.
void add_verilate_job(cluster::JobRegistry& r);

/// Before the shards of an eval (rtl source) or verilate run start: the gate and the netlist
/// for every geometry of the manifest, so that shards find them in the cache instead of
/// building the same files at once. Progress to stderr; throws as run_verilate.
void prepare_rtl(const cluster::Manifest& m);

}  // namespace hc::vl

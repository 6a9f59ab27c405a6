// registry.hpp: every job kind of harris-cosim in one hc::cluster registry, assembled here
// beside the executable from the libraries that own the kinds (each library's <kind>_job.hpp
// adds its own), so that a worker (`harris-cosim shard run DIR INDEX`) and a merge
// (`harris-cosim shard merge DIR`, cluster::merge_run) can run any manifest.
#pragma once

#include "io/cluster/cluster.hpp"

namespace hc::tools {

/// Every job kind of the project: eval, verilate, sweep, sweep-check, mutate, mutants,
/// landmarks, slam.
const cluster::JobRegistry& registry();

}  // namespace hc::tools

// sweep_command.hpp: `harris-cosim sweep` as the command line hands it over: the bit-width
// exploration of a sweep spec (sweep.hpp) in one process, or its configurations in shards
// and then the RTL checks of the merged Pareto front, one shard per check (sweep_job.hpp).
#pragma once

#include <string>

#include "io/cluster/runner.hpp"

namespace hc::sweep {

/// The command's settings, one field per flag.
struct SweepCommand {
    std::string config, out = "sweep-report", cache, kitti, data, backend, middlebury, regression_set;
    int threads = 0;
    bool no_rtl = false, quiet = false;
    bool stage_proofs = false;   ///< --stage-proofs: every configuration's stage proofs (SweepOptions::stage_proofs)
    std::string command_line;   ///< the command as typed, less its sharding flags: the reports quote it
};

/// Runs the sweep and writes its reports into c.out. The runner's --jobs is also the
/// synthesis and GHDL processes at once of a single-process run. MismatchError when the RTL
/// check of a Pareto point fails, InputError for bad input.
void run_sweep_command(const SweepCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::sweep

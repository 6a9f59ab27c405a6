// mutate_command.hpp: `harris-cosim mutate` as the command line hands it over: the
// hand-written smoke list (smoke.hpp) in one process or in shards, or, with --generate, the
// generated campaign (campaign.hpp): list, run in shards, render a run's finished shards, or
// reuse an earlier run's verdicts.
#pragma once

#include <string>
#include <vector>

#include "io/cluster/runner.hpp"

namespace hc::mutation {

/// The hand-written smoke list of the source tree, mutation/mutations.json.
std::string default_smoke_list();

/// The command's settings, one field per flag.
struct MutateCommand {
    std::string list = default_smoke_list();   ///< the smoke list
    std::string report;           ///< Markdown report; with --generate the CSV and the proofs' folder beside it
    std::vector<std::string> only;
    bool generate = false;
    bool list_only = false;       ///< --list: the selected generated mutants' names
    std::vector<std::string> classes, files;
    std::string data;             ///< data directory (KITTI crop stimulus)
    bool quick_only = false;      ///< only the quick stimulus (no longer ones, no proof)
    bool no_prove = false;
    int proof_timeout = 120;
    int per_shard = 8;
    bool render = false;          ///< only render the report from the run directory's finished shards
    std::string reuse;            ///< a verdict CSV whose killed, stillborn and proven verdicts stand
    std::string command_line;     ///< the command as the user typed it (less the sharding flags), for the report
};

/// Runs the campaign the settings choose, prints or writes its report and a summary line.
/// MismatchError when a mutant is not caught or not localised (smoke list) or survives
/// (generated), InputError for bad input.
void run_mutate_command(const MutateCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::mutation

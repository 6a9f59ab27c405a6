// cmd_mutants.hpp: the generated-mutants side of `harris-cosim mutate` (--generate): its
// flags and its run (mutation/mutation.hpp through the job kind "mutants" of mutation/mutants_job.hpp).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tools/runner_flags.hpp"

namespace hc::tools {

struct GeneratedFlags {
    bool generate = false;
    bool list = false;
    std::vector<std::string> only, classes, files;
    std::string report;           ///< Markdown report; the CSV and the proofs' folder beside it
    std::string data;             ///< data directory (KITTI crop stimulus)
    bool quick_only = false;      ///< only the quick stimulus (no longer ones, no proof)
    bool no_prove = false;
    int proof_timeout = 120;
    int per_shard = 8;
    bool render = false;          ///< only render the report from --run-dir's finished shards
    std::string reuse;            ///< a verdict CSV whose killed, stillborn and proven verdicts stand
    RunnerFlags runner;
};

/// Adds --generate, --list, --class, --file, --data, --quick-only, --no-prove,
/// --proof-timeout, --per-shard, --render and the sharding flags to `mutate`. `only` and `report` are
/// bound by the caller (the hand campaign shares them).
void add_generated_flags(CLI::App* cmd, GeneratedFlags& f);
/// Lists or runs the selected generated mutants and prints or writes the report.
/// MismatchError (status 1) when a mutant survives.
void run_generated(const GeneratedFlags& f);

}  // namespace hc::tools

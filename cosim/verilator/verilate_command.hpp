// verilate_command.hpp: `harris-cosim verilate` as the command line hands it over: the
// three-way gate and the lock-step run of one stream (verilate.hpp), or KITTI sequences as a
// job of one part per sequence, in one process or in shards (verilate_job.hpp).
#pragma once

#include <string>
#include <vector>

#include "io/cluster/runner.hpp"
#include "io/frames/frames.hpp"

namespace hc::vl {

/// The command's settings, one field per flag.
struct VerilateCommand {
    frames::FrameSource src;   ///< the frame-source flags shared with `rtl` and `model`
    std::string config;        ///< JSON formats (as `rtl --config`)
    bool keep_going = false, obs = false, no_gate = false, gate_only = false, build_only = false;
    std::string json_path, reads_path, cache;
    std::vector<std::string> variants;
    std::string sequences;     ///< several KITTI sequences, each from its own reset
};

/// Runs the command, printing progress and counts on stderr and writing --json and --reads.
/// TranslationFault when GHDL's netlist and GHDL's simulation disagree, MismatchError when
/// the RTL or the netlist differs from the model, InputError for bad input.
void run_verilate_command(const VerilateCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::vl

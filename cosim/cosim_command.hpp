// cosim_command.hpp: `harris-cosim rtl` (the VHDL in GHDL against the cycle model, after
// every write: run_ghdl) and `harris-cosim model` (the cycle model alone through the host
// driver's write order: run_cycle_model) as the command line hands them over.
#pragma once

#include <string>

#include "io/frames/frames.hpp"

namespace hc::cosim {

/// `rtl`'s settings, one field per flag.
struct RtlCommand {
    frames::FrameSource src;
    std::string backend = "gcc";
    std::string config;
    std::string sim_dir;
    bool keep_going = false;
    std::string compare = "all";
    std::string wave;
    std::string vcd = "harris-cosim-mismatch.vcd";
    std::string json_out;
    std::string reads_out;
    std::string expect_reads;
    int idle_every = 0;
    long max_writes = 0;
    bool quiet = false;
};

/// Runs the co-simulation and prints its summary on stdout (progress on stderr unless
/// quiet). MismatchError when the RTL differs from the model or its reads from
/// --expect-reads, SimulatorError when the run did not complete, InputError for bad input.
void run_rtl_command(const RtlCommand& c);

/// `model`'s settings, one field per flag.
struct ModelCommand {
    frames::FrameSource src;
    std::string config;
    std::string reads_out;
    std::string json_out;
};

/// Runs the cycle model over the frames, prints one summary line, writes --reads and --json.
void run_model_command(const ModelCommand& c);

/// Compares the reads CSV `actual` with the golden file `golden` ('#' lines aside), printing
/// the first differing row or the row count. True when equal.
bool reads_equal(const std::string& golden, const std::filesystem::path& actual);

}  // namespace hc::cosim

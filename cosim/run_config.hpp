// run_config.hpp: the files that cross the process boundary between harris-cosim and the
// GHDL simulator: what one run does (RunConfig, a JSON file named by $HC_COSIM_CONFIG), the
// binary frame file it streams, and what the run found (Summary, the JSON file the bridge
// writes at the end). Each file has one schema, written and read by the code here.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc::cosim {

struct RunConfig {
    Geometry geometry;
    Formats formats;
    std::string frames_file;         ///< binary frame file (write_frames)
    std::vector<std::string> frame_names;   ///< what each frame is, for reports
    std::string backend;             ///< gcc, llvm or mcode (informational)
    bool keep_going = false;         ///< count every mismatch instead of stopping
    bool compare_all = true;         ///< every register after every cycle; false: only the reads
    int idle_every = 0;              ///< an idle (write = '0') cycle after every N writes
    long max_writes = 0;             ///< stop after this many writes (0: the whole stream)
    int post_mismatch = 8;           ///< writes simulated after the first mismatch (for the VCD)
    int pre_mismatch = 24;           ///< writes kept before it
    std::string vcd_file;            ///< VCD of the cycles around the first mismatch
    std::string summary_file;        ///< JSON summary written at the end
    std::string reads_file;          ///< CSV of every read (empty: none)
    bool progress = true;            ///< progress lines on stderr
};

std::string to_json(const RunConfig& c);
RunConfig run_config_from_json(const std::string& text);   ///< throws InternalError

/// Mismatch counts of one pipeline stage (stage_order() of model/harris/observation.hpp).
struct StageCount {
    std::string stage;
    long elements_compared_per_cycle = 0;
    long mismatching_cycles = 0;
    long mismatching_elements = 0;
    long first_mismatching_stage_cycles = 0;   ///< cycles on which it was the earliest stage
};

/// The first mismatching cycle of a run.
struct FirstMismatch {
    long write = 0;
    std::string stage;    ///< earliest mismatching stage
    std::string signal;   ///< its first mismatching element, e.g. "mbm(2,3)"
    std::string report;   ///< the one-screen report
    std::string vcd;      ///< VCD of the cycles around it (as configured)
};

/// What one co-simulation run found.
struct Summary {
    std::string backend;
    Geometry geometry;
    Formats formats;
    std::vector<std::string> frame_names;
    std::vector<long> corners_per_frame;
    bool complete = false;           ///< the whole stream (or max_writes) was simulated
    long writes = 0, writes_in_stream = 0, idle_cycles = 0, cycles = 0, reads = 0, read_mismatches = 0,
         corners = 0;
    bool compare_all = true;
    long signals_compared_per_cycle = 0, bits_compared_per_cycle = 0;
    std::vector<StageCount> stages;
    long mismatching_cycles = 0, mismatching_elements = 0, metavalue_elements = 0;
    double wall_seconds = 0, cycles_per_second = 0;
    std::optional<FirstMismatch> first_mismatch;
    bool pass() const { return mismatching_cycles == 0 && read_mismatches == 0; }
};
std::string to_json(const Summary& s);
Summary summary_from_json(const std::string& text);   ///< throws InternalError

/// Frame file: "HCFRAMES" magic, then int32 count, width, height, then the pixels.
void write_frames(const std::filesystem::path& p, const std::vector<Image>& frames);
std::vector<Image> read_frames(const std::filesystem::path& p);

}  // namespace hc::cosim

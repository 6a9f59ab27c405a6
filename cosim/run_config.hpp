// run_config.hpp: what one co-simulation run does, as the CLI hands it to the simulator
// process (a JSON file named by $HC_COSIM_CONFIG), and the binary frame file it streams.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harris/harris_pkg.hpp"
#include "image/image.hpp"

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
RunConfig run_config_from_json(const std::string& text);   ///< throws std::invalid_argument

/// Formats from a JSON object {"sobel_w": 11, ...}; missing keys keep the thesis values,
/// unknown keys are an error.
Formats formats_from_json(const std::string& text);
std::string formats_to_json(const Formats& f);

/// Frame file: "HCFRAMES" magic, then int32 count, width, height, then the pixels.
void write_frames(const std::filesystem::path& p, const std::vector<Image>& frames);
std::vector<Image> read_frames(const std::filesystem::path& p);

}  // namespace hc::cosim

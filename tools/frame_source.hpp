// frame_source.hpp: the command-line options every subcommand uses to say which frames to
// stream (image files, a KITTI sequence or a synthetic pattern), and loading them.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace hc::tools {

struct FrameSourceOptions {
    std::vector<std::string> images;   ///< image files, streamed in order
    std::string pattern;               ///< synthetic pattern name
    std::string size;                  ///< WxH: pattern size, or centred crop of images
    int frames = 0;                    ///< number of frames (patterns; first N images or pairs)
    std::string kitti;                 ///< KITTI odometry root (holding sequences/)
    std::string sequence = "01";
    std::string pairs;                 ///< a:b stereo pairs of the KITTI sequence
    std::string data;                  ///< data directory (else $HARRIS_COSIM_DATA, ../shared/data)
    std::uint32_t seed = 1;
};

void add_frame_source_options(CLI::App* cmd, FrameSourceOptions& o);

struct LoadedFrames {
    std::vector<Image> frames;
    std::vector<std::string> names;
    std::string description;
};

/// Loads the frames; throws InputError naming the bad input. With nothing chosen, three
/// 64x36 frames of the `blocks` pattern.
LoadedFrames load_frames(const FrameSourceOptions& o);

/// "WxH" -> (W, H); throws InputError.
std::pair<int, int> parse_size(const std::string& s);

}  // namespace hc::tools

// frame_source.cpp: see frame_source.hpp.
#include "tools/frame_source.hpp"

#include "tools/commands.hpp"

namespace hc::tools {

void add_frame_source_options(CLI::App* cmd, frames::FrameSource& o) {
    cmd->add_option("images", o.images, "8-bit image files streamed as chained frames, in order");
    cmd->add_option("--pattern", o.pattern, "synthetic frames: " + pattern_names());
    cmd->add_option("--size", o.size, "WxH: size of synthetic frames, or a centred crop of images/KITTI frames");
    cmd->add_option("--frames", o.frames, "number of chained frames (patterns: default 3; images/KITTI: the first N)")
        ->check(whole_number(1));
    cmd->add_option("--kitti", o.kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    cmd->add_option("--sequence", o.sequence, "KITTI sequence (with --kitti or --pairs)")->capture_default_str();
    cmd->add_option("--pairs", o.pairs, "a:b stereo pairs of the KITTI sequence (b excluded), streamed L R L R ...");
    cmd->add_option("--data", o.data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    cmd->add_option("--seed", o.seed, "seed of random patterns")->capture_default_str();
}

void add_pair_range_option(CLI::App* cmd, std::string& range, const std::string& help) {
    CLI::Option* pairs = cmd->add_option("--pairs", range, help);
    cmd->add_option("--frames", range, "the older name of --pairs (the same range a:b)")->excludes(pairs);
}

}  // namespace hc::tools

// frame_source.hpp: the command-line flags every subcommand uses to say which frames to
// stream (image files, a KITTI sequence or a synthetic pattern); io/frames/frames.hpp loads them.
#pragma once

#include <CLI/CLI.hpp>

#include "io/frames/frames.hpp"

namespace hc::tools {

/// Bad user input, as the commands throw it (status 2): the library type.
using InputError = hc::InputError;

/// Adds the frame-source flags to `cmd`, bound to `o`.
void add_frame_source_options(CLI::App* cmd, frames::FrameSource& o);

/// Adds `--pairs a:b`, a range of a KITTI sequence's stereo pairs (b excluded), the name every
/// command gives it, bound to `range`; and `--frames` as the older spelling of the same flag on
/// the commands that had it (its help says so; giving both is an error).
void add_pair_range_option(CLI::App* cmd, std::string& range, const std::string& help);

}  // namespace hc::tools

// frame_source.hpp: the command-line flags every subcommand uses to say which frames to
// stream (image files, a KITTI sequence or a synthetic pattern); frames/frames.hpp loads them.
#pragma once

#include <CLI/CLI.hpp>

#include "frames/frames.hpp"

namespace hc::tools {

/// Bad user input, as the commands throw it (status 2): the library type.
using InputError = hc::InputError;

/// Adds the frame-source flags to `cmd`, bound to `o`.
void add_frame_source_options(CLI::App* cmd, frames::FrameSource& o);

}  // namespace hc::tools

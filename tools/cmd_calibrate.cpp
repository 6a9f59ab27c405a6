// cmd_calibrate.cpp: the flags of `harris-cosim calibrate` (mapping/landmarks/calibrate_command.hpp),
// stereo calibration of a rig from chessboard pairs (docs/calibration.md).
#include "mapping/landmarks/calibrate_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_calibrate_command(CLI::App& app) {
    const auto [cmd, o] = add_command<landmarks::CalibrateCommand>(app,
        "calibrate", "stereo calibration from chessboard pairs (thesis 4.3): KITTI calib.txt, YAML/JSON with "
                     "distortion and Q, report");
    cmd->add_option("--left", o->left, "left images: files, quoted glob patterns or folders, paired in sorted order")
        ->required();
    cmd->add_option("--right", o->right, "right images: files, quoted glob patterns or folders")->required();
    cmd->add_option("--board", o->board, "inner corners per row x per column")->capture_default_str();
    cmd->add_option("--square", o->square, "side of a square (unit of T and of the baseline)")->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--min-pairs", o->min_pairs, "fewest pairs with the board in both images")->capture_default_str();
    cmd->add_option("--subpix-window", o->subpix_window,
                    "cornerSubPix half window, px (0: a third of the corner spacing, within 2..11)")
        ->capture_default_str();
    cmd->add_option("--alpha", o->alpha, "stereoRectify scaling: 0 valid pixels only, 1 all pixels, -1 OpenCV's")
        ->capture_default_str();
    cmd->add_flag("--fix-intrinsic", o->fix_intrinsic, "keep each camera's own intrinsics in the stereo optimisation");
    cmd->callback([o] { landmarks::run_calibrate_command(*o); });
}

}  // namespace hc::tools

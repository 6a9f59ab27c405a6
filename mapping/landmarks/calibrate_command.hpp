// calibrate_command.hpp: `harris-cosim calibrate` as the command line hands it over: stereo
// calibration of a rig from chessboard pairs (calib.hpp) into a KITTI-style calib.txt, the
// OpenCV YAML/JSON with the distortion model and Q, per-view errors (CSV), the worst view
// rectified (PNG) and a Markdown report (docs/calibration.md).
#pragma once

#include <string>
#include <vector>

namespace hc::landmarks {

/// The command's settings, one field per flag.
struct CalibrateCommand {
    std::vector<std::string> left, right;   ///< files, glob patterns or folders, paired in sorted order
    std::string board = "9x6", out = "calib";
    double square = 1.0, alpha = 0;
    int min_pairs = 5, subpix_window = 0;
    bool fix_intrinsic = false;
};

/// Calibrates, writes the files into c.out and prints the figures. InputError for bad input.
void run_calibrate_command(const CalibrateCommand& c);

}  // namespace hc::landmarks

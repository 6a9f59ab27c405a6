// stage_stimulus.hpp: a stage proof's counterexample as a co-simulation stimulus.
//
// A counterexample of a stage miter (stage_equivalence.hpp) is a set of values at the stage's
// inputs. Where they can be made from pixels, the stimulus is a small frame that holds a pixel
// window giving exactly those inputs at its centre: sobel_x and sobel_y take the 3x3 pixels as
// they are; m_products takes the gradients ix, iy, and z3 finds a 3x3 window whose Sobel
// gradients (the model's stage functions at the same formats) are those values, or proves that
// none has them. The frame is written as a regression-set stream (golden/regression-set.txt's
// format: the image chained twice) with its golden files made by the unmutated cycle model, so
// that the RTL the counterexample came from can be co-simulated on it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/util/util.hpp"
#include "model/harris/harris_pkg.hpp"
#include "sweep/ranges.hpp"
#include "sweep/stage_equivalence.hpp"

namespace hc::sweep {

/// The 5x5 pixel window whose centre 3x3 pixels give `p`'s counterexample at the inputs of its
/// stage at formats `f` (the border repeats the nearest of them). nullopt where the stage's
/// inputs are not made from one 3x3 window (block_filter, harris_response, threshold), where
/// `p`'s verdict is not "counterexample" (a netlist that differs from the VHDL is no
/// difference the GHDL co-simulation of the VHDL can show), or where no window gives the m_products inputs (z3 proves it, or
/// gives up at `rlimit` resource units).
std::optional<Window5> stimulus_window(const StageProof& p, const Formats& f, std::int64_t rlimit = 300'000'000);

/// A counterexample written as a regression-set stream.
struct StageStimulus {
    std::filesystem::path image;     ///< <dir>/<stem>.pgm: witness_image() of the window (16x12)
    std::filesystem::path formats;   ///< <dir>/<stem>.json, the --config file, when `f` is not the thesis's (else empty)
    std::filesystem::path set;       ///< <dir>/regression-set.txt: the stream's one line
    std::vector<std::filesystem::path> golden;   ///< <dir>/reads_<stem>_16x12.csv and maxima_<stem>_16x12.csv
    std::string line;                ///< the stream's regression-set line (paths relative to <dir>)
};

/// Writes the stimulus of `p` (stimulus_window) under `dir` with the file stem `stem`; nullopt
/// (nothing written) where stimulus_window has no window.
std::optional<StageStimulus> write_stage_stimulus(const StageProof& p, const Formats& f, const std::filesystem::path& dir,
                                                  const std::string& stem, std::int64_t rlimit = 300'000'000);

}  // namespace hc::sweep

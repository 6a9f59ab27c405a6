// evaluate.hpp: the whole evaluation of one corner source against the OpenCV reference
// (thesis section 6.3.2, docs/metrics.md): frames, reference, source, scoring, the ablation
// of each approximation (spec model), the deviation catalog (cycle source) and every output
// file (report.hpp). `harris-cosim eval` parses its flags into a Request and prints.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "eval/eval.hpp"
#include "eval/report.hpp"
#include "model/util/util.hpp"

namespace hc::eval {

struct Request {
    Source source = Source::spec;
    /// The frames (io/frames' one description, the command line's frame-source flags): with
    /// no source named, KITTI's --sequence from the data directory, else the default stereo
    /// stream (frames::open_feed with WhenNone::stereo); a KITTI stream spans two pairs at least.
    frames::FrameSource frames;
    std::vector<int> overlays;          ///< stream frames to draw as overlay_NNN.png
    std::filesystem::path out;          ///< output directory
    int threads = 0;                    ///< 0: all cores
    bool ablation = true;
    std::string command;                ///< the command line, for the report
};

/// Runs the evaluation and writes its outputs into r.out. Throws InputError (data, range,
/// overlay frame), MismatchError (the RTL source's gate fails), SimulatorError (a tool).
Report evaluate(const Request& r);


}  // namespace hc::eval

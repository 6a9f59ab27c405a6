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
#include "io/util/util.hpp"

namespace hc::eval {

struct Request {
    Source source = Source::spec;
    std::optional<frames::FrameSource> frames;   ///< images, a video or a pattern (else KITTI or the default stream)
    std::filesystem::path kitti;        ///< KITTI root (holds sequences/NN); empty: the default stream
    std::string sequence = "01";
    util::Range pairs{0, 1 << 30};      ///< stereo pairs [first, last); an open end takes them all
    std::string pairs_flag = "--pairs";    ///< how the range is named in errors
    std::vector<int> overlays;          ///< stream frames to draw as overlay_NNN.png
    std::filesystem::path out;          ///< output directory
    int threads = 0;                    ///< 0: all cores
    bool ablation = true;
    std::string command;                ///< the command line, for the report
};

/// Runs the evaluation and writes its outputs into r.out. Throws InputError (data, range,
/// overlay frame), MismatchError (the RTL source's gate fails), SimulatorError (a tool).
Report evaluate(const Request& r);

/// The stream used without KITTI data: pairs of consecutive frames of OpenCV's sample video
/// vtest.avi (opencv-doc) when installed, else the synthetic `blocks` pattern, 640x360.
Stream default_stream(int first, int last);

}  // namespace hc::eval

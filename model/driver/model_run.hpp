// model_run.hpp: the cycle model alone on a stream of frames, driven in the host driver's
// write order (no simulator): what `harris-cosim model` reports.
#pragma once

#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc {

struct ModelRun {
    long writes = 0, reads = 0;
    std::vector<long> corners_per_frame;   ///< corners the host decodes from each frame's reads
    double seconds = 0;                    ///< wall time of the stream
    /// every read as CSV, `write,frame,x,y,value` under its header (empty unless asked for)
    std::string reads_csv;
    long corners() const;                  ///< summed over the frames
};

/// Streams `frames` (all of the first frame's size, at least one) through HostDriver into
/// HarrisTop with formats `f`; with `record_reads` it also lists every read.
ModelRun run_cycle_model(const std::vector<Image>& frames, const Formats& f, bool record_reads);

}  // namespace hc

// eval_command.hpp: `harris-cosim eval` as the command line hands it over: the evaluation of
// one stream in this process (evaluate.hpp), or of KITTI sequences as a job of parts in one
// process or in shards (eval_job.hpp), the report rendered from the merged data.
#pragma once

#include <string>

#include "io/cluster/runner.hpp"
#include "io/frames/frames.hpp"

namespace hc::eval {

/// The command's settings, one field per flag.
struct EvalCommand {
    frames::FrameSource src;   ///< the frames: a KITTI sequence (the default), images, a video or a pattern
    std::string sequences;     ///< several KITTI sequences, each from its own reset
    std::string source = "spec", out = "eval-report", overlay;
    int threads = 0;
    bool threads_given = false;   ///< --threads was given (a shard otherwise runs on one)
    bool ablation = true;
    std::string command_line;     ///< the command as the user typed it (less the sharding flags), for the report
};

/// Runs the evaluation, writes the report into c.out and prints its totals. Without images,
/// a pattern or a KITTI root: the default stereo stream (frames::default_stereo_feed).
/// InputError for bad input (--frames with --sequences or sharding, which split stereo
/// pairs), MismatchError when the RTL source disagrees with the cycle model.
void run_eval_command(const EvalCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::eval

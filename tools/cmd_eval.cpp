// cmd_eval.cpp: the flags of `harris-cosim eval` (eval/eval_command.hpp), the thesis's
// precision/recall evaluation against OpenCV's Harris (docs/metrics.md).
#include "cosim/corners/corners.hpp"
#include "eval/eval_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_eval_command(CLI::App& app) {
    const auto [cmd, o] = add_command<Sharded<eval::EvalCommand>>(app,
        "eval", "precision/recall of the co-processor against OpenCV's Harris (thesis 6.3.2), with ablation");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--sequences", o->sequences,
                    "KITTI sequences, each from its own reset: a range 00-21 or a list 00,01,05 (per-sequence rows "
                    "and the total; --pairs applies to each)");
    cmd->add_option("--source", o->source, "corner source: " + corners::source_list(true))->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--overlay", o->overlay, "stream frames to draw, e.g. 2,3");
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(whole_number(0));
    cmd->add_flag("!--no-ablation", o->ablation, "skip the ablation table");
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->threads_given = cmd->count("--threads") > 0;
        run_quoting_command_line(cmd, *o, eval::run_eval_command);
    });
}

}  // namespace hc::tools

// cmd_eval.cpp: `harris-cosim eval`, the thesis's precision/recall evaluation against
// OpenCV's Harris (section 6.3.2): flags and printing around eval::evaluate
// (eval/evaluate.hpp). Protocol and metrics: docs/metrics.md; outputs: eval/report.hpp.
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "eval/evaluate.hpp"
#include "frames/frames.hpp"
#include "tools/commands.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct EvalOptions {
    std::string kitti, sequence = "01", source = "spec", out = "eval-report", frames, overlay, data;
    int threads = 0;
    bool ablation = true;
};

std::vector<int> parse_list(const std::string& s) {
    std::vector<int> v;
    for (const auto& tok : util::split_csv(s)) {
        std::size_t used = 0;
        try {
            v.push_back(std::stoi(tok, &used));
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != tok.size() || v.empty())
            throw InputError("--overlay '" + s + "' is not a comma-separated list of frame numbers");
    }
    return v;
}

void run_eval(const EvalOptions& o) {
    eval::Request r;
    r.source = eval::parse_source(o.source);
    if (!o.frames.empty()) r.pairs = util::parse_range(o.frames, "--frames");
    r.pairs_flag = "--frames " + (o.frames.empty() ? std::string("(all)") : o.frames);
    r.overlays = parse_list(o.overlay);
    if (!o.kitti.empty()) r.kitti = o.kitti;
    else if (auto d = frames::data_dir(o.data); d && fs::is_directory(*d / "kitti")) r.kitti = *d / "kitti";
    r.sequence = o.sequence;
    r.out = o.out;
    r.threads = o.threads;
    r.ablation = o.ablation;
    r.command = fmt::format("harris-cosim eval --source {}{}{} --out {}", o.source,
                            r.kitti.empty() ? "" : " --kitti " + r.kitti.string() + " --sequence " + o.sequence,
                            o.frames.empty() ? "" : " --frames " + o.frames, o.out);
    const eval::Report rep = eval::evaluate(r);
    std::fprintf(stderr, "eval: %s: recall %.6f precision %.6f (TP %llu FP %llu FN %llu) in %.2f s; report in %s\n",
                 rep.source.c_str(), rep.total.recall(), rep.total.precision(), (unsigned long long)rep.total.tp,
                 (unsigned long long)rep.total.fp, (unsigned long long)rep.total.fn, rep.seconds_total,
                 (fs::path(o.out) / "summary.md").c_str());
}

}  // namespace

void add_eval_command(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* cmd = app.add_subcommand(
        "eval", "precision/recall of the co-processor against OpenCV's Harris (thesis 6.3.2), with ablation");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence")->capture_default_str();
    cmd->add_option("--source", o->source, "corner source: spec, cycle or rtl")->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--frames", o->frames, "stereo pair range a:b (b excluded)");
    cmd->add_option("--overlay", o->overlay, "stream frames to draw, e.g. 2,3");
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(whole_number(0));
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_flag("!--no-ablation", o->ablation, "skip the ablation table");
    cmd->callback([o] { run_eval(*o); });
}

}  // namespace hc::tools

// cmd_eval.cpp: `harris-cosim eval`, the thesis's precision/recall evaluation against
// OpenCV's Harris (section 6.3.2): flags and printing around eval::evaluate
// (eval/evaluate.hpp). Protocol and metrics: docs/metrics.md; outputs: eval/report.hpp.
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "io/cluster/cluster.hpp"
#include "eval/evaluate.hpp"
#include "cosim/verilator/verilate_job.hpp"
#include "eval/eval_job.hpp"
#include "eval/sequences.hpp"
#include "io/frames/frames.hpp"
#include "tools/registry.hpp"
#include "tools/commands.hpp"
#include "tools/frame_source.hpp"
#include "tools/runner_flags.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace hc::tools {

namespace {

struct EvalOptions {
    std::string kitti, sequence = "01", sequences, source = "spec", out = "eval-report", frames, overlay, data;
    int threads = 0;
    bool ablation = true;
    RunnerFlags runner;
    bool sharded = false;        ///< a sharding flag was given
    bool threads_given = false;
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

/// Several sequences, or any run through the runner: a manifest of parts, run in this
/// process or sharded, the report rendered from the merged data only.
void run_eval_job(const EvalOptions& o, const fs::path& kitti) {
    if (!o.overlay.empty())
        throw InputError("--overlay draws frames of a single stream: leave out --sequences and the sharding flags");
    eval::EvalJob j;
    j.source = eval::source_name(eval::parse_source(o.source));
    j.kitti = kitti;
    j.sequences = o.sequences.empty() ? std::vector<std::string>{o.sequence} : eval::parse_sequences(o.sequences);
    if (!o.frames.empty()) j.pairs = util::parse_range(o.frames, "--pairs");
    j.pairs_flag = "--pairs " + (o.frames.empty() ? std::string("(all)") : o.frames);
    j.ablation = o.ablation;
    j.shards = o.sharded ? o.runner.shards : 0;
    // a shard is one process on one core unless --threads says otherwise
    j.threads = o.sharded && !o.threads_given ? 1 : o.threads;
    const cluster::Manifest m = eval::eval_manifest(j);
    if (j.source == "rtl") vl::prepare_rtl(m);
    json merged;
    if (o.sharded) {
        const fs::path dir = run_dir(o.runner, o.out);
        std::fprintf(stderr, "eval: %zu shard(s) in %s\n", m.shards.size(), dir.c_str());
        auto got = run_sharded(dir, m, o.runner, /*fork=*/true);
        if (!got) return;
        merged = std::move(*got);
    } else {
        merged = cluster::run_in_process(registry(), m);
    }
    eval::Report rep = eval::eval_report(merged);
    rep.command = fmt::format("harris-cosim eval --source {} --kitti {} --sequences {}{}{} --out {}", j.source,
                              kitti.string(), o.sequences.empty() ? o.sequence : o.sequences,
                              o.frames.empty() ? "" : " --pairs " + o.frames, o.ablation ? "" : " --no-ablation", o.out);
    fs::create_directories(o.out);
    eval::write_plot(o.out, rep);
    eval::write_reports(o.out, rep);
    for (const auto& q : rep.sequences)
        std::fprintf(stderr, "eval: sequence %s: %d scored frames, recall %.6f precision %.6f\n", q.sequence.c_str(),
                     q.scored, q.c.recall(), q.c.precision());
    std::fprintf(stderr, "eval: %s: recall %.6f precision %.6f (TP %llu FP %llu FN %llu); report in %s\n",
                 rep.source.c_str(), rep.total.recall(), rep.total.precision(), (unsigned long long)rep.total.tp,
                 (unsigned long long)rep.total.fp, (unsigned long long)rep.total.fn,
                 (fs::path(o.out) / "summary.md").c_str());
    eval::require_rtl_agreement(rep, o.out);
}

void run_eval(const EvalOptions& o) {
    if (!o.sequences.empty() || o.sharded) {
        run_eval_job(o, frames::require_kitti_root(o.kitti, o.data, "--sequences and sharded runs need KITTI data"));
        return;
    }
    eval::Request r;
    r.source = eval::parse_source(o.source);
    if (!o.frames.empty()) r.pairs = util::parse_range(o.frames, "--pairs");
    r.pairs_flag = "--pairs " + (o.frames.empty() ? std::string("(all)") : o.frames);
    r.overlays = parse_list(o.overlay);
    r.kitti = frames::kitti_root(o.kitti, o.data);   // none: the built-in stream
    r.sequence = o.sequence;
    r.out = o.out;
    r.threads = o.threads;
    r.ablation = o.ablation;
    r.command = fmt::format("harris-cosim eval --source {}{}{} --out {}", o.source,
                            r.kitti.empty() ? "" : " --kitti " + r.kitti.string() + " --sequence " + o.sequence,
                            o.frames.empty() ? "" : " --pairs " + o.frames, o.out);
    const eval::Report rep = eval::evaluate(r);
    std::fprintf(stderr, "eval: %s: recall %.6f precision %.6f (TP %llu FP %llu FN %llu) in %.2f s; report in %s\n",
                 rep.source.c_str(), rep.total.recall(), rep.total.precision(), (unsigned long long)rep.total.tp,
                 (unsigned long long)rep.total.fp, (unsigned long long)rep.total.fn, rep.seconds_total,
                 (fs::path(o.out) / "summary.md").c_str());
    eval::require_rtl_agreement(rep, o.out);
}

}  // namespace

void add_eval_command(CLI::App& app) {
    const auto [cmd, o] = add_command<EvalOptions>(app,
        "eval", "precision/recall of the co-processor against OpenCV's Harris (thesis 6.3.2), with ablation");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence")->capture_default_str();
    cmd->add_option("--sequences", o->sequences,
                    "KITTI sequences, each from its own reset: a range 00-21 or a list 00,01,05 (per-sequence rows "
                    "and the total; --pairs applies to each)");
    cmd->add_option("--source", o->source, "corner source: spec, cycle or rtl")->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    add_pair_range_option(cmd, o->frames, "stereo pair range a:b of each sequence (b excluded)");
    cmd->add_option("--overlay", o->overlay, "stream frames to draw, e.g. 2,3");
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(whole_number(0));
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_flag("!--no-ablation", o->ablation, "skip the ablation table");
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->sharded = sharded(cmd);
        o->threads_given = cmd->count("--threads") > 0;
        run_eval(*o);
    });
}

}  // namespace hc::tools

// eval_command.cpp: see eval_command.hpp.
#include "eval/eval_command.hpp"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cosim/verilator/verilate_job.hpp"
#include "eval/eval_job.hpp"
#include "eval/evaluate.hpp"
#include "eval/sequences.hpp"

namespace fs = std::filesystem;

namespace hc::eval {

namespace {

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

void print_totals(const Report& rep, const std::string& out, const std::string& timing) {
    std::fprintf(stderr, "eval: %s: recall %.6f precision %.6f (TP %llu FP %llu FN %llu)%s; report in %s\n",
                 rep.source.c_str(), rep.total.recall(), rep.total.precision(), (unsigned long long)rep.total.tp,
                 (unsigned long long)rep.total.fp, (unsigned long long)rep.total.fn, timing.c_str(),
                 (fs::path(out) / "summary.md").c_str());
}

/// Several sequences, or any run through the runner: a manifest of parts, run in this
/// process or sharded, the report rendered from the merged data only.
void run_job(const EvalCommand& c, const cluster::JobRunner& runner) {
    const frames::FrameSource& s = c.src;
    if (!c.overlay.empty())
        throw InputError("--overlay draws frames of a single stream: leave out --sequences and the sharding flags");
    if (!s.images.empty() || !s.pattern.empty())
        throw InputError("--sequences and the sharding flags evaluate KITTI sequences: leave out images and --pattern");
    const fs::path kitti = frames::require_kitti_root(s.kitti, s.data, "--sequences and sharded runs need KITTI data");
    EvalJob j;
    j.source = source_name(parse_source(c.source, "--source"));
    j.kitti = kitti;
    j.sequences = c.sequences.empty() ? std::vector<std::string>{s.sequence} : frames::parse_sequences(c.sequences);
    j.pairs = frames::job_pair_range(s);
    j.pairs_flag = frames::pairs_flag(s);
    j.ablation = c.ablation;
    j.shards = runner.sharded() ? runner.settings().shards : 0;
    // a shard is one process on one core unless --threads says otherwise
    j.threads = runner.sharded() && !c.threads_given ? 1 : c.threads;
    const cluster::Manifest m = eval_manifest(j);
    if (corners::source_info(parse_source(j.source)).needs_simulator) vl::prepare_rtl(m);
    if (runner.sharded())
        std::fprintf(stderr, "eval: %zu shard(s) in %s\n", m.shards.size(), runner.run_dir(c.out).c_str());
    const auto merged = runner.run(m, c.out, /*fork=*/true);
    if (!merged) return;
    Report rep = eval_report(*merged);
    rep.command = c.command_line;
    fs::create_directories(c.out);
    write_plot(c.out, rep);
    write_reports(c.out, rep);
    for (const auto& q : rep.sequences)
        std::fprintf(stderr, "eval: sequence %s: %d scored frames, recall %.6f precision %.6f\n", q.sequence.c_str(),
                     q.scored, q.c.recall(), q.c.precision());
    print_totals(rep, c.out, "");
    require_rtl_agreement(rep, c.out);
}

}  // namespace

void run_eval_command(const EvalCommand& c, const cluster::JobRunner& runner) {
    if (!c.src.size.empty() && c.src.images.empty() && c.src.pattern.empty())
        throw InputError("--size " + c.src.size + ": eval crops images, a video or a pattern; KITTI frames are scored whole");
    if (!c.sequences.empty() || runner.sharded()) {
        run_job(c, runner);
        return;
    }
    Request r;
    r.source = parse_source(c.source, "--source");
    r.frames = c.src;
    r.overlays = parse_list(c.overlay);
    r.out = c.out;
    r.threads = c.threads;
    r.ablation = c.ablation;
    r.command = c.command_line;
    const Report rep = evaluate(r);
    print_totals(rep, c.out, fmt::format(" in {:.2f} s", rep.seconds_total));
    require_rtl_agreement(rep, c.out);
}

}  // namespace hc::eval

// mutate_command.cpp: see mutate_command.hpp.
#include "mutation/mutate_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "io/frames/frames.hpp"
#include "mutation/mutate_generated_job.hpp"
#include "mutation/mutate_job.hpp"
#include "mutation/mutation.hpp"

namespace fs = std::filesystem;

namespace hc::mutation {

namespace {

/// Writes (or prints) the report, its CSV and the proven mutants' scripts.
void write_report(const MutateCommand& f, const cluster::RunnerSettings& s, const std::vector<Result>& rs,
                  const Stimulus& quick, const std::vector<Stimulus>& longer, int generated, std::size_t shards,
                  double wall, const std::string& reused = {}) {
    ReportInfo info;
    info.command = f.command_line;
    info.quick = quick;
    info.longer = longer;
    info.generated = generated;
    info.runner = s.runner == "local"
                      ? "local runner, " + std::to_string(s.jobs) + " jobs, " + std::to_string(shards) + " shards"
                      : "Slurm job array, " + std::to_string(shards) + " shards";
    info.wall_seconds = wall;
    info.reused = reused;
    if (!reused.empty()) info.runner.clear();   // the reuse text says what ran
    info.proofs_dir = "mutation-proofs";
    if (!f.report.empty()) write_report_files(f.report, rs, info);
    else std::printf("%s", markdown(rs, info).c_str());
}

/// The tally line of a generated campaign (`what`: the command's words), and MismatchError
/// when a mutant survives (unless `rendering`).
void print_tally(const std::vector<Result>& rs, const std::string& what, bool rendering = false, std::size_t all = 0) {
    const Tally t = tally(rs);
    std::printf("harris-cosim mutate --generate%s: %d %s: %d stillborn, %d killed, %d proven equivalent, "
                "%d proven equivalent under assumptions, %d surviving; score %.1f %%\n", what.c_str(), t.mutants,
                rendering ? ("of " + std::to_string(all) + " mutants have a verdict").c_str() : "mutants", t.stillborn,
                t.killed, t.equivalent, t.assuming, t.surviving, 100.0 * t.score());
    if (!rendering && t.surviving) throw MismatchError(std::to_string(t.surviving) + " generated mutant(s) survive");
}

/// --reuse-verdicts: the verdicts of `f.reuse` for the selection, the surviving ones and those
/// proven under assumptions proven again under proven assumptions, `jobs` at a time.
void run_reusing(const MutateCommand& f, const cluster::RunnerSettings& s, const std::vector<Mutant>& sel, int generated) {
    const auto old = results_from_csv(util::read_file(f.reuse, "--reuse-verdicts"), f.reuse, rtl_hash());
    const Reuse u = reuse_verdicts(old, sel, std::max(1, s.jobs), f.proof_timeout,
                                   [](const std::string& l) { std::fprintf(stderr, "[mutate] %s\n", l.c_str()); });
    const std::string how = reuse_note(u, f.reuse, std::max(1, s.jobs));
    write_report(f, s, u.results, quick_stimulus(), long_stimuli(frames::data_dir(f.data).value_or(fs::path{})),
                 generated, 0, 0, how);
    print_tally(u.results, " --reuse-verdicts");
}

void run_generated(const MutateCommand& f, const cluster::JobRunner& runner) {
    const cluster::RunnerSettings& s = runner.settings();
    const auto all = generate_all();
    const auto sel = select(all, {f.only, f.classes, f.files});
    if (!f.reuse.empty() && !f.list_only) {
        if (f.render) throw InputError("--reuse-verdicts and --render do not go together (--render reads a run directory)");
        run_reusing(f, s, sel, static_cast<int>(all.size()));
        return;
    }
    if (f.list_only) {
        for (const auto& m : sel) std::printf("%s\n", m.name().c_str());
        std::printf("harris-cosim mutate --generate --list: %zu of %zu generated mutants\n", sel.size(), all.size());
        return;
    }
    const fs::path dir = runner.run_dir(cluster::folder_of(f.report));
    if (f.render) {
        const MutantsProgress p = mutants_finished(dir);
        write_report(f, s, p.results, p.quick, p.longer, static_cast<int>(all.size()), p.shards, p.wall_seconds);
        print_tally(p.results, " --render", true, all.size());
        return;
    }
    MutantsJob job;
    for (const auto& m : sel) job.names.push_back(m.name());
    if (!f.quick_only) {
        const auto data = frames::data_dir(f.data);
        if (!data) std::fprintf(stderr, "[mutate] no data directory: the KITTI crop stimulus is left out\n");
        job.longer = long_stimuli(data ? *data : fs::path{});
    }
    job.prove = !f.quick_only && !f.no_prove;
    job.proof_timeout_s = f.proof_timeout;
    job.per_shard = f.per_shard;
    job.shards = s.shards;
    const cluster::Manifest m = mutants_manifest(job);
    {
        Options control;
        control.quick = job.quick;
        control.progress = [](const std::string& l) { std::fprintf(stderr, "[mutate] %s\n", l.c_str()); };
        check_unmutated(control);
    }
    std::fprintf(stderr, "[mutate] %zu generated mutants in %zu shards, run directory %s\n", sel.size(),
                 m.shards.size(), dir.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const auto got = runner.run_in(dir, m);   // always in shards: each a worker of its own
    if (!got) return;
    const auto rs = mutants_results(*got);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_report(f, s, rs, job.quick, job.longer, static_cast<int>(all.size()), m.shards.size(), wall);
    print_tally(rs, "");
}

}  // namespace

std::string default_smoke_list() { return std::string(HC_SOURCE_DIR) + "/mutation/mutations.json"; }

void run_mutate_command(const MutateCommand& c, const cluster::JobRunner& runner) {
    if (c.generate) {
        run_generated(c, runner);
        return;
    }
    if (c.only.size() > 1) throw InputError("--only takes one mutant id of the hand-written list");
    const std::string only = c.only.empty() ? "" : c.only.front();
    const SmokeList list = load_smoke_list(c.list);
    SmokeResult r;
    if (runner.sharded()) {
        const cluster::Manifest m = mutate_manifest({c.list, only, runner.settings().shards});
        const auto merged = runner.run(m, cluster::folder_of(c.report));
        if (!merged) return;
        r = mutate_result(m, *merged);
    } else {
        r = run_smoke_list(list, only, [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); });
    }
    const std::string md = smoke_markdown(list, r, "mutation/mutations.json", c.command_line);
    if (!c.report.empty()) util::write_file_atomic(c.report, md);
    else std::printf("%s", md.c_str());
    std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", r.caught, r.total, r.problems);
    if (r.problems) throw MismatchError(std::to_string(r.problems) + " mutant(s) not caught or not localised");
}

}  // namespace hc::mutation

// cmd_mutants.cpp: `harris-cosim mutate --generate`: see cmd_mutants.hpp.
#include "tools/cmd_mutants.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <fmt/format.h>

#include "io/frames/frames.hpp"
#include "mutation/mutants_job.hpp"
#include "mutation/mutation.hpp"
#include "io/util/util.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

void add_generated_flags(CLI::App* cmd, GeneratedFlags& f) {
    const std::string g = "Generated mutants";
    cmd->add_flag("--generate", f.generate,
                  "run the generated mutants of rtl/ (mutation/vhdl_mutants.hpp) instead of the hand-written list:\n"
                  "kill each by co-simulation or prove it equivalent with yosys")->group(g);
    cmd->add_flag("--list", f.list, "with --generate: list the selected mutants' names and stop")->group(g);
    cmd->add_option("--class", f.classes, "with --generate: only these classes (arith, rel, logic, negate, literal, "
                                          "slice, resize, shift, stuck, enable)")->delimiter(',')->group(g);
    cmd->add_option("--file", f.files, "with --generate: only the mutants of these rtl/ files (e.g. sobel_x.vhd)")
        ->delimiter(',')->group(g);
    cmd->add_option("--data", f.data, "data directory for the KITTI crop stimulus (else $HARRIS_COSIM_DATA, ../shared/data)")->group(g);
    cmd->add_flag("--quick-only", f.quick_only, "with --generate: only the quick stimulus, no longer ones, no proofs")->group(g);
    cmd->add_flag("--no-prove", f.no_prove, "with --generate: report the survivors without proof attempts")->group(g);
    cmd->add_option("--proof-timeout", f.proof_timeout, "seconds per yosys proof attempt")
        ->check(CLI::Range(1, 86400))->capture_default_str()->group(g);
    cmd->add_option("--per-shard", f.per_shard, "mutants per shard (when --shards is not given)")
        ->check(CLI::Range(1, 100000))->capture_default_str()->group(g);
    cmd->add_flag("--render", f.render, "with --generate: render the report from the finished shards of the run in --run-dir "
                                        "(default <report folder>/run) without running any (marked partial when shards are missing)")->group(g);
    cmd->add_option("--reuse-verdicts", f.reuse,
                    "with --generate: a verdict CSV of an earlier run on the same rtl/ (checked by its rtl_hash):\n"
                    "its killed, stillborn and unconditionally proven verdicts stand; its surviving mutants and those\n"
                    "proven under assumptions are proven again under proven assumptions (no co-simulation runs:\n"
                    "they passed every stimulus on this rtl/); the report says which were reused")->group(g);
    add_runner_flags(cmd, f.runner);
}

namespace {

std::string command_line(const GeneratedFlags& f) {
    std::string c = "harris-cosim mutate --generate";
    if (!f.classes.empty()) {
        c += " --class ";
        for (size_t i = 0; i < f.classes.size(); ++i) c += (i ? "," : "") + f.classes[i];
    }
    if (!f.files.empty()) {
        c += " --file ";
        for (size_t i = 0; i < f.files.size(); ++i) c += (i ? "," : "") + f.files[i];
    }
    for (const auto& o : f.only) c += " --only '" + o + "'";
    if (f.quick_only) c += " --quick-only";
    if (f.no_prove) c += " --no-prove";
    if (f.proof_timeout != 120) c += " --proof-timeout " + std::to_string(f.proof_timeout);
    c += " --runner " + f.runner.runner;
    if (f.runner.runner == "local") c += " --jobs " + std::to_string(f.runner.jobs);
    if (!f.report.empty()) c += " --report " + f.report;
    if (f.render) c += " --run-dir RUN --render";
    if (!f.reuse.empty()) c += " --reuse-verdicts " + f.reuse;
    return c;
}

/// Writes (or prints) the report, its CSV and the proven mutants' scripts.
void write_report(const GeneratedFlags& f, const std::vector<mutation::Result>& rs, const mutation::Stimulus& quick,
                  const std::vector<mutation::Stimulus>& longer, int generated, std::size_t shards, double wall,
                  const std::string& reused = {}) {
    mutation::ReportInfo info;
    info.command = command_line(f);
    info.quick = quick;
    info.longer = longer;
    info.generated = generated;
    info.runner = f.runner.runner == "local"
                      ? "local runner, " + std::to_string(f.runner.jobs) + " jobs, " + std::to_string(shards) + " shards"
                      : "Slurm job array, " + std::to_string(shards) + " shards";
    info.wall_seconds = wall;
    info.reused = reused;
    if (!reused.empty()) info.runner.clear();   // the reuse text says what ran
    info.proofs_dir = "mutation-proofs";
    if (!f.report.empty()) mutation::write_report_files(f.report, rs, info);
    else std::printf("%s", mutation::markdown(rs, info).c_str());
}

/// --reuse-verdicts: the verdicts of `f.reuse` for the selection, the surviving ones and those
/// proven under assumptions proven again under proven assumptions, `jobs` at a time.
void run_reusing(const GeneratedFlags& f, const std::vector<mutation::Mutant>& sel, int generated) {
    const auto old = mutation::results_from_csv(util::read_file(f.reuse, "--reuse-verdicts"), f.reuse, mutation::rtl_hash());
    const mutation::Reuse u = mutation::reuse_verdicts(old, sel, std::max(1, f.runner.jobs), f.proof_timeout,
                                                     [](const std::string& l) { std::fprintf(stderr, "[mutate] %s\n", l.c_str()); });
    const auto& rs = u.results;
    const std::string how = mutation::reuse_note(u, f.reuse, std::max(1, f.runner.jobs));
    write_report(f, rs, mutation::quick_stimulus(), mutation::long_stimuli(frames::data_dir(f.data).value_or(fs::path{})),
                 generated, 0, 0, how);
    const mutation::Tally t = mutation::tally(rs);
    std::printf("harris-cosim mutate --generate --reuse-verdicts: %d mutants: %d stillborn, %d killed, %d proven "
                "equivalent, %d proven equivalent under assumptions, %d surviving; score %.1f %%\n",
                t.mutants, t.stillborn, t.killed, t.equivalent, t.assuming, t.surviving, 100.0 * t.score());
    if (t.surviving) throw MismatchError(std::to_string(t.surviving) + " generated mutant(s) survive");
}

}  // namespace

void run_generated(const GeneratedFlags& f) {
    const auto all = mutation::generate_all();
    const auto sel = mutation::select(all, {f.only, f.classes, f.files});
    if (!f.reuse.empty() && !f.list) {
        if (f.render) throw InputError("--reuse-verdicts and --render do not go together (--render reads a run directory)");
        run_reusing(f, sel, static_cast<int>(all.size()));
        return;
    }
    if (f.list) {
        for (const auto& m : sel) std::printf("%s\n", m.name().c_str());
        std::printf("harris-cosim mutate --generate --list: %zu of %zu generated mutants\n", sel.size(), all.size());
        return;
    }
    if (f.render) {
        const mutation::MutantsProgress p = mutation::mutants_finished(run_dir(f.runner, folder_of(f.report)));
        const auto& rs = p.results;
        write_report(f, rs, p.quick, p.longer, static_cast<int>(all.size()), p.shards, p.wall_seconds);
        const mutation::Tally t = mutation::tally(rs);
        std::printf("harris-cosim mutate --generate --render: %d of %zu mutants have a verdict: %d stillborn, %d killed, "
                    "%d proven equivalent, %d proven equivalent under assumptions, %d surviving; score %.1f %%\n",
                    t.mutants, all.size(), t.stillborn, t.killed, t.equivalent, t.assuming, t.surviving,
                    100.0 * t.score());
        return;
    }
    mutation::MutantsJob job;
    for (const auto& m : sel) job.names.push_back(m.name());
    if (!f.quick_only) {
        const auto data = frames::data_dir(f.data);
        if (!data) std::fprintf(stderr, "[mutate] no data directory: the KITTI crop stimulus is left out\n");
        job.longer = mutation::long_stimuli(data ? *data : fs::path{});
    }
    job.prove = !f.quick_only && !f.no_prove;
    job.proof_timeout_s = f.proof_timeout;
    job.per_shard = f.per_shard;
    job.shards = f.runner.shards;
    const cluster::Manifest m = mutation::mutants_manifest(job);
    {
        mutation::Options control;
        control.quick = job.quick;
        control.progress = [](const std::string& s) { std::fprintf(stderr, "[mutate] %s\n", s.c_str()); };
        mutation::check_unmutated(control);
    }

    const fs::path dir = run_dir(f.runner, folder_of(f.report));
    std::fprintf(stderr, "[mutate] %zu generated mutants in %zu shards, run directory %s\n", sel.size(),
                 m.shards.size(), dir.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const auto got = run_sharded(dir, m, f.runner);
    if (!got) return;
    const nlohmann::json& merged = *got;
    const auto rs = mutation::mutants_results(merged);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_report(f, rs, job.quick, job.longer, static_cast<int>(all.size()), m.shards.size(), wall);
    const mutation::Tally t = mutation::tally(rs);
    std::printf("harris-cosim mutate --generate: %d mutants: %d stillborn, %d killed, %d proven equivalent, "
                "%d proven equivalent under assumptions, %d surviving; score %.1f %%\n", t.mutants, t.stillborn, t.killed,
                t.equivalent, t.assuming, t.surviving, 100.0 * t.score());
    if (t.surviving) throw MismatchError(std::to_string(t.surviving) + " generated mutant(s) survive");
}

}  // namespace hc::tools

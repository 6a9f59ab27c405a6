// sweep_command.cpp: see sweep_command.hpp.
#include "sweep/sweep_command.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "cosim/cosim.hpp"
#include "io/frames/frames.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_job.hpp"
#include "sweep/sweep_report.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

/// The sweep's options from the command's settings: defaults of the cache, the data and the
/// regression set resolved, each path checked.
SweepOptions sweep_options(const SweepCommand& c, int jobs) {
    SweepOptions o;
    o.spec_file = c.config;
    if (!fs::is_regular_file(o.spec_file)) throw InputError("--config '" + c.config + "': no such file");
    o.out = c.out;
    if (fs::exists(o.out) && !fs::is_directory(o.out)) throw InputError("--out '" + c.out + "' exists and is not a directory");
    o.cache = !c.cache.empty() ? fs::path(c.cache)
              : std::getenv("HARRIS_COSIM_SWEEP_CACHE") ? fs::path(std::getenv("HARRIS_COSIM_SWEEP_CACHE"))
                                                        : fs::path(HC_BUILD_DIR) / "sweep-cache";
    o.kitti = frames::require_kitti_root(c.kitti, c.data, "the sweep needs KITTI data");
    if (!c.middlebury.empty()) {
        if (!fs::is_directory(c.middlebury)) throw InputError("--middlebury '" + c.middlebury + "' is not a directory");
        o.middlebury = c.middlebury;
    } else if (auto d = frames::data_dir(c.data); d && fs::is_directory(*d / "middlebury2006" / "half")) {
        o.middlebury = *d / "middlebury2006" / "half";
    }   // else: no landmark column (the report says why)
    o.regression_set = !c.regression_set.empty() ? fs::path(c.regression_set)
                                                 : fs::path(HC_SOURCE_DIR) / "golden" / "regression-set.txt";
    if (!fs::is_regular_file(o.regression_set))
        throw InputError("--regression-set '" + o.regression_set.string() + "': no such file");
    const auto backends = cosim::ghdl_backends();
    o.ghdl_backend = !c.backend.empty() ? c.backend : backends.empty() ? "gcc" : backends.front();
    o.threads = c.threads;
    o.jobs = jobs;
    o.trust = !c.no_rtl;
    o.stage_proofs = c.stage_proofs;
    o.progress = !c.quiet;
    return o;
}

/// The configurations in shards, then the RTL checks of the merged Pareto front: a second
/// run beside the first, one shard per check. Nothing when a run was submitted without waiting.
std::optional<SweepResult> run_sharded(const SweepCommand& c, const SweepOptions& o, const cluster::JobRunner& runner) {
    const auto t0 = std::chrono::steady_clock::now();
    SweepJob p;
    p.spec_text = util::read_file(o.spec_file, "--config");
    p.spec_name = c.config;
    p.kitti = o.kitti;
    p.middlebury = o.middlebury;
    p.cache = o.cache;
    p.threads = c.threads;
    p.jobs = 1;
    p.stage_proofs = o.stage_proofs;
    p.shards = runner.settings().shards;
    const cluster::Manifest m = sweep_manifest(p);
    const fs::path dir = runner.run_dir(o.out);
    const auto merged = runner.run_in(dir, m);
    if (!merged) return std::nullopt;
    SweepResult r = sweep_result(m, *merged);
    const auto tc = std::chrono::steady_clock::now();
    const CheckPlan plan = plan_checks(r, o);
    if (!plan.tasks.empty()) {
        const cluster::Manifest cm = sweep_check_manifest(p.spec_text, p.spec_name, r, plan, o);
        const auto checked = runner.run_in(dir / "checks", cm);
        if (!checked) return std::nullopt;
        apply_sweep_checks(r, plan, *checked, o);
    }
    r.seconds_trust = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
    r.seconds_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace

void run_sweep_command(const SweepCommand& c, const cluster::JobRunner& runner) {
    const SweepOptions o = sweep_options(c, runner.settings().jobs);
    SweepResult r;
    if (runner.sharded()) {
        auto got = run_sharded(c, o, runner);
        if (!got) return;
        r = std::move(*got);
    } else {
        r = run_sweep(o);
    }
    if (!c.regression_set.empty()) r.regression_set = c.regression_set;
    r.command = c.command_line;
    write_reports(r, o.out);
    std::fprintf(stderr, "sweep: %zu configurations in %.1f s; reports in %s (sweep.md, sweep.csv, sweep.json, pareto.png)\n",
                 r.points.size(), r.seconds_total, o.out.string().c_str());
    for (const auto& p : r.points)
        if (p.verify && ((p.rtl.ran && p.rtl.failed) || (p.verilator.ran && p.verilator.failed))) {
            std::fprintf(stderr, "sweep: RTL check failed for %s: %s %s\n", p.config.name.c_str(),
                         p.rtl.detail.c_str(), p.verilator.detail.c_str());
            throw MismatchError("the RTL check of " + p.config.name + " failed");
        }
}

}  // namespace hc::sweep

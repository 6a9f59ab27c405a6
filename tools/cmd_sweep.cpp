// cmd_sweep.cpp: `harris-cosim sweep`, the bit-width exploration (sweep/sweep.hpp): accuracy
// against OpenCV, overflow audit and synthesis cost per configuration, the Pareto front,
// and every Pareto-optimal configuration run through the RTL. docs/bit-widths.md.
// Exit status: 0 done (wrapping configurations are reported, not failures), 1 an RTL
// check of a Pareto point failed, 2 bad input, 3 a tool failed.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "cosim/cosim.hpp"
#include "io/frames/frames.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_job.hpp"
#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"
#include "sweep/sweep_report.hpp"
#include "io/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct SweepCli {
    std::string config, out = "sweep-report", cache, kitti, data, backend, middlebury, regression_set;
    int threads = 0;
    bool no_rtl = false, quiet = false;
    RunnerFlags runner;   ///< runner.jobs: also the synthesis / GHDL processes at once
    bool sharded = false;
};

void run(const SweepCli& c) {
    sweep::SweepOptions o;
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
    o.jobs = c.runner.jobs;
    o.trust = !c.no_rtl;
    o.progress = !c.quiet;
    sweep::SweepResult r;
    if (c.sharded) {
        // configurations in shards, then the RTL checks of the merged Pareto front here
        const auto t0 = std::chrono::steady_clock::now();
        sweep::SweepShards p;
        p.spec_text = util::read_file(o.spec_file, "--config");
        p.spec_name = c.config;
        p.kitti = o.kitti;
        p.middlebury = o.middlebury;
        p.cache = o.cache;
        p.threads = c.threads;
        p.jobs = 1;
        p.shards = c.runner.shards;
        const cluster::Manifest m = sweep::sweep_manifest(p);
        const fs::path dir = run_dir(c.runner, o.out);
        const auto merged = run_sharded(dir, m, c.runner);
        if (!merged) return;
        r = sweep::sweep_result(m, *merged);
        // the RTL checks of the merged Pareto front: a second run, one shard per check
        const auto tc = std::chrono::steady_clock::now();
        const sweep::CheckPlan plan = sweep::plan_checks(r, o);
        if (!plan.tasks.empty()) {
            const cluster::Manifest cm = sweep::sweep_check_manifest(p.spec_text, p.spec_name, r, plan, o);
            const auto checked = run_sharded(dir / "checks", cm, c.runner);
            if (!checked) return;
            sweep::apply_sweep_checks(r, plan, *checked, o);
        }
        r.seconds_trust = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
        r.seconds_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } else {
        r = sweep::run_sweep(o);
    }
    if (!c.regression_set.empty()) r.regression_set = c.regression_set;
    r.command = fmt::format("harris-cosim sweep --config {} --out {}{}{}", c.config, c.out,
                            c.regression_set.empty() ? "" : " --regression-set " + c.regression_set,
                            c.no_rtl ? " --no-rtl" : "");
    sweep::write_reports(r, o.out);
    std::fprintf(stderr, "sweep: %zu configurations in %.1f s; reports in %s (sweep.md, sweep.csv, sweep.json, pareto.png)\n",
                 r.points.size(), r.seconds_total, o.out.string().c_str());
    for (const auto& p : r.points)
        if (p.verify && ((p.rtl.ran && p.rtl.failed) || (p.verilator.ran && p.verilator.failed))) {
            std::fprintf(stderr, "sweep: RTL check failed for %s: %s %s\n", p.config.name.c_str(),
                         p.rtl.detail.c_str(), p.verilator.detail.c_str());
            throw MismatchError("the RTL check of " + p.config.name + " failed");
        }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
    const auto [s, c] = add_command<SweepCli>(app, "sweep",
        "Bit-width exploration: per configuration of a JSON sweep spec, recall/precision against OpenCV on KITTI\n"
        "(spec model), correct stereo matches of the landmark chain on Middlebury pairs, overflow audit, yosys\n"
        "synth_xilinx cost (cached); Pareto front, each Pareto point verified on the RTL (GHDL co-simulation +\n"
        "Verilator). Exit status: 0 done, 1 an RTL check failed, 2 bad input, 3 tool failure.\n"
        "--jobs: shards at once; in a single-process run, the synthesis / GHDL processes at once.\n"
        "With " + sharding_flags_named() + " the configurations run in shards (run directory --run-dir, default <out>/run), then the RTL\n"
        "checks of the merged Pareto front, one shard per check (run directory <run-dir>/checks); --shards counts the\n"
        "configurations' shards only.");
    s->add_option("--config", c->config, "JSON sweep spec (sweep/configs/*.json; see sweep/sweep_config.hpp)")->required();
    s->add_option("--out", c->out, "output directory (sweep.md, sweep.csv, sweep.json, pareto.png)")->capture_default_str();
    s->add_option("--cache", c->cache, "synthesis/RTL-check cache (else $HARRIS_COSIM_SWEEP_CACHE or <build>/sweep-cache)");
    s->add_option("--kitti", c->kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    s->add_option("--data", c->data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    s->add_option("--middlebury", c->middlebury,
                  "Middlebury 2006 half-size folder of the stereo-match column (default <data>/middlebury2006/half)");
    s->add_option("--threads", c->threads, "threads for the accuracy runs (0: all cores)")->check(whole_number(0));
    s->add_option("--backend", c->backend, "GHDL back end of the RTL checks (default: the first built: gcc, llvm, mcode)");
    s->add_option("--regression-set", c->regression_set,
                  "the GHDL checks' streams, one per line as golden/regression-set.txt (the default)");
    s->add_flag("--no-rtl", c->no_rtl, "skip the RTL checks of the Pareto points");
    s->add_flag("--quiet", c->quiet, "no progress lines");
    c->runner.jobs = 2;
    add_runner_flags(s, c->runner);
    s->callback([c, s] {
        c->sharded = sharded(s, /*single_jobs=*/true);
        run(*c);
    });
}

}  // namespace hc::tools

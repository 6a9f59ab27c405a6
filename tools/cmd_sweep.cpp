// cmd_sweep.cpp: `harris-cosim sweep`, the bit-width exploration of issue 5: accuracy
// against OpenCV, overflow audit and synthesis cost per configuration, the Pareto front,
// and every Pareto-optimal configuration run through the RTL. docs/bit-widths.md.
// Exit status: 0 done (wrapping configurations are reported, not failures), 1 an RTL
// check of a Pareto point failed, 2 bad input, 3 a tool failed.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "commands.hpp"
#include "frames.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_report.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct SweepCli {
    std::string config, out = "sweep-report", cache, kitti, data, sim_dir = HC_SIM_DIR;
    int threads = 0, jobs = 2;
    bool no_rtl = false, quiet = false;
};

std::vector<std::string> split_csv(const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    for (std::string t; std::getline(ss, t, ',');) v.push_back(t);
    return v;
}

void run(const SweepCli& c) {
    sweep::SweepOptions o;
    o.spec_file = c.config;
    if (!fs::is_regular_file(o.spec_file)) throw InputError("--config '" + c.config + "': no such file");
    o.out = c.out;
    if (fs::exists(o.out) && !fs::is_directory(o.out)) throw InputError("--out '" + c.out + "' exists and is not a directory");
    o.cache = !c.cache.empty() ? fs::path(c.cache)
              : std::getenv("HARRIS_COSIM_SWEEP_CACHE") ? fs::path(std::getenv("HARRIS_COSIM_SWEEP_CACHE"))
                                                        : fs::path(HC_SIM_DIR).parent_path() / "sweep-cache";
    if (!c.kitti.empty()) {
        o.kitti = c.kitti;
    } else if (auto d = data_dir(c.data); d && fs::is_directory(*d / "kitti")) {
        o.kitti = *d / "kitti";
    } else {
        throw InputError("no KITTI data: give --kitti DIR (holding sequences/NN) or --data DIR (holding kitti/)");
    }
    o.self = fs::read_symlink("/proc/self/exe");
    o.source_dir = HC_SOURCE_DIR;
    o.rtl_order = split_csv(HC_RTL_ORDER);
    o.sim_dir = c.sim_dir;
    o.threads = c.threads;
    if (c.jobs < 1 || c.jobs > 2) throw InputError(fmt::format("--jobs {}: 1 or 2 (this machine has 2 shared cores)", c.jobs));
    o.jobs = c.jobs;
    o.trust = !c.no_rtl;
    o.progress = !c.quiet;
    sweep::SweepResult r;
    try {
        r = sweep::run_sweep(o);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }
    r.command = fmt::format("harris-cosim sweep --config {} --out {}{}", c.config, c.out, c.no_rtl ? " --no-rtl" : "");
    sweep::write_reports(r, o.out);
    std::fprintf(stderr, "sweep: %zu configurations in %.1f s; reports in %s (sweep.md, sweep.csv, sweep.json, pareto.png)\n",
                 r.points.size(), r.seconds_total, o.out.string().c_str());
    for (const auto& p : r.points)
        if (p.verify && ((p.rtl.ran && p.rtl.failed) || (p.verilator.ran && p.verilator.failed))) {
            std::fprintf(stderr, "sweep: RTL check failed for %s: %s %s\n", p.config.name.c_str(),
                         p.rtl.detail.c_str(), p.verilator.detail.c_str());
            throw CLI::RuntimeError(1);
        }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
    auto c = std::make_shared<SweepCli>();
    auto* s = app.add_subcommand(
        "sweep",
        "Bit-width exploration: per configuration of a JSON sweep spec, recall/precision against OpenCV on KITTI\n"
        "(spec model), overflow audit, yosys synth_xilinx cost (cached); Pareto front, each Pareto point verified on\n"
        "the RTL (GHDL co-simulation + Verilator). Exit status: 0 done, 1 an RTL check failed, 2 bad input, 3 tool failure.");
    s->add_option("--config", c->config, "JSON sweep spec (configs/*.json; see tools/sweep/sweep_config.hpp)")->required();
    s->add_option("--out", c->out, "output directory (sweep.md, sweep.csv, sweep.json, pareto.png)")->capture_default_str();
    s->add_option("--cache", c->cache, "synthesis/RTL-check cache (else $HARRIS_COSIM_SWEEP_CACHE or <build>/sweep-cache)");
    s->add_option("--kitti", c->kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    s->add_option("--data", c->data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    s->add_option("--threads", c->threads, "threads for the accuracy runs (0: all cores)")->check(CLI::NonNegativeNumber);
    s->add_option("--jobs", c->jobs, "synthesis / simulator processes at once (1..2)")->capture_default_str();
    s->add_option("--sim-dir", c->sim_dir, "directory of the built GHDL simulators (for the RTL checks)")->capture_default_str();
    s->add_flag("--no-rtl", c->no_rtl, "skip the RTL checks of the Pareto points");
    s->add_flag("--quiet", c->quiet, "no progress lines");
    s->callback([c] { run(*c); });
}

}  // namespace hc::tools

// cosim.cpp: run_ghdl and the GHDL helpers (cosim.hpp).
#include "cosim/cosim.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "model/util/util.hpp"

// Build facts from cosim/CMakeLists.txt.
#ifndef HC_SIM_DIR
#error "HC_SIM_DIR, HC_BUILD_DIR, HC_GHDL_MCODE, HC_GHDL_BACKENDS, HC_SOURCE_DIR, HC_RTL_ORDER must be defined"
#endif

namespace fs = std::filesystem;

namespace hc::cosim {

std::vector<std::string> ghdl_backends() { return util::split_csv(HC_GHDL_BACKENDS); }

fs::path rtl_dir() { return fs::path(HC_SOURCE_DIR) / "rtl"; }

std::vector<fs::path> rtl_sources(const fs::path& dir) {
    const fs::path d = dir.empty() ? rtl_dir() : dir;
    std::vector<fs::path> v;
    for (const auto& stem : util::split_csv(HC_RTL_ORDER)) v.push_back(d / (stem + ".vhd"));
    return v;
}

namespace {

const fs::path kTestbench = fs::path(HC_SIM_DIR) / "harris_top_tb.vhd";   // made from harris_top_tb.vhd.in

/// Copies `from` to `to` through a temporary beside it (to stays whole or absent).
void move_into_place(const fs::path& from, const fs::path& to) {
    if (to.empty() || !fs::exists(from)) return;
    if (to.has_parent_path()) fs::create_directories(to.parent_path());
    const fs::path tmp = to.string() + ".part";
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing);
    fs::rename(tmp, to);
}

/// Refuses to run a simulator older than a VHDL file it was built from; for the build's own
/// simulators (`inputs`: the copy of rtl/ the build took before analysing it) also one whose
/// RTL differs from that copy, whatever the files' dates.
void check_fresh(const fs::path& sim, const std::string& backend, const fs::path& inputs = {}) {
    if (!fs::exists(sim))
        throw SimulatorError("the GHDL " + backend + " simulator '" + sim.string() +
                             "' is not built: run `cmake --build " HC_BUILD_DIR "`");
    const auto built = fs::last_write_time(sim);
    std::vector<fs::path> files = rtl_sources();
    for (const char* f : {"harris_top_tb.vhd.in", "hc_bridge_pkg.vhd.in", "hc_bridge.h"})
        files.push_back(fs::path(HC_SOURCE_DIR) / "cosim" / f);
    for (const auto& p : files)
        if (fs::exists(p) && fs::last_write_time(p) > built)
            throw SimulatorError("the GHDL " + backend + " simulator is older than " + p.string() +
                                 ", which changed since it was built: run `cmake --build " HC_BUILD_DIR "`");
    if (inputs.empty()) return;
    for (const auto& p : rtl_sources()) {
        const fs::path copy = inputs / p.filename();
        if (!fs::exists(copy) || util::read_file(copy) != util::read_file(p))
            throw SimulatorError("the GHDL " + backend + " simulator was built from another " + p.string() +
                                 " (its copy " + copy.string() + (fs::exists(copy) ? " differs" : " is missing") +
                                 "): run `cmake --build " HC_BUILD_DIR "`");
    }
}

}  // namespace

bool analyse_mcode(const fs::path& rtl, const fs::path& sim_dir, const fs::path& log) {
    if (std::string(HC_GHDL_MCODE).empty() || std::string(HC_GHDL_MCODE).find("NOTFOUND") != std::string::npos)
        throw SimulatorError("ghdl-mcode was not found when this build was configured");
    fs::create_directories(sim_dir / "ghdl-mcode");
    std::vector<std::string> ana = {HC_GHDL_MCODE, "-a", "--std=08", "--workdir=" + (sim_dir / "ghdl-mcode").string()};
    for (const auto& p : rtl_sources(rtl)) ana.push_back(p.string());
    ana.push_back((fs::path(HC_SIM_DIR) / "hc_bridge_pkg.vhd").string());
    ana.push_back(kTestbench.string());
    if (util::run_process(ana, {.log = log}) != 0) return false;
    // the analysis's date, as the build's mcode library has: run_ghdl refuses it once an
    // RTL file of the source tree is newer
    util::write_file_atomic(sim_dir / "ghdl-mcode" / "analysed.stamp", "analysed from " + rtl.string() + "\n");
    const fs::path lib = sim_dir / "libhc_bridge.so";
    if (!fs::exists(lib)) fs::create_symlink(fs::path(HC_SIM_DIR) / "libhc_bridge.so", lib);
    return true;
}

GhdlResult run_ghdl(const GhdlRun& r) {
    const auto backends = ghdl_backends();
    if (r.backend != "gcc" && r.backend != "llvm" && r.backend != "mcode")
        throw InputError("unknown back end '" + r.backend + "' (gcc, llvm or mcode)");
    if (std::find(backends.begin(), backends.end(), r.backend) == backends.end())
        throw InputError("GHDL back end '" + r.backend + "' was not found when this build was configured "
                         "(install ghdl-" + r.backend + " and re-run cmake)");
    if (r.frames.empty()) throw InternalError("run_ghdl: no frames");
    for (const fs::path* out : {&r.summary_json, &r.reads_csv, &r.vcd, &r.wave})
        if (!out->empty() && fs::is_directory(*out)) throw InputError("output '" + out->string() + "' is a directory");
    const Geometry g{r.frames[0].width, r.frames[0].height};
    const fs::path sim_dir = r.sim_dir.empty() ? fs::path(HC_SIM_DIR) : r.sim_dir;

    util::ScratchDir scratch;
    RunConfig cfg;
    cfg.geometry = g;
    cfg.formats = r.formats;
    cfg.frames_file = (scratch.path() / "frames.bin").string();
    cfg.frame_names = r.frame_names;
    cfg.backend = r.backend;
    cfg.keep_going = r.keep_going;
    cfg.compare_all = r.compare_all;
    cfg.idle_every = r.idle_every;
    cfg.max_writes = r.max_writes;
    cfg.vcd_file = r.vcd.empty() ? "" : (scratch.path() / "mismatch.vcd").string();
    cfg.summary_file = (scratch.path() / "summary.json").string();
    cfg.reads_file = r.reads_csv.empty() ? "" : (scratch.path() / "reads.csv").string();
    cfg.progress = r.progress;
    write_frames(cfg.frames_file, r.frames);
    const fs::path cfg_path = scratch.path() / "run.json";
    util::write_file_atomic(cfg_path, to_json(cfg));

    std::vector<std::string> argv;
    // the build's own simulators are also checked against the copy of rtl/ they were built from
    std::error_code ec;
    const fs::path inputs = fs::equivalent(sim_dir, fs::path(HC_SIM_DIR), ec)
                                ? sim_dir / ("ghdl-" + r.backend) / "inputs" : fs::path{};
    if (r.backend == "mcode") {
        const fs::path work = sim_dir / "ghdl-mcode";
        check_fresh(work / "analysed.stamp", r.backend, inputs);   // the build's or analyse_mcode()'s
        argv = {HC_GHDL_MCODE, "-r", "--std=08", "--workdir=" + work.string(), "harris_top_tb"};
    } else {
        const fs::path exe = sim_dir / ("harris_top_tb_" + r.backend);
        check_fresh(exe, r.backend, inputs);   // this build's or another directory's: never older than rtl/
        argv = {exe.string()};
    }
    for (const auto& [name, value] : generics(g, r.formats)) argv.push_back("-g" + name + "=" + std::to_string(value));
    // the design computes from power-up 'U' values before the first write; numeric_std warns
    // about them at time 0 only, which says nothing about the run
    argv.push_back("--ieee-asserts=disable-at-0");
    if (!r.wave.empty()) argv.push_back("--wave=" + (scratch.path() / "wave.ghw").string());

    std::vector<std::string> env = {"HC_COSIM_CONFIG=" + cfg_path.string()};
    if (r.backend == "mcode") {   // mcode loads the bridge by file name
        const char* old = std::getenv("LD_LIBRARY_PATH");
        env.push_back("LD_LIBRARY_PATH=" + sim_dir.string() + (old && *old ? std::string(":") + old : ""));
    }
    GhdlResult res;
    res.simulator_status = util::run_process(argv, {.extra_env = env, .log = r.log});
    const fs::path summary = cfg.summary_file;
    if (!fs::exists(summary))
        throw SimulatorError("the GHDL simulator exited with status " + std::to_string(res.simulator_status) +
                             " without a summary" + (r.log.empty() ? "" : " (log " + r.log.string() + ")"));
    res.summary = summary_from_json(util::read_file(summary));
    move_into_place(summary, r.summary_json);
    if (!cfg.reads_file.empty()) {
        move_into_place(cfg.reads_file, r.reads_csv);
        res.reads_csv = r.reads_csv;
    }
    if (!r.wave.empty()) move_into_place(scratch.path() / "wave.ghw", r.wave);
    if (res.summary.first_mismatch && !cfg.vcd_file.empty()) move_into_place(cfg.vcd_file, r.vcd);
    return res;
}

}  // namespace hc::cosim

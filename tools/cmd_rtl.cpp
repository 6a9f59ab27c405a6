// cmd_rtl.cpp: `harris-cosim rtl` (GHDL co-simulation against the cycle model) and
// `harris-cosim model` (the cycle model alone, for speed and read-back lists).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "commands.hpp"
#include "driver/host_driver.hpp"
#include "frame_source.hpp"
#include "frames.hpp"
#include "harris/harris_top.hpp"
#include "process.hpp"
#include "run_config.hpp"

namespace hc::tools {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string read_text(const fs::path& p) {
    std::ifstream f(p);
    if (!f) throw InputError("cannot read '" + p.string() + "'");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/// A scratch directory removed when the run ends.
struct ScratchDir {
    fs::path path;
    ScratchDir() {
        std::string tmpl = (fs::temp_directory_path() / "harris-cosim-XXXXXX").string();
        if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a scratch directory");
        path = tmpl;
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

std::vector<std::string> split_list(const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, ','))
        if (!x.empty()) v.push_back(x);
    return v;
}

struct RtlOptions {
    FrameSourceOptions src;
    std::string backend = "gcc";
    std::string config;
    bool keep_going = false;
    std::string compare = "all";
    std::string wave;
    std::string vcd = "harris-cosim-mismatch.vcd";
    std::string json_out;
    std::string reads_out;
    std::string expect_reads;
    int idle_every = 0;
    long max_writes = 0;
    bool quiet = false;
    std::string sim_dir = HC_SIM_DIR;
};

void move_into_place(const fs::path& from, const std::string& to) {
    if (to.empty() || !fs::exists(from)) return;
    const fs::path target(to);
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
    const fs::path tmp = target.string() + ".part";
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing);
    fs::rename(tmp, target);
}

/// The lines of a reads CSV without '#' comments.
std::vector<std::string> csv_rows(const fs::path& p) {
    std::ifstream f(p);
    if (!f) throw InputError("cannot read '" + p.string() + "'");
    std::vector<std::string> rows;
    std::string line;
    while (std::getline(f, line))
        if (!line.empty() && line[0] != '#') rows.push_back(line);
    return rows;
}

/// Compares the RTL's reads with a golden file; prints the first difference. 0 if equal.
int compare_reads(const std::string& golden, const std::string& actual) {
    const auto want = csv_rows(golden);
    const auto got = csv_rows(actual);
    for (size_t k = 0; k < std::max(want.size(), got.size()); ++k) {
        const std::string a = k < want.size() ? want[k] : "<none>";
        const std::string b = k < got.size() ? got[k] : "<none>";
        if (a != b) {
            std::printf("  GOLDEN READS DIFFER at row %zu: golden '%s', RTL '%s' (%s)\n", k, a.c_str(), b.c_str(),
                        golden.c_str());
            return 1;
        }
    }
    std::printf("  reads equal the golden file %s (%zu rows)\n", golden.c_str(), want.size());
    return 0;
}

int run_rtl(const RtlOptions& o) {
    const auto backends = split_list(HC_GHDL_BACKENDS);
    if (o.backend != "gcc" && o.backend != "llvm" && o.backend != "mcode")
        throw InputError("unknown back end '" + o.backend + "' (gcc, llvm or mcode)");
    if (std::find(backends.begin(), backends.end(), o.backend) == backends.end())
        throw InputError("GHDL back end '" + o.backend + "' was not found when this build was configured "
                         "(install ghdl-" + o.backend + " and re-run cmake)");
    const Formats formats = load_config_formats(o.config);
    LoadedFrames lf = load_frames(o.src);
    const Geometry g{lf.frames[0].width, lf.frames[0].height};
    {   // the host driver's own checks (e.g. chaining), before a simulator starts
        std::vector<const Image*> ptrs;
        for (const auto& f : lf.frames) ptrs.push_back(&f);
        try {
            HostDriver check(g, ptrs);
        } catch (const std::invalid_argument& e) {
            throw InputError(lf.description + ": " + e.what());
        }
    }
    for (const std::string* out : {&o.json_out, &o.reads_out, &o.vcd, &o.wave})
        if (!out->empty() && fs::is_directory(*out)) throw InputError("output '" + *out + "' is a directory");

    ScratchDir scratch;
    cosim::RunConfig cfg;
    cfg.geometry = g;
    cfg.formats = formats;
    cfg.frames_file = (scratch.path / "frames.bin").string();
    cfg.frame_names = lf.names;
    cfg.backend = o.backend;
    cfg.keep_going = o.keep_going;
    if (o.compare != "all" && o.compare != "reads") throw InputError("--compare '" + o.compare + "' (all or reads)");
    cfg.compare_all = o.compare == "all";
    cfg.idle_every = o.idle_every;
    cfg.max_writes = o.max_writes;
    cfg.vcd_file = o.vcd.empty() ? "" : (scratch.path / "mismatch.vcd").string();
    cfg.summary_file = (scratch.path / "summary.json").string();
    cfg.reads_file = o.reads_out.empty() && o.expect_reads.empty() ? "" : (scratch.path / "reads.csv").string();
    cfg.progress = !o.quiet;
    cosim::write_frames(cfg.frames_file, lf.frames);
    const fs::path cfg_path = scratch.path / "run.json";
    write_file_atomic(cfg_path, cosim::to_json(cfg));

    std::vector<std::string> argv;
    if (o.backend == "mcode") {
        argv = {HC_GHDL_MCODE, "-r", "--std=08", "--workdir=" + o.sim_dir + "/ghdl-mcode", "harris_top_tb"};
    } else {
        const std::string exe = o.sim_dir + "/harris_top_tb_" + o.backend;
        if (!fs::exists(exe)) throw InputError("simulator '" + exe + "' is not built (cmake --build the project)");
        argv = {exe};
    }
    for (const auto& [name, value] : generics(g, formats)) argv.push_back("-g" + name + "=" + std::to_string(value));
    // the design computes from power-up 'U' values before the first write; numeric_std warns
    // about them at time 0 only, which says nothing about the run
    argv.push_back("--ieee-asserts=disable-at-0");
    if (!o.wave.empty()) argv.push_back("--wave=" + (scratch.path / "wave.ghw").string());

    if (!o.quiet)
        std::fprintf(stderr, "[cosim] %s, %dx%d, back end %s: %ld writes\n", lf.description.c_str(), g.width, g.height,
                     o.backend.c_str(),
                     o.max_writes > 0 ? std::min(o.max_writes, static_cast<long>(lf.frames.size()) * g.frame_writes())
                                      : static_cast<long>(lf.frames.size()) * g.frame_writes());
    std::vector<std::string> env = {"HC_COSIM_CONFIG=" + cfg_path.string()};
    if (o.backend == "mcode") {   // mcode loads the bridge by file name
        const char* old = std::getenv("LD_LIBRARY_PATH");
        env.push_back("LD_LIBRARY_PATH=" + o.sim_dir + (old && *old ? std::string(":") + old : ""));
    }
    const int rc = run_process(argv, env);
    const fs::path summary = cfg.summary_file;
    if (!fs::exists(summary)) {
        std::fprintf(stderr, "harris-cosim: the simulator exited with status %d without a summary\n", rc);
        return 3;
    }
    const json j = json::parse(read_text(summary));
    move_into_place(summary, o.json_out);
    int golden_status = 0;
    if (!o.expect_reads.empty()) golden_status = compare_reads(o.expect_reads, cfg.reads_file);
    if (!cfg.reads_file.empty()) move_into_place(cfg.reads_file, o.reads_out);
    if (!o.wave.empty()) move_into_place(scratch.path / "wave.ghw", o.wave);
    if (j.contains("first_mismatch") && !cfg.vcd_file.empty()) move_into_place(cfg.vcd_file, o.vcd);

    std::printf("harris-cosim rtl: %s\n", j.at("status").get<std::string>().c_str());
    std::printf("  frames %zu (%s), %dx%d, back end %s\n", lf.frames.size(), lf.description.c_str(), g.width,
                g.height, o.backend.c_str());
    std::printf("  writes %ld of %ld, idle cycles %ld, reads %ld, corners %ld\n", j.at("writes").get<long>(),
                j.at("writes_in_stream").get<long>(), j.at("idle_cycles").get<long>(), j.at("reads").get<long>(),
                j.at("corners").get<long>());
    if (j.at("compare") == "all")
        std::printf("  compared per cycle: %d signals (%d bits) in %zu stages\n",
                    j.at("signals_compared_per_cycle").get<int>(), j.at("bits_compared_per_cycle").get<int>(),
                    j.at("stages").size());
    else
        std::printf("  compared: the corner port on every read only (--compare reads)\n");
    std::printf("  mismatching cycles %ld, elements %ld (metavalues %ld)\n", j.at("mismatches").at("cycles").get<long>(),
                j.at("mismatches").at("elements").get<long>(), j.at("mismatches").at("metavalue_elements").get<long>());
    if (j.contains("first_mismatch")) {
        for (const auto& [st, v] : j.at("stages").items())
            if (v.at("mismatching_cycles").get<long>() > 0)
                std::printf("    %-24s %ld cycles, %ld elements, first stage on %ld cycles\n", st.c_str(),
                            v.at("mismatching_cycles").get<long>(), v.at("mismatching_elements").get<long>(),
                            v.at("first_mismatching_stage_cycles").get<long>());
        std::printf("%s", j.at("first_mismatch").at("report").get<std::string>().c_str());
        if (!o.vcd.empty()) std::printf("  waveform written to %s\n", o.vcd.c_str());
    }
    std::printf("  %.1f s, %.0f cycles/s\n", j.at("wall_seconds").get<double>(), j.at("cycles_per_second").get<double>());
    if (golden_status != 0) return 1;
    if (rc == 0 && j.at("status") == "pass" && j.at("complete").get<bool>()) return 0;
    if (j.at("status") == "mismatch") return 1;
    std::fprintf(stderr, "harris-cosim: the run did not complete (simulator status %d)\n", rc);
    return 3;
}

struct ModelOptions {
    FrameSourceOptions src;
    std::string config;
    std::string reads_out;
    std::string json_out;
};

int run_model(const ModelOptions& o) {
    const Formats formats = load_config_formats(o.config);
    LoadedFrames lf = load_frames(o.src);
    const Geometry g{lf.frames[0].width, lf.frames[0].height};
    std::vector<const Image*> ptrs;
    for (const auto& f : lf.frames) ptrs.push_back(&f);
    HostDriver drv(g, ptrs);
    HarrisTop top(g, formats);
    std::ostringstream reads;
    reads << "write,frame,x,y,value\n";
    std::vector<long> corners(lf.frames.size(), 0);
    std::vector<Corner> cs;
    BusEvent ev;
    long nreads = 0;
    const auto t0 = std::chrono::steady_clock::now();
    while (drv.next(ev)) {
        top.write(ev.data);
        if (ev.read) {
            ++nreads;
            cs.clear();
            drv.decode(*ev.read, top.corner(), cs);
            corners[ev.read->frame] += static_cast<long>(cs.size());
            if (!o.reads_out.empty())
                reads << top.writes() << ',' << ev.read->frame << ',' << ev.read->x << ',' << ev.read->y << ','
                      << top.corner() << '\n';
        }
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    long total = 0;
    for (long c : corners) total += c;
    json j = {{"geometry", {{"width", g.width}, {"height", g.height}}},
              {"frames", lf.frames.size()},
              {"writes", top.writes()},
              {"reads", nreads},
              {"corners", total},
              {"corners_per_frame", corners},
              {"wall_seconds", secs},
              {"writes_per_second", secs > 0 ? static_cast<double>(top.writes()) / secs : 0.0}};
    if (!o.reads_out.empty()) write_file_atomic(o.reads_out, reads.str());
    if (!o.json_out.empty()) write_file_atomic(o.json_out, j.dump(2) + "\n");
    std::printf("harris-cosim model: %s, %dx%d: %ld writes, %ld reads, %ld corners, %.3f s (%.2f M writes/s)\n",
                lf.description.c_str(), g.width, g.height, top.writes(), nreads, total, secs,
                secs > 0 ? static_cast<double>(top.writes()) / secs / 1e6 : 0.0);
    return 0;
}

}  // namespace

Formats load_config_formats(const std::string& path) {
    if (path.empty()) return Formats{};
    std::string text;
    try {
        text = read_text(path);
    } catch (const InputError&) {
        throw InputError("--config '" + path + "' cannot be read");
    }
    try {
        return cosim::formats_from_json(text);   // validates the formats
    } catch (const std::invalid_argument& e) {
        throw InputError("--config '" + path + "': " + e.what());
    }
}

void add_rtl_command(CLI::App& app) {
    auto o = std::make_shared<RtlOptions>();
    CLI::App* cmd = app.add_subcommand(
        "rtl",
        "Co-simulate the VHDL co-processor in GHDL against the cycle-accurate model, comparing every\n"
        "inter-stage register after every write. Exit status: 0 all equal, 1 mismatch, 2 bad input,\n"
        "3 simulator failure.");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--backend", o->backend, "GHDL back end: gcc, llvm or mcode")->capture_default_str();
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--compare", o->compare,
                    "all: every inter-stage register after every cycle; reads: only the corner bits the host reads")
        ->capture_default_str();
    cmd->add_flag("--keep-going", o->keep_going, "count every mismatch per stage instead of stopping at the first");
    cmd->add_option("--vcd", o->vcd, "VCD of the cycles around the first mismatch (RTL and model side by side)")
        ->capture_default_str();
    cmd->add_option("--wave", o->wave, "GHW waveform of the whole run (GHDL --wave; large for big frames)");
    cmd->add_option("--json", o->json_out, "write the JSON summary here");
    cmd->add_option("--reads", o->reads_out, "write every read as CSV: write,frame,x,y,value");
    cmd->add_option("--expect-reads", o->expect_reads, "fail unless the RTL's reads equal this golden CSV");
    cmd->add_option("--idle-every", o->idle_every, "insert an idle cycle (write='0') after every N writes")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--max-writes", o->max_writes, "stop after N writes")->check(CLI::NonNegativeNumber);
    cmd->add_flag("--quiet", o->quiet, "no progress lines");
    cmd->add_option("--sim-dir", o->sim_dir, "directory of the built GHDL simulators")->capture_default_str();
    cmd->callback([o]() {
        const int rc = run_rtl(*o);
        if (rc != 0) throw CLI::RuntimeError(rc);
    });
}

void add_model_command(CLI::App& app) {
    auto o = std::make_shared<ModelOptions>();
    CLI::App* cmd = app.add_subcommand(
        "model", "Run the cycle-accurate model alone through the host driver's write order (no simulator).");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--reads", o->reads_out, "write every read as CSV: write,frame,x,y,value");
    cmd->add_option("--json", o->json_out, "write a JSON summary here");
    cmd->callback([o]() {
        const int rc = run_model(*o);
        if (rc != 0) throw CLI::RuntimeError(rc);
    });
}

}  // namespace hc::tools

// cmd_rtl.cpp: `harris-cosim rtl` (GHDL co-simulation against the cycle model, through
// cosim::run_ghdl) and `harris-cosim model` (the cycle model alone, for speed and read lists:
// run_cycle_model, model/driver/model_run.hpp).
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cosim/cosim.hpp"
#include "model/driver/model_run.hpp"
#include "model/harris/formats_json.hpp"
#include "tools/commands.hpp"
#include "tools/frame_source.hpp"
#include "io/util/util.hpp"

namespace hc::tools {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct RtlOptions {
    frames::FrameSource src;
    std::string backend = "gcc";
    std::string config;
    std::string sim_dir;
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
};

/// The lines of a reads CSV without '#' comments.
std::vector<std::string> csv_rows(const fs::path& p) {
    std::istringstream f(util::read_file(p));
    std::vector<std::string> rows;
    for (std::string line; std::getline(f, line);)
        if (!line.empty() && line[0] != '#') rows.push_back(line);
    return rows;
}

/// Compares the RTL's reads with a golden file; prints the first difference. True if equal.
bool reads_equal(const std::string& golden, const fs::path& actual) {
    const auto want = csv_rows(golden);
    const auto got = csv_rows(actual);
    for (size_t k = 0; k < std::max(want.size(), got.size()); ++k) {
        const std::string a = k < want.size() ? want[k] : "<none>";
        const std::string b = k < got.size() ? got[k] : "<none>";
        if (a != b) {
            std::printf("  GOLDEN READS DIFFER at row %zu: golden '%s', RTL '%s' (%s)\n", k, a.c_str(), b.c_str(),
                        golden.c_str());
            return false;
        }
    }
    std::printf("  reads equal the golden file %s (%zu rows)\n", golden.c_str(), want.size());
    return true;
}

void print_summary(const cosim::Summary& s, const frames::LoadedFrames& lf, const RtlOptions& o) {
    std::printf("harris-cosim rtl: %s\n", s.mismatching_cycles > 0 ? "mismatch" : "pass");
    std::printf("  frames %zu (%s), %dx%d, back end %s\n", lf.frames.size(), lf.description.c_str(), s.geometry.width,
                s.geometry.height, o.backend.c_str());
    std::printf("  writes %ld of %ld, idle cycles %ld, reads %ld, corners %ld\n", s.writes, s.writes_in_stream,
                s.idle_cycles, s.reads, s.corners);
    if (s.compare_all)
        std::printf("  compared per cycle: %ld signals (%ld bits) in %zu stages\n", s.signals_compared_per_cycle,
                    s.bits_compared_per_cycle, s.stages.size());
    else
        std::printf("  compared: the corner port on every read only (--compare reads)\n");
    std::printf("  mismatching cycles %ld, elements %ld (metavalues %ld)\n", s.mismatching_cycles,
                s.mismatching_elements, s.metavalue_elements);
    if (s.first_mismatch) {
        for (const auto& st : s.stages)
            if (st.mismatching_cycles > 0)
                std::printf("    %-24s %ld cycles, %ld elements, first stage on %ld cycles\n", st.stage.c_str(),
                            st.mismatching_cycles, st.mismatching_elements, st.first_mismatching_stage_cycles);
        std::printf("%s", s.first_mismatch->report.c_str());
        if (!o.vcd.empty()) std::printf("  waveform written to %s\n", o.vcd.c_str());
    }
    std::printf("  %.1f s, %.0f cycles/s\n", s.wall_seconds, s.cycles_per_second);
}

void run_rtl(const RtlOptions& o) {
    if (o.compare != "all" && o.compare != "reads") throw InputError("--compare '" + o.compare + "' (all or reads)");
    cosim::GhdlRun run;
    run.formats = o.config.empty() ? Formats{} : formats_from_file(o.config);
    frames::LoadedFrames lf = frames::load_frames(o.src);
    const Geometry g{lf.frames[0].width, lf.frames[0].height};
    util::ScratchDir scratch;
    run.frame_names = lf.names;
    run.backend = o.backend;
    run.sim_dir = o.sim_dir;
    run.keep_going = o.keep_going;
    run.compare_all = o.compare == "all";
    run.idle_every = o.idle_every;
    run.max_writes = o.max_writes;
    run.progress = !o.quiet;
    run.summary_json = o.json_out;
    run.vcd = o.vcd;
    run.wave = o.wave;
    run.reads_csv = !o.reads_out.empty() ? fs::path(o.reads_out)
                    : !o.expect_reads.empty() ? scratch.path() / "reads.csv"
                                              : fs::path();
    const long total = static_cast<long>(lf.frames.size()) * g.frame_writes();
    if (!o.quiet)
        std::fprintf(stderr, "[cosim] %s, %dx%d, back end %s: %ld writes\n", lf.description.c_str(), g.width, g.height,
                     o.backend.c_str(), o.max_writes > 0 ? std::min(o.max_writes, total) : total);
    run.frames = std::move(lf.frames);
    const cosim::GhdlResult r = cosim::run_ghdl(run);
    lf.frames = std::move(run.frames);
    print_summary(r.summary, lf, o);
    if (!o.expect_reads.empty() && !reads_equal(o.expect_reads, r.reads_csv))
        throw MismatchError("the RTL's reads differ from the golden file " + o.expect_reads);
    if (r.summary.mismatching_cycles > 0)
        throw MismatchError("the RTL differs from the model" +
                            (r.summary.first_mismatch ? " first at write " + std::to_string(r.summary.first_mismatch->write) +
                                                            ", stage " + r.summary.first_mismatch->stage + ", signal " +
                                                            r.summary.first_mismatch->signal
                                                      : std::string()));
    if (r.simulator_status != 0 || !r.summary.complete)
        throw SimulatorError("the run did not complete (simulator status " + std::to_string(r.simulator_status) + ")");
}

struct ModelOptions {
    frames::FrameSource src;
    std::string config;
    std::string reads_out;
    std::string json_out;
};

void run_model(const ModelOptions& o) {
    const Formats formats = o.config.empty() ? Formats{} : formats_from_file(o.config);
    const frames::LoadedFrames lf = frames::load_frames(o.src);
    const Geometry g{lf.frames[0].width, lf.frames[0].height};
    const ModelRun r = run_cycle_model(lf.frames, formats, !o.reads_out.empty());
    const double secs = r.seconds;
    json j = {{"geometry", {{"width", g.width}, {"height", g.height}}},
              {"frames", lf.frames.size()},
              {"writes", r.writes},
              {"reads", r.reads},
              {"corners", r.corners()},
              {"corners_per_frame", r.corners_per_frame},
              {"wall_seconds", secs},
              {"writes_per_second", secs > 0 ? static_cast<double>(r.writes) / secs : 0.0}};
    if (!o.reads_out.empty()) util::write_file_atomic(o.reads_out, r.reads_csv);
    if (!o.json_out.empty()) util::write_file_atomic(o.json_out, j.dump(2) + "\n");
    std::printf("harris-cosim model: %s, %dx%d: %ld writes, %ld reads, %ld corners, %.3f s (%.2f M writes/s)\n",
                lf.description.c_str(), g.width, g.height, r.writes, r.reads, r.corners(), secs,
                secs > 0 ? static_cast<double>(r.writes) / secs / 1e6 : 0.0);
}

}  // namespace

void add_rtl_command(CLI::App& app) {
    const auto [cmd, o] = add_command<RtlOptions>(app, "rtl",
        "Co-simulate the VHDL co-processor in GHDL against the cycle-accurate model, comparing every\n"
        "inter-stage register after every write. Exit status: 0 all equal, 1 mismatch, 2 bad input,\n"
        "3 simulator failure (including a simulator older than the RTL: rebuild).");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--backend", o->backend, "GHDL back end: gcc, llvm or mcode")->capture_default_str();
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--sim-dir", o->sim_dir,
                    "gcc/llvm: directory holding another build of harris_top_tb_<backend> (e.g. the coverage build of "
                    "tools/rtl-coverage.sh); refused when older than rtl/");
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
        ->check(whole_number(0));
    cmd->add_option("--max-writes", o->max_writes, "stop after N writes")->check(whole_number(0));
    cmd->add_flag("--quiet", o->quiet, "no progress lines");
    cmd->callback([o]() { run_rtl(*o); });
}

void add_model_command(CLI::App& app) {
    const auto [cmd, o] = add_command<ModelOptions>(app,
        "model", "Run the cycle-accurate model alone through the host driver's write order (no simulator).");
    add_frame_source_options(cmd, o->src);
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--reads", o->reads_out, "write every read as CSV: write,frame,x,y,value");
    cmd->add_option("--json", o->json_out, "write a JSON summary here");
    cmd->callback([o]() { run_model(*o); });
}

}  // namespace hc::tools

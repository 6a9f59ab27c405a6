// cosim_command.cpp: see cosim_command.hpp.
#include "cosim/cosim_command.hpp"

#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "model/driver/model_run.hpp"
#include "model/harris/formats_json.hpp"

namespace fs = std::filesystem;

namespace hc::cosim {

namespace {

/// The lines of a reads CSV without '#' comments.
std::vector<std::string> csv_rows(const fs::path& p) {
    std::istringstream f(util::read_file(p));
    std::vector<std::string> rows;
    for (std::string line; std::getline(f, line);)
        if (!line.empty() && line[0] != '#') rows.push_back(line);
    return rows;
}

void print_summary(const Summary& s, const frames::LoadedFrames& lf, const RtlCommand& o) {
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

}  // namespace

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

void run_rtl_command(const RtlCommand& o) {
    if (o.compare != "all" && o.compare != "reads") throw InputError("--compare '" + o.compare + "' (all or reads)");
    GhdlRun run;
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
    const GhdlResult r = run_ghdl(run);
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

void run_model_command(const ModelCommand& o) {
    const Formats formats = o.config.empty() ? Formats{} : formats_from_file(o.config);
    const frames::LoadedFrames lf = frames::load_frames(o.src);
    const Geometry g{lf.frames[0].width, lf.frames[0].height};
    const ModelRun r = run_cycle_model(lf.frames, formats, !o.reads_out.empty());
    const double secs = r.seconds;
    const nlohmann::json j = {{"geometry", {{"width", g.width}, {"height", g.height}}},
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

}  // namespace hc::cosim

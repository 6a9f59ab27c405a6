// mutated_run.cpp: see mutated_run.hpp.
#include "mutation/mutated_run.hpp"

#include <chrono>

#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::mutation {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

fs::path mutated_copy(const FileEdit* e, const fs::path& dir) {
    const fs::path rtl = dir / "rtl";
    fs::create_directories(rtl);
    for (const auto& p : cosim::rtl_sources()) fs::copy_file(p, rtl / p.filename(), fs::copy_options::overwrite_existing);
    if (e) {
        const fs::path f = rtl / e->file;
        util::write_file_atomic(f, e->apply(util::read_file(f, e->what)));
    }
    return rtl;
}

MutatedRun run_mutated(const FileEdit* e, const fs::path& work, const NextStream& next) {
    MutatedRun out;
    fs::remove_all(work);
    const fs::path rtl = mutated_copy(e, work);
    out.analyse_log = work / "analyse.log";
    const auto ta = Clock::now();
    out.analysed = cosim::analyse_mcode(rtl, work, out.analyse_log);
    out.analyse_seconds = since(ta);
    if (!out.analysed) return out;
    for (std::optional<cosim::GhdlRun> given; (given = next(out));) {
        cosim::GhdlRun run = std::move(*given);
        run.backend = "mcode";
        run.sim_dir = work;
        run.progress = false;
        run.log = work / "sim.log";
        fs::remove(run.log);
        StreamOutcome s;
        s.log = run.log;
        const auto ts = Clock::now();
        try {
            s.result = cosim::run_ghdl(run);
        } catch (const SimulatorError& err) {
            s.error = err.what();
        }
        s.seconds = since(ts);
        out.streams.push_back(std::move(s));
    }
    return out;
}

MutatedRun run_mutated(const FileEdit* e, const fs::path& work, const cosim::GhdlRun& stream) {
    return run_mutated(e, work, [&](const MutatedRun& so_far) {
        return so_far.streams.empty() ? std::optional<cosim::GhdlRun>(stream) : std::nullopt;
    });
}

}  // namespace hc::mutation

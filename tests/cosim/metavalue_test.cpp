// metavalue_test.cpp: a register that powers up as 'U' (its reset removed in a scratch copy
// of rtl/) is a METAVALUE failure of the system-level co-simulation, named by register and
// stage; the unedited copy passes, so the failure is the edit's.
#include <catch2/catch.hpp>

#include <string>

#include "cosim/cosim.hpp"
#include "model/image/image.hpp"
#include "util/util.hpp"

namespace fs = std::filesystem;
using namespace hc;

namespace {

// Copies rtl/ to `dir`, optionally with `find` replaced by `replace` in `file`.
void copy_rtl(const fs::path& dir, const std::string& file = {}, const std::string& find = {},
              const std::string& replace = {}) {
    fs::create_directories(dir);
    for (const auto& p : cosim::rtl_sources()) {
        std::string text = util::read_file(p);
        if (p.filename() == file) {
            const auto at = text.find(find);
            REQUIRE(at != std::string::npos);
            text.replace(at, find.size(), replace);
        }
        util::write_file_atomic(dir / p.filename(), text);
    }
}

cosim::GhdlResult run_copy(const fs::path& rtl, const fs::path& sim) {
    REQUIRE(cosim::analyse_mcode(rtl, sim, sim.string() + ".analysis.log"));
    cosim::GhdlRun run;
    for (int k = 0; k < 2; ++k) {
        run.frames.push_back(make_pattern(Pattern::random, 16, 12, k, 1));
        run.frame_names.push_back("random#" + std::to_string(k));
    }
    run.backend = "mcode";
    run.sim_dir = sim;
    run.progress = false;
    run.log = sim.string() + ".log";
    return cosim::run_ghdl(run);
}

}  // namespace

TEST_CASE("a register without reset in a copy of the RTL is a METAVALUE failure naming the register",
          "[cosim][metavalue]") {
    util::ScratchDir scratch("hc-metavalue");

    // the unedited copy passes
    copy_rtl(scratch.path() / "rtl");
    const cosim::GhdlResult ok = run_copy(scratch.path() / "rtl", scratch.path() / "sim");
    CHECK(ok.summary.pass());
    CHECK(ok.summary.metavalue_elements == 0);

    // control_shift_register's enables `tt` lose their asynchronous reset: 'U' at power-up
    copy_rtl(scratch.path() / "rtl-noreset", "control_shift_register.vhd",
             "    if rst = '0' then\n      tt <= (others => '0');\n    elsif clk'event and clk = '1' then",
             "    if clk'event and clk = '1' then");
    const cosim::GhdlResult r = run_copy(scratch.path() / "rtl-noreset", scratch.path() / "sim-noreset");
    CHECK_FALSE(r.summary.pass());
    CHECK(r.summary.metavalue_elements > 0);
    REQUIRE(r.summary.first_mismatch.has_value());
    CHECK(r.summary.first_mismatch->stage == "control_shift_register");
    CHECK(r.summary.first_mismatch->signal == "t");
    CHECK_THAT(r.summary.first_mismatch->report, Catch::Contains("(METAVALUE)"));
    CHECK_THAT(r.summary.first_mismatch->report, Catch::Contains("control_shift_register"));
}

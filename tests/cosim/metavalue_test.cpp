// metavalue_test.cpp: edits of a scratch copy of rtl/ that only the testbench's checks off the
// rising edge see: a register that powers up as 'U' (its reset removed) is a METAVALUE
// failure; a wrong reset value is seen after reset; a register clocked on the falling edge is
// seen while the clock is low. Each is named by register and stage; the unedited copy passes,
// so each failure is the edit's.
#include <catch2/catch.hpp>

#include <string>

#include "cosim/cosim.hpp"
#include "model/image/image.hpp"
#include "model/util/util.hpp"

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

// The summary of a run of the copy of rtl/ in `dir`/`name` with `find` replaced by `replace`
// in `file`, which must fail and name its first mismatch.
cosim::Summary failing_edit(const fs::path& dir, const std::string& name, const std::string& file,
                            const std::string& find, const std::string& replace) {
    copy_rtl(dir / ("rtl" + name), file, find, replace);
    const cosim::GhdlResult r = run_copy(dir / ("rtl" + name), dir / ("sim" + name));
    CHECK_FALSE(r.summary.pass());
    REQUIRE(r.summary.first_mismatch.has_value());
    return r.summary;
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
    const cosim::Summary r =
        failing_edit(scratch.path(), "-noreset", "control_shift_register.vhd",
                     "    if rst = '0' then\n      tt <= (others => '0');\n    elsif clk'event and clk = '1' then",
                     "    if clk'event and clk = '1' then");
    CHECK(r.metavalue_elements > 0);
    CHECK(r.first_mismatch->stage == "control_shift_register");
    CHECK(r.first_mismatch->signal == "t");
    CHECK_THAT(r.first_mismatch->report, Catch::Contains("(METAVALUE)"));
    CHECK_THAT(r.first_mismatch->report, Catch::Contains("control_shift_register"));
}

TEST_CASE("a register clocked on the falling edge in a copy of the RTL fails while the clock is low",
          "[cosim][metavalue]") {
    // with the inputs changing while the clock is low, such a register holds after the next
    // rising edge what the design holds: only the look at the port between the edges sees it
    util::ScratchDir scratch("hc-falling-edge");
    const cosim::Summary r = failing_edit(scratch.path(), "", "corner_shift_register.vhd",
                                          "elsif clk'event and clk = '1' then", "elsif clk'event and clk = '0' then");
    CHECK(r.first_mismatch->stage == "corner_shift_register");
    CHECK_THAT(r.first_mismatch->report, Catch::Contains("while the clock was low"));
}

TEST_CASE("a wrong reset value in a copy of the RTL fails after reset, before the first edge", "[cosim][metavalue]") {
    // threshold's output register resets to 1 instead of 0; the first write overwrites it
    util::ScratchDir scratch("hc-reset-value");
    const cosim::Summary r = failing_edit(scratch.path(), "", "threshold.vhd", "      r1       <= to_signed(0, RESP_W);",
                                          "      r1       <= to_signed(1, RESP_W);");
    CHECK(r.first_mismatch->write == 0);
    CHECK_THAT(r.first_mismatch->report, Catch::Contains("after reset, before the first clock edge"));
}

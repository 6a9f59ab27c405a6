// A stage mutant of the generated campaign: its stage proof's counterexample written as a
// regression-set stream, on which the mutated RTL fails the co-simulation and the unmutated
// RTL passes with the golden reads (GHDL mcode, yosys, z3 and cvc5 on PATH).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "cosim/cosim_command.hpp"
#include "golden/golden.hpp"
#include "model/util/util.hpp"
#include "model/fixed/word.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/image/image.hpp"
#include "mutation/campaign.hpp"
#include "mutation/mutated_run.hpp"
#include "sweep/stage_stimulus.hpp"

using namespace hc;
using namespace hc::sweep;
namespace fs = std::filesystem;

namespace {

/// The co-simulation of `stream` on rtl/ with `edit` applied (nullptr: unmutated), reads into `reads`.
cosim::GhdlResult cosimulate(const mutation::FileEdit* edit, const util::RegressionStream& stream, const fs::path& work,
                             const fs::path& reads) {
    cosim::GhdlRun run;
    run.frames = golden::stream_frames(stream);
    run.frame_names.assign(run.frames.size(), stream.stem());
    run.idle_every = stream.idle_every;
    run.reads_csv = reads;
    const mutation::MutatedRun r = mutation::run_mutated(edit, work, run);
    REQUIRE(r.analysed);
    REQUIRE(r.streams.size() == 1);
    INFO(r.streams[0].error);
    REQUIRE(r.streams[0].result);
    return *r.streams[0].result;
}

}  // namespace

TEST_CASE("a killed sobel_x mutant: its stage counterexample as a stimulus fails the co-simulation, the RTL passes it",
          "[stage-stimulus]") {
    const util::ScratchDir dir;
    // the mutant: ix_next's second '+' made '-' (resize(p21) subtracted), killed by the campaign's quick stream
    const std::vector<mutation::Mutant> sel =
        mutation::select(mutation::generate_all(), {.only = {"sobel_x.vhd:36:58 arith `+` -> `-`"}, .classes = {}, .files = {}});
    REQUIRE(sel.size() == 1);
    const mutation::Mutant& m = sel.front();
    mutation::Options mo;
    mo.prove = false;
    const mutation::Result killed = mutation::run_mutant(m, mo);
    CHECK(killed.fate == mutation::Fate::killed);

    // the stage proof on the mutated VHDL (a copy of rtl/) gives a counterexample and writes its stimulus
    const mutation::FileEdit edit{m.file, [&](const std::string& text) { return m.apply(text); }, m.name()};
    StageOptions o;
    o.rtl_dir = mutation::mutated_copy(&edit, dir.path() / "copy");
    o.dir = dir.path() / "proof";
    o.config = "mutant";
    const StageProof p = prove_stage(EqStage::sobel_x, Formats{}, o);
    INFO(p.detail);
    REQUIRE(p.verdict == EqVerdict::counterexample);
    REQUIRE_FALSE(p.stimulus.empty());
    const std::vector<util::RegressionStream> set = util::read_regression_set(p.stimulus);
    REQUIRE(set.size() == 1);
    const util::RegressionStream& s = set.front();
    CHECK(s.image == o.dir / "stimulus" / "mutant_sobel_x.pgm");
    CHECK(s.breaks.empty());   // the thesis's formats
    CHECK(s.frames == 2);

    // the image holds the counterexample's window around pixel (7, 5): the model's gradient there is the proof's
    const Image im = read_pgm(s.image.string());
    REQUIRE(im.width == 16);
    REQUIRE(im.height == 12);
    Pixels3 px{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            px[i][j] = im.at(4 + i, 6 + j);
            CHECK(px[i][j] == p.counterexample.at(pixel_input(i, j)));
        }
    CHECK(p.detail.rfind("ix: model " + std::to_string(sobel_x<Word>(px, Formats{}).value()) + ", netlist ", 0) == 0);

    // the golden reads beside it are the unmutated model's (harris-cosim golden's files of that stream)
    const fs::path golden_reads = o.dir / "stimulus" / ("reads_" + s.stem() + ".csv");
    REQUIRE(fs::exists(golden_reads));
    CHECK(util::read_file(golden_reads) == golden::golden_files(set, o.dir / "stimulus").front().text);

    // the mutated RTL fails the co-simulation on it, first in sobel_x
    const cosim::GhdlResult bad = cosimulate(&edit, s, dir.path() / "mutant-run", dir.path() / "mutant-reads.csv");
    CHECK_FALSE(bad.summary.pass());
    REQUIRE(bad.summary.first_mismatch);
    CHECK(bad.summary.first_mismatch->stage == "sobel_x");
    // the unmutated RTL passes it, its reads equal to the golden file
    const cosim::GhdlResult good = cosimulate(nullptr, s, dir.path() / "rtl-run", dir.path() / "rtl-reads.csv");
    CHECK(good.summary.pass());
    CHECK(good.summary.complete);
    CHECK(cosim::reads_equal(golden_reads.string(), good.reads_csv));
}

TEST_CASE("an m_products counterexample's gradients become a pixel window whose Sobel gradients are them", "[stage-stimulus]") {
    StageProof p;
    p.stage = EqStage::m_products;
    p.verdict = EqVerdict::counterexample;
    p.counterexample = {{"ix", -517}, {"iy", 803}};
    const std::optional<Window5> w = stimulus_window(p, Formats{});
    REQUIRE(w);
    Pixels3 px{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) px[i][j] = static_cast<Pixel>((*w)[i + 1][j + 1]);
    CHECK(sobel_x<Word>(px, Formats{}).value() == -517);
    CHECK(sobel_y<Word>(px, Formats{}).value() == 803);
    // -1024 is outside what any window gives (|Sobel| <= 1020): no stimulus
    p.counterexample = {{"ix", -1024}, {"iy", 0}};
    CHECK_FALSE(stimulus_window(p, Formats{}));
    // the deeper stages' inputs are not one 3x3 window
    p.stage = EqStage::block_filter;
    CHECK_FALSE(stimulus_window(p, Formats{}));
}

// Stage equivalence: each datapath entity's GHDL netlist against the model's stage function,
// for every input (ghdl, yosys, z3 and cvc5 on PATH; label netlist).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "model/util/util.hpp"
#include "model/fixed/word.hpp"
#include "model/harris/sobel_x.hpp"
#include "sweep/stage_equivalence.hpp"

using namespace hc;
using namespace hc::sweep;
namespace fs = std::filesystem;

TEST_CASE("thesis configuration: every stage's netlist is proven equal to its model stage function", "[stages]") {
    const util::ScratchDir dir;
    StageOptions o;
    o.dir = dir.path();
    const StageEquivalence r = stage_equivalence(Formats{}, o);
    REQUIRE(r.stages.size() == static_cast<size_t>(kEqStageCount));
    for (const auto& p : r.stages) {
        INFO(kEqStageNames[static_cast<int>(p.stage)] << ": " << p.detail << " / " << p.recheck);
        CHECK(p.verdict == EqVerdict::equal);
        // the second solver answered (unsat, or unknown at its time limit; a sat would have thrown)
        CHECK(p.recheck.rfind("cvc5 --tlimit=", 0) == 0);
        // cvc5 proves the Sobel and product stages again on the same query
        if (p.stage == EqStage::sobel_x || p.stage == EqStage::sobel_y || p.stage == EqStage::m_products) CHECK(p.rechecked);
        // a counterexample beside a proof only where the proof assumes a domain (the input outside it);
        // harris_response assumes its current step-1 registers are step 1's of some block sums
        if (p.stage != EqStage::harris_response) CHECK(p.counterexample.empty() == p.assumed.empty());
        // the rerun command names a query that is there
        const std::string file = p.command.substr(p.command.rfind(' ') + 1);
        CHECK(fs::exists(file));
    }
    // m_products: -1024 * -1024 = 2^20 overflows the 21-bit signed shrink of GHDL's netlist, but not the Sobel range
    CHECK(r.stages[static_cast<int>(EqStage::m_products)].assumed == "ix in [-1020, 1020], iy in [-1020, 1020]");
    CHECK(r.stages[static_cast<int>(EqStage::sobel_x)].assumed.empty());
    CHECK(r.stages[static_cast<int>(EqStage::harris_response)].assumed == "ac, bb, ktr2 are step 1's of a_prev, b_prev, c_prev");
    // the JSON beside the report holds every verdict
    const StageEquivalence back = stage_equivalence_from_json(stage_equivalence_to_json(r));
    REQUIRE(back.stages.size() == r.stages.size());
    for (size_t k = 0; k < r.stages.size(); ++k) {
        CHECK(back.stages[k].verdict == r.stages[k].verdict);
        CHECK(back.stages[k].command == r.stages[k].command);
        CHECK(back.stages[k].assumed == r.stages[k].assumed);
    }
}

TEST_CASE("a Sobel coefficient changed in a copy of the VHDL yields a counterexample that differs in the model", "[stages]") {
    const util::ScratchDir dir;
    const fs::path rtl = dir.path() / "rtl";
    fs::create_directories(rtl);
    for (const auto& e : fs::directory_iterator(HC_SOURCE_DIR "/rtl")) fs::copy_file(e.path(), rtl / e.path().filename());
    // the middle right coefficient +2 becomes +1
    const std::string twice = "  p23 <= signed(resize(a(2, 3), PIXEL_W + 2)) + signed(resize(a(2, 3), PIXEL_W + 2));";
    std::string vhdl = util::read_file(rtl / "sobel_x.vhd");
    const size_t at = vhdl.find(twice);
    REQUIRE(at != std::string::npos);
    vhdl.replace(at, twice.size(), "  p23 <= signed(resize(a(2, 3), PIXEL_W + 2));");
    util::write_file_atomic(rtl / "sobel_x.vhd", vhdl);
    StageOptions o;
    o.rtl_dir = rtl;
    o.dir = dir.path() / "proof";
    const StageProof p = prove_stage(EqStage::sobel_x, Formats{}, o);
    INFO(p.detail);
    REQUIRE(p.verdict == EqVerdict::counterexample);
    // the counterexample's pixels, through the model: the mutant's gradient lacks one p_1_2 (p23 in the VHDL)
    Pixels3 px{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) px[i][j] = static_cast<Pixel>(p.counterexample.at("p_" + std::to_string(i) + "_" + std::to_string(j)));
    CHECK(px[1][2] != 0);
    const std::int64_t model = sobel_x<Word>(px, Formats{}).value();
    CHECK(p.detail.find("ix: model " + std::to_string(model) + ", netlist ") == 0);
    // the unchanged VHDL proves equal
    o.rtl_dir.clear();
    o.dir = dir.path() / "proof-original";
    CHECK(prove_stage(EqStage::sobel_x, Formats{}, o).verdict == EqVerdict::equal);
}

TEST_CASE("resp_w 27: harris_response's netlist differs from the VHDL at an overflowing signed shrink", "[stages]") {
    Formats f;
    f.resp_w = 27;
    const StageProof p = prove_stage(EqStage::harris_response, f, {});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::netlist_differs);
    CHECK(p.detail.find("-> 27 bits") != std::string::npos);
    CHECK(p.detail.find("r: model ") != std::string::npos);
    REQUIRE_FALSE(p.counterexample.empty());
    // the witness is reachable: the current step-1 registers are step 1's of the block sums before, in their proven ranges
    const auto& x = p.counterexample;
    CHECK(x.at("ac") == x.at("a_prev") * x.at("c_prev"));
    CHECK(x.at("bb") == x.at("b_prev") * x.at("b_prev"));
    for (const char* v : {"a_prev", "c_prev"}) CHECK((x.at(v) >= 0 && x.at(v) <= 18288));
    CHECK((x.at("b_prev") >= -18289 && x.at("b_prev") <= 18288));
    // one of them (all three are not negative there) needs more than 27 signed bits
    CHECK(std::max({x.at("ac"), x.at("bb"), x.at("ktr2")}) >= (std::int64_t{1} << 26));
    CHECK(p.assumed.rfind("ac, bb, ktr2 are step 1's of a_prev, b_prev, c_prev; ", 0) == 0);
}

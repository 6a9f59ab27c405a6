// Datapath induction: every register of harris_top's netlist against the cycle model's from
// reset, for every input sequence (ghdl, yosys, z3 and cvc5 on PATH).
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "model/util/util.hpp"
#include "sweep/datapath_induction.hpp"
#include "sweep/ranges_command.hpp"
#include "tests/sweep/mutated_rtl.hpp"

using namespace hc;
using namespace hc::sweep;
namespace fs = std::filesystem;

TEST_CASE("datapath induction at the thesis's 640x360: every register of the netlist follows the model's from reset, z3 and cvc5",
          "[datapath-induction]") {
    const util::ScratchDir dir;
    const DatapathInduction p = prove_datapath_from_reset(Formats{}, Geometry{640, 360}, {.dir = dir.path(), .rtl_dir = {}});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::equal);
    // 640x360: the control classes the model reaches from reset until its frame part repeats,
    // and the writes that took
    CHECK(p.classes == 37);
    CHECK(p.model_writes == 400'251);
    // the side conditions: 75 signed resizes of the M products (3 x 25, 22 -> 21 bits) in each of
    // the 9 classes where the M products are enabled
    CHECK(p.side_conditions == 9 * 75);
    // the same 75 products (of the current gradients) in each of those classes: each proven once
    CHECK(p.distinct_side_conditions == 75);
    CHECK(p.rechecked);
    // 38 queries (reset, 37 classes), 38 checks of the invariants in the next state, 75 side conditions
    CHECK(p.recheck == "cvc5: 151 unsat of 151");
    // every register the co-simulation compares: 4 windows of 49 pixels, 3 pixel delays, icm's 49
    // pixels, 2 x 25 gradients, 3 x 25 M coefficients, 3 x 9 block sums, 3 x 9 response terms,
    // 9 responses, 9 delayed and 9 thresholded responses, the running and published maximum, the
    // corner shift register
    CHECK(p.registers.size() == 196 + 3 + 49 + 50 + 75 + 27 + 27 + 27 + 2 + 1);
    CHECK(p.registers.front() == "win0(1,1) = u.icmux.win[1567:1560]");
}

TEST_CASE("datapath induction through the ranges command: a Sobel coefficient changed in a copy of the VHDL is a difference naming the gradient",
          "[datapath-induction-mutant]") {
    const util::ScratchDir dir;
    RangesCommand c;
    c.no_netlist = true;
    c.datapath_induction = (dir.path() / "di").string();
    c.json = (dir.path() / "ranges.json").string();
    c.out = (dir.path() / "ranges.md").string();
    c.rtl = mutated_rtl(dir.path(), "sobel_x.vhd", "+ resize(p23, SOBEL_W)", "+ resize(p13, SOBEL_W)").string();
    run_ranges_command(c);
    const nlohmann::json j = nlohmann::json::parse(util::read_file(c.json));
    const nlohmann::json& di = j.at(0).at("datapath_induction").at(0);
    INFO(di.dump(1));
    CHECK(di.at("size") == "10x8");
    CHECK(di.at("verdict") == "counterexample");
    CHECK(di.at("classes") == 33);   // the model's classes, not the mutant's
    // the first class whose step query z3 finds sat names the x gradient it writes (which
    // class answers first depends on the solvers' order on the cores)
    CHECK(std::regex_search(di.at("detail").get<std::string>(), std::regex(R"(the netlist's next sxm\(\d,\d\) differs)")));
    CHECK(di.at("rechecked") == false);
    CHECK(fs::is_regular_file(dir.path() / "di" / "thesis" / "10x8" / "which.smt2"));
    CHECK(util::read_file(c.out).find("## Every register from reset: thesis") != std::string::npos);
}

TEST_CASE("datapath induction where the M products' signed resize can overflow (m_prod_w 20): open, naming the resize",
          "[datapath-induction-overflow]") {
    Formats f;   // the widths of sweep/configs/bit-widths.json's "m_prod_w=20"
    f.m_prod_w = 20;
    f.m_drop = 4;
    const util::ScratchDir dir;
    const DatapathInduction p = prove_datapath_from_reset(f, Geometry{10, 8}, {.dir = dir.path(), .rtl_dir = {}});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::open);
    CHECK(p.side_conditions == 7 * 75);
    CHECK(p.distinct_side_conditions == 75);
    // 1020^2 needs 21 bits as a signed number: the side condition is found false on the model
    CHECK(p.detail.find("(22 -> 20 bits)") != std::string::npos);
    CHECK(p.detail.find("may overflow (z3: sat; unsat expected)") != std::string::npos);
    CHECK_FALSE(p.rechecked);
}

TEST_CASE("datapath induction's report: one row per size, the command's pipes escaped in its table cell", "[model]") {
    DatapathInduction p;
    p.geometry = {10, 8};
    p.verdict = EqVerdict::equal;
    p.classes = 33;
    p.model_writes = 112;
    p.recheck = "cvc5: 34 unsat of 34";
    p.command = "cd D && cat head.smt2 q | z3 -in";
    const std::string md = datapath_induction_markdown("thesis", {p});
    p.side_conditions = 525;
    p.distinct_side_conditions = 75;
    const std::string md2 = datapath_induction_markdown("thesis", {p});
    CHECK(md.find("| 10x8 | proven equal | 33 | 112 | - | 0 (0 distinct) | cvc5: 34 unsat of 34 |") != std::string::npos);
    CHECK(md2.find("| 10x8 | proven equal | 33 | 112 | - | 525 (75 distinct) | cvc5: 34 unsat of 34 |") != std::string::npos);
    CHECK(md.find("`cd D && cat head.smt2 q \\| z3 -in`") != std::string::npos);
}

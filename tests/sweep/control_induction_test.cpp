// Control induction: harris_top's control registers on GHDL's netlist against the cycle
// model's from reset, for every input sequence (ghdl, yosys, z3 and cvc5 on PATH).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "model/util/errors.hpp"
#include "model/util/util.hpp"
#include "sweep/control_induction.hpp"
#include "sweep/ranges_command.hpp"
#include "tests/sweep/mutated_rtl.hpp"

using namespace hc;
using namespace hc::sweep;
namespace fs = std::filesystem;

TEST_CASE("control induction at the smallest image: the netlist's control registers follow the model's from reset", "[control-induction]") {
    const util::ScratchDir dir;
    const ControlInduction p = prove_control_from_reset(Formats{}, Geometry{10, 8}, {.dir = dir.path()});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::equal);
    // 10x8: 56 writes a frame, of which 4 enable find_max; its period is 32 enabled steps, so the
    // control state repeats after 8 frames
    CHECK(p.period == 8 * 56);
    CHECK(p.queries == p.prefix + p.period);
    CHECK(p.rechecked);
    CHECK(p.recheck == fmt::format("cvc5: {} unsat of {}", p.queries, p.queries));
    CHECK(p.registers.size() == 7);
    CHECK(fs::is_regular_file(dir.path() / "query.smt2"));
    CHECK(p.command == "z3 -smt2 " + (dir.path() / "query.smt2").string());
}

TEST_CASE("control induction: load control's fill constant changed in a copy of the VHDL gives the write where load differs",
          "[control-induction]") {
    const util::ScratchDir dir;
    ControlInductionOptions o;
    o.rtl_dir = mutated_rtl(dir.path(), "load_control.vhd", "FILL       : positive := 49;", "FILL       : positive := 48;");
    o.dir = dir.path() / "proof";
    o.recheck = false;
    const ControlInduction p = prove_control_from_reset(Formats{}, Geometry{10, 8}, o);
    CHECK(p.verdict == EqVerdict::counterexample);
    // the model lowers load after write 49 of a row (col 49 -> 50); the mutant after write 48
    CHECK(p.detail.find("write 47: the netlist's next lc.load (model 1)") != std::string::npos);
    INFO(p.detail);
}

TEST_CASE("control induction: more distinct control states than the limit is open, not proven", "[control-induction]") {
    ControlInductionOptions o;
    o.max_states = 10;
    const ControlInduction p = prove_control_from_reset(Formats{}, Geometry{10, 8}, o);
    CHECK(p.verdict == EqVerdict::open);
    CHECK(p.detail == "more than 10 distinct control states from reset");
    CHECK(p.queries == 0);
}

TEST_CASE("ranges --control-induction: the command reports each size's verdict in its JSON, and takes --rtl without --stages",
          "[control-induction]") {
    const util::ScratchDir dir;
    RangesCommand c;
    c.no_netlist = true;
    c.control_induction = (dir.path() / "ci").string();
    c.json = (dir.path() / "ranges.json").string();
    c.out = (dir.path() / "ranges.md").string();
    c.rtl = mutated_rtl(dir.path(), "load_control.vhd", "FILL       : positive := 49;", "FILL       : positive := 48;").string();
    run_ranges_command(c);
    const nlohmann::json j = nlohmann::json::parse(util::read_file(c.json));
    const nlohmann::json& ci = j.at(0).at("control_induction").at(0);
    CHECK(ci.at("size") == "10x8");
    CHECK(ci.at("verdict") == "counterexample");
    CHECK(ci.at("detail").get<std::string>().rfind("write 47: the netlist's next lc.load", 0) == 0);
    CHECK(fs::is_regular_file(dir.path() / "ci" / "thesis" / "10x8" / "query.smt2"));
    CHECK(util::read_file(c.out).find("## Control registers from reset: thesis") != std::string::npos);

    c.control_sizes = {"8x8"};   // below the smallest width
    CHECK_THROWS_AS(run_ranges_command(c), InputError);
}

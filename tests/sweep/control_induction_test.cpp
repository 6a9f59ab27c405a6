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

namespace {

/// The proof at 10x8 (no second solver) on a copy of rtl/ with `from` replaced by `to` in `file`.
ControlInduction prove_mutant(const util::ScratchDir& dir, const std::string& file, const std::string& from, const std::string& to) {
    ControlInductionOptions o;
    o.rtl_dir = mutated_rtl(dir.path(), file, from, to);
    o.dir = dir.path() / "proof";
    o.recheck = false;
    return prove_control_from_reset(Formats{}, Geometry{10, 8}, o);
}

}  // namespace

TEST_CASE("control induction at the smallest image: the netlist's control registers follow the model's from reset", "[control-induction]") {
    const util::ScratchDir dir;
    const ControlInduction p = prove_control_from_reset(Formats{}, Geometry{10, 8}, {.dir = dir.path()});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::equal);
    // 10x8: 56 writes a frame, of which 4 enable find_max; its period is 32 enabled steps. The
    // frame part of the control state (all but find_max's counter) repeats every frame, the
    // whole control state after 8 frames: one query per frame part, the counter symbolic in each
    CHECK(p.prefix == 4);
    CHECK(p.period == 56);
    CHECK(p.queries == p.prefix + p.period);
    CHECK(p.model_writes == p.prefix + 8 * 56);
    CHECK(p.count_range == std::pair<long, long>{1, 32});
    CHECK(p.rechecked);
    CHECK(p.recheck == fmt::format("cvc5: {} unsat of {}", p.queries, p.queries));
    CHECK(p.registers.size() == 7);
    CHECK(fs::is_regular_file(dir.path() / "query.smt2"));
    CHECK(p.command == "z3 -smt2 " + (dir.path() / "query.smt2").string());
}

TEST_CASE("control induction at 40x30: one query per state of a frame covers the 23 frames the whole control state takes to repeat",
          "[control-induction]") {
    const util::ScratchDir dir;
    const ControlInduction p = prove_control_from_reset(Formats{}, Geometry{40, 30}, {.dir = dir.path()});
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::equal);
    // 40x30: (15 - 3) x (20 + 3) x 7 = 1,932 writes a frame, 768 of them enable find_max, whose
    // period is 1,104 enabled steps: the whole control state repeats after 1,104 / gcd(1,104, 768)
    // = 23 frames (44,436 states), the frame part after one
    CHECK(p.period == 1932);
    CHECK(p.queries == p.prefix + 1932);
    CHECK(p.model_writes == p.prefix + 23 * 1932);
    CHECK(p.count_range == std::pair<long, long>{1, 1104});
    CHECK(p.rechecked);
    CHECK(p.recheck == fmt::format("cvc5: {} unsat of {}", p.queries, p.queries));
}

TEST_CASE("control induction: load control's fill constant changed in a copy of the VHDL gives the write where load differs",
          "[control-induction]") {
    const util::ScratchDir dir;
    const ControlInduction p = prove_mutant(dir, "load_control.vhd", "FILL       : positive := 49;", "FILL       : positive := 48;");
    CHECK(p.verdict == EqVerdict::counterexample);
    // the model lowers load after write 49 of a row (col 49 -> 50); the mutant after write 48
    CHECK(p.detail.find("write 47: the netlist's next lc.load (model 1)") != std::string::npos);
    INFO(p.detail);
}

TEST_CASE("control induction: more frame-part states than the limit, or a model run shorter than the whole control state's period, is open",
          "[control-induction]") {
    ControlInductionOptions few_states, few_writes;
    few_states.max_states = 10;
    few_writes.max_writes = 100;
    const ControlInduction a = prove_control_from_reset(Formats{}, Geometry{10, 8}, few_states);
    const ControlInduction b = prove_control_from_reset(Formats{}, Geometry{10, 8}, few_writes);
    CHECK(a.verdict == EqVerdict::open);
    CHECK(a.detail == "more than 10 distinct control states (less find_max's counter) from reset");
    CHECK(a.queries == 0);
    CHECK(b.verdict == EqVerdict::open);
    CHECK(b.detail == "the model after write 100: its control state did not repeat within 100 writes");
    CHECK(b.queries == 0);
}

TEST_CASE("control induction: find_max's counter wrapping to another value in a copy of the VHDL is a counterexample naming it",
          "[control-induction]") {
    const util::ScratchDir dir;
    const ControlInduction p = prove_mutant(dir, "find_max.vhd", "          count   <= 1;", "          count   <= 2;");
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::counterexample);
    // the counter is symbolic in each query, so the first state whose write moves it (at 10x8
    // the frame's write 55) meets it at its wrap
    CHECK(p.detail.rfind("write 55: the netlist's next fm.count (model count + 1, wrapping)", 0) == 0);
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
    CHECK(ci.at("model_writes") == 4 + 8 * 56);   // the model's run, not the mutant's
    CHECK(ci.at("count_range") == nlohmann::json::array({1, 32}));
    CHECK(ci.at("detail").get<std::string>().rfind("write 47: the netlist's next lc.load", 0) == 0);
    CHECK(fs::is_regular_file(dir.path() / "ci" / "thesis" / "10x8" / "query.smt2"));
    CHECK(util::read_file(c.out).find("## Control registers from reset: thesis") != std::string::npos);

    c.control_sizes = {"8x8"};   // below the smallest width
    CHECK_THROWS_AS(run_ranges_command(c), InputError);
}

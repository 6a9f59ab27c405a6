// Stage equivalence: each datapath entity's GHDL netlist against the model's stage function,
// for every input (ghdl, yosys, z3 and cvc5 on PATH; label netlist).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "model/util/util.hpp"
#include "model/fixed/word.hpp"
#include "model/harris/find_max.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/util/errors.hpp"
#include "sweep/cost.hpp"
#include "sweep/ranges_command.hpp"
#include "sweep/stage_equivalence.hpp"
#include "tests/sweep/mutated_rtl.hpp"

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

TEST_CASE("find_max: the comparison flipped in a copy of the VHDL yields a counterexample that holds in the model", "[stages]") {
    const util::ScratchDir dir;
    StageOptions o;
    o.rtl_dir = mutated_rtl(dir.path(), "find_max.vhd", "if response > running then", "if response < running then");
    o.dir = dir.path() / "proof";
    const StageProof p = prove_stage(EqStage::find_max, Formats{}, o);
    INFO(p.detail);
    REQUIRE(p.verdict == EqVerdict::counterexample);
    // the counterexample's registers through the model's step: the mutant differs in the running maximum
    const auto& x = p.counterexample;
    FindMax fm(Formats{});
    fm.count = x.at("count");
    fm.running = Word::sgn(x.at("running"), 32);
    fm.max = Word::sgn(x.at("max"), 32);
    const Word response = Word::sgn(x.at("response"), 32);
    const FindMax n = fm.next(response, Geometry{});
    CHECK(x.at("count") < Geometry{}.find_max_period());   // inside the period: the update is not overridden
    CHECK(response != fm.running);
    CHECK(n.running.value() == std::max(response.value(), fm.running.value()));
    CHECK(p.detail.find("running: model " + std::to_string(n.running.value()) + ", netlist ") == 0);
    // the unchanged VHDL proves equal, also at the smallest image (a period of 32 steps)
    o.rtl_dir.clear();
    o.dir = dir.path() / "proof-original";
    CHECK(prove_stage(EqStage::find_max, Formats{}, o).verdict == EqVerdict::equal);
    o.geometry = {Geometry::min_width, Geometry::min_height};
    o.dir = dir.path() / "proof-small";
    const StageProof small = prove_stage(EqStage::find_max, Formats{}, o);
    CHECK(small.verdict == EqVerdict::equal);
    CHECK(util::read_file(o.dir / "commands.txt").find("-gIMG_WIDTH=10 -gIMG_HEIGHT=8") != std::string::npos);
}

TEST_CASE("find_max at a 38-bit response: GHDL's bit-string constants are read as sized literals, and it proves equal", "[stages]") {
    const util::ScratchDir dir;
    Formats f;   // tight-m3-b2 of sweep/configs/bit-widths.json
    f.m_drop = 3;
    f.bf_sum_w = 22;
    f.bf_drop = 2;
    f.ktr_w = 35;
    f.resp_w = 38;
    StageOptions o;
    o.dir = dir.path();
    const StageProof p = prove_stage(EqStage::find_max, f, o);
    INFO(p.detail);
    CHECK(p.verdict == EqVerdict::equal);
    // GHDL writes the most negative value as a string, which Verilog reads as text; the netlist
    // the proof read holds it as a sized literal, and the command in commands.txt makes both
    const std::string most_negative(37, '0');
    const std::string netlist = util::read_file(dir.path() / "find_max.v");
    CHECK(netlist.find("38'b1" + most_negative) != std::string::npos);
    CHECK(netlist.find('"') == std::string::npos);
    const std::string cmds = util::read_file(dir.path() / "commands.txt");
    const size_t from = cmds.find("ghdl "), pipe = cmds.find(" | perl "), to = cmds.find(" > find_max.v");
    REQUIRE(from != std::string::npos);
    REQUIRE(pipe < to);
    REQUIRE(util::run_process({"sh", "-c", cmds.substr(from, pipe - from) + " > raw.v"}, {.cwd = dir.path()}) == 0);
    CHECK(util::read_file(dir.path() / "raw.v").find("\"1" + most_negative + "\"") != std::string::npos);
    REQUIRE(util::run_process({"sh", "-c", cmds.substr(from, to - from) + " > again.v"}, {.cwd = dir.path()}) == 0);
    CHECK(util::read_file(dir.path() / "again.v") == netlist);
}

TEST_CASE("local_maximum: a strict comparison made non-strict in a copy of the VHDL yields a tie as counterexample", "[stages]") {
    const util::ScratchDir dir;
    StageOptions o;
    o.rtl_dir = mutated_rtl(dir.path(), "local_maximum.vhd", "r(2, 2) > r(1, 3)", "r(2, 2) >= r(1, 3)");
    o.dir = dir.path() / "proof";
    Formats f;
    f.resp_w = 20;
    const StageProof p = prove_stage(EqStage::local_maximum, f, o);
    INFO(p.detail);
    REQUIRE(p.verdict == EqVerdict::counterexample);
    // the counterexample's responses through the model: the centre ties its top-right neighbour, so no corner
    Matrix3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = Word::sgn(p.counterexample.at("r_" + std::to_string(i) + "_" + std::to_string(j)), 20);
    CHECK(r[1][1] == r[0][2]);
    CHECK_FALSE(local_maximum(r));
    CHECK(p.detail.find("corner: model 0, netlist 1") == 0);
    o.rtl_dir.clear();
    o.dir = dir.path() / "proof-original";
    CHECK(prove_stage(EqStage::local_maximum, f, o).verdict == EqVerdict::equal);
}

TEST_CASE("a Sobel coefficient changed in a copy of the VHDL yields a counterexample that differs in the model", "[stages]") {
    const util::ScratchDir dir;
    // the middle right coefficient +2 becomes +1
    const fs::path rtl = mutated_rtl(dir.path(), "sobel_x.vhd",
                                     "  p23 <= signed(resize(a(2, 3), PIXEL_W + 2)) + signed(resize(a(2, 3), PIXEL_W + 2));",
                                     "  p23 <= signed(resize(a(2, 3), PIXEL_W + 2));");
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

TEST_CASE("ranges --rtl: the stage proofs run on a mutated copy of rtl/ give its counterexample", "[stages]") {
    const util::ScratchDir dir;
    RangesCommand c;
    c.no_netlist = true;
    c.ro.solver_rlimit = 0;
    c.stages = (dir.path() / "stages").string();
    c.json = (dir.path() / "ranges.json").string();
    c.out = (dir.path() / "ranges.md").string();
    // threshold keeps a response equal to thr; the mutant drops it
    c.rtl = mutated_rtl(dir.path(), "threshold.vhd", "r0_delay >= thr", "r0_delay > thr").string();
    run_ranges_command(c);
    const auto j = nlohmann::json::parse(util::read_file(c.json));
    REQUIRE(j.size() == 1);
    const auto& stages = j[0].at("stages").at("stages");
    REQUIRE(stages.size() == static_cast<size_t>(kEqStageCount));
    for (const auto& st : stages) {
        INFO(st.at("stage") << ": " << st.at("detail"));
        CHECK(st.at("verdict") == (st.at("stage") == "threshold" ? "counterexample" : "proven equal"));
    }
    // the counterexample is a tie (r0_delay = thr): the model keeps it, the mutant zeroes it
    const auto& cx = stages[static_cast<int>(EqStage::threshold)].at("counterexample");
    CHECK(cx.at("r0_delay") == cx.at("thr"));
    CHECK(cx.at("r0_delay") != 0);
    // the proof kept its queries under DIR/<configuration>/<stage>
    CHECK(fs::exists(dir.path() / "stages" / "thesis" / "threshold" / "query-2.smt2"));
    // the project's rtl/ proves the same stage equal
    CHECK(prove_stage(EqStage::threshold, Formats{}, {}).verdict == EqVerdict::equal);
    // bad input: a directory without the VHDL, or --rtl without --stages
    c.rtl = (dir.path() / "no-such-rtl").string();
    CHECK_THROWS_AS(run_ranges_command(c), InputError);
    c.rtl = mutated_rtl(dir.path() / "again", "threshold.vhd", "r0_delay >= thr", "r0_delay > thr").string();
    c.stages.clear();
    CHECK_THROWS_AS(run_ranges_command(c), InputError);
}

TEST_CASE("the sweep's stage proofs are cached under the synthesis key: read back by a second run, keyed anew by an edited RTL "
          "file or other formats", "[stages]") {
    const util::ScratchDir dir;
    CostOptions co;
    co.rtl_sources = cosim::rtl_sources();
    co.cache_dir = dir.path() / "cost";
    const CostContext ctx(co);
    const std::string key = cost_key(ctx, Formats{}, Variant::signed_mul);
    StageOptions o;
    o.recheck = false;   // z3 alone: the cache is under test here, not the second solver
    const fs::path cache = dir.path() / "stages";
    const StageEquivalence first = cached_stage_equivalence(Formats{}, key, cache, o);
    CHECK_FALSE(first.cached);
    CHECK(first.all_proven());
    CHECK(first.column() == "8/8 proven");
    REQUIRE(fs::exists(cache / (key + ".json")));
    const auto t0 = std::chrono::steady_clock::now();
    const StageEquivalence second = cached_stage_equivalence(Formats{}, key, cache, o);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);   // no synthesis, no solver
    CHECK(second.cached);
    CHECK(second.column() == first.column());
    CHECK(second.seconds == first.seconds);   // the first run's time, recorded
    REQUIRE(second.stages.size() == first.stages.size());
    for (size_t k = 0; k < first.stages.size(); ++k) CHECK(second.stages[k].rlimit == first.stages[k].rlimit);
    // an entry recorded under other options is not this run's verdict
    nlohmann::json entry = nlohmann::json::parse(util::read_file(cache / (key + ".json")));
    CHECK(entry.at("key") == key);
    entry["options"] = "rlimit=1";
    for (auto& s : entry["stages"]) s["verdict"] = "open";
    util::write_file_atomic(cache / (key + ".json"), entry.dump());
    const StageEquivalence again = cached_stage_equivalence(Formats{}, key, cache, o);
    CHECK_FALSE(again.cached);
    CHECK(again.all_proven());
    // the key: other formats, an edited RTL file
    Formats f;
    f.resp_w = 31;
    CHECK(cost_key(ctx, f, Variant::signed_mul) != key);
    const fs::path rtl = mutated_rtl(dir.path(), "find_max.vhd", "if response > running then", "if response >  running then");
    CostOptions edited = co;
    edited.rtl_sources = cosim::rtl_sources(rtl);
    CHECK(cost_key(CostContext(edited), Formats{}, Variant::signed_mul) != key);
}

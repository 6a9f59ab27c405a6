// sweep_test.cpp: the pure-C++ parts of the bit-width sweep (tools/sweep/): overflow audit,
// spec file parsing, Pareto selection, the signed-multiply rewrite of GHDL's Verilog.
#include <catch2/catch.hpp>

#include "sweep/cost.hpp"
#include "sweep/overflow.hpp"
#include "sweep/pareto.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_config.hpp"
#include "sweep/sweep_report.hpp"

using namespace hc;
using namespace hc::sweep;

namespace {

/// A vertical step edge 0 | 255: |Gx| = 4*255 = 1020, the largest Sobel value.
Image step_edge(int w, int h) {
    Image im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) im.at(y, x) = x < w / 2 ? 0 : 255;
    return im;
}

}  // namespace

TEST_CASE("the thesis formats never wrap, on the extremes pattern and on a 0|255 edge", "[model][sweep]") {
    const Formats thesis;
    for (int k = 0; k < 3; ++k) {
        const OverflowCounts c = count_overflows(make_pattern(Pattern::extremes, 40, 30, k), thesis);
        INFO("extremes frame " << k << ": " << c.summary());
        CHECK(c.total_wrapped() == 0);
        CHECK(c.values[sobel] == 2u * 38 * 28);
    }
    CHECK(count_overflows(step_edge(20, 12), thesis).total_wrapped() == 0);
}

TEST_CASE("sobel_w=9 wraps the Sobel sum of a 0|255 edge and the audit says so", "[model][sweep]") {
    Formats f;
    f.sobel_w = 9;   // +-255 only; the edge gives +-1020
    const OverflowCounts c = count_overflows(step_edge(20, 12), f);
    INFO(c.summary());
    // every Sobel x value whose 3x3 window straddles the edge: 2 columns x 10 rows
    CHECK(c.wrapped[sobel] == 20);
    CHECK(c.summary().find("sobel 20") == 0);
}

TEST_CASE("too few block-sum bits wrap the block sum, too few response bits the response", "[model][sweep]") {
    const Image im = step_edge(20, 12);
    Formats f;
    f.bf_sum_w = 17;   // nine values of up to 32512 need 20 bits
    f.bf_drop = 1;
    CHECK(count_overflows(im, f).wrapped[block_sum] > 0);
    Formats g;
    g.resp_w = 20;
    CHECK(count_overflows(im, g).wrapped[response] > 0);
    Formats h;
    h.ktr_w = 16;
    CHECK(count_overflows(im, h).wrapped[k_term] > 0);
    Formats m;
    m.m_prod_w = 18;   // 1020^2 needs 21 bits
    m.m_drop = 2;
    CHECK(count_overflows(im, m).wrapped[m_resize] > 0);
}

TEST_CASE("a sweep spec expands configs and grid, names grid points by their values, adds the thesis", "[model][sweep]") {
    const SweepSpec s = parse_sweep_spec(R"({"name": "t", "base": {"resp_w": 32},
        "configs": [{"name": "narrow", "sobel_w": 10}],
        "grid": {"bf_drop": [4, 5], "m_drop": [5, 6]}})", "test");
    REQUIRE(s.configs.size() == 5);   // narrow + 4 grid points (m_drop=5,bf_drop=4 is the thesis)
    CHECK(s.configs[0].name == "narrow");
    CHECK(s.configs[0].formats.sobel_w == 10);
    CHECK(s.configs[1].name == "m_drop=5,bf_drop=4");   // struct order, not JSON order
    CHECK(s.configs[1].formats == Formats{});
    CHECK(s.configs[4].name == "m_drop=6,bf_drop=5");
    CHECK(s.configs[4].formats.m_drop == 6);
    CHECK(s.configs[4].formats.bf_drop == 5);
    CHECK(s.notes.empty());
}

TEST_CASE("a sweep spec without the thesis formats gets them under the name thesis, and equal formats are merged", "[model][sweep]") {
    const SweepSpec s = parse_sweep_spec(R"({"configs": [{"sobel_w": 12}, {"name": "again", "sobel_w": 12}]})", "test");
    REQUIRE(s.configs.size() == 2);
    CHECK(s.configs[0].name == "sobel_w=12");
    CHECK(s.configs[1].name == "thesis");
    CHECK(s.notes.size() == 2);
}

TEST_CASE("bad sweep specs are rejected with the input and the entry named", "[model][sweep]") {
    auto error_of = [](const std::string& text) {
        try {
            parse_sweep_spec(text, "spec.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    using Catch::Matchers::Contains;
    CHECK_THAT(error_of("{nope"), Contains("spec.json: not valid JSON"));
    CHECK_THAT(error_of("[1]"), Contains("must be a JSON object"));
    CHECK_THAT(error_of("{}"), Contains("no configuration"));
    CHECK_THAT(error_of(R"({"configs": [{"sobel": 10}]})"), Contains("configs[0]: unknown key 'sobel'"));
    CHECK_THAT(error_of(R"({"configs": [{"sobel_w": "10"}]})"), Contains("configs[0].sobel_w: must be an integer"));
    CHECK_THAT(error_of(R"({"configs": [{"name": "x", "m_drop": 21}]})"), Contains("m_drop must be 0..m_prod_w-1"));
    CHECK_THAT(error_of(R"({"configs": [{"name": "a", "sobel_w": 10}, {"name": "a", "sobel_w": 12}]})"),
               Contains("name \"a\" already used by configs[0]"));
    CHECK_THAT(error_of(R"({"grid": {"sobel_w": []}})"), Contains("grid.sobel_w: must be a non-empty list"));
    CHECK_THAT(error_of(R"({"grid": {"sobel_w": [10]}, "colour": 1})"), Contains("top level: unknown key 'colour'"));
    CHECK_THAT(error_of(R"({"grid": {"sobel_w": [10]}, "cost": {"img_width": 4}})"), Contains("cost: image 4x360"));
    CHECK_THAT(error_of(R"({"configs": [{"name": "thesis", "sobel_w": 12}]})"), Contains("reserved"));
}

TEST_CASE("the Pareto front keeps the non-dominated points and ties, and skips ineligible ones", "[model][sweep]") {
    // objectives: LUTs, DSPs, -F1
    const std::vector<std::vector<double>> o{
        {100, 10, -0.90},   // 0: front (best F1)
        {80, 10, -0.85},    // 1: front (cheaper)
        {90, 10, -0.84},    // 2: dominated by 1
        {80, 10, -0.85},    // 3: tie with 1: kept
        {50, 10, -0.95},    // 4: dominates everything, but ineligible (wraps)
        {60, 12, -0.80}};   // 5: front (fewest LUTs among eligible)
    const std::vector<bool> eligible{true, true, true, true, false, true};
    const auto f = pareto_front(o, eligible);
    CHECK(f == std::vector<bool>{true, true, false, true, false, true});
    CHECK(pareto_front(o) == std::vector<bool>{false, false, false, false, true, false});
}

TEST_CASE("mark_pareto uses LUTs, DSPs and F1 and leaves wrapping configurations out", "[model][sweep]") {
    std::vector<PointResult> pts(3);
    pts[0].cost.luts = 100; pts[0].cost.dsps = 102; pts[0].accuracy = {90, 0, 10, 10};
    pts[1].cost.luts = 90;  pts[1].cost.dsps = 102; pts[1].accuracy = {80, 0, 20, 20};
    pts[2].cost.luts = 10;  pts[2].cost.dsps = 1;   pts[2].accuracy = {99, 0, 1, 1}; pts[2].wraps = true;
    mark_pareto(pts);
    CHECK(pts[0].pareto);
    CHECK(pts[1].pareto);
    CHECK_FALSE(pts[2].pareto);
}

TEST_CASE("GHDL's sign-extended products become signed multiplies of the original operands", "[model][sweep]") {
    std::string v =
        "  assign n1134_o = {{11{ix[10]}}, ix}; // sext\n"
        "  assign n1135_o = {{11{iy[10]}}, iy}; // sext\n"
        "  assign n1136_o = n1134_o * n1135_o; // smul\n"
        "  assign n2 = n1134_o * other; // smul\n"
        "  assign n3 = {{4{q[3]}}, r}; // sext\n";
    CHECK(rewrite_signed_multiplies(v) == 1);
    CHECK(v.find("assign n1136_o = $signed(ix) * $signed(iy);") != std::string::npos);
    CHECK(v.find("assign n2 = n1134_o * other; // smul") != std::string::npos);   // other operand unknown: kept
}

TEST_CASE("the analytic register count follows every datapath width", "[model][sweep]") {
    const Geometry g{640, 360};
    const Formats t;
    const long base = datapath_register_bits(t, g);
    Formats f = t;
    f.sobel_w = 12;
    CHECK(datapath_register_bits(f, g) - base == 50);   // 2 x 25 Sobel registers
    f = t;
    f.m_drop = 6;
    CHECK(datapath_register_bits(f, g) - base == -75);   // 3 x 25 M registers
    f = t;
    f.bf_drop = 5;
    CHECK(datapath_register_bits(f, g) - base == -(27 + 9 * 4));   // block sums, a*c and b*b
}

TEST_CASE("the sweep report shows each checked point's three-way gate in its Gate column", "[model][sweep]") {
    sweep::SweepResult r;
    r.spec.name = "gate-column";
    r.spec.trust.verilator_gate = true;
    sweep::PointResult pass, fault, unchecked;
    pass.config.name = "passes";
    pass.pareto = pass.verify = true;
    pass.gate = {.ran = true, .runs = 1, .seconds = 81, .detail = "pass: 4564 writes, 432 reads agree three ways (81 s)"};
    fault.config.name = "faults";
    fault.config.formats.m_drop = 4;
    fault.pareto = fault.verify = true;
    fault.gate = {.ran = true, .runs = 1, .failed = 1,
                  .detail = "gate: translation fault: translation fault: 10x10 ..., write 5: mbm(1,1) (log g.log)"};
    unchecked.config.name = "unchecked";
    unchecked.config.formats.m_drop = 6;
    // the ranges column: a proven Pareto point, a point without ranges, one that wraps
    pass.ranges = sweep::interval_ranges(pass.config.formats);
    pass.has_ranges = true;
    sweep::PointResult narrow;
    narrow.config.name = "sobel_w=10";
    narrow.config.formats.sobel_w = 10;
    sweep::RangeOptions model_only;
    model_only.netlist = false;
    narrow.ranges = sweep::analyse_ranges(narrow.config.formats, model_only);
    narrow.has_ranges = true;
    r.points = {pass, fault, unchecked, narrow};
    const std::string md = sweep::to_markdown(r);
    CHECK_THAT(md, Catch::Contains("| ranges | P | GHDL | Gate | Verilator |"));
    CHECK_THAT(md, Catch::Contains("| proven safe (interval 14; netlist not run) | **P** proven | - | pass (81 s) | - |"));
    CHECK_THAT(md, Catch::Contains("| - | **P** not proven | - | **gate: translation fault** | - |"));
    CHECK_THAT(md, Catch::Contains("| - |  | - | - | - |"));
    CHECK_THAT(md, Catch::Contains("| **wraps at sobel_x** (witnesses/sobel_w-10_sobel_x.pgm) (interval 12, search 2; netlist not run) |  | - | - | - |"));
    const std::string csv = sweep::to_csv(r);
    // after the name, one column per row of the formats table, in its order, with the
    // configuration's values (here the point sobel_w=10)
    std::string fields = "name", values = "sobel_w=10";
    for (const auto& fld : format_fields()) {
        fields += std::string(",") + fld.name;
        values += "," + std::to_string(narrow.config.formats.*(fld.member));
    }
    CHECK(csv.rfind(fields + ",recall,", 0) == 0);
    CHECK_THAT(csv, Catch::Contains("\n" + values + ","));
    CHECK_THAT(csv, Catch::Contains("gate_passed,gate_seconds,ranges,ranges_first_wrap,trajectory_ape_slam,"
                                    "trajectory_ape_odometry,trajectory_path_length,trajectory_odometry_failures,"
                                    "stages_proven,stages_not_proven,verilator_trust\n"));
    // the four trajectory columns stay empty (no trajectory was scored), as do the stage proofs' (not run)
    CHECK_THAT(csv, Catch::Contains(",1,81.0,proven,,,,,,,,samples only\n"));
    CHECK_THAT(csv, Catch::Contains(",0,0.0,,,,,,,,,failed\n"));
    CHECK_THAT(csv, Catch::Contains(",,,wraps,sobel_x,,,,,,,-\n"));
}

TEST_CASE("the sweep report's stage proofs and Verilator trust: proven only where every stage proof ran and proved", "[model][sweep]") {
    auto proofs = [](std::vector<EqVerdict> v) {
        StageEquivalence e;
        for (size_t k = 0; k < v.size(); ++k) {
            StageProof p;
            p.stage = static_cast<EqStage>(k);
            p.verdict = v[k];
            e.stages.push_back(p);
        }
        return e;
    };
    const TrustResult passed{.ran = true, .runs = 1, .seconds = 12, .detail = "pass"};
    sweep::SweepResult r;
    r.spec.name = "stage-column";
    sweep::PointResult all, differs, none, unchecked;
    all.config.name = "all-proven";
    all.gate = all.verilator = passed;
    all.stages = proofs(std::vector<EqVerdict>(kEqStageCount, EqVerdict::equal));
    all.stages.cached = true;
    all.has_stages = true;
    differs.config.name = "response-differs";
    differs.config.formats.resp_w = 27;
    differs.gate = differs.verilator = passed;
    std::vector<EqVerdict> v(kEqStageCount, EqVerdict::equal);
    v[static_cast<int>(EqStage::harris_response)] = EqVerdict::netlist_differs;
    v[static_cast<int>(EqStage::block_filter)] = EqVerdict::open;
    differs.stages = proofs(v);
    differs.has_stages = true;
    none.config.name = "not-proven";   // the gate passed, the proofs did not run
    none.config.formats.resp_w = 31;
    none.gate = passed;
    unchecked.config.name = "unchecked";   // proven, but no Verilator run to trust
    unchecked.config.formats.resp_w = 33;
    unchecked.stages = all.stages;
    unchecked.stages.cached = false;
    unchecked.has_stages = true;
    r.points = {all, differs, none, unchecked};

    CHECK(all.stages.column() == "8/8 proven");
    CHECK(differs.stages.column() == "6 proven, 1 netlist differs (harris_response), 1 open (block_filter)");
    CHECK(verilator_trust(all) == VerilatorTrust::stages_proven);
    CHECK(verilator_trust(differs) == VerilatorTrust::samples);
    CHECK(verilator_trust(none) == VerilatorTrust::samples);
    CHECK(verilator_trust(unchecked) == VerilatorTrust::not_run);
    sweep::PointResult failed = all;
    failed.verilator.failed = 1;
    CHECK(verilator_trust(failed) == VerilatorTrust::failed);

    const std::string md = to_markdown(r);
    CHECK_THAT(md, Catch::Contains("| stage proofs | Verilator trust |"));
    CHECK_THAT(md, Catch::Contains("| 8/8 proven (cached) | stages proven |"));
    CHECK_THAT(md, Catch::Contains("| 6 proven, 1 netlist differs (harris_response), 1 open (block_filter) | samples only |"));
    CHECK_THAT(md, Catch::Contains("| not run | samples only |"));
    CHECK_THAT(md, Catch::Contains("| 8/8 proven | - |"));
    CHECK_THAT(md, Catch::Contains("not stage-proven"));
    const std::string csv = to_csv(r);
    CHECK_THAT(csv, Catch::Contains(",8,,stages proven\n"));
    CHECK_THAT(csv, Catch::Contains(",6,block_filter:open;harris_response:netlist differs from the VHDL,samples only\n"));
    CHECK_THAT(csv, Catch::Contains(",,,samples only\n"));
    const nlohmann::json j = nlohmann::json::parse(sweep::to_json(r));
    CHECK(j.at("points").at(0).at("verilator_trust") == "stages proven");
    CHECK(j.at("points").at(0).at("stages").at("cached") == true);
    CHECK(j.at("points").at(2).at("stages").is_null());
}

TEST_CASE("the trajectory column's spec: off unless asked for, a sequence and a descriptor, bad keys refused", "[sweep]") {
    CHECK_FALSE(parse_sweep_spec(R"({"configs": [{"name": "a"}]})", "t").trajectory.enabled);
    const SweepSpec s = parse_sweep_spec(R"({"configs": [{"name": "a"}], "trajectory": {"sequence": "07", "descriptor": "brief"}})", "t");
    CHECK(s.trajectory.enabled);
    CHECK(s.trajectory.sequence == "07");
    CHECK(s.trajectory.descriptor == "brief");
    const SweepSpec d = parse_sweep_spec(R"({"configs": [{"name": "a"}], "trajectory": true})", "t");
    CHECK(d.trajectory.enabled);
    CHECK(d.trajectory.sequence == "01");
    CHECK(d.trajectory.descriptor == "orb");
    CHECK_THROWS_WITH(parse_sweep_spec(R"({"configs": [{"name": "a"}], "trajectory": {"descriptor": "surf2"}})", "t"),
                      Catch::Contains("trajectory.descriptor"));
    CHECK_THROWS_WITH(parse_sweep_spec(R"({"configs": [{"name": "a"}], "trajectory": {"seq": "01"}})", "t"),
                      Catch::Contains("unknown key 'seq'"));
    CHECK_THROWS_WITH(parse_sweep_spec(R"({"configs": [{"name": "a"}], "trajectory": 3})", "t"), Catch::Contains("trajectory"));
}

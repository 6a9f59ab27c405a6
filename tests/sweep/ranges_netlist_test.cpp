// The netlist route of the derived ranges: z3 on GHDL's synthesis of the stage chain
// (ghdl, yosys and z3 on PATH; label netlist).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <random>

#include <nlohmann/json.hpp>

#include "model/fixed/word.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "sweep/overflow.hpp"
#include "sweep/ranges.hpp"
#include "model/util/util.hpp"

using namespace hc;
using namespace hc::sweep;

namespace {

/// The registers the stage chain holds (the threshold is computed in harris_top, outside it).
bool on_chain(Reg r) { return r != Reg::threshold; }

Pixels3 top_left(const Window5& w) {
    Pixels3 nb;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) nb[i][j] = static_cast<Pixel>(w[i][j]);
    return nb;
}

/// Every register of the chain asked on the netlist with a verdict that agrees with the model route's.
void check_agreement(const RangeReport& r) {
    for (const auto& x : r.regs) {
        INFO(kRegNames[static_cast<int>(x.reg)] << ": " << x.netlist);
        if (!on_chain(x.reg)) {
            CHECK_FALSE(x.netlist_asked);
            continue;
        }
        CHECK(x.netlist_asked);
        if (x.netlist_verdict != Verdict::open) CHECK(x.netlist_verdict == x.verdict);
    }
}

/// The netlist route's answers of `a` equal those of `b`, register by register.
void check_same_netlist_answers(const RangeReport& a, const RangeReport& b) {
    REQUIRE(a.regs.size() == b.regs.size());
    for (size_t i = 0; i < a.regs.size(); ++i) {
        INFO(kRegNames[i]);
        CHECK(a.regs[i].netlist == b.regs[i].netlist);
        CHECK(a.regs[i].netlist_verdict == b.regs[i].netlist_verdict);
        CHECK(a.regs[i].netlist_range == b.regs[i].netlist_range);
        CHECK(a.regs[i].netlist_rlimit == b.regs[i].netlist_rlimit);
        CHECK(a.regs[i].decided_by == b.regs[i].decided_by);
    }
}

}  // namespace

TEST_CASE("the netlist's registers equal the model's at windows of the thesis formats and of a narrow one", "[netlist][sweep][ranges]") {
    std::mt19937 rng(3);
    for (const int sobel_w : {11, 10}) {
        Formats f;
        f.sobel_w = sobel_w;   // 10: the Sobel registers wrap, the netlist must wrap alike
        const util::ScratchDir dir;
        const StageNetlists n = stage_netlists(f, dir.path());
        std::vector<Window5> windows;
        Window5 stripe{};
        for (auto& row : stripe) row = {0, 0, 255, 255, 0};   // |ix| = 1020 at every position
        windows.push_back(stripe);
        for (int k = 0; k < 3; ++k) {
            Window5 w{};
            for (auto& row : w)
                for (auto& p : row) p = static_cast<int>(rng() % 256);
            windows.push_back(w);
        }
        for (const Window5& w : windows) {
            const auto net = netlist_values(n, f, w);
            const auto model = window_values(w, f, true);
            const Word ix = sobel_x<Word>(top_left(w), f), iy = sobel_y<Word>(top_left(w), f);
            const MProducts m = m_products(ix, iy, f);
            INFO("sobel_w " << sobel_w << ", window row 0: " << w[0][0] << " " << w[0][1] << " " << w[0][2]);
            CHECK(net[static_cast<int>(Reg::sobel_x)] == ix.value());
            CHECK(net[static_cast<int>(Reg::sobel_y)] == iy.value());
            CHECK(net[static_cast<int>(Reg::m_a)] == m.a.value());
            CHECK(net[static_cast<int>(Reg::m_b)] == m.b.value());
            CHECK(net[static_cast<int>(Reg::m_c)] == m.c.value());
            for (Reg r : {Reg::block_a, Reg::block_b, Reg::block_c, Reg::trace, Reg::k_term, Reg::det, Reg::response}) {
                INFO(kRegNames[static_cast<int>(r)]);
                CHECK(net[static_cast<int>(r)] == model[static_cast<int>(r)].narrowed);
            }
            CHECK_FALSE(net[static_cast<int>(Reg::threshold)].has_value());
        }
    }
}

TEST_CASE("the thesis configuration: every register of the chain proven on the netlist, as the interval bound proves it",
          "[netlist][sweep][ranges]") {
    const RangeReport r = analyse_ranges(Formats{});
    INFO(r.netlist_note);
    CHECK(r.overall() == Verdict::proven);
    check_agreement(r);
    for (const auto& x : r.regs) {
        if (!on_chain(x.reg)) continue;
        INFO(kRegNames[static_cast<int>(x.reg)] << ": " << x.netlist);
        CHECK(x.netlist_verdict == Verdict::proven);
        CHECK(x.decided_by == "interval");
        if (x.reg != Reg::maximum) {
            REQUIRE(x.netlist_range);
            CHECK(*x.netlist_range == x.bound);   // the bound itself, proven on the netlist
        }
    }
    CHECK(r.netlist_query_rlimit == RangeOptions{}.netlist_query_rlimit);
    CHECK(r.netlist_rlimit > 0);
    CHECK(r.netlist_rlimit <= RangeOptions{}.netlist_budget);
    // the netlist fields survive the report's JSON
    check_same_netlist_answers(range_report_from_json(range_report_to_json(r)), r);
}

TEST_CASE("sobel_w=10: the netlist wraps the Sobel registers at the model's witness, the rest proven, and a rerun spends the same",
          "[netlist][sweep][ranges]") {
    Formats f;
    f.sobel_w = 10;
    const RangeReport r = analyse_ranges(f);
    check_agreement(r);
    for (Reg reg : {Reg::sobel_x, Reg::sobel_y}) {
        const RegisterRange& x = r.at(reg);
        INFO(x.netlist);
        CHECK(x.verdict == Verdict::wraps);
        CHECK(x.netlist_verdict == Verdict::wraps);
        CHECK(count_overflows(witness_image(x.witness), f).wrapped[sobel] > 0);
    }
    for (Reg reg : {Reg::m_a, Reg::m_b, Reg::m_c, Reg::block_a, Reg::block_b, Reg::block_c, Reg::trace, Reg::det, Reg::k_term,
                    Reg::response}) {
        INFO(kRegNames[static_cast<int>(reg)] << ": " << r.at(reg).netlist);
        CHECK(r.at(reg).netlist_verdict == Verdict::proven);
    }
    // z3's resource limit, not time: the same questions spend the same units
    check_same_netlist_answers(analyse_ranges(f), r);
}

TEST_CASE("m_prod_w=20: the netlist wraps every M register at a window the model wraps, and agrees elsewhere",
          "[netlist][sweep][ranges]") {
    Formats f;
    f.m_prod_w = 20;
    f.m_drop = 4;
    const RangeReport r = analyse_ranges(f);
    check_agreement(r);
    for (Reg reg : {Reg::m_a, Reg::m_b, Reg::m_c}) {
        INFO(r.at(reg).netlist);
        CHECK(r.at(reg).netlist_verdict == Verdict::wraps);
    }
    CHECK(r.at(Reg::sobel_x).netlist_verdict == Verdict::proven);
}

TEST_CASE("the netlist route refuses a report whose proof is false: a wrapping register claimed proven, a range claimed too tight",
          "[netlist][sweep][ranges]") {
    RangeOptions o;
    o.solver_rlimit = 0;
    o.netlist = false;
    Formats narrow;
    narrow.sobel_w = 10;
    {
        RangeReport r = analyse_ranges(narrow, o);
        REQUIRE(r.at(Reg::sobel_x).verdict == Verdict::wraps);
        r.regs[static_cast<int>(Reg::sobel_x)].verdict = Verdict::proven;   // false
        r.regs[static_cast<int>(Reg::sobel_x)].bound = {-511, 511};
        CHECK_THROWS_AS(netlist_route(r, RangeOptions{}), std::logic_error);
    }
    {
        // an upstream guarantee weakened below what the pixels reach: m_b's range claimed [-100, 100]
        RangeReport r = analyse_ranges(Formats{}, o);
        r.regs[static_cast<int>(Reg::m_b)].solver_range = Interval{-100, 100};
        CHECK_THROWS_AS(netlist_route(r, RangeOptions{}), std::logic_error);
    }
}

TEST_CASE("without GHDL the netlist route proves nothing and says why", "[netlist][sweep][ranges]") {
    const char* path = std::getenv("PATH");
    const std::string saved = path ? path : "";
    setenv("PATH", "/nonexistent", 1);
    RangeOptions o;
    o.solver_rlimit = 0;
    Formats f;
    f.bf_sum_w = 19;   // block_b: open by the model route without its solver
    const RangeReport r = analyse_ranges(f, o);
    setenv("PATH", saved.c_str(), 1);
    CHECK_THAT(r.netlist_note, Catch::StartsWith("not run"));
    for (const auto& x : r.regs) {
        CHECK_FALSE(x.netlist_asked);
        CHECK(x.decided_by != "netlist");
    }
    CHECK(r.at(Reg::block_b).verdict == Verdict::open);
}

TEST_CASE("the netlists are made in a directory given relative to the working directory", "[netlist][sweep][ranges]") {
    const util::ScratchDir d;
    const std::filesystem::path rel = std::filesystem::relative(d.path() / "nets", std::filesystem::current_path());
    REQUIRE(rel.is_relative());
    const StageNetlists n = stage_netlists(Formats{}, rel);
    CHECK_THAT(n.chain, Catch::Contains("chain_n"));
    CHECK_THAT(n.response, Catch::Contains("stage_response_n"));
    CHECK(std::filesystem::exists(d.path() / "nets" / "chain.log"));
    CHECK(std::filesystem::exists(d.path() / "nets" / "commands.txt"));
}

namespace {

/// A configuration whose resize(ac, RESP_W) overflows: the model (numeric_std) wraps the
/// response at its witness, GHDL's netlist (which truncates) does not; the report says both.
void check_wraps_and_netlist_differs(const Formats& f) {
    const RangeReport r = analyse_ranges(f);
    INFO(r.summary());
    REQUIRE(r.overall() == Verdict::wraps);
    const RegisterRange& resp = r.at(Reg::response);
    INFO(resp.netlist);
    CHECK(resp.verdict == Verdict::wraps);
    CHECK(resp.decided_by != "netlist");
    REQUIRE(resp.netlist_differs);
    CHECK(resp.netlist_verdict == Verdict::open);
    CHECK_THAT(resp.netlist_vhdl, Catch::StartsWith("GHDL's netlist only") && Catch::Contains("resize(ac, RESP_W)"));
    CHECK_THAT(r.summary(), Catch::Contains("the netlist differs from the VHDL at the witness of response"));
    // the VHDL's value is the model's at the witness, and it wraps; the netlist's is another
    bool model_value = false;
    for (bool maximise : {true, false}) {
        const WindowValue v = window_values(resp.witness, f, maximise)[static_cast<int>(Reg::response)];
        if (v.exact != v.narrowed && v.narrowed == resp.vhdl_value) model_value = true;
    }
    CHECK(model_value);
    CHECK(resp.netlist_value != resp.vhdl_value);
    // on the netlist the witness's response is its exact value modulo 2^resp_w
    const util::ScratchDir dir;
    const StageNetlists n = stage_netlists(f, dir.path() / "nets");
    CHECK(netlist_values(n, f, resp.witness)[static_cast<int>(Reg::response)] == resp.netlist_value);
    // the overflow audit counts the witness as a wrap of the response (numeric_std's value)
    CHECK(count_overflows(witness_image(resp.witness), f).wrapped[response] > 0);
    // the shrink that overflows is listed, and does not fit
    bool ac = false;
    for (const SignedShrink& s : signed_shrinks(r))
        if (s.what == "resize(ac, RESP_W) in harris_response") ac = !s.fits && s.to == f.resp_w && s.from == f.prod_w();
    CHECK(ac);
    // the registers upstream hold for the VHDL (no signed shrink there) and are proven on the netlist
    for (Reg reg : {Reg::sobel_x, Reg::m_b, Reg::block_a, Reg::trace}) {
        INFO(kRegNames[static_cast<int>(reg)] << ": " << r.at(reg).netlist_vhdl);
        CHECK_THAT(r.at(reg).netlist_vhdl, Catch::StartsWith("holds for the VHDL"));
        CHECK(r.at(reg).netlist_verdict == Verdict::proven);
    }
    // the new fields survive the report's JSON
    const RangeReport back = range_report_from_json(range_report_to_json(r));
    CHECK(back.at(Reg::response).netlist_differs);
    CHECK(back.at(Reg::response).netlist_value == resp.netlist_value);
    CHECK(back.at(Reg::response).vhdl_value == resp.vhdl_value);
    CHECK(back.at(Reg::response).netlist_vhdl == resp.netlist_vhdl);
}

}  // namespace

TEST_CASE("resp_w=27: the response wraps (numeric_std keeps the sign of resize(ac, 27)) and the netlist differs from the VHDL there",
          "[netlist][sweep][ranges]") {
    Formats f;
    f.resp_w = 27;
    check_wraps_and_netlist_differs(f);
}

TEST_CASE("k_shift1=4, k_shift2=5, resp_w=27: wraps, and the netlist differs from the VHDL at the witness",
          "[netlist][sweep][ranges]") {
    Formats f;
    f.k_shift1 = 4;
    f.k_shift2 = 5;
    f.resp_w = 27;
    check_wraps_and_netlist_differs(f);
}

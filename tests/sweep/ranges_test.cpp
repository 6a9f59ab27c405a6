// ranges_test.cpp: the derived ranges (sweep/ranges.hpp): interval bounds against the exact
// extremes of stages small enough to enumerate, verdicts of the sweep's configurations,
// witnesses that wrap in the model (the overflow audit sees them), the report's JSON. That the RTL wraps alike is the cosim label's (tests/cosim/CMakeLists.txt).
#include <catch2/catch.hpp>

#include <map>

#include <algorithm>
#include <limits>

#include <nlohmann/json.hpp>

#include "model/harris/formats_json.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "golden/golden.hpp"
#include "sweep/overflow.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_config.hpp"

using namespace hc;
using namespace hc::sweep;

namespace {

struct Extremes {
    std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = std::numeric_limits<std::int64_t>::min();
    void add(std::int64_t v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
};

/// Every 3x3 window of pixels in [0, pmax] that the stage depends on: the Sobel kernels
/// read 8 of the 9 (not the centre); `use` says which.
template <class F>
void every_window(int pmax, const std::array<bool, 9>& use, F&& fn) {
    std::array<int, 9> v{};
    for (;;) {
        Pixels3 nb;
        for (int k = 0; k < 9; ++k) nb[k / 3][k % 3] = static_cast<Pixel>(v[k]);
        fn(nb);
        int k = 0;
        for (; k < 9; ++k) {
            if (!use[k]) continue;
            if (++v[k] <= pmax) break;
            v[k] = 0;
        }
        if (k == 9) return;
    }
}

/// The interval bound and the witness search alone (the solvers' tests are [solver] and [netlist]).
RangeOptions no_solver() {
    RangeOptions o;
    o.solver_rlimit = 0;
    o.netlist = false;
    return o;
}

const sweep::Config* find_config(const SweepSpec& spec, const std::string& name) {
    for (const auto& c : spec.configs)
        if (c.name == name) return &c;
    return nullptr;
}

}  // namespace

TEST_CASE("interval bounds of Sobel equal the exact extremes over every 3x3 window of 4-bit pixels", "[model][sweep][ranges]") {
    const Formats f;
    const RangeReport r = interval_ranges(f, 15);
    Extremes ex, ey;
    // x reads columns 0 and 2, y rows 0 and 2: each enumerated over its six pixels
    every_window(15, {true, false, true, true, false, true, true, false, true}, [&](const Pixels3& nb) {
        ex.add(sobel_x<Word>(nb, f).value());
    });
    every_window(15, {true, true, true, false, false, false, true, true, true}, [&](const Pixels3& nb) {
        ey.add(sobel_y<Word>(nb, f).value());
    });
    CHECK(ex.lo == -60);
    CHECK(ex.hi == 60);
    CHECK(r.at(Reg::sobel_x).bound == Interval{ex.lo, ex.hi});
    CHECK(r.at(Reg::sobel_y).bound == Interval{ey.lo, ey.hi});
}

TEST_CASE("interval bounds of M contain the exact extremes over every 3x3 window of 3-bit pixels, a and c are exact",
          "[model][sweep][ranges]") {
    Formats f;
    f.m_drop = 0;   // the products themselves
    const RangeReport r = interval_ranges(f, 7);
    Extremes ea, eb, ec;
    every_window(7, {true, true, true, true, false, true, true, true, true}, [&](const Pixels3& nb) {
        const MProducts m = m_products(sobel_x<Word>(nb, f), sobel_y<Word>(nb, f), f);
        ea.add(m.a.value());
        eb.add(m.b.value());
        ec.add(m.c.value());
    });
    CHECK(r.at(Reg::m_a).bound == Interval{ea.lo, ea.hi});   // a square: [0, 28^2]
    CHECK(r.at(Reg::m_c).bound == Interval{ec.lo, ec.hi});
    CHECK(ea.hi == 28 * 28);
    // b = ix*iy: the interval is sound but not tight (x and y share the corner pixels)
    CHECK(r.at(Reg::m_b).bound.lo <= eb.lo);
    CHECK(r.at(Reg::m_b).bound.hi >= eb.hi);
    CHECK(eb.hi < r.at(Reg::m_b).bound.hi);
}

TEST_CASE("the thesis configuration: every register proven by the interval bound alone", "[model][sweep][ranges]") {
    const RangeReport r = analyse_ranges(Formats{}, no_solver());
    INFO(r.summary());
    CHECK(r.overall() == Verdict::proven);
    for (const auto& x : r.regs) {
        INFO(kRegNames[static_cast<int>(x.reg)]);
        CHECK(x.bound_fits);
        CHECK_FALSE(x.searched);
        CHECK(x.bound.lo >= x.held.lo);
        CHECK(x.bound.hi <= x.held.hi);
    }
    CHECK(r.at(Reg::sobel_x).bound == Interval{-1020, 1020});
    CHECK(r.at(Reg::m_a).bound == Interval{0, 1020 * 1020 / 32});
    CHECK(r.at(Reg::block_a).bound == Interval{0, 9 * (1020 * 1020 / 32) / 16});
    CHECK(r.at(Reg::response).held == Interval{-(std::int64_t{1} << 31), (std::int64_t{1} << 31) - 1});
}

TEST_CASE("the signed shrinks of the stage chain: where they are and whether their operand fits", "[model][sweep][ranges]") {
    const auto shrinks = [](const Formats& f) {
        std::map<std::string, bool> m;   // what -> fits
        for (const SignedShrink& s : signed_shrinks(analyse_ranges(f, no_solver()))) {
            CHECK(s.to < s.from);
            CHECK(s.fits == fits(s.operand, s.to, true));
            m[s.what] = s.fits;
        }
        return m;
    };
    // the thesis: only the products of m_products are shrunk (22 to 21 bits), and they fit (|ix*iy| <= 1020^2 < 2^20)
    const std::map<std::string, bool> thesis = {{"resize(ix * ix, M_PROD_W) in m_products", true},
                                                {"resize(ix * iy, M_PROD_W) in m_products", true},
                                                {"resize(iy * iy, M_PROD_W) in m_products", true}};
    CHECK(shrinks(Formats{}) == thesis);
    Formats r27;
    r27.resp_w = 27;
    const auto m27 = shrinks(r27);
    CHECK(m27.at("resize(ac, RESP_W) in harris_response") == false);   // a*c up to 18288^2 > 2^26
    CHECK(m27.at("resize(bb, RESP_W) in harris_response") == false);
    CHECK(m27.at("resize(ktr2, RESP_W) in harris_response") == true);  // the k-term's bound [0, 52,257,960] < 2^26
    Formats s9;
    s9.sobel_w = 9;
    const auto m9 = shrinks(s9);
    CHECK(m9.at("resize(p21, SOBEL_W) in sobel_x") == false);   // -2 * 255 does not fit 9 bits
    CHECK(m9.at("resize(p12, SOBEL_W) in sobel_y") == false);
    CHECK(m9.count("resize(p11, SOBEL_W) in sobel_x") == 0);    // 9 bits to 9: no shrink
}

TEST_CASE("sweep/configs/bit-widths.json: the tight points are proven, each too-narrow point wraps with a witness the audit sees",
          "[model][sweep][ranges]") {
    const SweepSpec spec = load_sweep_spec(std::filesystem::path(HC_SOURCE_DIR) / "sweep" / "configs" / "bit-widths.json");
    int tight = 0;
    for (const auto& c : spec.configs) {
        if (c.name.rfind("tight-", 0) != 0) continue;
        ++tight;
        INFO(c.name);
        CHECK(interval_ranges(c.formats).overall() == Verdict::proven);
    }
    CHECK(tight >= 20);
    const std::vector<std::pair<std::string, Reg>> narrow = {
        {"sobel_w=10", Reg::sobel_x}, {"sobel_w=9", Reg::sobel_x}, {"m_prod_w=20", Reg::m_a}, {"bf_sum_w=19", Reg::block_a}};
    for (const auto& [name, reg] : narrow) {
        INFO(name);
        const sweep::Config* c = find_config(spec, name);
        REQUIRE(c);
        const RangeReport r = analyse_ranges(c->formats, no_solver());
        REQUIRE(r.overall() == Verdict::wraps);
        REQUIRE(r.first_wrap()->reg == reg);
        const Window5& w = r.first_wrap()->witness;
        // the window wraps the register in the model ...
        const auto v = window_values(w, c->formats, r.first_wrap()->bound.hi > r.first_wrap()->held.hi);
        CHECK(v[static_cast<int>(reg)].exact != v[static_cast<int>(reg)].narrowed);
        // ... the overflow audit counts it on the witness image, and the thesis widths do not wrap there
        const Image im = witness_image(w);
        CHECK(count_overflows(im, c->formats).wrapped[audit_stage(reg)] > 0);
        CHECK(count_overflows(im, Formats{}).total_wrapped() == 0);
    }
}

TEST_CASE("a block sum narrowed by one bit is reachable, with the exact maximum at the interval bound", "[model][sweep][ranges]") {
    Formats f;
    f.bf_sum_w = 19;   // 9 * 32512 = 292608 needs 20 signed bits
    const RangeReport r = analyse_ranges(f, no_solver());
    const RegisterRange& a = r.at(Reg::block_a);
    CHECK(a.bound.hi == (9 * 32512) >> 4);
    REQUIRE(a.verdict == Verdict::wraps);
    const auto v = window_values(a.witness, f, true);
    CHECK(v[static_cast<int>(Reg::block_a)].exact == a.bound.hi);   // the witness reaches the bound: it is exact
}

TEST_CASE("a response one or two bits too narrow for the interval bound: det and the response proven through the block sums' "
          "relations and every register decided but one more bit less wraps",
          "[model][sweep][ranges]") {
    for (int w : {29, 28}) {
        Formats f;
        f.resp_w = w;   // the thesis's interval bound 18288^2 = 334,450,944 needs 30 signed bits
        const RangeReport r = analyse_ranges(f, no_solver());
        INFO("resp_w " << w << ": " << r.summary());
        CHECK(r.overall() == Verdict::proven);
        for (const auto& x : r.regs) {
            INFO(kRegNames[static_cast<int>(x.reg)] << ": " << x.relation);
            CHECK(x.verdict == Verdict::proven);
            CHECK_FALSE(x.decided_by.empty());
        }
        for (Reg reg : {Reg::det, Reg::response}) {
            const RegisterRange& x = r.at(reg);
            INFO(kRegNames[static_cast<int>(reg)] << ": " << x.relation);
            CHECK_FALSE(x.bound_fits);
            CHECK(x.decided_by == "relation");
            REQUIRE(x.relation_range);
            CHECK(fits(*x.relation_range, w, true));
            // the values the witness search reached lie inside the relation's range
            REQUIRE(x.searched);
            CHECK(x.relation_range->lo <= x.reached.lo);
            CHECK(x.reached.hi <= x.relation_range->hi);
        }
        CHECK(r.at(Reg::maximum).decided_by == "relation");
    }
    // the relation's figures at the thesis formats: max ix^2 + iy^2 = 1020^2 + 510^2, a + c <= 9 * floor(1,300,500 / 32) / 16
    Formats f28;
    f28.resp_w = 28;
    const ResponseRelation rel = response_relation(interval_ranges(f28));
    REQUIRE(rel.applies);
    CHECK(rel.energy == 1020 * 1020 + 510 * 510);
    CHECK(rel.trace == 9 * (1300500 / 32) / 16);   // 22,860
    CHECK(rel.ac.hi == 11430LL * 11430);            // 130,644,900 < 2^27
    CHECK(rel.g == 2);
    CHECK(rel.det_fits);
    CHECK(rel.response_fits);
    // resp_w=27: a*c reaches more than 2^26, and the search has a witness
    Formats f27;
    f27.resp_w = 27;
    const RangeReport r27 = analyse_ranges(f27, no_solver());
    CHECK_FALSE(response_relation(r27).det_fits);
    CHECK(r27.at(Reg::response).verdict == Verdict::wraps);
}

TEST_CASE("the relation's largest gradient energy is the largest over every window of 2-bit pixels", "[model][sweep][ranges]") {
    // ix^2 + iy^2 is convex in the pixels, so its maximum over the box is at a vertex: all 4^9 windows agree
    std::int64_t best = 0;
    for (int v = 0; v < (1 << 18); ++v) {
        int p[3][3];
        for (int k = 0; k < 9; ++k) p[k / 3][k % 3] = (v >> (2 * k)) & 3;
        const std::int64_t ix = (p[0][2] + 2 * p[1][2] + p[2][2]) - (p[0][0] + 2 * p[1][0] + p[2][0]);
        const std::int64_t iy = (p[0][0] + 2 * p[0][1] + p[0][2]) - (p[2][0] + 2 * p[2][1] + p[2][2]);
        best = std::max(best, ix * ix + iy * iy);
    }
    CHECK(response_relation(interval_ranges(Formats{}, 3)).energy == best);
}

TEST_CASE("a range report survives its JSON", "[model][sweep][ranges]") {
    Formats f;
    f.sobel_w = 10;
    const RangeReport r = analyse_ranges(f, no_solver());
    const RangeReport back = range_report_from_json(range_report_to_json(r));
    REQUIRE(back.regs.size() == r.regs.size());
    for (size_t i = 0; i < r.regs.size(); ++i) {
        CHECK(back.regs[i].bound == r.regs[i].bound);
        CHECK(back.regs[i].held == r.regs[i].held);
        CHECK(back.regs[i].verdict == r.regs[i].verdict);
        CHECK(back.regs[i].witness == r.regs[i].witness);
    }
    CHECK(back.summary() == r.summary());
    nlohmann::json bad = range_report_to_json(r);
    bad["registers"][0]["verdict"] = "maybe";
    CHECK_THROWS(range_report_from_json(bad));
}

TEST_CASE("each witness stream of the regression set wraps its configuration in the model (the audit counts it)",
          "[model][sweep][ranges]") {
    const auto set = util::read_regression_set(std::filesystem::path(HC_SOURCE_DIR) / "golden" / "regression-set.txt");
    int witnesses = 0;
    for (const auto& s : set) {
        if (s.breaks.empty()) continue;
        ++witnesses;
        INFO(s.stem());
        const Formats broken = formats_from_file(s.breaks.string());
        const std::vector<Image> frames = golden::stream_frames(s);
        // the register named by the file wraps: the overflow audit counts it at its stage
        Reg reg = Reg::count;
        for (int k = 0; k < kRegCount; ++k)
            if (s.image.stem().string().ends_with(std::string("_") + kRegNames[k])) reg = static_cast<Reg>(k);
        REQUIRE(reg != Reg::count);
        const OverflowCounts c = count_overflows(frames.front(), broken);
        INFO(c.summary());
        CHECK(c.wrapped[audit_stage(reg)] > 0);
        CHECK(count_overflows(frames.front(), Formats{}).total_wrapped() == 0);
        // the range analysis agrees that the configuration wraps there
        CHECK(analyse_ranges(broken, no_solver()).at(reg).verdict == Verdict::wraps);
    }
    CHECK(witnesses >= 4);
}

TEST_CASE("the range analysis is cached under the key it is given, an unreadable entry or one of other options is analysed again",
          "[model][sweep][ranges]") {
    const util::ScratchDir d;
    Formats f;
    f.m_prod_w = 20;
    f.m_drop = 4;
    const RangeReport first = cached_ranges(f, "0123456789abcdef", d.path());
    CHECK_FALSE(first.cached);
    CHECK(first.key == "0123456789abcdef");
    REQUIRE(std::filesystem::exists(d.path() / "0123456789abcdef.json"));
    const RangeReport again = cached_ranges(f, "0123456789abcdef", d.path());
    CHECK(again.cached);
    CHECK(again.summary() == first.summary());
    CHECK(again.at(Reg::m_a).witness == first.at(Reg::m_a).witness);
    // an entry made with other options (here without the solver and the netlist) is not read
    // back; the cheaper options keep the rest of the case quick
    const RangeOptions cheap = no_solver();
    const RangeReport other = cached_ranges(f, "0123456789abcdef", d.path(), cheap);
    CHECK_FALSE(other.cached);
    CHECK(cached_ranges(f, "0123456789abcdef", d.path(), cheap).cached);
    // an unreadable entry is analysed again, to the same report
    util::write_file_atomic(d.path() / "0123456789abcdef.json", "{ not json");
    const RangeReport redone = cached_ranges(f, "0123456789abcdef", d.path(), cheap);
    CHECK_FALSE(redone.cached);
    CHECK(redone.summary() == other.summary());
    CHECK(cached_ranges(f, "0123456789abcdef", d.path(), cheap).cached);
}

TEST_CASE("the solver's exact extremes of b = ix*iy equal the extremes over every 3x3 window of 2-bit pixels",
          "[model][sweep][ranges][solver]") {
    Formats f;
    f.m_drop = 0;   // the products themselves
    RangeOptions o;
    o.pixel_max = 3;
    Extremes eb;
    every_window(3, {true, true, true, true, false, true, true, true, true}, [&](const Pixels3& nb) {
        eb.add(m_products(sobel_x<Word>(nb, f), sobel_y<Word>(nb, f), f).b.value());
    });
    const Interval bound = interval_ranges(f, 3).at(Reg::m_b).bound;
    REQUIRE(eb.hi < bound.hi);   // the interval is loose here: the solver has something to prove
    const SolverExtreme hi = solver_extreme(f, Reg::m_b, true, o, 150'000'000);
    const SolverExtreme lo = solver_extreme(f, Reg::m_b, false, o, 150'000'000);
    CHECK(hi.proven == eb.hi);   // proven not exceeded, and reached: exact
    CHECK(hi.reached == eb.hi);
    CHECK(lo.proven == eb.lo);
    CHECK(lo.reached == eb.lo);
}

TEST_CASE("the solver finds a window that wraps m_b one bit short, and the model and the overflow audit agree",
          "[model][sweep][ranges][solver]") {
    Formats f;
    f.m_prod_w = 20;   // ix*iy reaches 765^2 = 585,225 > 2^19
    f.m_drop = 4;
    const SolverVerdict v = solver_wrap(f, Reg::m_b);
    INFO(v.why);
    REQUIRE(v.verdict == Verdict::wraps);
    // the window's Sobel product leaves m_prod_w bits: the audit counts an M wrap on its image
    CHECK((v.exact > (std::int64_t{1} << 15) - 1 || v.exact < -(std::int64_t{1} << 15)));
    CHECK(count_overflows(witness_image(v.window), f).wrapped[m_resize] > 0);
    // with the thesis's widths the same question is unsat
    CHECK(solver_wrap(Formats{}, Reg::m_b).verdict == Verdict::proven);
}

TEST_CASE("bf_sum_w=19: the solver settles the registers the search left open, within the budget",
          "[model][sweep][ranges][solver]") {
    const Formats f = formats_from_file(std::string(HC_SOURCE_DIR) + "/golden/witnesses/bf_sum_w-19.json");
    const RangeReport r = analyse_ranges(f);
    INFO(r.summary());
    CHECK(r.seconds_solver <= 61);
    // the interval bound of block_b does not fit; the search found no witness
    const RegisterRange& b = r.at(Reg::block_b);
    CHECK_FALSE(b.bound_fits);
    CHECK(b.searched);
    CHECK(b.verdict == Verdict::proven);
    CHECK(b.solver_asked);
    // it rests on the solver's range of m_b, which contains a window's exact value
    // (ix = iy = 765: 585,225 / 32 = 18,288) and is tighter than the interval's
    const RegisterRange& mb = r.at(Reg::m_b);
    REQUIRE(mb.solver_range);
    CHECK(mb.solver_range->hi >= 18288);
    CHECK(mb.solver_range->hi < mb.bound.hi);
    Window5 w{};
    const std::array<std::array<int, 3>, 3> corner{{{0, 255, 255}, {0, 0, 255}, {0, 0, 0}}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) w[i][j] = corner[i][j];
    CHECK(window_values(w, f, true)[static_cast<int>(Reg::m_b)].exact == 18288);
    // the maximum follows the response
    CHECK(r.at(Reg::maximum).verdict == r.at(Reg::response).verdict);
    CHECK(r.at(Reg::block_a).verdict == Verdict::wraps);
    // the solver's findings survive the report's JSON (the sweep's cache)
    const RangeReport back = range_report_from_json(range_report_to_json(r));
    REQUIRE(back.at(Reg::m_b).solver_range);
    CHECK(*back.at(Reg::m_b).solver_range == *mb.solver_range);
    CHECK(back.at(Reg::block_b).solver == b.solver);
    CHECK(back.at(Reg::block_b).verdict == Verdict::proven);
    CHECK(back.summary() == r.summary());
}

TEST_CASE("the witness search stops after a count of windows: two runs give the same verdicts, and a small count binds exactly",
          "[model][sweep][ranges]") {
    Formats f;
    f.resp_w = 29;   // det and the response: the search finds no witness and spends its seeds
    RangeOptions o = no_solver();
    const RangeReport one = analyse_ranges(f, o), two = analyse_ranges(f, o);
    for (int k = 0; k < kRegCount; ++k) {
        INFO(kRegNames[k]);
        CHECK(one.regs[k].verdict == two.regs[k].verdict);
        CHECK(one.regs[k].search_windows == two.regs[k].search_windows);
        CHECK(one.regs[k].reached == two.regs[k].reached);
    }
    const RegisterRange& r = one.at(Reg::response);
    REQUIRE(r.searched);
    // the default count does not bind here: the search ends with its seeds, below the bound on each side
    CHECK(r.search_windows < 2 * o.search_windows);
    CHECK(r.search_windows > 1000);
    // a count of 300 per side: the response's bound leaves the register on both sides, so exactly 600
    o.search_windows = 300;
    const RangeReport small = analyse_ranges(f, o);
    CHECK(small.at(Reg::response).search_windows == 600);
    CHECK(small.at(Reg::response).verdict != Verdict::wraps);
    CHECK(analyse_ranges(f, o).at(Reg::response).reached == small.at(Reg::response).reached);
    // m_prod_w=20: the witness of m_b is found after 72 windows; a count of 10 leaves it open, the same on every run
    Formats narrow;
    narrow.m_prod_w = 20;
    narrow.m_drop = 4;
    CHECK(analyse_ranges(narrow, no_solver()).at(Reg::m_b).verdict == Verdict::wraps);
    o.search_windows = 10;
    const RangeReport cut = analyse_ranges(narrow, o);
    CHECK(cut.at(Reg::m_b).verdict == Verdict::open);
    CHECK(cut.at(Reg::m_b).search_windows <= 20);
    CHECK(analyse_ranges(narrow, o).at(Reg::m_b).reached == cut.at(Reg::m_b).reached);
}

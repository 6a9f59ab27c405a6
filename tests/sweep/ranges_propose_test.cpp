// ranges_propose_test.cpp: the narrowest proven widths (propose_widths, `ranges --propose`).
#include <catch2/catch.hpp>

#include <sstream>

#include "golden/golden.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/harris_top.hpp"
#include "model/util/util.hpp"
#include "cosim/cosim.hpp"
#include "sweep/cost.hpp"
#include "sweep/ranges.hpp"
#include "sweep/stage_equivalence.hpp"
#include "sweep/sweep_config.hpp"

using namespace hc;
using namespace hc::sweep;

namespace {

const ProposedWidth& width_of(const WidthProposal& p, const std::string& field) {
    for (const auto& w : p.widths)
        if (w.field == field) return w;
    FAIL("no width field " << field);
    throw std::logic_error("unreachable");
}

/// What the co-processor gives the host for a stream of frames, by the cycle model: every
/// read (write index, frame, x, y, corner bits), and every change of find-max's published
/// maximum after its reset value (write index, value).
struct Outputs {
    std::string reads, maxima;
    long reset_max = 0;
};
Outputs model_outputs(const std::vector<Image>& frames, const Geometry& g, const Formats& f) {
    std::vector<const Image*> ptrs;
    for (const auto& im : frames) ptrs.push_back(&im);
    HostDriver drv(g, ptrs);
    HarrisTop top(g, f);
    std::ostringstream reads, maxima;
    Outputs o;
    o.reset_max = top.find_max().max.value();
    long last = o.reset_max;
    BusEvent ev;
    while (drv.next(ev)) {
        top.write(ev.data);
        if (ev.read) reads << top.writes() << ',' << ev.read->frame << ',' << ev.read->x << ',' << ev.read->y << ',' << top.corner() << '\n';
        if (top.find_max().max.value() != last) {
            last = top.find_max().max.value();
            maxima << top.writes() << ',' << last << '\n';
        }
    }
    o.reads = reads.str();
    o.maxima = maxima.str();
    return o;
}

/// det and the response proven at `f` by their interval bounds or by the block sums' relations.
bool det_and_response_proven(const Formats& f) {
    const RangeReport iv = interval_ranges(f);
    const ResponseRelation rel = response_relation(iv);
    return (iv.at(Reg::det).bound_fits || rel.det_fits) && (iv.at(Reg::response).bound_fits || rel.response_fits);
}

RangeReport model_route(const Formats& f) {
    RangeOptions o;
    o.netlist = false;
    return analyse_ranges(f, o);
}

}  // namespace

TEST_CASE("propose_widths on the thesis: the width fields from the register table, resp_w 28 by the block sums' relations, ktr_w 27",
          "[model][sweep][ranges][propose]") {
    const WidthProposal p = propose_widths(interval_ranges(Formats{}));
    std::vector<std::string> fields;
    for (const auto& w : p.widths) fields.push_back(w.field);
    CHECK(fields == std::vector<std::string>{"sobel_w", "m_prod_w", "bf_sum_w", "resp_w", "ktr_w"});
    CHECK(width_of(p, "sobel_w").regs == std::vector<Reg>{Reg::sobel_x, Reg::sobel_y});
    CHECK(width_of(p, "m_prod_w").regs == std::vector<Reg>{Reg::m_a, Reg::m_b, Reg::m_c});
    CHECK(width_of(p, "bf_sum_w").regs == std::vector<Reg>{Reg::block_a, Reg::block_b, Reg::block_c, Reg::trace});
    CHECK(width_of(p, "resp_w").regs == std::vector<Reg>{Reg::det, Reg::response, Reg::maximum, Reg::threshold});
    CHECK(width_of(p, "ktr_w").regs == std::vector<Reg>{Reg::k_term});
    // det: a + c <= T = 22,860, g = 2; a*c <= 11,430^2, |b| < T/2 + 2g = 11,434, det >= -2gT - 4g^2
    const ProposedWidth& r = width_of(p, "resp_w");
    CHECK(r.proposed == 28);
    CHECK(r.setter == Reg::det);
    CHECK(r.range == Interval{-2 * 2 * 22860 - 4 * 2 * 2, 11434L * 11434L});
    CHECK(r.bits == 28);
    CHECK(r.from == "the block sums' relations (a*c, b*b, det)");
    const ProposedWidth& k = width_of(p, "ktr_w");
    CHECK(k.proposed == 27);
    CHECK(k.range == Interval{0, 52257960});
    CHECK(k.from == "interval bound");
    Formats want;
    want.resp_w = 28;
    want.ktr_w = 27;
    CHECK(p.formats == want);
    for (const auto& w : p.widths) CHECK(w.kept.empty());
    // proven at the proposal: det and the response by the relations (their interval bounds need
    // 30 bits), everything else by its interval bound
    const RangeReport at = interval_ranges(want);
    CHECK_FALSE(at.at(Reg::det).bound_fits);
    const ResponseRelation rel = response_relation(at);
    CHECK(rel.det_fits);
    CHECK(rel.response_fits);
    // the narrowest: one bit fewer on either width and nothing proves its register
    Formats r27 = want, k26 = want;
    r27.resp_w = 27;
    k26.ktr_w = 26;
    CHECK_FALSE(response_relation(interval_ranges(r27)).det_fits);
    CHECK_FALSE(interval_ranges(r27).at(Reg::det).bound_fits);
    CHECK_FALSE(interval_ranges(k26).at(Reg::k_term).bound_fits);
    const std::string md = proposal_markdown(p);
    CHECK(md.find("| `resp_w` | 32 | 28 | det, response, maximum, threshold | `det` | [-91456, 130736356] | 28 | the block sums' relations (a*c, b*b, det) |") !=
          std::string::npos);
    CHECK(md.find("Proposal: resp_w 32 -> 28, ktr_w 30 -> 27") != std::string::npos);
}

TEST_CASE("propose_widths on a hand-made report: the solver's closed extreme, an open register, a narrowing inside a stage",
          "[model][sweep][ranges][propose]") {
    RangeReport rep = interval_ranges(Formats{});
    // the k-term proven by the solver with its maximum closed at 1000: 11 signed bits hold [0, 1000]
    RegisterRange& kt = rep.regs[static_cast<int>(Reg::k_term)];
    kt.decided_by = "model-smt";
    kt.extreme_side = +1;
    kt.extreme = {1000, 1000};
    // block_b open: bf_sum_w stays, saying why
    rep.regs[static_cast<int>(Reg::block_b)].verdict = Verdict::open;
    WidthProposal p = propose_widths(rep);
    CHECK(width_of(p, "ktr_w").proposed == 11);
    CHECK(width_of(p, "ktr_w").range == Interval{0, 1000});
    CHECK(width_of(p, "ktr_w").from == "interval bound, exact maximum (solver)");
    CHECK(width_of(p, "bf_sum_w").proposed == 20);
    CHECK(width_of(p, "bf_sum_w").kept == "not proven: block_b open");
    CHECK(proposal_markdown(p).find("| `bf_sum_w` | 20 | 20 (kept) |") != std::string::npos);
    // a bracket that did not close is not an extreme: the bound sets the width
    kt.extreme = {900, 2000};
    CHECK(width_of(propose_widths(rep), "ktr_w").proposed == 27);
    // a hand-made bound the interval pass does not prove at the proposed width: the width stays
    kt.extreme_side = 0;
    kt.decided_by = "interval";
    kt.bound = {0, 1000};
    p = propose_widths(rep);
    CHECK(width_of(p, "ktr_w").proposed == 30);
    CHECK(width_of(p, "ktr_w").kept == "11 bits no longer prove k_term by the interval bound or the block sums' relations");
    CHECK(p.formats.ktr_w == 30);
}

TEST_CASE("propose_widths: a width whose register wraps stays, and every tight-* point of bit-widths.json is its own proposal "
          "but for resp_w, which the block sums' relations narrow further",
          "[model][sweep][ranges][propose]") {
    Formats s10;
    s10.sobel_w = 10;
    const WidthProposal p = propose_widths(model_route(s10));
    CHECK(width_of(p, "sobel_w").proposed == 10);
    CHECK(width_of(p, "sobel_w").kept == "not proven: sobel_x wraps, sobel_y wraps");
    // the tight family was made as the smallest widths the interval bounds of their inputs need
    // (docs/bit-widths.md): the proposal from the register table agrees with it point by point
    // on every width but resp_w, where the relations prove fewer bits, and not one bit fewer
    int tight = 0, narrower = 0;
    for (const auto& c : load_sweep_spec(std::string(HC_SOURCE_DIR) + "/sweep/configs/bit-widths.json").configs)
        if (c.name.rfind("tight-", 0) == 0) {
            ++tight;
            INFO(c.name);
            const Formats prop = propose_widths(interval_ranges(c.formats)).formats;
            Formats same = prop;
            same.resp_w = c.formats.resp_w;
            CHECK(same == c.formats);
            CHECK(prop.resp_w <= c.formats.resp_w);
            narrower += prop.resp_w < c.formats.resp_w;
            CHECK(det_and_response_proven(prop));
            Formats less = prop;
            --less.resp_w;
            CHECK_FALSE(det_and_response_proven(less));
        }
    CHECK(tight == 25);
    CHECK(narrower > 0);
}

TEST_CASE("sweep/configs/proposed-thesis.json is `ranges --propose` of the thesis configuration",
          "[model][sweep][ranges][propose]") {
    const WidthProposal p = propose_widths(model_route(Formats{}));
    CHECK(util::read_file(std::string(HC_SOURCE_DIR) + "/sweep/configs/proposed-thesis.json", "proposed-thesis.json") ==
          formats_to_json(p.formats));
}

TEST_CASE("the thesis's proposal reads the same corners and maxima as the thesis on every regression stream",
          "[model][sweep][ranges][propose]") {
    const Formats base{};
    const Formats prop = propose_widths(model_route(base)).formats;
    REQUIRE(prop != base);
    const std::string set = std::string(HC_SOURCE_DIR) + "/golden/regression-set.txt";
    int streams = 0;
    for (const auto& s : util::read_regression_set(set)) {
        INFO(s.stem());
        const std::vector<Image> frames = golden::stream_frames(s);
        const Geometry g{s.width, s.height};
        const Outputs a = model_outputs(frames, g, base), b = model_outputs(frames, g, prop);
        CHECK(a.reads == b.reads);
        CHECK(a.maxima == b.maxima);
        CHECK_FALSE(a.reads.empty());
        // the one value that is not a datapath value: find-max's reset, the width's most negative
        CHECK(a.reset_max == -(1L << 31));
        CHECK(b.reset_max == -(1L << (prop.resp_w - 1)));
        ++streams;
    }
    CHECK(streams == 21);
}

TEST_CASE("the thesis's proposal: proven on both routes, its stages proven equal, fewer flip-flops and LUTs in yosys",
          "[propose-slow]") {
    const Formats base{};
    const Formats prop = propose_widths(model_route(base)).formats;
    // (a) every register proven, the netlist route included
    const RangeReport r = analyse_ranges(prop);
    CHECK(r.summary() == "proven safe");
    for (const auto& x : r.regs) {
        INFO(kRegNames[static_cast<int>(x.reg)]);
        CHECK(x.verdict == Verdict::proven);
    }
    // (c) every stage entity's netlist at the proposal's generics equals the model's stage function
    util::ScratchDir dir("propose-stages");
    StageOptions so;
    so.dir = dir.path();
    so.config = "proposed-thesis";
    const StageEquivalence se = stage_equivalence(prop, so);
    CHECK(se.summary() == "8 proven equal");
    // (b) the cost beside the base's (the sweep's synthesis and cache)
    CostOptions o;
    o.rtl_sources = cosim::rtl_sources();
    o.cache_dir = std::string(HC_BUILD_DIR) + "/sweep-cache";
    const CostContext ctx(o);
    const Cost b = synth_cost(ctx, base, Variant::signed_mul), p = synth_cost(ctx, prop, Variant::signed_mul);
    WARN("thesis: " << b.luts << " LUT, " << b.ffs << " FF, " << b.dsps << " DSP; proposal: " << p.luts << " LUT, " << p.ffs
                    << " FF, " << p.dsps << " DSP; register bits " << datapath_register_bits(base, Geometry{}) << " -> "
                    << datapath_register_bits(prop, Geometry{}));
    CHECK(p.ffs < b.ffs);
    CHECK(p.luts < b.luts);
    CHECK(p.dsps <= b.dsps);
}

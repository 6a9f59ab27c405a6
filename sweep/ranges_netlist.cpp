// ranges_netlist.cpp: the netlist route of the derived ranges (see ranges.hpp): each
// register's question asked by z3 on GHDL's synthesis of the stage chain, as yosys writes
// it in SMT-LIB.
#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "sweep/ranges.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
constexpr int idx(Reg r) { return static_cast<int>(r); }

// ---- the netlists ------------------------------------------------------------------------

/// A register replaced by its input: the pipeline's value once its inputs have held still
/// for as many writes as it is deep (every enable and reset tied to its active and inactive
/// level, so that yosys has folded them away before this map applies).
constexpr const char* kFlopToWire =
    "module \\$dff (CLK, D, Q);\n"
    "  parameter WIDTH = 1;\n  parameter CLK_POLARITY = 1'b1;\n"
    "  input CLK;\n  input [WIDTH-1:0] D;\n  output [WIDTH-1:0] Q;\n"
    "  assign Q = D;\nendmodule\n";

/// The port list of a module's stage-input ports "input signed [w-1:0] name".
std::string in_port(const std::string& name, int w) { return fmt::format("input signed [{}:0] {}", w - 1, name); }

std::string tie(const std::string& ports) { return ".clk(clk), .rst(1'b1), .write(1'b1), " + ports; }

/// The three block filters of one window: sums a, b, c of ma_*, mb_*, mc_*.
std::string block_instances() {
    std::string s;
    for (const char* m : {"a", "b", "c"}) {
        std::string cat;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) cat += fmt::format("{}m{}_{}_{}", cat.empty() ? "" : ", ", m, i, j);
        s += fmt::format("  block_filter bf_{0}({1});\n", m, tie(fmt::format(".en(1'b1), .a({{{}}}), .sum({})", cat, m)));
    }
    return s;
}

std::string response_instance() {
    return "  harris_response hr(.clk(clk), .rst(1'b1), .en0(1'b1), .en1(1'b1), .write(1'b1), .a(a), .b(b), .c(c), .r(r));\n";
}

/// The chain of one 5x5 window and the two stage modules, in Verilog over GHDL's modules.
std::string wrappers(const Formats& f) {
    const int sw = f.sobel_w, mw = f.m_w(), bw = f.bf_w(), rw = f.resp_w;
    std::string chain = "module chain(input clk";
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) chain += fmt::format(", input [7:0] p_{}_{}", i, j);
    chain += fmt::format(", output signed [{}:0] r);\n", rw - 1);
    chain += fmt::format("  wire signed [{}:0] a, b, c;\n", bw - 1);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // u8_matrix3 as GHDL packs it: element (1, 1) in the top byte, row by row
            std::string nb;
            for (int di = 0; di < 3; ++di)
                for (int dj = 0; dj < 3; ++dj) nb += fmt::format("{}p_{}_{}", nb.empty() ? "" : ", ", i + di, j + dj);
            const std::string at = fmt::format("{}_{}", i, j);
            chain += fmt::format("  wire signed [{0}:0] ix_{2}, iy_{2};\n  wire signed [{1}:0] ma_{2}, mb_{2}, mc_{2};\n", sw - 1, mw - 1, at);
            chain += fmt::format("  sobel_x sx_{0}({1});\n", at, tie(fmt::format(".en(1'b1), .a({{{}}}), .ix(ix_{})", nb, at)));
            chain += fmt::format("  sobel_y sy_{0}({1});\n", at, tie(fmt::format(".en(1'b1), .a({{{}}}), .iy(iy_{})", nb, at)));
            chain += fmt::format("  m_products mm_{0}({1});\n", at,
                                 tie(fmt::format(".en(1'b1), .ix(ix_{0}), .iy(iy_{0}), .a(ma_{0}), .b(mb_{0}), .c(mc_{0})", at)));
        }
    chain += block_instances() + response_instance() + "endmodule\n";

    std::string block = "module stage_block(input clk";
    for (const char* m : {"a", "b", "c"})
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) block += ", " + in_port(fmt::format("m{}_{}_{}", m, i, j), mw);
    block += fmt::format(", output signed [{0}:0] a, output signed [{0}:0] b, output signed [{0}:0] c);\n", bw - 1);
    block += block_instances() + "endmodule\n";

    const std::string response = fmt::format("module stage_response(input clk, {}, {}, {}, output signed [{}:0] r);\n", in_port("a", bw),
                                             in_port("b", bw), in_port("c", bw), rw - 1) +
                                 response_instance() + "endmodule\n";
    return chain + block + response;
}

/// The yosys script that writes `top` as SMT-LIB, refusing a register that does not fold to a plain flop.
std::string smt_script(const std::string& top, const std::vector<std::string>& modules) {
    std::string read = "read_verilog";
    for (const auto& m : modules) read += " " + m + ".v";
    return read + " wrappers.v\nhierarchy -top " + top +
           "\nproc\nflatten\nopt\n"
           "select -assert-none t:$adff t:$dffe t:$adffe t:$sdff t:$sdffe t:$sdffce t:$aldff t:$aldffe t:$dffsr t:$dffsre "
           "t:$dlatch t:$adlatch t:$dlatchsr t:$sr t:$mem t:$mem_v2\n"
           "techmap -map flop_to_wire.v t:$dff\nopt\ncheck -assert\nselect -assert-none t:$dff\n"
           "write_smt2 -wires " + top + ".smt2\n";
}

// ---- where the netlist can differ from numeric_std -------------------------------------

/// The interval of x * y for x, y in the two intervals; a square when `square`.
Interval product(const Interval& x, const Interval& y, bool square) {
    const std::int64_t c[4] = {x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi};
    Interval p{*std::min_element(c, c + 4), *std::max_element(c, c + 4)};
    if (square) p.lo = (x.lo <= 0 && x.hi >= 0) ? 0 : std::min(x.lo * x.lo, x.hi * x.hi);
    return p;
}

/// What the next stage sees of register r: its proven range (the solver's, else its bound,
/// within its width) where the model route proves it, else what its width holds.
Interval seen(const RangeReport& rep, Reg r) {
    const RegisterRange& x = rep.at(r);
    if (x.verdict != Verdict::proven || x.decided_by == "netlist") return x.held;
    const Interval v = x.solver_range ? *x.solver_range : x.bound;
    return {std::max(v.lo, x.held.lo), std::min(v.hi, x.held.hi)};
}

/// The pipeline stage of a register (0 Sobel, 1 M, 2 block sums, 3 the response's stage).
int stage_index(Reg r) {
    switch (r) {
        case Reg::sobel_x: case Reg::sobel_y: return 0;
        case Reg::m_a: case Reg::m_b: case Reg::m_c: return 1;
        case Reg::block_a: case Reg::block_b: case Reg::block_c: return 2;
        default: return 3;
    }
}

/// The register's signed shrinks that may overflow, as far as the VHDL's value is concerned:
/// those of its stage that feed it, unless the model route proves it (its VHDL value is then
/// its exact value), and those of the stages upstream, unless the model route proves a
/// register they feed.
std::vector<const SignedShrink*> unsafe_shrinks(const RangeReport& rep, Reg r, const std::vector<SignedShrink>& all) {
    const auto model_proven = [&](Reg x) { return rep.at(x).verdict == Verdict::proven && rep.at(x).decided_by != "netlist"; };
    std::vector<const SignedShrink*> v;
    for (const SignedShrink& s : all) {
        if (s.fits || stage_index(s.feeds.front()) > stage_index(r)) continue;
        const bool own = stage_index(s.feeds.front()) == stage_index(r);
        if (own && std::find(s.feeds.begin(), s.feeds.end(), r) == s.feeds.end()) continue;
        if (own ? model_proven(r) : std::any_of(s.feeds.begin(), s.feeds.end(), model_proven)) continue;
        v.push_back(&s);
    }
    return v;
}

std::string shrink_list(const std::vector<const SignedShrink*>& v) {
    std::string s;
    for (const SignedShrink* x : v)
        s += fmt::format("{}{} from {} bits (operand in [{}, {}])", s.empty() ? "" : "; ", x->what, x->from, x->operand.lo,
                         x->operand.hi);
    return s;
}

/// The side condition under which the netlist's answer on register r is the VHDL's.
std::string vhdl_condition(const RangeReport& rep, Reg r, const std::vector<SignedShrink>& all) {
    const auto v = unsafe_shrinks(rep, r, all);
    if (!v.empty()) return "GHDL's netlist only: " + shrink_list(v) + " may overflow, where GHDL's synthesis drops the sign bit";
    int n = 0;
    for (const SignedShrink& s : all) n += stage_index(s.feeds.front()) <= stage_index(r);
    return n == 0 ? "holds for the VHDL: no signed shrink upstream"
                  : fmt::format("holds for the VHDL: each of the {} signed shrinks upstream fits its width (its bound, or the "
                                "model route's proof of the register it feeds)",
                                n);
}

// ---- the questions ---------------------------------------------------------------------

constexpr int kW = 64;   // every exact value fits 64 bits

std::string bv(std::int64_t v) { return fmt::format("(_ bv{} 64)", static_cast<std::uint64_t>(v)); }
std::string ashr(const std::string& x, int k) { return k == 0 ? x : fmt::format("(bvashr {} (_ bv{} 64))", x, k); }

/// Terms of one module's wires in state `s`.
struct Terms {
    std::string module;
    std::string wire(const std::string& name) const { return fmt::format("(|{}_n {}| s)", module, name); }
    /// A signed wire of `w` bits as 64 bits.
    std::string sx(const std::string& name, int w) const { return fmt::format("((_ sign_extend {}) {})", kW - w, wire(name)); }
    /// A pixel (unsigned 8 bits) as 64 bits.
    std::string px(int i, int j) const { return fmt::format("((_ zero_extend {}) p_{}_{})", kW - 8, i, j); }
    /// numeric_std's resize of a signed wire of `w` bits to `n` bits, then as 64 bits.
    std::string resized(const std::string& name, int w, int n) const {
        if (n >= w) return sx(name, w);
        const std::string x = wire(name);
        return fmt::format("((_ sign_extend {}) (concat ((_ extract {} {}) {}) ((_ extract {} 0) {})))", kW - n, w - 1, w - 1, x, n - 2, x);
    }
};

/// The stage module a register's question is asked on first (its inputs free in the ranges
/// proven upstream), or "chain" when the stage's inputs are pixels.
std::string stage_of(Reg r) {
    switch (r) {
        case Reg::sobel_x: case Reg::sobel_y: case Reg::m_a: case Reg::m_b: case Reg::m_c: return "chain";
        case Reg::block_a: case Reg::block_b: case Reg::block_c: return "stage_block";
        default: return "stage_response";
    }
}

/// A signed term of `w` bits (to widen exactly).
struct Signed {
    std::string e;
    int w = 1;
};
Signed widen(const Signed& x, int n) { return n == x.w ? x : Signed{fmt::format("((_ sign_extend {}) {})", n - x.w, x.e), n}; }
/// The exact product, computed in the width that holds every product of the two (w1 + w2
/// bits), the form GHDL's netlist has, so that the solver need not prove two multipliers equal.
Signed times(const Signed& x, const Signed& y) {
    const int n = x.w + y.w;
    return {fmt::format("(bvmul {} {})", widen(x, n).e, widen(y, n).e), n};
}
/// The exact sum, in one bit more than the wider operand.
Signed plus(const Signed& x, const Signed& y) {
    const int n = std::max(x.w, y.w) + 1;
    return {fmt::format("(bvadd {} {})", widen(x, n).e, widen(y, n).e), n};
}
std::string wide(const Signed& x) { return widen(x, kW).e; }

/// The register's exact value and its hardware value on module `t`, as RegisterRange's
/// questions read them (Sobel and M at the window's 3x3 position `at`, row and column).
std::pair<std::string, std::string> exact_and_hw(Reg r, const Formats& f, const Terms& t, std::pair<int, int> at = {0, 0}) {
    const auto sum = [](const std::vector<std::string>& xs) {
        std::string s = xs[0];
        for (size_t k = 1; k < xs.size(); ++k) s = fmt::format("(bvadd {} {})", s, xs[k]);
        return s;
    };
    const auto weighted = [&](std::initializer_list<std::pair<int, int>> ps, std::initializer_list<std::pair<int, int>> twice) {
        std::vector<std::string> xs;
        for (auto [i, j] : ps) xs.push_back(t.px(at.first + i, at.second + j));
        for (auto [i, j] : twice) xs.push_back(fmt::format("(bvadd {0} {0})", t.px(at.first + i, at.second + j)));
        return sum(xs);
    };
    const auto sig = [&](const std::string& name, int w) { return Signed{t.wire(name), w}; };
    const int bw = f.bf_w(), pw = 2 * f.bf_w();
    const Signed a = sig("a", bw), b = sig("b", bw), c = sig("c", bw);
    const std::string ac_bb = fmt::format("(bvsub {} {})", wide(times(a, c)), wide(times(b, b)));
    const std::string pos = fmt::format("{}_{}", at.first, at.second);
    switch (r) {
        case Reg::sobel_x:
            return {fmt::format("(bvsub {} {})", weighted({{0, 2}, {2, 2}}, {{1, 2}}), weighted({{0, 0}, {2, 0}}, {{1, 0}})),
                    t.sx("ix_" + pos, f.sobel_w)};
        case Reg::sobel_y:
            return {fmt::format("(bvsub {} {})", weighted({{0, 0}, {0, 2}}, {{0, 1}}), weighted({{2, 0}, {2, 2}}, {{2, 1}})),
                    t.sx("iy_" + pos, f.sobel_w)};
        case Reg::m_a: case Reg::m_b: case Reg::m_c: {
            const Signed x = sig((r == Reg::m_c ? "iy_" : "ix_") + pos, f.sobel_w);
            const Signed y = sig((r == Reg::m_a ? "ix_" : "iy_") + pos, f.sobel_w);
            const char* m = r == Reg::m_a ? "ma" : r == Reg::m_b ? "mb" : "mc";
            return {ashr(wide(times(x, y)), f.m_drop), t.sx(fmt::format("{}_{}", m, pos), f.m_w())};
        }
        case Reg::block_a: case Reg::block_b: case Reg::block_c: {
            const char* m = r == Reg::block_a ? "ma" : r == Reg::block_b ? "mb" : "mc";
            std::vector<std::string> xs;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) xs.push_back(t.sx(fmt::format("{}_{}_{}", m, i, j), f.m_w()));
            return {ashr(sum(xs), f.bf_drop), t.sx(r == Reg::block_a ? "a" : r == Reg::block_b ? "b" : "c", bw)};
        }
        case Reg::trace: return {wide(plus(a, c)), t.sx("hr.trace", bw + 1)};
        case Reg::k_term: {
            const Signed tr = plus(a, c);
            const std::string tr2 = wide(times(tr, tr));
            return {fmt::format("(bvadd {} {})", ashr(tr2, f.k_shift1), ashr(tr2, f.k_shift2)), t.sx("hr.ktr2", f.ktr_w)};
        }
        // the netlist has no register for det: a*c and b*b are its registers ac, bb, resized as r_next resizes them
        case Reg::det:
            return {ac_bb, fmt::format("(bvsub {} {})", t.resized("hr.ac", pw, f.resp_w), t.resized("hr.bb", pw, f.resp_w))};
        case Reg::response:
            return {fmt::format("(bvsub {} {})", ac_bb, t.sx("hr.ktr2", f.ktr_w)), t.sx("r", f.resp_w)};
        default: throw std::logic_error(std::string("netlist route: no question for ") + kRegNames[idx(r)]);
    }
}

/// The registers the stage module's inputs are (their proven ranges are its assumptions).
std::vector<std::pair<std::string, Reg>> stage_inputs(const std::string& module, const Formats& f, int& width) {
    std::vector<std::pair<std::string, Reg>> v;
    if (module == "stage_block") {
        width = f.m_w();
        for (auto [m, r] : {std::pair{"ma", Reg::m_a}, std::pair{"mb", Reg::m_b}, std::pair{"mc", Reg::m_c}})
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) v.emplace_back(fmt::format("{}_{}_{}", m, i, j), r);
    }
    if (module == "stage_response") {
        width = f.bf_w();
        v = {{"a", Reg::block_a}, {"b", Reg::block_b}, {"c", Reg::block_c}};
    }
    return v;
}

/// The head of a query on `module`: its netlist, one state, the pixels (chain: in
/// [0, pixel_max]) or the stage inputs in `ranges` (the assumptions).
std::string query_head(const StageNetlists& n, const std::string& module, const Formats& f, int pixel_max,
                       const std::array<Interval, kRegCount>& ranges) {
    const std::string& net = module == "chain" ? n.chain : module == "stage_block" ? n.block : n.response;
    std::string s = net + fmt::format("(declare-fun s () |{0}_s|)\n(assert (|{0}_h| s))\n", module);
    const Terms t{module};
    if (module == "chain") {
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j)
                s += fmt::format("(define-fun p_{0}_{1} () (_ BitVec 8) {2})\n(assert (bvule p_{0}_{1} (_ bv{3} 8)))\n", i, j,
                                 t.wire(fmt::format("p_{}_{}", i, j)), pixel_max);
        return s;
    }
    int w = 0;
    for (const auto& [name, reg] : stage_inputs(module, f, w)) {
        const Interval v = ranges[idx(reg)];
        s += fmt::format("(assert (and (bvsge {0} {1}) (bvsle {0} {2})))\n", t.sx(name, w), bv(v.lo), bv(v.hi));
    }
    return s;
}

std::string range_text(const Interval& v) { return fmt::format("[{}, {}]", v.lo, v.hi); }

Interval meet(const Interval& a, const Interval& b) { return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)}; }

bool wraps_in_model(const Window5& w, const Formats& f, Reg r) {
    for (bool maximise : {true, false}) {
        const WindowValue x = window_values(w, f, maximise)[idx(r)];
        if (x.exact != x.narrowed) return true;
    }
    return false;
}

std::string window_text(const Window5& w) {
    std::string s;
    for (const auto& row : w) {
        s += s.empty() ? "" : " / ";
        for (size_t j = 0; j < row.size(); ++j) s += fmt::format("{}{}", j ? " " : "", row[j]);
    }
    return s;
}

/// The netlist route's state for one configuration.
struct Route {
    const StageNetlists& n;
    const Formats& f;
    const RangeOptions& o;
    std::int64_t left = 0;
    fs::path keep;                          ///< where the queries are kept (empty: nowhere)
    std::array<int, kRegCount> asked{};     ///< queries per register so far
    /// the hardware value of each register as proven on the netlist (else what its width holds)
    std::array<Interval, kRegCount> proven{};
    const RangeReport* rep = nullptr;       ///< the model route's report (its verdicts, for the shrinks' side conditions)
    std::vector<SignedShrink> shrinks;      ///< the chain's signed shrinks at the configuration

    struct Ask {
        Sat sat = Sat::unknown;
        Window5 window{};
        std::int64_t exact = 0, hw = 0;
        std::int64_t rlimit = 0;
        std::string why;
    };
    /// Is there a state of `module` (pixels or stage inputs as above; `fixed`: the chain's
    /// pixels equal to a window) where r's exact value differs from its hardware value, or
    /// the hardware value leaves `claim`?
    Ask ask(Reg r, const std::string& module, const Interval& claim, const Window5* fixed, std::pair<int, int> at = {0, 0}) {
        Ask a;
        if (left <= 1'000'000) {
            a.why = "not asked: the netlist route's budget is spent";
            return a;
        }
        std::string q = query_head(n, module, f, o.pixel_max, proven);
        if (fixed)
            for (int i = 0; i < 5; ++i)
                for (int j = 0; j < 5; ++j) q += fmt::format("(assert (= p_{}_{} (_ bv{} 8)))\n", i, j, (*fixed)[i][j]);
        const auto [exact, hw] = exact_and_hw(r, f, Terms{module}, at);
        q += fmt::format("(define-fun exact () (_ BitVec 64) {})\n(define-fun hw () (_ BitVec 64) {})\n", exact, hw);
        q += fmt::format("(assert (or (distinct exact hw) (bvslt hw {}) (bvsgt hw {})))\n", bv(claim.lo), bv(claim.hi));
        std::vector<std::string> get = {"exact", "hw"};
        if (module == "chain")
            for (int i = 0; i < 5; ++i)
                for (int j = 0; j < 5; ++j) get.push_back(fmt::format("p_{}_{}", i, j));
        const int k = ++asked[idx(r)];
        const fs::path file = keep.empty() ? fs::path() : keep / fmt::format("query-{}-{}.smt2", kRegNames[idx(r)], k);
        const Z3Answer z = run_z3(q, std::min(o.netlist_query_rlimit, left), get, file);
        left -= z.rlimit;
        a.sat = z.sat;
        a.rlimit = z.rlimit;
        a.why = z.why;
        if (z.sat == Sat::sat) {
            a.exact = z.values.at("exact");
            a.hw = z.values.at("hw");
            if (module == "chain")
                for (int i = 0; i < 5; ++i)
                    for (int j = 0; j < 5; ++j) a.window[i][j] = static_cast<int>(z.values.at(fmt::format("p_{}_{}", i, j)));
        }
        return a;
    }

    /// The assumptions a stage module's question rests on, as text.
    std::string assumed(const std::string& module) const {
        int w = 0;
        std::string s;
        Reg last = Reg::count;
        for (const auto& [name, reg] : stage_inputs(module, f, w)) {
            if (reg == last) continue;
            last = reg;
            s += fmt::format("{}{} in {}", s.empty() ? "" : ", ", kRegNames[idx(reg)], range_text(proven[idx(reg)]));
        }
        return s;
    }

    /// A window from the chain where r's exact value and hardware value differ: it must wrap r in the model too.
    void witness(RegisterRange& rr, const Ask& a, const std::string& how) {
        if (a.exact == a.hw)
            throw std::logic_error(fmt::format("netlist route: {}'s value {} at window {} leaves the range the model route proves",
                                               kRegNames[idx(rr.reg)], a.hw, window_text(a.window)));
        if (!wraps_in_model(a.window, f, rr.reg)) {
            if (const auto v = unsafe_shrinks(*rep, rr.reg, shrinks); !v.empty()) {
                rr.netlist = fmt::format("sat {} on GHDL's netlist only (exact {}, netlist {}), not a wrap of the VHDL at window {}: "
                                         "the netlist differs from the VHDL where {} overflows",
                                         how, a.exact, a.hw, window_text(a.window), shrink_list(v));
                return;
            }
            throw std::logic_error(fmt::format("netlist route: {} wraps on the netlist at window {} (exact {}, netlist {}), "
                                               "not in the model",
                                               kRegNames[idx(rr.reg)], window_text(a.window), a.exact, a.hw));
        }
        rr.netlist_verdict = Verdict::wraps;
        rr.netlist = fmt::format("sat {}: exact {}, netlist {}", how, a.exact, a.hw);
        if (rr.verdict != Verdict::wraps) rr.witness = a.window;
    }

    /// The model's witness does not wrap r on the netlist (its exact value there at every
    /// position asked): where a signed shrink may overflow, the netlist differs from the VHDL
    /// at the witness; elsewhere that is a fault of the analysis.
    void differs(RegisterRange& rr) {
        const auto v = unsafe_shrinks(*rep, rr.reg, shrinks);
        if (v.empty())
            throw std::logic_error(fmt::format("netlist route: {} does not wrap on the netlist at the model's witness {}",
                                               kRegNames[idx(rr.reg)], window_text(rr.witness)));
        WindowValue m{};
        for (bool maximise : {true, false})
            if (const WindowValue x = window_values(rr.witness, f, maximise)[idx(rr.reg)]; x.exact != x.narrowed) m = x;
        // Sobel and M: the netlist holds the exact value at each position (the queries above); the rest at the centre
        const std::int64_t net = stage_of(rr.reg) == "chain" ? m.exact : netlist_values(n, f, rr.witness)[idx(rr.reg)].value();
        if (net == m.narrowed)
            throw std::logic_error(fmt::format("netlist route: {} at the model's witness {}: the netlist holds the model's {}",
                                               kRegNames[idx(rr.reg)], window_text(rr.witness), net));
        rr.netlist_differs = true;
        rr.netlist_value = net;
        rr.vhdl_value = m.narrowed;
        rr.netlist = fmt::format("unsat at the model's witness window: the netlist differs from the VHDL there (netlist {}, "
                                 "VHDL {}, exact {}), where {} may overflow (GHDL's synthesis drops the sign bit numeric_std keeps)",
                                 net, m.narrowed, m.exact, shrink_list(v));
    }

    void decide(RegisterRange& rr) {
        rr.netlist_asked = true;
        rr.netlist_vhdl = vhdl_condition(*rep, rr.reg, shrinks);
        const Interval held = rr.held;
        // the range claimed: the model route's proven range (the solver's, else the bound), within the register
        Interval claim = held;
        if (rr.verdict == Verdict::proven) claim = meet(held, rr.solver_range ? *rr.solver_range : rr.bound);
        if (rr.verdict == Verdict::wraps) {
            // the model's witness, on the netlist: it must wrap there too (Sobel and M: at one of the nine positions)
            const bool positions = stage_of(rr.reg) == "chain";
            Ask a;
            for (int k = 0; k < (positions ? 9 : 1) && a.sat != Sat::sat; ++k) {
                a = ask(rr.reg, "chain", held, &rr.witness, {k / 3, k % 3});
                rr.netlist_rlimit += a.rlimit;
                if (a.sat == Sat::unknown) break;
            }
            if (a.sat == Sat::sat) return witness(rr, a, "at the model's witness window");
            if (a.sat == Sat::unsat) return differs(rr);
            rr.netlist = a.why;
            return;
        }
        const std::string module = stage_of(rr.reg);
        std::string said;
        if (module != "chain") {
            const Ask a = ask(rr.reg, module, claim, nullptr);
            rr.netlist_rlimit += a.rlimit;
            if (a.sat == Sat::unsat) {
                rr.netlist_verdict = Verdict::proven;
                rr.netlist_range = claim;
                rr.netlist = fmt::format("unsat on {} assuming {}: in {}", module, assumed(module), range_text(claim));
                proven[idx(rr.reg)] = claim;
                return;
            }
            if (a.sat != Sat::sat) {   // the chain from pixels is the harder question
                rr.netlist = fmt::format("{} assuming {}: {}", module, assumed(module), a.why);
                return;
            }
            said = fmt::format("sat on {} assuming {} (exact {}, netlist {}); ", module, assumed(module), a.exact, a.hw);
        }
        // from the pixels through the whole chain
        Ask a = ask(rr.reg, "chain", claim, nullptr);
        rr.netlist_rlimit += a.rlimit;
        if (a.sat == Sat::unknown && claim != held && rr.reg != Reg::sobel_x && rr.reg != Reg::sobel_y) {
            // the tight claim out of reach: whether it cannot wrap at all
            said += fmt::format("chain in {}: {}; ", range_text(claim), a.why);
            claim = held;
            const Ask b = ask(rr.reg, "chain", claim, nullptr);
            a = b;
            rr.netlist_rlimit += a.rlimit;
        }
        if (a.sat == Sat::unsat) {
            rr.netlist_verdict = Verdict::proven;
            rr.netlist_range = claim;
            rr.netlist = said + fmt::format("unsat on the chain from pixels: in {}", range_text(claim));
            proven[idx(rr.reg)] = claim;
            return;
        }
        if (a.sat == Sat::sat) return witness(rr, a, "from pixels");
        rr.netlist = said + "chain from pixels: " + a.why;
    }
};

}  // namespace

std::vector<SignedShrink> signed_shrinks(const RangeReport& rep) {
    const Formats& f = rep.formats;
    std::vector<SignedShrink> v;
    const auto add = [&](std::string what, int from, int to, std::vector<Reg> feeds, Interval operand) {
        if (to < from) v.push_back({std::move(what), from, to, std::move(feeds), operand, fits(operand, to, true)});
    };
    // sobel_x: p11, p13, p31, p33 = +-pixel in 9 bits, p21, p23 = +-2 pixel in 10; sobel_y: p12, p32 the doubled ones
    const std::int64_t pm = rep.pixel_max;
    for (const char* p : {"p11", "p13", "p31", "p33"}) {
        add(fmt::format("resize({}, SOBEL_W) in sobel_x", p), 9, f.sobel_w, {Reg::sobel_x}, p[2] == '1' ? Interval{-pm, 0} : Interval{0, pm});
    }
    add("resize(p21, SOBEL_W) in sobel_x", 10, f.sobel_w, {Reg::sobel_x}, {-2 * pm, 0});
    add("resize(p23, SOBEL_W) in sobel_x", 10, f.sobel_w, {Reg::sobel_x}, {0, 2 * pm});
    for (const char* p : {"p11", "p13", "p31", "p33"})
        add(fmt::format("resize({}, SOBEL_W) in sobel_y", p), 9, f.sobel_w, {Reg::sobel_y}, p[1] == '1' ? Interval{0, pm} : Interval{-pm, 0});
    add("resize(p12, SOBEL_W) in sobel_y", 10, f.sobel_w, {Reg::sobel_y}, {0, 2 * pm});
    add("resize(p32, SOBEL_W) in sobel_y", 10, f.sobel_w, {Reg::sobel_y}, {-2 * pm, 0});
    const Interval ix = seen(rep, Reg::sobel_x), iy = seen(rep, Reg::sobel_y);
    add("resize(ix * ix, M_PROD_W) in m_products", 2 * f.sobel_w, f.m_prod_w, {Reg::m_a}, product(ix, ix, true));
    add("resize(ix * iy, M_PROD_W) in m_products", 2 * f.sobel_w, f.m_prod_w, {Reg::m_b}, product(ix, iy, false));
    add("resize(iy * iy, M_PROD_W) in m_products", 2 * f.sobel_w, f.m_prod_w, {Reg::m_c}, product(iy, iy, true));
    for (auto [m, blk] : {std::pair{Reg::m_a, Reg::block_a}, std::pair{Reg::m_b, Reg::block_b}, std::pair{Reg::m_c, Reg::block_c}})
        add(fmt::format("resize(a(i, j), BF_SUM_W) in block_filter ({})", kRegNames[idx(blk)]), f.m_w(), f.bf_sum_w, {blk}, seen(rep, m));
    const Interval a = seen(rep, Reg::block_a), b = seen(rep, Reg::block_b), c = seen(rep, Reg::block_c);
    const Interval tr{a.lo + c.lo, a.hi + c.hi}, tr2 = product(tr, tr, true);
    const int tr2_w = 2 * f.trace_w();
    for (int k : {f.k_shift1, f.k_shift2})
        add(fmt::format("resize(trace_sq(TR2_W - 1 downto {}), KTR_W) in harris_response", k), tr2_w - k, f.ktr_w,
            {Reg::k_term, Reg::response}, floor_div_pow2(tr2, k));
    add("resize(ac, RESP_W) in harris_response", f.prod_w(), f.resp_w, {Reg::det, Reg::response}, product(a, c, false));
    add("resize(bb, RESP_W) in harris_response", f.prod_w(), f.resp_w, {Reg::det, Reg::response}, product(b, b, true));
    add("resize(ktr2, RESP_W) in harris_response", f.ktr_w, f.resp_w, {Reg::response}, seen(rep, Reg::k_term));
    return v;
}

std::vector<std::string> entity_generics(const std::string& e, const Formats& f, const Geometry& geo) {
    std::vector<std::pair<const char*, int>> g;
    if (e == "sobel_x" || e == "sobel_y") g = {{"SOBEL_W", f.sobel_w}};
    if (e == "m_products") g = {{"SOBEL_W", f.sobel_w}, {"M_PROD_W", f.m_prod_w}, {"M_DROP", f.m_drop}};
    if (e == "block_filter") g = {{"IN_W", f.m_w()}, {"BF_SUM_W", f.bf_sum_w}, {"BF_DROP", f.bf_drop}};
    if (e == "harris_response")
        g = {{"BF_W", f.bf_w()}, {"RESP_W", f.resp_w}, {"KTR_W", f.ktr_w}, {"K_SHIFT1", f.k_shift1}, {"K_SHIFT2", f.k_shift2}};
    if (e == "threshold" || e == "local_maximum") g = {{"RESP_W", f.resp_w}};
    if (e == "find_max") g = {{"IMG_WIDTH", geo.width}, {"IMG_HEIGHT", geo.height}, {"RESP_W", f.resp_w}};
    std::vector<std::string> v;
    for (const auto& [name, val] : g) v.push_back(fmt::format("-g{}={}", name, val));
    return v;
}

StageNetlists stage_netlists(const Formats& f, const fs::path& where) {
    f.validate();
    // absolute: yosys runs in the directory, and its log is named from here
    const fs::path dir = fs::absolute(where);
    fs::create_directories(dir);
    StageNetlists n;
    const std::vector<std::string> entities = {"sobel_x", "sobel_y", "m_products", "block_filter", "harris_response"};
    std::string sources;
    for (const auto& s : cosim::rtl_sources()) sources += " rtl/" + s.filename().string();
    for (const auto& e : entities) {
        std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + (dir / ("work-" + e)).string()};
        fs::create_directories(dir / ("work-" + e));
        const std::vector<std::string> g = entity_generics(e, f);
        argv.insert(argv.end(), g.begin(), g.end());
        argv.push_back("--out=verilog");
        for (const auto& s : cosim::rtl_sources()) argv.push_back(s.string());
        argv.insert(argv.end(), {"-e", e});
        std::string gens;
        for (const auto& x : g) gens += " " + x;
        n.commands += fmt::format("ghdl --synth --std=08 --workdir=work-{0}{1} --out=verilog{2} -e {0} | {3} > {0}.v\n", e, gens,
                                  sources, cosim::kSizedBitLiteralsFilter);
        const fs::path log = dir / (e + "-synth.log");
        if (cosim::synth_verilog(argv, dir / (e + ".v"), {.log = log}) != 0)
            throw SimulatorError("ghdl --synth of " + e + " failed: " + util::log_tail(log, 1500));
    }
    util::write_file_atomic(dir / "wrappers.v", wrappers(f));
    util::write_file_atomic(dir / "flop_to_wire.v", kFlopToWire);
    const std::vector<std::pair<std::string, std::vector<std::string>>> tops = {
        {"chain", entities}, {"stage_block", {"block_filter"}}, {"stage_response", {"harris_response"}}};
    for (const auto& [top, modules] : tops) {
        const fs::path ys = dir / (top + ".ys"), log = dir / (top + ".log");
        util::write_file_atomic(ys, smt_script(top, modules));
        fs::remove(log);
        if (util::run_process({"yosys", "-q", "-s", ys.filename().string()}, {.cwd = dir, .log = log}) != 0)
            throw SimulatorError("yosys could not write " + top + " as SMT-LIB: " + util::log_tail(log, 1500));
        n.commands += fmt::format("yosys -q -s {}.ys    # writes {}.smt2\n", top, top);
    }
    util::write_file_atomic(dir / "commands.txt", n.commands);
    n.chain = util::read_file(dir / "chain.smt2");
    n.block = util::read_file(dir / "stage_block.smt2");
    n.response = util::read_file(dir / "stage_response.smt2");
    return n;
}

std::array<std::optional<std::int64_t>, kRegCount> netlist_values(const StageNetlists& n, const Formats& f, const Window5& w) {
    std::array<Interval, kRegCount> any{};
    std::string q = query_head(n, "chain", f, 255, any);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) q += fmt::format("(assert (= p_{}_{} (_ bv{} 8)))\n", i, j, w[i][j]);
    std::vector<std::string> get;
    for (int r = 0; r < kRegCount; ++r) {
        const Reg reg = static_cast<Reg>(r);
        if (reg == Reg::maximum || reg == Reg::threshold) continue;
        q += fmt::format("(define-fun hw_{} () (_ BitVec 64) {})\n", kRegNames[r], exact_and_hw(reg, f, Terms{"chain"}).second);
        get.push_back(fmt::format("hw_{}", kRegNames[r]));
    }
    const Z3Answer z = run_z3(q, 100'000'000, get);
    if (z.sat != Sat::sat) throw std::runtime_error("netlist_values: z3 found no value of the chain at the window: " + z.why);
    std::array<std::optional<std::int64_t>, kRegCount> v{};
    for (int r = 0; r < kRegCount; ++r)
        if (z.values.count(fmt::format("hw_{}", kRegNames[r]))) v[r] = z.values.at(fmt::format("hw_{}", kRegNames[r]));
    return v;
}

void netlist_route(RangeReport& rep, const RangeOptions& o) {
    const auto t0 = Clock::now();
    rep.netlist_query_rlimit = o.netlist_query_rlimit;
    const util::ScratchDir scratch;
    const fs::path dir = o.netlist_dir.empty() ? scratch.path() : o.netlist_dir;
    StageNetlists n;
    try {
        n = stage_netlists(rep.formats, dir);
    } catch (const SimulatorError& e) {
        rep.netlist_note = std::string("not run (no verdict taken from it): ") + e.what();
        rep.seconds_netlist = since(t0);
        return;
    }
    rep.netlist_note = "GHDL's synthesis of sobel_x, sobel_y, m_products, block_filter and harris_response at the "
                       "configuration's generics, through yosys write_smt2; z3 with rlimit";
    Route route{n, rep.formats, o, o.netlist_budget, o.netlist_dir, {}, {}, &rep, signed_shrinks(rep)};
    for (const auto& rr : rep.regs) route.proven[idx(rr.reg)] = rr.held;
    for (Reg r : {Reg::sobel_x, Reg::sobel_y, Reg::m_a, Reg::m_b, Reg::m_c, Reg::block_a, Reg::block_b, Reg::block_c, Reg::trace,
                  Reg::response, Reg::det, Reg::k_term})
        route.decide(rep.regs[idx(r)]);
    rep.netlist_rlimit = o.netlist_budget - route.left;
    // the maximum holds a response
    RegisterRange& m = rep.regs[idx(Reg::maximum)];
    const RegisterRange& resp = rep.regs[idx(Reg::response)];
    m.netlist_asked = true;
    m.netlist_verdict = resp.netlist_verdict;
    m.netlist = "the response's";
    m.netlist_vhdl = resp.netlist_vhdl;
    // the routes together, where the netlist's answer holds for the VHDL: a disagreement is an
    // error; an open register takes the netlist's verdict
    for (auto& rr : rep.regs) {
        if (!rr.netlist_asked || rr.netlist_verdict == Verdict::open) continue;
        if (rr.netlist_vhdl.rfind("holds for the VHDL", 0) != 0 && rr.netlist_verdict == Verdict::proven) continue;
        if (rr.verdict != Verdict::open && rr.verdict != rr.netlist_verdict)
            throw std::logic_error(fmt::format("the routes disagree on {}: the model route says {}, the netlist route {} ({})",
                                               kRegNames[idx(rr.reg)], verdict_name(rr.verdict), verdict_name(rr.netlist_verdict),
                                               rr.netlist));
        if (rr.verdict == Verdict::open) {
            rr.verdict = rr.netlist_verdict;
            rr.decided_by = "netlist";
        }
    }
    if (m.verdict == Verdict::wraps) m.witness = resp.witness;
    rep.seconds_netlist = since(t0);
}

}  // namespace hc::sweep

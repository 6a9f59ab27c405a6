// stage_equivalence.cpp: the miter of each datapath entity's netlist against the model's
// stage function (see stage_equivalence.hpp).
#include "sweep/stage_equivalence.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "model/util/errors.hpp"
#include "model/util/util.hpp"
#include "model/fixed/word.hpp"
#include "model/harris/block_filter.hpp"
#include "model/harris/find_max.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"
#include "sweep/ranges.hpp"
#include "sweep/smt_word.hpp"
#include "sweep/stage_stimulus.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---- the stages ------------------------------------------------------------------------

/// One input of a stage: the name of its variable in the query, its term on the netlist
/// ("@<register>": the register's current value), its width (0: the register's width on the
/// netlist) and signedness, and the registers whose range is its domain (none: any value).
struct Input {
    std::string name, netlist;
    int w = 1;
    bool is_signed = true;
    std::vector<Reg> domain;
};
/// One next register of a stage: its name and the candidate names of its `.d` output on the
/// netlist; or, `combinational`, an output port of the wrapper (an entity without registers).
struct Output {
    std::string name;
    std::vector<std::string> netlist;
    bool combinational = false;
};
struct Spec {
    std::string entity, wrapper;
    std::vector<Input> in;
    std::vector<Output> out;
    /// harris_response: the block sums of the write before (free variables, not netlist terms)
    /// whose step 1 the current registers ac, bb, ktr2 hold (reachable_registers)
    std::vector<Input> prior;
};

std::string wire(const std::string& n) { return fmt::format("(|stage_n {}| s)", n); }

/// Element (i, j) (from 0) of a 3x3 matrix port of `w`-bit elements as GHDL packs it:
/// element (1, 1) in the top bits, row by row.
std::string element(const std::string& port, int i, int j, int w) {
    const int hi = 9 * w - 1 - w * (3 * i + j);
    return fmt::format("((_ extract {} {}) {})", hi, hi - w + 1, wire(port));
}

std::string tied(const std::string& entity, const std::string& ports) {
    return fmt::format("  {} u(.clk(clk), .rst(1'b1), .write(1'b1), {});\n", entity, ports);
}

/// The wrapper module `stage`, its inputs and its next registers.
Spec spec_of(EqStage s, const Formats& f) {
    const int sw = f.sobel_w, mw = f.m_w(), bw = f.bf_w(), rw = f.resp_w;
    Spec sp;
    sp.entity = kEqStageNames[static_cast<int>(s)];
    switch (s) {
        case EqStage::sobel_x: case EqStage::sobel_y: {
            const std::string o = s == EqStage::sobel_x ? "ix" : "iy";
            sp.wrapper = fmt::format("module stage(input clk, input [71:0] a, output signed [{}:0] {});\n", sw - 1, o) +
                         tied(sp.entity, fmt::format(".en(1'b1), .a(a), .{0}({0})", o)) + "endmodule\n";
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) sp.in.push_back({pixel_input(i, j), element("a", i, j, 8), 8, false, {}});
            sp.out = {{o, {o, "u." + o}}};
            break;
        }
        case EqStage::m_products:
            sp.wrapper = fmt::format("module stage(input clk, input signed [{0}:0] ix, iy, output signed [{1}:0] a, b, c);\n", sw - 1, mw - 1) +
                         tied(sp.entity, ".en(1'b1), .ix(ix), .iy(iy), .a(a), .b(b), .c(c)") + "endmodule\n";
            sp.in = {{"ix", wire("ix"), sw, true, {Reg::sobel_x}}, {"iy", wire("iy"), sw, true, {Reg::sobel_y}}};
            sp.out = {{"a", {"a", "u.a"}}, {"b", {"b", "u.b"}}, {"c", {"c", "u.c"}}};
            break;
        case EqStage::block_filter:
            sp.wrapper = fmt::format("module stage(input clk, input [{}:0] a, output signed [{}:0] sum);\n", 9 * mw - 1, bw - 1) +
                         tied(sp.entity, ".en(1'b1), .a(a), .sum(sum)") + "endmodule\n";
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    sp.in.push_back({fmt::format("m_{}_{}", i, j), element("a", i, j, mw), mw, true, {Reg::m_a, Reg::m_b, Reg::m_c}});
            sp.out = {{"sum", {"sum", "u.sum"}}};
            break;
        case EqStage::harris_response:
            sp.wrapper = fmt::format("module stage(input clk, input signed [{}:0] a, b, c, output signed [{}:0] r);\n", bw - 1, rw - 1) +
                         "  harris_response u(.clk(clk), .rst(1'b1), .en0(1'b1), .en1(1'b1), .write(1'b1), .a(a), .b(b), .c(c), .r(r));\n"
                         "endmodule\n";
            sp.in = {{"a", wire("a"), bw, true, {Reg::block_a}},        {"b", wire("b"), bw, true, {Reg::block_b}},
                     {"c", wire("c"), bw, true, {Reg::block_c}},        {"ac", "@u.ac", 2 * bw, true, {}},
                     {"bb", "@u.bb", 2 * bw, true, {}},          {"ktr2", "@u.ktr2", f.ktr_w, true, {}}};
            sp.out = {{"ac", {"u.ac"}}, {"bb", {"u.bb"}}, {"ktr2", {"u.ktr2"}}, {"r", {"r", "u.r"}}};
            sp.prior = {{"a_prev", "", bw, true, {Reg::block_a}}, {"b_prev", "", bw, true, {Reg::block_b}},
                        {"c_prev", "", bw, true, {Reg::block_c}}};
            break;
        case EqStage::threshold:
            sp.wrapper = fmt::format("module stage(input clk, input signed [{0}:0] r0, thr, output signed [{0}:0] r1);\n", rw - 1) +
                         tied(sp.entity, ".en(1'b1), .r0(r0), .thr(thr), .r1(r1)") + "endmodule\n";
            sp.in = {{"r0", wire("r0"), rw, true, {}}, {"thr", wire("thr"), rw, true, {}}, {"r0_delay", "@u.r0_delay", rw, true, {}}};
            sp.out = {{"r0_delay", {"u.r0_delay"}}, {"r1", {"r1", "u.r1"}}};
            break;
        case EqStage::find_max:
            sp.wrapper = fmt::format("module stage(input clk, input signed [{0}:0] response, output signed [{0}:0] max);\n", rw - 1) +
                         tied(sp.entity, ".en(1'b1), .response(response), .max(max)") + "endmodule\n";
            sp.in = {{"response", wire("response"), rw, true, {}}, {"count", "@u.count", 0, false, {}},
                     {"running", "@u.running", rw, true, {}},     {"max", "@u.max", rw, true, {}}};
            sp.out = {{"count", {"u.count"}}, {"running", {"u.running"}}, {"max", {"max", "u.max"}}};
            break;
        case EqStage::local_maximum:
            sp.wrapper = fmt::format("module stage(input [{}:0] r, output corner);\n  local_maximum u(.r(r), .corner(corner));\nendmodule\n",
                                     9 * rw - 1);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) sp.in.push_back({fmt::format("r_{}_{}", i, j), element("r", i, j, rw), rw, true, {}});
            sp.out = {{"corner", {"corner"}, true}};
            break;
        case EqStage::count: break;
    }
    return sp;
}

/// The model's next registers of stage `s` from its inputs (Spec order), on Word or SmtWord;
/// `g`: the image size of find_max's period.
template <class T>
std::vector<T> model_outputs(EqStage s, const std::vector<T>& in, const Formats& f, const Geometry& g) {
    const auto m3 = [&](size_t at) {
        std::array<std::array<T, 3>, 3> m;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = in[at + 3 * i + j];
        return m;
    };
    switch (s) {
        case EqStage::sobel_x: case EqStage::sobel_y: {
            if constexpr (std::is_same_v<T, Word>) {
                Pixels3 p{};
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) p[i][j] = static_cast<Pixel>(in[3 * i + j].value());
                return {s == EqStage::sobel_x ? sobel_x<Word>(p, f) : sobel_y<Word>(p, f)};
            } else {
                const auto p = m3(0);
                return {s == EqStage::sobel_x ? sobel_x<T>(p, f) : sobel_y<T>(p, f)};
            }
        }
        case EqStage::m_products: {
            const MProductsT<T> m = m_products(in[0], in[1], f);
            return {m.a, m.b, m.c};
        }
        case EqStage::block_filter: return {block_filter(m3(0), f)};
        case EqStage::harris_response: {
            const ResponseTermsT<T> t = harris_response_terms(in[0], in[1], in[2], f);
            return {t.ac, t.bb, t.ktr2, harris_response(ResponseTermsT<T>{in[3], in[4], in[5]}, f)};
        }
        case EqStage::threshold: return {in[0], threshold(in[2], in[1])};   // enable high: r0_delay <= r0
        case EqStage::find_max: {
            if constexpr (std::is_same_v<T, Word>) {   // the cycle model's register step
                FindMax fm(f);
                fm.count = in[1].value();
                fm.running = in[2];
                fm.max = in[3];
                const FindMax n = fm.next(in[0], g);
                return {Word::uns(n.count, in[1].width()), n.running, n.max};
            } else {
                const FindMaxStep<T, T> n = find_max_step(in[1], in[2], in[3], in[0], g.find_max_period());
                return {n.count, n.running, n.max};
            }
        }
        case EqStage::local_maximum: {
            if constexpr (std::is_same_v<T, Word>) return {Word::uns(local_maximum(m3(0)) ? 1 : 0, 1)};
            else return {as_bit(local_maximum(m3(0)))};
        }
        case EqStage::count: break;
    }
    throw std::logic_error("model_outputs: no such stage");
}

// ---- the netlist -----------------------------------------------------------------------

/// The yosys script: the wrapper over GHDL's module, registers everted into inputs (.q) and outputs (.d).
std::string eq_script(const std::string& entity) {
    return "read_verilog " + entity + ".v stage.v\nhierarchy -top stage\nproc\nflatten\nopt -nosdff -nodffe\n"
           // every register must have folded to a plain flop (enables and resets tied)
           "select -assert-none t:$*latch* t:$sr t:$mem* t:$*dff* t:$dff %d\n"
           "opt_clean -purge\nexpose -evert-dff\nopt_clean\nselect -assert-none t:$dff\n"
           "write_smt2 -wires stage.smt2\n";
}

/// Synthesises the stage in `dir`: its SMT-LIB text (module `stage`).
std::string synthesise(const Spec& sp, const Formats& f, const Geometry& geo, const fs::path& dir, const fs::path& rtl_dir) {
    fs::create_directories(dir / "work");
    const std::vector<std::string> g = entity_generics(sp.entity, f, geo);
    std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + (dir / "work").string()};
    argv.insert(argv.end(), g.begin(), g.end());
    argv.push_back("--out=verilog");
    std::string sources, gens;
    for (const auto& s : cosim::rtl_sources(rtl_dir)) {
        argv.push_back(s.string());
        sources += " " + s.string();
    }
    argv.insert(argv.end(), {"-e", sp.entity});
    for (const auto& x : g) gens += " " + x;
    const fs::path log = dir / "synth.log";
    if (cosim::synth_verilog(argv, dir / (sp.entity + ".v"), {.log = log}) != 0)
        throw SimulatorError("ghdl --synth of " + sp.entity + " failed: " + util::log_tail(log, 1500));
    util::write_file_atomic(dir / "stage.v", sp.wrapper);
    util::write_file_atomic(dir / "stage.ys", eq_script(sp.entity));
    const fs::path ylog = dir / "yosys.log";
    fs::remove(ylog);
    if (util::run_process({"yosys", "-q", "-s", "stage.ys"}, {.cwd = dir, .log = ylog}) != 0)
        throw SimulatorError("yosys could not write " + sp.entity + "'s transition as SMT-LIB: " + util::log_tail(ylog, 1500));
    util::write_file_atomic(dir / "commands.txt",
                            fmt::format("ghdl --synth --std=08 --workdir=work{0} --out=verilog{1} -e {2} | {3} > {2}.v\n"
                                        "yosys -q -s stage.ys    # writes stage.smt2\n",
                                        gens, sources, sp.entity, cosim::kSizedBitLiteralsFilter));
    return util::read_file(dir / "stage.smt2");
}

/// GHDL's register nets by the signal they drive: "assign ac = n32_q; // (signal)" gives ac -> n32_q,
/// as does a signal with an initial value, "always @*\n    count = n37_q; // (isignal)".
std::map<std::string, std::string> register_aliases(const std::string& verilog) {
    std::map<std::string, std::string> a;
    std::istringstream in(verilog);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream l(line);
        std::string name, eq, net;
        if (!(l >> name)) continue;
        if (name == "assign" && !(l >> name)) continue;
        if (!(l >> eq >> net) || eq != "=") continue;
        if (net.size() > 3 && net.compare(net.size() - 3, 3, "_q;") == 0) a[name] = net.substr(0, net.size() - 1);
    }
    return a;
}

/// The name under which yosys everted register `base` ("r", "u.ac"): itself, or the GHDL net
/// it aliases (opt_clean -purge keeps one of the two); "" when the netlist has neither.
std::string flop(const std::string& base, const std::map<std::string, int>& ports, const std::map<std::string, std::string>& aliases) {
    if (ports.count(base + ".d")) return base;
    const size_t dot = base.rfind('.');
    const std::string prefix = dot == std::string::npos ? "" : base.substr(0, dot + 1);
    if (const auto a = aliases.find(base.substr(prefix.size())); a != aliases.end() && ports.count(prefix + a->second + ".d"))
        return prefix + a->second;
    return "";
}

/// The stage with its register names resolved on the netlist: every register input's term
/// (<flop>.q) and width, and every next register's `.d` output or combinational output port (in `next`).
Spec resolve(Spec sp, const std::string& netlist, const std::string& verilog, std::vector<std::string>& next) {
    const std::map<std::string, int> ports = yosys_smt2_ports(netlist);
    const auto aliases = register_aliases(verilog);
    for (auto& x : sp.in) {
        if (x.netlist.rfind("@", 0) != 0) continue;
        std::string f = flop(x.netlist.substr(1), ports, aliases);
        // or under one of the names of the next register of the same name ("max": the wrapper's port it drives)
        for (const auto& o : sp.out)
            if (o.name == x.name && !o.combinational)
                for (const auto& c : o.netlist)
                    if (f.empty()) f = flop(c, ports, aliases);
        if (f.empty())
            throw std::logic_error(fmt::format("stage equivalence: {}'s netlist has no register {}", sp.entity, x.netlist.substr(1)));
        x.netlist = wire(f + ".q");
        if (x.w == 0) x.w = ports.at(f + ".q");
    }
    next.clear();
    for (const auto& o : sp.out) {
        std::string found;
        for (const auto& c : o.netlist)
            if (found.empty()) found = o.combinational ? (ports.count(c) ? c : "") : flop(c, ports, aliases);
        if (found.empty())
            throw std::logic_error(fmt::format("stage equivalence: {}'s netlist has no {} of {} (looked for {}{})", sp.entity,
                                               o.combinational ? "output" : "next value", o.name, o.netlist.front(),
                                               o.combinational ? "" : ".d"));
        next.push_back(o.combinational ? found : found + ".d");
    }
    return sp;
}

// ---- the queries -----------------------------------------------------------------------

/// `v` as a `w`-bit literal (two's complement).
std::string literal(std::int64_t v, int w) {
    const std::uint64_t bits = w >= 64 ? static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v) & ((std::uint64_t{1} << w) - 1);
    return fmt::format("(_ bv{} {})", bits, w);
}

struct Miter {
    std::string text;                  ///< without check-sat
    std::vector<std::string> get;      ///< inputs, model outputs m_<k>, netlist outputs n_<k>, shrinks ovf_<k>
    std::vector<SmtShrink> shrinks;
};

/// harris_response: the current step-1 registers (in[3..5]) are what step 1 makes of the block
/// sums of the write before (sp.prior), the model's step 1 on the same shrinks as the query's
/// (the netlist's step 1 is proven equal to it in the same query): the two steps together.
void reachable_registers(EqStage s, const Spec& sp, const std::vector<SmtWord>& in, const Formats& f) {
    if (s != EqStage::harris_response) return;
    std::vector<SmtWord> prev;
    for (const auto& x : sp.prior) prev.push_back({x.name, x.w, x.is_signed});
    const ResponseTermsT<SmtWord> t = harris_response_terms(prev[0], prev[1], prev[2], f);
    smt_query->text += fmt::format("(assert (and (= {} {}) (= {} {}) (= {} {})))\n", in[3].e, t.ac.e, in[4].e, t.bb.e, in[5].e, t.ktr2.e);
}

/// numeric_std (truncate false) or GHDL's truncation of signed shrinks; `domain`: the inputs' assumed ranges.
Miter miter(EqStage s, const Formats& f, const Geometry& g, const Spec& sp, const std::string& netlist,
            const std::vector<std::string>& next, bool truncate, const std::map<std::string, Interval>& domain,
            const std::string& assume = {}) {
    Miter m;
    m.text = "(set-logic ALL)\n" + netlist + "(declare-fun s () |stage_s|)\n(assert (|stage_h| s))\n";
    std::vector<SmtWord> in;
    for (const auto& x : sp.in) {
        m.text += fmt::format("(define-fun {} () (_ BitVec {}) {})\n", x.name, x.w, x.netlist);
        in.push_back({x.name, x.w, x.is_signed});
        m.get.push_back(x.name);
        if (const auto d = domain.find(x.name); d != domain.end())
            m.text += fmt::format("(assert (and (bvsge {0} {1}) (bvsle {0} {2})))\n", x.name, literal(d->second.lo, x.w),
                                  literal(d->second.hi, x.w));
    }
    for (const auto& x : sp.prior) {
        m.text += fmt::format("(declare-fun {} () (_ BitVec {}))\n", x.name, x.w);
        m.get.push_back(x.name);
        if (const auto d = domain.find(x.name); d != domain.end())
            m.text += fmt::format("(assert (and (bvsge {0} {1}) (bvsle {0} {2})))\n", x.name, literal(d->second.lo, x.w),
                                  literal(d->second.hi, x.w));
    }
    m.text += assume;
    SmtQuery q;
    q.text = m.text;
    q.truncate_signed_shrink = truncate;
    q.yosys_sign_extend = true;
    smt_query = &q;
    std::vector<SmtWord> out;
    try {
        reachable_registers(s, sp, in, f);
        out = model_outputs<SmtWord>(s, in, f, g);
    } catch (...) {
        smt_query = nullptr;
        throw;
    }
    smt_query = nullptr;
    m.text = q.text;
    m.shrinks = q.shrinks;
    std::string any;
    for (size_t k = 0; k < out.size(); ++k) {
        // yosys writes a one-bit net as a Bool
        const std::string net = out[k].w == 1 ? fmt::format("(ite {} #b1 #b0)", wire(next[k])) : wire(next[k]);
        m.text += fmt::format("(define-fun m_{0} () (_ BitVec {1}) {2})\n(define-fun n_{0} () (_ BitVec {1}) {3})\n", k, out[k].w,
                              out[k].e, net);
        any += fmt::format(" (distinct m_{0} n_{0})", k);
        m.get.push_back(fmt::format("m_{}", k));
        m.get.push_back(fmt::format("n_{}", k));
    }
    for (size_t k = 0; k < m.shrinks.size(); ++k) {
        m.text += fmt::format("(define-fun ovf_{} () (_ BitVec 1) (ite {} #b1 #b0))\n", k, m.shrinks[k].overflow);
        m.get.push_back(fmt::format("ovf_{}", k));
    }
    m.text += fmt::format("(assert (or{}))\n", any);
    return m;
}

std::int64_t as_signed_bits(std::int64_t bits, int w) {
    const std::uint64_t u = static_cast<std::uint64_t>(bits) & (w >= 64 ? ~0ULL : ((1ULL << w) - 1));
    return w < 64 && (u >> (w - 1)) ? static_cast<std::int64_t>(u) - (std::int64_t{1} << w) : static_cast<std::int64_t>(u);
}

/// The counterexample's inputs as numbers (signed inputs read as signed).
std::map<std::string, std::int64_t> inputs_at(const Spec& sp, const Z3Answer& z) {
    std::map<std::string, std::int64_t> v;
    for (const auto* list : {&sp.in, &sp.prior})
        for (const auto& x : *list) v[x.name] = x.is_signed ? as_signed_bits(z.values.at(x.name), x.w) : z.values.at(x.name);
    return v;
}

/// The model's next registers at the counterexample on Word must be what the query's model side says; returns
/// "r: model -123, netlist 456" for the first output that differs.
std::string check_in_model(EqStage s, const Formats& f, const Geometry& g, const Spec& sp, const Z3Answer& z) {
    std::vector<Word> in;
    const auto vals = inputs_at(sp, z);
    for (const auto& x : sp.in) in.push_back(x.is_signed ? Word::sgn(vals.at(x.name), x.w) : Word::uns(vals.at(x.name), x.w));
    const std::vector<Word> out = model_outputs<Word>(s, in, f, g);
    std::string first;
    for (size_t k = 0; k < out.size(); ++k) {
        const int w = out[k].width();
        const auto read = [&](std::int64_t bits) {   // as the output's type reads them
            return out[k].is_signed() ? as_signed_bits(bits, w) : static_cast<std::int64_t>(Word::from_bits(bits, w, false).value());
        };
        const std::int64_t smt = read(z.values.at(fmt::format("m_{}", k)));
        const std::int64_t net = read(z.values.at(fmt::format("n_{}", k)));
        const std::int64_t word = read(out[k].value());
        if (smt != word)
            throw std::logic_error(fmt::format("stage equivalence: {}'s {} at the counterexample is {} in the query, {} in the model",
                                               sp.entity, sp.out[k].name, smt, word));
        if (first.empty() && word != net) first = fmt::format("{}: model {}, netlist {}", sp.out[k].name, word, net);
    }
    if (first.empty())
        throw std::logic_error(fmt::format("stage equivalence: {}'s counterexample does not differ in the model", sp.entity));
    return first;
}

/// The signed shrinks that overflow at the counterexample: "resize of ac (32 -> 27 bits)".
std::string overflowing(const Miter& m, const Spec& sp, const Z3Answer& z) {
    std::string s;
    for (size_t k = 0; k < m.shrinks.size(); ++k) {
        if (z.values.at(fmt::format("ovf_{}", k)) == 0) continue;
        const SmtShrink& x = m.shrinks[k];
        std::string what = fmt::format("a {}-bit term", x.from);
        for (const auto& in : sp.in)
            if (in.name == x.source) what = in.name;
        const std::string one = fmt::format("resize of {} ({} -> {} bits)", what, x.from, x.to);
        if (s.find(one) == std::string::npos) s += (s.empty() ? "" : ", ") + one;
    }
    return s;
}

std::string values_text(const std::map<std::string, std::int64_t>& v) {
    std::string s;
    for (const auto& [k, x] : v) s += fmt::format("{}{}={}", s.empty() ? "" : " ", k, x);
    return s;
}

/// cvc5 on the same query (check-sat only), within its resource limit.
void recheck(StageProof& p, const std::string& text, const fs::path& dir, int seconds) {
    const fs::path file = dir / "query-cvc5.smt2", out = dir / "cvc5-answer.txt";
    util::write_file_atomic(file, text + "(check-sat)\n");
    try {
        util::run_process({"cvc5", "--lang=smt2", fmt::format("--tlimit={}", seconds * 1000), file.string()},
                          {.log = dir / "cvc5.log", .stdout_file = out});
    } catch (const SimulatorError& e) {
        p.recheck = std::string("cvc5: not run: ") + e.what();
        return;
    }
    std::string ans = fs::exists(out) ? util::read_file(out) : "";
    ans = ans.substr(0, ans.find('\n'));
    p.rechecked = ans == "unsat";
    p.recheck = fmt::format("cvc5 --tlimit={}: {}", seconds * 1000, ans.empty() ? "no answer within its time limit" : ans);
    if (ans.rfind("(error", 0) == 0) p.recheck += " (" + util::log_tail(dir / "cvc5.log", 300) + ")";
    if (ans == "sat") throw std::logic_error(fmt::format("stage equivalence: z3 proves {} equal, cvc5 finds a difference", p.command));
}

/// The inputs' domain: the interval bound of the registers that feed them, where it fits (the register cannot wrap).
std::map<std::string, Interval> domain_of(const Spec& sp, const Formats& f) {
    const RangeReport r = interval_ranges(f);
    std::map<std::string, Interval> d;
    std::vector<Input> all = sp.in;
    all.insert(all.end(), sp.prior.begin(), sp.prior.end());
    for (const auto& x : all) {
        if (x.domain.empty()) continue;
        Interval hull{std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min()};
        bool fits = true;
        for (Reg reg : x.domain) {
            const RegisterRange& rr = r.at(reg);
            fits = fits && rr.bound_fits;
            hull = {std::min(hull.lo, rr.bound.lo), std::max(hull.hi, rr.bound.hi)};
        }
        if (fits) d[x.name] = hull;
    }
    return d;
}

/// harris_response's inputs within the block sums' relations (response_relation, where it
/// applies at `f`): a, c >= 0 with a + c <= T and |b| <= the relation's bound, for the block sums
/// of this write and of the write before. The domain `d` is narrowed to them (b, b_prev) and the
/// sums' bound returned as assertions, with what is assumed in `text`; "" when the relation does
/// not apply or the stage is another.
std::string relation_assumption(const Spec& sp, const Formats& f, std::map<std::string, Interval>& d, std::string& text) {
    if (sp.entity != "harris_response") return {};
    const ResponseRelation rel = response_relation(interval_ranges(f));
    if (!rel.applies) return {};
    std::int64_t bmax = static_cast<std::int64_t>(std::sqrt(static_cast<double>(rel.bb.hi)));
    while (bmax * bmax > rel.bb.hi) --bmax;
    while ((bmax + 1) * (bmax + 1) <= rel.bb.hi) ++bmax;
    std::string smt;
    const std::int64_t w = sp.in[0].w + 1;   // a + c without overflow
    for (const auto& [a, b, c] : {std::array<const char*, 3>{"a", "b", "c"}, std::array<const char*, 3>{"a_prev", "b_prev", "c_prev"}}) {
        for (const char* x : {a, c}) d[x] = {0, std::min(d.count(x) ? d[x].hi : rel.trace, rel.trace)};
        d[b] = {std::max(d.count(b) ? d[b].lo : -bmax, -bmax), std::min(d.count(b) ? d[b].hi : bmax, bmax)};
        smt += fmt::format("(assert (bvsle (bvadd ((_ sign_extend 1) {0}) ((_ sign_extend 1) {1})) {2}))\n", a, c,
                           literal(rel.trace, static_cast<int>(w)));
    }
    text = fmt::format("the block sums' relations: a + c <= {0}, |b| <= {1} (and of a_prev, b_prev, c_prev)", rel.trace, bmax);
    return smt;
}

/// What the stage assumes beside its inputs' domain `d`: the current registers step 1 can hold (sp.prior).
std::string domain_text(const Spec& sp, const std::map<std::string, Interval>& d) {
    std::string s;
    if (!sp.prior.empty()) {
        s = "ac, bb, ktr2 are step 1's of";
        for (size_t k = 0; k < sp.prior.size(); ++k) s += (k ? ", " : " ") + sp.prior[k].name;
    }
    std::string dom;
    for (const auto& [k, v] : d) dom += fmt::format("{}{} in [{}, {}]", dom.empty() ? "" : ", ", k, v.lo, v.hi);
    return s.empty() || dom.empty() ? s + dom : s + "; " + dom;
}

}  // namespace

std::map<std::string, int> yosys_smt2_ports(const std::string& smt) {
    std::map<std::string, int> names;
    std::istringstream in(smt);
    std::string line;
    for (std::string kind, name; std::getline(in, line);)
        if (line.rfind("; yosys-smt2-input ", 0) == 0 || line.rfind("; yosys-smt2-output ", 0) == 0) {
            std::istringstream l(line.substr(2));
            int w = 0;
            l >> kind >> name >> w;
            names[name] = w;
        }
    return names;
}


std::string pixel_input(int i, int j) { return fmt::format("p_{}_{}", i, j); }

EqStage eq_stage(const std::string& name) {
    for (int k = 0; k < kEqStageCount; ++k)
        if (name == kEqStageNames[k]) return static_cast<EqStage>(k);
    std::string names;
    for (const char* n : kEqStageNames) names += (names.empty() ? "" : ", ") + std::string(n);
    throw InputError("no stage named '" + name + "' (" + names + ")");
}

const char* eq_verdict_name(EqVerdict v) {
    switch (v) {
        case EqVerdict::equal: return "proven equal";
        case EqVerdict::counterexample: return "counterexample";
        case EqVerdict::netlist_differs: return "netlist differs from the VHDL";
        case EqVerdict::open: return "open";
    }
    return "?";
}

namespace {

/// One z3 query of the stage, kept as <dir>/query-<k>.smt2; the command that reruns it.
struct Asked {
    Z3Answer z;
    std::string command, text;
};
Asked ask(StageProof& p, const Miter& m, const fs::path& dir, int k, std::int64_t rlimit) {
    const fs::path file = dir / fmt::format("query-{}.smt2", k);
    Asked a{run_z3(m.text, rlimit, m.get, file), fmt::format("z3 -smt2 rlimit={} {}", rlimit, file.string()), m.text};
    p.rlimit += a.z.rlimit;
    return a;
}

void proven(StageProof& p, const Asked& a, const fs::path& dir, const StageOptions& o) {
    p.verdict = EqVerdict::equal;
    p.command = a.command;
    if (o.recheck) recheck(p, a.text, dir, o.recheck_seconds);
}

/// The stage under proof: what miter() needs besides the question.
struct StageCase {
    EqStage s;
    const Formats& f;
    const Geometry& g;
    const Spec& sp;
    const std::string& netlist;
    const std::vector<std::string>& next;
};

/// The proof asked again on the inputs' domain `d` (query 3), after the signed `shrink`
/// overflowed on the free inputs (`differ`: the values there); where it overflows on `d` too,
/// for harris_response once more within the block sums' relations (query 4,
/// relation_assumption). Sets p's verdict.
void prove_on_domain(StageProof& p, const StageCase& c, std::map<std::string, Interval> d, const std::string& shrink,
                     const std::string& differ, const fs::path& dir, const StageOptions& o) {
    const Miter m2 = miter(c.s, c.f, c.g, c.sp, c.netlist, c.next, false, d);
    Asked a = ask(p, m2, dir, 3, o.rlimit);
    p.assumed = domain_text(c.sp, d);
    std::string where = "the inputs' domain";
    if (a.z.sat == Sat::sat) {
        std::string text;
        if (const std::string rel = relation_assumption(c.sp, c.f, d, text); !rel.empty()) {
            const Miter m3 = miter(c.s, c.f, c.g, c.sp, c.netlist, c.next, false, d, rel);
            if (Asked a3 = ask(p, m3, dir, 4, o.rlimit); a3.z.sat == Sat::unsat) {
                a = std::move(a3);
                p.assumed = domain_text(c.sp, d) + "; " + text;
                where = "the block sums' relations";
            }
        }
    }
    if (a.z.sat == Sat::unsat) {
        proven(p, a, dir, o);
        p.detail = fmt::format("signed {} overflows only outside {} ({}): the proof holds for the VHDL because the shrink "
                               "cannot overflow on {}", shrink, where, differ, where == "the inputs' domain" ? "the domain" : "them");
        return;
    }
    p.verdict = a.z.sat == Sat::sat ? EqVerdict::netlist_differs : EqVerdict::open;
    if (a.z.sat != Sat::sat) {
        p.detail = "on the domain: " + a.z.why;
        return;
    }
    p.counterexample = inputs_at(c.sp, a.z);
    p.detail = fmt::format("signed {} overflows on the domain: {} at {}", overflowing(m2, c.sp, a.z),
                           check_in_model(c.s, c.f, c.g, c.sp, a.z), values_text(p.counterexample));
    p.command = a.command;
}

}  // namespace

StageProof prove_stage(EqStage s, const Formats& f, const StageOptions& o) {
    f.validate();
    const auto t0 = Clock::now();
    const util::ScratchDir scratch;
    const fs::path dir = fs::absolute(o.dir.empty() ? scratch.path() : o.dir);
    StageProof p;
    p.stage = s;
    const Geometry& g = o.geometry;
    const std::string netlist = synthesise(spec_of(s, f), f, g, dir, o.rtl_dir);
    std::vector<std::string> next;
    const Spec sp = resolve(spec_of(s, f), netlist, util::read_file(dir / (std::string(kEqStageNames[static_cast<int>(s)]) + ".v")), next);
    const Miter m0 = miter(s, f, g, sp, netlist, next, false, {});
    const Asked a0 = ask(p, m0, dir, 1, o.rlimit);
    p.command = a0.command;
    p.assumed = domain_text(sp, {});
    if (a0.z.sat == Sat::unsat) {
        proven(p, a0, dir, o);
        if (!m0.shrinks.empty()) p.detail = "no signed shrink overflows on any input: the proof holds for the VHDL";
    } else if (a0.z.sat == Sat::unknown) {
        p.detail = a0.z.why;
    } else {
        p.counterexample = inputs_at(sp, a0.z);
        const std::string differ = check_in_model(s, f, g, sp, a0.z);
        const std::string shrink = overflowing(m0, sp, a0.z);
        // GHDL's synthesis of a signed shrink: the same question with truncations
        const Asked a1 = ask(p, miter(s, f, g, sp, netlist, next, true, {}), dir, 2, o.rlimit);
        if (a1.z.sat != Sat::unsat || shrink.empty()) {
            p.verdict = a1.z.sat == Sat::unknown ? EqVerdict::open : EqVerdict::counterexample;
            p.detail = fmt::format("{} at {}{}", differ, values_text(p.counterexample),
                                   a1.z.sat == Sat::unknown ? "; with truncating shrinks: " + a1.z.why : "");
            if (p.verdict == EqVerdict::counterexample && !o.dir.empty())
                if (const auto st = write_stage_stimulus(p, f, dir / "stimulus", o.config + "_" + kEqStageNames[static_cast<int>(s)],
                                                         o.rlimit))
                    p.stimulus = st->set.string();
        } else if (const auto d = domain_of(sp, f); !d.empty()) {
            prove_on_domain(p, {s, f, g, sp, netlist, next}, d, shrink, differ + " at " + values_text(p.counterexample), dir, o);
        } else {
            p.verdict = EqVerdict::netlist_differs;
            p.detail = fmt::format("signed {} overflows: {} at {}", shrink, differ, values_text(p.counterexample));
        }
    }
    p.seconds = since(t0);
    return p;
}

StageEquivalence stage_equivalence(const Formats& f, const StageOptions& o) {
    const auto t0 = Clock::now();
    StageEquivalence r;
    r.formats = f;
    for (int k = 0; k < kEqStageCount; ++k) {
        StageOptions one = o;
        if (!o.dir.empty()) one.dir = o.dir / kEqStageNames[k];
        r.stages.push_back(prove_stage(static_cast<EqStage>(k), f, one));
    }
    r.seconds = since(t0);
    return r;
}

std::string StageEquivalence::summary() const {
    int equal = 0;
    std::string rest;
    for (const auto& p : stages) {
        if (p.verdict == EqVerdict::equal) ++equal;
        else rest += fmt::format(", {}: {}", kEqStageNames[static_cast<int>(p.stage)], eq_verdict_name(p.verdict));
    }
    return fmt::format("{} proven equal{}", equal, rest);
}

std::string StageEquivalence::column() const {
    int equal = 0;
    std::map<std::string, std::vector<std::string>> others;   // short verdict -> stages
    for (const auto& p : stages) {
        if (p.verdict == EqVerdict::equal) ++equal;
        else others[p.verdict == EqVerdict::netlist_differs ? "netlist differs" : eq_verdict_name(p.verdict)].push_back(
            kEqStageNames[static_cast<int>(p.stage)]);
    }
    if (others.empty()) return fmt::format("{}/{} proven", equal, stages.size());
    std::string s = fmt::format("{} proven", equal);
    for (const auto& [verdict, names] : others) s += fmt::format(", {} {} ({})", names.size(), verdict, fmt::join(names, ", "));
    return s;
}

bool StageEquivalence::all_proven() const {
    return stages.size() == static_cast<size_t>(kEqStageCount) &&
           std::all_of(stages.begin(), stages.end(), [](const StageProof& p) { return p.verdict == EqVerdict::equal; });
}

StageEquivalence cached_stage_equivalence(const Formats& f, const std::string& key, const fs::path& cache_dir,
                                          const StageOptions& o) {
    const fs::path p = cache_dir / (key + ".json");
    const std::string options = fmt::format("rlimit={} recheck={} recheck_seconds={} geometry={}x{} rtl={}", o.rlimit, o.recheck,
                                            o.recheck_seconds, o.geometry.width, o.geometry.height, o.rtl_dir.string());
    // an entry under other options, or one that does not read, is no verdict: prove again, overwrite it
    std::optional<StageEquivalence> recorded;
    try {
        if (fs::exists(p))
            if (const auto j = nlohmann::json::parse(util::read_file(p)); j.value("options", std::string()) == options)
                recorded = stage_equivalence_from_json(j);
    } catch (const std::exception&) {
        recorded.reset();
    }
    if (recorded) {
        recorded->formats = f;
        recorded->cached = true;
        return *recorded;
    }
    StageEquivalence r = stage_equivalence(f, o);
    fs::create_directories(cache_dir);
    nlohmann::json j = stage_equivalence_to_json(r);
    j["options"] = options;
    j["key"] = key;
    util::write_file_atomic(p, j.dump(1) + "\n");
    return r;
}

std::string stage_equivalence_markdown(const std::string& config, const StageEquivalence& r) {
    std::string s = fmt::format("### Stage equivalence: {}\n\n{} ({:.1f} s)\n\n", config, r.summary(), r.seconds);
    s += "| stage | verdict | solver | second solver | z3 rlimit | seconds | assumed | detail | rerun | stimulus |\n"
         "|---|---|---|---|---:|---:|---|---|---|---|\n";
    for (const auto& p : r.stages)
        s += fmt::format("| {} | {} | {} | {} | {} | {:.1f} | {} | {} | `{}` | {} |\n", kEqStageNames[static_cast<int>(p.stage)],
                         eq_verdict_name(p.verdict), p.solver, p.recheck.empty() ? "-" : p.recheck, p.rlimit, p.seconds,
                         p.assumed.empty() ? "every input" : p.assumed, p.detail.empty() ? "-" : p.detail, p.command,
                         p.stimulus.empty() ? "-" : "`" + p.stimulus + "`");
    return s;
}

nlohmann::json stage_equivalence_to_json(const StageEquivalence& r) {
    nlohmann::json j;
    j["formats"] = nlohmann::json::parse(formats_to_json(r.formats));
    j["seconds"] = r.seconds;
    j["stages"] = nlohmann::json::array();
    for (const auto& p : r.stages)
        j["stages"].push_back({{"stage", kEqStageNames[static_cast<int>(p.stage)]},
                               {"verdict", eq_verdict_name(p.verdict)},
                               {"solver", p.solver},
                               {"rlimit", p.rlimit},
                               {"seconds", p.seconds},
                               {"assumed", p.assumed},
                               {"recheck", p.recheck},
                               {"rechecked", p.rechecked},
                               {"counterexample", p.counterexample},
                               {"detail", p.detail},
                               {"command", p.command},
                               {"stimulus", p.stimulus}});
    return j;
}

StageEquivalence stage_equivalence_from_json(const nlohmann::json& j) {
    StageEquivalence r;
    r.formats = formats_from_json(j.at("formats"), "stage-equivalence report");
    r.seconds = j.at("seconds").get<double>();
    for (const auto& x : j.at("stages")) {
        StageProof p;
        p.stage = eq_stage(x.at("stage").get<std::string>());
        const std::string v = x.at("verdict").get<std::string>();
        bool known = false;
        for (EqVerdict e : {EqVerdict::equal, EqVerdict::counterexample, EqVerdict::netlist_differs, EqVerdict::open})
            if (v == eq_verdict_name(e)) p.verdict = e, known = true;
        if (!known) throw std::runtime_error("stage equivalence: unknown verdict '" + v + "'");
        p.solver = x.at("solver").get<std::string>();
        p.rlimit = x.at("rlimit").get<std::int64_t>();
        p.seconds = x.at("seconds").get<double>();
        p.assumed = x.at("assumed").get<std::string>();
        p.recheck = x.at("recheck").get<std::string>();
        p.rechecked = x.at("rechecked").get<bool>();
        p.counterexample = x.at("counterexample").get<std::map<std::string, std::int64_t>>();
        p.detail = x.at("detail").get<std::string>();
        p.command = x.at("command").get<std::string>();
        p.stimulus = x.at("stimulus").get<std::string>();
        r.stages.push_back(p);
    }
    return r;
}

}  // namespace hc::sweep

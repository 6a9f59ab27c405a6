// datapath_induction.cpp: every register of GHDL's netlist of harris_top against the cycle
// model's, one clock edge per control class, from reset (see datapath_induction.hpp).
#include "sweep/datapath_induction.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <regex>
#include <set>
#include <string_view>
#include <tuple>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/harris/harris_top_t.hpp"
#include "model/util/errors.hpp"
#include "model/util/util.hpp"
#include "sweep/ranges.hpp"
#include "sweep/smt_word.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

using Clock = std::chrono::steady_clock;
using Concrete = HarrisCycle<DynamicFormats, CycleNumbers<DynamicFormats>>;
using Symbolic = HarrisCycle<DynamicFormats, SmtNumbers>;

/// The values of the control registers the model's datapath processes read, with icm's and
/// step 1's definedness: one step query per distinct class; load control's row and column
/// (which no datapath process reads) of the first state of the class.
struct ControlClass {
    bool load = true;
    int i = 1;
    std::array<int, 3> i_dly{1, 1, 1};
    std::uint8_t t = 0;
    bool a_defined = false, step1_defined = false;
    int row = 1, col = 1;
    long first_write = 0;   ///< the write after which the model first reached it
    auto key() const { return std::tuple(load, i, i_dly, t, a_defined, step1_defined); }
};

ControlClass control_class(const Concrete::Registers& r, long writes) {
    return {r.lc.load, r.icmux.i, r.icmux.i_dly, r.ctrl.t, r.icmux.a_defined, r.step1_defined, r.lc.row, r.lc.col, writes};
}

/// The model from reset until its frame part (control registers less find_max's counter) and
/// both definedness flags repeat: every class it reaches (none past `max_writes` writes).
std::vector<ControlClass> control_classes(const Formats& f, const Geometry& g, long max_writes, long& writes) {
    Concrete m(g, DynamicFormats{f});
    std::set<std::tuple<int, int, bool, int, std::array<int, 3>, std::uint8_t, bool, bool>> seen;
    std::map<decltype(ControlClass{}.key()), ControlClass> classes;
    for (writes = 0;; ++writes) {
        const Concrete::Registers& r = m.registers();
        if (!seen.emplace(r.lc.row, r.lc.col, r.lc.load, r.icmux.i, r.icmux.i_dly, r.ctrl.t, r.icmux.a_defined, r.step1_defined).second)
            break;
        const ControlClass c = control_class(r, writes);
        classes.emplace(c.key(), c);
        if (writes >= max_writes) return {};
        m.write(0x80808080U);   // any pixels: the control registers do not read them
    }
    std::vector<ControlClass> v;
    for (const auto& [k, c] : classes) v.push_back(c);
    std::sort(v.begin(), v.end(), [](const ControlClass& a, const ControlClass& b) { return a.first_write < b.first_write; });
    return v;
}

/// The netlist's signals (yosys-smt2-wire lines): name -> width.
std::map<std::string, int> wires_of(const std::string& smt) {
    std::map<std::string, int> w;
    static const std::regex line(R"(; yosys-smt2-wire (\S+) (\d+))");
    for (std::sregex_iterator it(smt.begin(), smt.end(), line), end; it != end; ++it) w[(*it)[1]] = std::stoi((*it)[2]);
    return w;
}

/// The top-level forms of an SMT-LIB text (comments dropped).
std::vector<std::string_view> forms_of(const std::string& text) {
    std::vector<std::string_view> v;
    int depth = 0;
    size_t start = 0;
    bool bar = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (bar) {
            bar = c != '|';
        } else if (c == '|') {
            bar = true;
        } else if (c == ';') {
            i = text.find('\n', i);
            if (i == std::string::npos) break;
        } else if (c == '(') {
            if (depth++ == 0) start = i;
        } else if (c == ')' && --depth == 0) {
            v.emplace_back(text.data() + start, i + 1 - start);
        }
    }
    return v;
}

/// `body` with every application (|f| state) (and (|f| next_state)) of a state function
/// replaced by the constant |f@X| of the named state.
std::string substitute(std::string_view body, const std::string& state, const std::string& next_state) {
    std::string out;
    out.reserve(body.size());
    for (size_t i = 0; i < body.size();) {
        if (body[i] == '(' && i + 1 < body.size() && body[i + 1] == '|') {
            const size_t close = body.find('|', i + 2);
            const std::string_view name = body.substr(i + 2, close - (i + 2));
            const std::string_view after = body.substr(close + 1);
            const bool now = after.substr(0, 7) == " state)", next = after.substr(0, 12) == " next_state)";
            if (now || next) {
                out += fmt::format("|{}@{}|", name, now ? state : next_state);
                i = close + 1 + (now ? 7 : 12);
                continue;
            }
        }
        out += body[i++];
    }
    return out;
}

/// yosys's transition system (write_smt2: a sort of states |top_s|, every register a declared
/// function of a state, every signal a defined one, the transition a function of two states)
/// instantiated at the named states as plain bit-vector logic: each register one constant per
/// state (|f@s|), each signal one definition per state, the transition one per pair
/// (|top_t@s@s2|). Of the named signals (|top_n name|, aliases of the others: most of the
/// file), only `wires` are kept. Without the sort and its functions, the solvers take it as QF_BV (z3 4.8
/// bit-blasts it after eliminating the definitions; with the functions, it expands each at every
/// use and searches with its general core, minutes on the whole design).
std::string instantiate(const std::string& smt, const std::vector<std::string>& states,
                        const std::vector<std::pair<std::string, std::string>>& steps, const std::set<std::string, std::less<>>& wires) {
    static constexpr std::string_view one = " ((state |top_s|)) ", two = " ((state |top_s|) (next_state |top_s|)) ",
                                      declared = " (|top_s|) ";
    const auto head = [](std::string_view f, std::string_view kind, std::string_view params) -> size_t {
        if (f.substr(0, kind.size()) != kind) return std::string_view::npos;
        const size_t close = f.find('|', kind.size() + 1);
        return f.substr(close + 1, params.size()) == params ? close + 1 : std::string_view::npos;
    };
    std::string out;
    for (const auto f : forms_of(smt)) {
        if (f.substr(0, 13) == "(declare-sort") continue;
        if (const size_t at = head(f, "(declare-fun ", declared); at != std::string_view::npos) {
            const std::string_view name = f.substr(14, at - 15), sort = f.substr(at + declared.size(), f.size() - 1 - at - declared.size());
            for (const auto& x : states) out += fmt::format("(declare-fun |{}@{}| () {})\n", name, x, sort);
        } else if (const size_t at1 = head(f, "(define-fun ", one); at1 != std::string_view::npos) {
            const std::string_view name = f.substr(13, at1 - 14), body = f.substr(at1 + one.size());
            if (name.substr(0, 6) == "top_n " && !wires.count(name.substr(6))) continue;
            for (const auto& x : states) out += fmt::format("(define-fun |{}@{}| () {}\n", name, x, substitute(body, x, x));
        } else if (const size_t at2 = head(f, "(define-fun ", two); at2 != std::string_view::npos) {
            const std::string_view name = f.substr(13, at2 - 14), body = f.substr(at2 + two.size());
            for (const auto& [a, b] : steps) out += fmt::format("(define-fun |{}@{}@{}| () {}\n", name, a, b, substitute(body, a, b));
        } else {
            throw std::logic_error(fmt::format("datapath induction: unexpected form in yosys's netlist: {}", f.substr(0, 80)));
        }
    }
    return out;
}

/// Terms of the netlist's signals in one state (`s`, the current one, or `s2`, the next).
class NetlistView {
public:
    NetlistView(const std::map<std::string, int>& wires, std::string state) : wires_(wires), state_(std::move(state)) {}

    /// Element k (row-major from (1, 1)) of a VHDL array of `n` elements of `w` bits, the
    /// first element in the most significant bits (GHDL's layout of an array as a vector).
    SmtWord element(const std::string& name, int n, int k, int w, bool is_signed) const {
        check(name, n * w);
        const int hi = (n - k) * w - 1, lo = (n - 1 - k) * w;
        return {fmt::format("((_ extract {} {}) |top_n {}@{}|)", hi, lo, name, state_), w, is_signed};
    }
    SmtWord whole(const std::string& name, int w, bool is_signed) const { return element(name, 1, 0, w, is_signed); }
    std::string flag(const std::string& name) const {
        check(name, 1);
        return fmt::format("|top_n {}@{}|", name, state_);
    }

private:
    void check(const std::string& name, int w) const {
        const auto it = wires_.find(name);
        if (it == wires_.end() || it->second != w)
            throw std::logic_error(fmt::format("datapath induction: the netlist has no signal {} of {} bits{}", name, w,
                                               it == wires_.end() ? "" : fmt::format(" (it has {} bits)", it->second)));
    }
    const std::map<std::string, int>& wires_;
    std::string state_;
};

/// One register of the relation: the model's value and the netlist's, both as terms.
struct Pair {
    std::string name;   ///< "sxm(1,1)"
    SmtWord model, netlist;
};

std::string rc(int n, int k) { return fmt::format("({},{})", k / n + 1, k % n + 1); }
std::string hr_name(int k, const char* unit, const char* sig) {
    return fmt::format("u.rows3_n{}_cols3_n{}_{}.{}", k / 3 + 1, k % 3 + 1, unit, sig);
}

/// Calls f(name, model register, netlist signal) on every register of the relation, in one
/// order: the model's registers `r`, the netlist's signals in `v`. icm and step 1's terms only
/// where the model holds them defined.
template <class Regs, class F>
void relation(const Formats& f, Regs& r, const NetlistView& v, F&& each) {
    const int sw = f.sobel_w, mw = f.m_w(), bw = f.bf_w(), pw = f.prod_w(), rw = f.resp_w;
    for (int q = 0; q < 4; ++q)
        for (int k = 0; k < 49; ++k)
            each(fmt::format("win{}{}", q, rc(7, k)), r.icmux.win[q][k / 7][k % 7], v.element("u.icmux.win", 4 * 49, q * 49 + k, 8, false));
    for (int k = 0; k < 3; ++k) each(fmt::format("data_dly({})", k + 1), r.icmux.data_dly[k], v.element("u.icmux.data_dly", 3, k, 32, false));
    if (r.icmux.a_defined)
        for (int k = 0; k < 49; ++k) each("icm" + rc(7, k), r.icmux.a[k / 7][k % 7], v.element("u.icm", 49, k, 8, false));
    const std::pair<decltype(r.sxm)*, const char*> p5[] = {{&r.sxm, "u.sxm"}, {&r.sym, "u.sym"}};
    for (const auto& [p, name] : p5)
        for (int k = 0; k < 25; ++k) each(std::string(name + 2) + rc(5, k), (*p)[k], v.element(name, 25, k, sw, true));
    const std::pair<decltype(r.mam)*, const char*> m5[] = {{&r.mam, "u.mam"}, {&r.mbm, "u.mbm"}, {&r.mcm, "u.mcm"}};
    for (const auto& [p, name] : m5)
        for (int k = 0; k < 25; ++k) each(std::string(name + 2) + rc(5, k), (*p)[k], v.element(name, 25, k, mw, true));
    const std::pair<decltype(r.bfam)*, const char*> b3[] = {{&r.bfam, "u.bfam"}, {&r.bfbm, "u.bfbm"}, {&r.bfcm, "u.bfcm"}};
    for (const auto& [p, name] : b3)
        for (int k = 0; k < 9; ++k) each(std::string(name + 2) + rc(3, k), (*p)[k], v.element(name, 9, k, bw, true));
    if (r.step1_defined)
        for (int k = 0; k < 9; ++k) {
            each("ac" + rc(3, k), r.ac[k], v.whole(hr_name(k, "hr", "ac"), pw, true));
            each("bb" + rc(3, k), r.bb[k], v.whole(hr_name(k, "hr", "bb"), pw, true));
            each("ktr2" + rc(3, k), r.ktr2[k], v.whole(hr_name(k, "hr", "ktr2"), f.ktr_w, true));
        }
    for (int k = 0; k < 9; ++k) {
        each("hrm" + rc(3, k), r.hrm[k], v.element("u.hrm", 9, k, rw, true));
        each("r0_delay" + rc(3, k), r.r0_delay[k], v.whole(hr_name(k, "th", "r0_delay"), rw, true));
        each("trm" + rc(3, k), r.trm[k], v.element("u.trm", 9, k, rw, true));
    }
    each("fm.running", r.fm.running, v.whole("u.fm.running", rw, true));
    each("fm.max", r.fm.max, v.whole("u.fm.max", rw, true));
    each("sr.c", r.sr.c, v.whole("u.sr.c", 6, false));
}

/// A fresh variable of the query: a register the VHDL leaves undefined.
SmtWord fresh(int w, bool is_signed) {
    SmtQuery& q = *smt_query;
    const std::string name = fmt::format("u{}", q.next++);
    q.text += fmt::format("(declare-fun {} () (_ BitVec {}))\n", name, w);
    return {name, w, is_signed};
}

/// The width of find_max's counter on the netlist.
int count_width(const std::map<std::string, int>& wires) {
    const auto it = wires.find("u.fm.count");
    if (it == wires.end()) throw std::logic_error("datapath induction: the netlist has no signal u.fm.count");
    return it->second;
}

std::string bv(long v, int w) { return fmt::format("(_ bv{} {})", v, w); }

/// The netlist's control signals at a class's values and find_max's counter in 1 .. period.
std::string control_at(const ControlClass& c, const NetlistView& v, const std::map<std::string, int>& wires, long period) {
    const int iw = wires.at("u.icmux.i"), cw = count_width(wires);
    std::string s = fmt::format("(and (= {} {}) (= {} {})", v.flag("u.lc.load"), c.load ? "true" : "false",
                                v.whole("u.icmux.i", iw, false).e, bv(c.i, iw));
    for (int k = 0; k < 3; ++k) s += fmt::format(" (= {} {})", v.element("u.icmux.i_dly", 3, k, iw, false).e, bv(c.i_dly[k], iw));
    const SmtWord count = v.whole("u.fm.count", cw, false);
    s += fmt::format(" (= {} {}) (bvule {} {}) (bvule {} {}))", v.whole("u.ctrl.t", 6, false).e, bv(c.t, 6), bv(1, cw), count.e, count.e,
                     bv(period, cw));
    return s;
}

/// Ranges carried with the relation: each register whose signed resize downstream could
/// overflow on the netlist but not in its proven range (the interval bound, for any pixels).
struct Invariant {
    std::string what;               ///< "sxm in [-1020, 1020]"
    Reg reg;
    Interval range;
};

std::vector<Invariant> invariants(const Formats& f) {
    const RangeReport rr = interval_ranges(f);
    std::vector<Invariant> v;
    for (Reg g : {Reg::sobel_x, Reg::sobel_y}) {
        const RegisterRange& x = rr.regs[static_cast<size_t>(g)];
        if (x.verdict == Verdict::proven) v.push_back({fmt::format("{} in [{}, {}]", kRegNames[static_cast<size_t>(g)], x.bound.lo, x.bound.hi), g, x.bound});
    }
    return v;
}

std::string in_range(const SmtWord& x, const Interval& i) {
    return fmt::format("(and (bvsle {} {}) (bvsle {} {}))", SmtWord::sgn(i.lo, x.w).e, x.e, x.e, SmtWord::sgn(i.hi, x.w).e);
}

/// The invariants on a model's registers (every Sobel register of the plane it names).
template <class Regs>
std::string invariant_terms(const std::vector<Invariant>& inv, const Regs& r) {
    std::string s = "(and true";
    for (const auto& i : inv)
        for (const auto& x : i.reg == Reg::sobel_x ? r.sxm : r.sym) s.append(" ").append(in_range(x, i.range));
    return s + ")";
}

/// One query: an edge of the netlist (the head's assertions), the model's registers and the
/// fresh values of undefined ones (definitions), the hypothesis on the current state and the
/// question whether a next register differs. Asked in three files: held-N.smt2 asks the
/// hypothesis alone (sat expected: the check is not vacuous), query-N.smt2 the difference
/// (unsat expected), each after head.smt2 (the netlist), with the side conditions assumed;
/// side-N.smt2, on the model alone, whether the invariants can fail in the next state (unsat
/// expected). The side conditions: no signed resize of the model's write overflows
/// (numeric_std's result, sign bit kept, is then the netlist's truncation). Each is asked once
/// for all classes (resize-J.smt2, DistinctResizes): on the model alone, with the current
/// registers free under the invariants (a weaker hypothesis than any class's), so it holds
/// wherever a class's hypothesis does; assuming it in query-N.smt2 is then sound and leaves a
/// hypothesis that is sat wherever held-N.smt2 finds it sat.
struct Query {
    std::string title{};              ///< "reset", "class 3 (first after write 49)"
    std::string edge{}, defs{}, hyp{}, any{};
    std::vector<std::string> diffs{};     ///< per compared register: its "(not (= model netlist))" term
    std::vector<std::string> names{};
    std::vector<std::string> signals{};   ///< per compared register: the netlist's, "u.sxm[274:264]"
    std::vector<SmtShrink> side{};        ///< the model's signed resizes to fewer bits
    std::string now{};                    ///< the invariants in the current state
    std::string broken{};                 ///< true where an invariant fails in the model's next state
    std::string held_text() const { return fmt::format("{}{}(assert {})\n(check-sat)\n", edge, defs, hyp); }
    std::string assumed() const {
        std::string s;
        for (const auto& x : side) s += fmt::format("(assert (not {}))\n", x.overflow);
        return s;
    }
    std::string text() const { return fmt::format("{}{}(assert {})\n{}(assert {})\n(check-sat)\n", edge, defs, hyp, assumed(), any); }
    /// The invariants' file: `decls` declares the current state's signals it names.
    std::string side_text(const std::string& decls) const {
        return fmt::format("(set-logic QF_BV)\n{}{}(assert {})\n(assert {})\n(check-sat)\n", decls, defs, hyp, broken);
    }
};

/// The definitions of one query's `defs` (one per line, as SmtQuery writes them) that some terms
/// read, directly or through others, renamed in their order: the same text for the same
/// condition in any query.
class Cone {
public:
    explicit Cone(const std::string& defs) {
        for (size_t at = 0, end; at < defs.size(); at = end + 1) {
            end = defs.find('\n', at);
            lines_.push_back(defs.substr(at, end - at));
            const size_t from = lines_.back().find(' ') + 1;   // "(define-fun NAME ..." or "(declare-fun NAME ..."
            bodies_.push_back(lines_.back().find(' ', from));
            names_.push_back(lines_.back().substr(from, bodies_.back() - from));
            index_[names_.back()] = lines_.size() - 1;
        }
    }
    /// The definitions `terms` read, and the terms, with every name of the cone as c0, c1, ...
    std::pair<std::string, std::vector<std::string>> of(const std::vector<std::string>& terms) const {
        std::set<size_t> in;
        std::vector<size_t> pending;
        const auto visit = [&](const std::string& text) {
            for (std::sregex_iterator it(text.begin(), text.end(), name_), end; it != end; ++it)
                if (const auto f = index_.find(it->str()); f != index_.end() && in.insert(f->second).second) pending.push_back(f->second);
        };
        for (const auto& t : terms) visit(t);
        while (!pending.empty()) {
            const size_t k = pending.back();
            pending.pop_back();
            visit(lines_[k].substr(bodies_[k]));
        }
        std::map<std::string, std::string, std::less<>> renamed;
        for (const size_t k : in) renamed[names_[k]] = "c" + std::to_string(renamed.size());
        const auto rename = [&](const std::string& text) {
            std::string out;
            size_t last = 0;
            for (std::sregex_iterator it(text.begin(), text.end(), name_), end; it != end; ++it)
                if (const auto r = renamed.find(it->str()); r != renamed.end()) {
                    out += text.substr(last, it->position() - last) + r->second;
                    last = it->position() + it->length();
                }
            return out + text.substr(last);
        };
        std::string defs;
        for (const size_t k : in) defs += rename(lines_[k]) + "\n";
        std::vector<std::string> out;
        for (const auto& t : terms) out.push_back(rename(t));
        return {defs, out};
    }

private:
    inline static const std::regex name_{R"(\b[tu]\d+\b)"};
    std::vector<std::string> lines_, names_;
    std::vector<size_t> bodies_;   ///< per line: where its sort and body start, after the name
    std::map<std::string, size_t, std::less<>> index_;
};

/// The side conditions of every query, each distinct one once (the same cone and terms up to
/// names): a check asks whether the resize can overflow where the current state's invariants
/// hold, chunked into files of `per_file` checks. Each check defines its cone inside its own
/// push/pop (SMT-LIB scopes definitions so), so every check may name it c0, c1, ...
struct DistinctResizes {
    std::vector<std::string> checks;   ///< push, the cone, the invariants, the overflow, check-sat, pop
    std::vector<std::string> what;     ///< "the signed resize of t184 (22 -> 21 bits) in class 12 (first after write 51)"
    static constexpr size_t per_file = 25;

    explicit DistinctResizes(const std::vector<Query>& queries) {
        std::set<std::string, std::less<>> seen;
        for (const auto& q : queries) {
            const Cone cone(q.defs);
            for (const auto& x : q.side) {
                const auto [defs, terms] = cone.of({q.now, x.overflow});
                std::string check = fmt::format("(push 1)\n{}(assert {})\n(assert {})\n(check-sat)\n(pop 1)\n", defs, terms[0], terms[1]);
                if (!seen.insert(check).second) continue;
                checks.push_back(std::move(check));
                what.push_back(fmt::format("the signed resize of {} ({} -> {} bits) in {}", x.source, x.from, x.to, q.title));
            }
        }
    }
    size_t files() const { return (checks.size() + per_file - 1) / per_file; }
    /// File j's checks after `decls` (the current state's signals they name).
    std::string text(size_t j, const std::string& decls) const {
        std::string s = "(set-logic QF_BV)\n" + decls;
        for (size_t k = j * per_file; k < std::min(checks.size(), (j + 1) * per_file); ++k) s += checks[k];
        return s;
    }
};

constexpr const char* kStepEdge = "(assert |top_h@s|)\n(assert |top_h@s2|)\n(assert |top_n rst@s|)\n(assert |top_n rst@s2|)\n"
                                  "(assert |top_t@s@s2|)\n";

/// Appends the relation on the next state to q's question (any differing register, one
/// difference per register for the question which) and the invariants there to its side file.
template <class Regs>
void ask_next(const Formats& f, Regs& r, const NetlistView& next, const std::vector<Invariant>& inv, Query& q) {
    q.any = "(or";
    relation(f, r, next, [&](const std::string& name, const SmtWord& model, const SmtWord& net) {
        static const std::regex extract(R"(\(\(_ extract (\d+) (\d+)\) \|top_n ([^@|]+)@\w+\|\))");
        q.names.push_back(name);
        q.signals.push_back(std::regex_replace(net.e, extract, "$3[$1:$2]"));
        q.diffs.push_back(fmt::format("(not (= {} {}))", model.e, net.e));
        q.any += " " + q.diffs.back();
    });
    q.any += ")";
    q.broken = fmt::format("(not {})", invariant_terms(inv, r));
}

Query class_step(const Formats& f, const Geometry& g, const ControlClass& c, const std::map<std::string, int>& wires,
                 const std::vector<Invariant>& inv) {
    SmtQuery sq;
    sq.yosys_sign_extend = true;
    smt_query = &sq;
    const NetlistView now(wires, "s"), next(wires, "s2");
    const int cw = count_width(wires);
    Symbolic m(g, DynamicFormats{f}, now.whole("u.fm.count", cw, false));
    Symbolic::Registers& r = m.registers();
    r.lc.row = c.row;
    r.lc.col = c.col;
    r.lc.load = c.load;
    r.icmux.i = c.i;
    r.icmux.i_dly = c.i_dly;
    r.icmux.a_defined = c.a_defined;
    r.ctrl.t = c.t;
    r.step1_defined = c.step1_defined;
    if (!c.a_defined)
        for (auto& row : r.icmux.a) for (auto& p : row) p = fresh(8, false);
    if (!c.step1_defined)
        for (int k = 0; k < 9; ++k) r.ac[k] = fresh(f.prod_w(), true), r.bb[k] = fresh(f.prod_w(), true), r.ktr2[k] = fresh(f.ktr_w, true);
    relation(f, r, now, [](const std::string&, auto& model, const SmtWord& net) { model = net; });
    Query q{.title = fmt::format("class (first after write {})", c.first_write), .edge = kStepEdge};
    q.now = invariant_terms(inv, r);
    q.hyp = fmt::format("(and {} {})", control_at(c, now, wires, g.find_max_period()), q.now);
    m.write(now.whole("data", 32, false));
    ask_next(f, r, next, inv, q);
    smt_query = nullptr;
    q.defs = sq.text;
    q.side = sq.shrinks;
    return q;
}

/// The base: one clock edge after power-up with the reset low, then the reset high: every
/// register of the relation (icm and step 1's terms are undefined then) and the control
/// signals equal to the model's reset state, and the invariants hold there.
Query base_query(const Formats& f, const Geometry& g, const std::map<std::string, int>& wires, const std::vector<Invariant>& inv) {
    SmtQuery sq;
    sq.yosys_sign_extend = true;
    smt_query = &sq;
    const NetlistView after(wires, "s2");
    const int cw = count_width(wires);
    Symbolic m(g, DynamicFormats{f}, SmtWord{SmtWord::constant(1, cw).e, cw, false});
    Query q{.title = "reset",
            .edge = "(assert |top_i@s|)\n(assert |top_h@s|)\n(assert |top_h@s2|)\n(assert (not |top_n rst@s|))\n"
                    "(assert |top_n rst@s2|)\n(assert |top_t@s@s2|)\n",
            .hyp = "true",
            .now = "true"};
    ask_next(f, m.registers(), after, inv, q);
    const ControlClass reset = control_class(Concrete(g, DynamicFormats{f}).registers(), 0);
    q.names.push_back("control registers");
    q.diffs.push_back(fmt::format("(not {})", control_at(reset, after, wires, 1)));
    q.any.insert(q.any.size() - 1, " " + q.diffs.back());
    smt_query = nullptr;
    q.defs = sq.text;
    q.side = sq.shrinks;
    return q;
}

/// Runs `solver` (its arguments reading SMT-LIB from standard input) on `file` in `dir`, after
/// head.smt2 where `with_head`; its answers.
std::vector<std::string> solve(const std::string& solver, const fs::path& dir, const std::string& file, bool with_head = true) {
    const std::string stem = fs::path(file).stem().string() + "-" + solver.substr(0, solver.find(' '));
    util::run_process({"sh", "-c", fmt::format("cat {}{} | {}", with_head ? "head.smt2 " : "", file, solver)},
                      {.cwd = dir, .log = dir / (stem + ".log"), .stdout_file = dir / (stem + ".txt")});
    return solver_answers(dir / (stem + ".txt"));
}

/// Which registers differ in the solver's counterexample to a query (its values of the
/// per-register differences); "" if it finds none.
std::string differing(const Query& q, const fs::path& dir) {
    std::string text = q.edge + q.defs;
    for (size_t k = 0; k < q.diffs.size(); ++k) text += fmt::format("(define-fun d{} () Bool {})\n", k, q.diffs[k]);
    text += fmt::format("(assert {})\n{}(assert {})\n(check-sat)\n(get-value (", q.hyp, q.assumed(), q.any);
    for (size_t k = 0; k < q.diffs.size(); ++k) text += fmt::format(" d{}", k);
    util::write_file_atomic(dir / "which.smt2", text + "))\n");
    util::run_process({"sh", "-c", "cat head.smt2 which.smt2 | z3 -in -smt2 -model"},
                      {.cwd = dir, .log = dir / "which-z3.log", .stdout_file = dir / "which-z3.txt"});
    const std::string answer = util::read_file(dir / "which-z3.txt");
    static const std::regex value(R"(\(d(\d+) true\))");
    std::string out;
    for (std::sregex_iterator it(answer.begin(), answer.end(), value), end; it != end; ++it)
        out += (out.empty() ? "" : ", ") + q.names.at(std::stoul((*it)[1]));
    return out;
}

const HarrisTopScript kScript{
    .top_v = "module top(input clk, input rst, input [31:0] data, output [31:0] corner);\n"
             "  harris_top u(.clk(clk), .rst(rst), .write(1'b1), .data(data), .corner(corner));\nendmodule\n",
    .script = "read_verilog harris_top.v top.v\nhierarchy -top top\nproc\nflatten\nasync2sync\ndffunmap\nopt -nosdff -nodffe\n"
              "select -assert-none t:$*latch* t:$sr t:$mem* t:$*dff* t:$dff %d\nopt_clean\nwrite_smt2 -wires top.smt2\n",
    .commands = "yosys -q -s top.ys    # writes top.smt2\n"};

/// Declarations of the current state's signals that `text` names, as free constants (their
/// sorts from `head`): the side files ask about every value of them, not only the netlist's.
std::string free_signals(const std::string& head, const std::string& text) {
    if (text.find("@s2|") != std::string::npos) throw std::logic_error("datapath induction: a side condition names the next state");
    static const std::regex used(R"(\|top_n ([^@|]+)@s\|)");
    std::set<std::string, std::less<>> names;
    for (std::sregex_iterator it(text.begin(), text.end(), used), end; it != end; ++it) names.insert((*it)[1]);
    std::string out;
    for (const auto& n : names) {
        const std::string def = fmt::format("(define-fun |top_n {}@s| () ", n);
        const size_t at = head.find(def);
        if (at == std::string::npos) throw std::logic_error("datapath induction: the head does not define " + n);
        const size_t from = at + def.size(), to = head[from] == '(' ? head.find(')', from) + 1 : head.find(' ', from);
        out += fmt::format("(declare-fun |top_n {}@s| () {})\n", n, head.substr(from, to - from));
    }
    return out;
}

/// The queries' files in `dir` (head.smt2: the netlist at the signals they name; held-N.smt2,
/// query-N.smt2, side-N.smt2, resize-J.smt2) and the registers of the relation into p.
void write_queries(const std::string& smt, const std::vector<Query>& queries, const DistinctResizes& resizes, const fs::path& dir,
                   DatapathInduction& p) {
    const Query& widest = *std::max_element(queries.begin(), queries.end(),
                                            [](const Query& a, const Query& b) { return a.signals.size() < b.signals.size(); });
    for (size_t k = 0; k < widest.signals.size(); ++k) p.registers.push_back(widest.names[k] + " = " + widest.signals[k]);
    std::set<std::string, std::less<>> named{"rst"};
    static const std::regex signal(R"(\|top_n ([^@|]+)@)");
    for (const auto& q : queries)
        for (const std::string* s : {&q.defs, &q.hyp, &q.any})
            for (std::sregex_iterator it(s->begin(), s->end(), signal), end; it != end; ++it) named.insert((*it)[1]);
    const std::string head = "(set-logic QF_BV)\n" + instantiate(smt, {"s", "s2"}, {{"s", "s2"}}, named);
    util::write_file_atomic(dir / "head.smt2", head);
    for (size_t k = 0; k < queries.size(); ++k) {
        const Query& q = queries[k];
        util::write_file_atomic(dir / fmt::format("held-{}.smt2", k), fmt::format("; {}\n{}", q.title, q.held_text()));
        util::write_file_atomic(dir / fmt::format("query-{}.smt2", k), fmt::format("; {}\n{}", q.title, q.text()));
        util::write_file_atomic(dir / fmt::format("side-{}.smt2", k),
                                fmt::format("; {}\n{}", q.title, q.side_text(free_signals(head, q.defs + q.hyp + q.broken))));
    }
    for (size_t j = 0; j < resizes.files(); ++j) {
        const std::string checks = resizes.text(j, "");
        util::write_file_atomic(dir / fmt::format("resize-{}.smt2", j), resizes.text(j, free_signals(head, checks)));
    }
    p.command = fmt::format("cd {} && for q in held-*.smt2 query-*.smt2; do cat head.smt2 $q | z3 -in -smt2; done && "
                            "for s in side-*.smt2 resize-*.smt2; do z3 $s; done",
                            dir.string());
}

/// A solver's answers to the files of n queries: per query, held-N.smt2's, query-N.smt2's and
/// side-N.smt2's (the first answer, "no answer" if none, "not asked"), and per resize-J.smt2
/// its answers.
struct Answers {
    std::vector<std::string> held, query, side;
    std::vector<std::vector<std::string>> resize;
};

/// The solver commands for each kind of file (an empty one: those files are not asked).
struct Solvers {
    std::string held, query, side, resize;
};

/// The solvers on every file of n queries and `resizes` resize files in `dir`, side by side on
/// `jobs` cores (0: every core), in this order: the resize files, every query file, every side
/// file, every held file (a difference, in a query file, is found before the checks that only
/// matter to a proof); with `stop`, the files not yet started after an unexpected answer are
/// skipped.
Answers solve_all(const Solvers& s, const fs::path& dir, size_t n, size_t resizes, int jobs, bool stop) {
    Answers a{std::vector<std::string>(n, "not asked"), std::vector<std::string>(n, "not asked"), std::vector<std::string>(n, "not asked"),
              std::vector<std::vector<std::string>>(resizes)};
    std::atomic<bool> failed = false;
    const auto first = [](const std::vector<std::string>& x) { return x.empty() ? std::string("no answer") : x[0]; };
    tbb::task_arena arena(jobs > 0 ? jobs : int(tbb::task_arena::automatic));
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, resizes + 3 * n, 1), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i < range.end(); ++i) {
                if (stop && failed) return;
                if (i < resizes) {
                    a.resize[i] = solve(s.resize, dir, fmt::format("resize-{}.smt2", i), false);
                    if (std::count(a.resize[i].begin(), a.resize[i].end(), "unsat") != static_cast<long>(a.resize[i].size())) failed = true;
                    continue;
                }
                const size_t j = i - resizes, k = j % n;
                if (j / n == 0) {
                    a.query[k] = first(solve(s.query, dir, fmt::format("query-{}.smt2", k)));
                    if (a.query[k] != "unsat") failed = true;
                } else if (j / n == 1) {
                    a.side[k] = first(solve(s.side, dir, fmt::format("side-{}.smt2", k), false));
                    if (a.side[k] != "unsat") failed = true;
                } else if (!s.held.empty()) {
                    a.held[k] = first(solve(s.held, dir, fmt::format("held-{}.smt2", k)));
                    if (a.held[k] != "sat") failed = true;
                }
            }
        }, tbb::simple_partitioner());
    });
    return a;
}

/// Why z3's answers prove nothing though no query is sat, in this order: a hypothesis found
/// unsat alone (the query would be vacuous), a side condition or an invariant answered other
/// than unsat (it may fail where the hypothesis holds), a file without its answers; "" if
/// every file has the expected answers.
std::string unproven(const std::vector<Query>& queries, const DistinctResizes& resizes, const Answers& a, int seconds) {
    for (size_t k = 0; k < queries.size(); ++k)
        if (a.held[k] != "sat" && a.held[k] != "not asked")
            return fmt::format("{}: z3 {} on the hypothesis alone (sat expected: a vacuous query proves nothing)", queries[k].title, a.held[k]);
    for (size_t j = 0; j < a.resize.size(); ++j)
        for (size_t c = 0; c < a.resize[j].size(); ++c)
            if (a.resize[j][c] != "unsat")
                return fmt::format("{} may overflow (z3: {}; unsat expected)", resizes.what[j * DistinctResizes::per_file + c], a.resize[j][c]);
    for (size_t k = 0; k < queries.size(); ++k)
        if (a.side[k] != "unsat" && a.side[k] != "not asked")
            return fmt::format("{}: an invariant may fail in the next state (z3: {}; unsat expected)", queries[k].title, a.side[k]);
    for (size_t j = 0; j < a.resize.size(); ++j)
        if (const size_t n = std::min(resizes.checks.size() - j * DistinctResizes::per_file, DistinctResizes::per_file); a.resize[j].size() != n)
            return fmt::format("resize-{}.smt2: z3 answered {} of its {} checks within {} s", j, a.resize[j].size(), n, seconds);
    for (size_t k = 0; k < queries.size(); ++k)
        for (const std::string* x : {&a.held[k], &a.query[k], &a.side[k]})
            if (*x != (x == &a.held[k] ? "sat" : "unsat")) return fmt::format("{}: z3 {} within {} s", queries[k].title, *x, seconds);
    return "";
}

/// cvc5 on the query, side and resize files of `dir` (after z3 proved them all): p's recheck.
void recheck_with_cvc5(const std::vector<Query>& queries, const DistinctResizes& resizes, const DatapathInductionOptions& o, const fs::path& dir,
                       DatapathInduction& p) {
    const std::string cvc5 = fmt::format("cvc5 --lang=smt2 --tlimit={}", o.seconds * 1000);
    const Answers c = solve_all({"", cvc5, cvc5, cvc5 + " --incremental"}, dir, queries.size(), resizes.files(), o.jobs, false);
    const long checks = 2 * static_cast<long>(queries.size()) + static_cast<long>(resizes.checks.size());
    long unsat = std::count(c.query.begin(), c.query.end(), "unsat") + std::count(c.side.begin(), c.side.end(), "unsat"), sat = 0;
    for (const auto& r : c.resize) unsat += std::count(r.begin(), r.end(), "unsat"), sat += std::count(r.begin(), r.end(), "sat");
    if (sat + std::count(c.query.begin(), c.query.end(), "sat") + std::count(c.side.begin(), c.side.end(), "sat") > 0)
        throw std::logic_error("datapath induction: z3 proves every check of " + dir.string() + ", cvc5 finds one sat");
    p.rechecked = unsat == checks;
    p.recheck = fmt::format("cvc5: {} unsat of {}", unsat, checks);
}

/// The proof in `dir`; every field of p but its seconds.
void prove_in(const Formats& f, const Geometry& g, const DatapathInductionOptions& o, const fs::path& dir, DatapathInduction& p) {
    const std::vector<ControlClass> classes = control_classes(f, g, o.max_writes, p.model_writes);
    if (classes.empty()) {
        p.detail = fmt::format("the model's frame part did not repeat within {} writes", o.max_writes);
        return;
    }
    p.classes = static_cast<long>(classes.size());
    const HarrisTopNetlist n = synthesise_harris_top(f, g, dir, o.rtl_dir, kScript);
    const std::map<std::string, int> wires = wires_of(n.smt);
    const std::vector<Invariant> inv = invariants(f);
    for (const auto& i : inv) p.invariants.push_back(i.what);
    std::vector<Query> queries{base_query(f, g, wires, inv)};
    for (const auto& c : classes) {
        queries.push_back(class_step(f, g, c, wires, inv));
        queries.back().title = fmt::format("class {} (first after write {})", queries.size() - 2, c.first_write);
    }
    for (const auto& q : queries) p.side_conditions += static_cast<long>(q.side.size());
    const DistinctResizes resizes(queries);
    p.distinct_side_conditions = static_cast<long>(resizes.checks.size());
    write_queries(n.smt, queries, resizes, dir, p);
    const std::string z3 = fmt::format("z3 -in -smt2 -T:{}", o.seconds);
    const Answers a = solve_all({z3, z3, z3, z3}, dir, queries.size(), resizes.files(), o.jobs, true);
    for (size_t k = 0; k < queries.size(); ++k)
        if (a.query[k] == "sat") {
            p.verdict = EqVerdict::counterexample;
            p.detail = fmt::format("{}: the netlist's next {} differs from the model's", queries[k].title, differing(queries[k], dir));
            return;
        }
    if (p.detail = unproven(queries, resizes, a, o.seconds); !p.detail.empty()) return;
    p.verdict = EqVerdict::equal;
    if (o.recheck) recheck_with_cvc5(queries, resizes, o, dir, p);
}

}  // namespace

DatapathInduction prove_datapath_from_reset(const Formats& f, const Geometry& g, const DatapathInductionOptions& o) {
    const auto t0 = Clock::now();
    const util::ScratchDir scratch("datapath-induction");
    const fs::path dir = fs::absolute(o.dir.empty() ? scratch.path() : o.dir);
    fs::create_directories(dir);
    DatapathInduction p;
    p.geometry = g;
    prove_in(f, g, o, dir, p);
    p.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return p;
}

std::string datapath_induction_markdown(const std::string& config, const std::vector<DatapathInduction>& r) {
    std::string s = fmt::format("## Every register from reset: {}\n\n"
                                "| size | verdict | control classes | model writes | invariants | side conditions | second solver | seconds | detail | command |\n"
                                "|---|---|---:|---:|---|---:|---|---:|---|---|\n",
                                config);
    for (const auto& p : r) {
        std::string inv;
        for (const auto& i : p.invariants) inv += (inv.empty() ? "" : "; ") + i;
        s += fmt::format("| {}x{} | {} | {} | {} | {} | {} | {} | {:.1f} | {} | `{}` |\n", p.geometry.width, p.geometry.height, eq_verdict_name(p.verdict),
                         p.classes, p.model_writes, inv.empty() ? "-" : inv,
                         fmt::format("{} ({} distinct)", p.side_conditions, p.distinct_side_conditions), p.recheck.empty() ? "-" : p.recheck, p.seconds,
                         p.detail.empty() ? "-" : p.detail, std::regex_replace(p.command, std::regex(R"(\|)"), R"(\|)"));   // a pipe ends a table cell
    }
    return s;
}

}  // namespace hc::sweep

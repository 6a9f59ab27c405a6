// control_induction.cpp: the control registers of GHDL's netlist of harris_top against the
// cycle model's, state by state from reset (see control_induction.hpp).
#include "sweep/control_induction.hpp"

#include <chrono>
#include <map>
#include <numeric>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "model/harris/harris_top_t.hpp"
#include "model/util/errors.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

using Clock = std::chrono::steady_clock;

/// One control register: its name in the report, the GHDL module (name prefix) and instance
/// that hold it, its VHDL signal, other names yosys may give its flop once flattened (the
/// nets it drives in harris_top), and its value in a model state as the netlist's bits.
struct ControlReg {
    const char* name;
    const char* module;
    const char* instance;
    const char* signal;
    std::vector<std::string> also;
    std::uint64_t (*bits)(const ControlRegisters&, int width);
};

const std::vector<ControlReg>& control_regs() {
    static const std::vector<ControlReg> regs = {
        {"lc.row", "load_control", "lc", "row", {}, [](const ControlRegisters& c, int) -> std::uint64_t { return c.row; }},
        {"lc.col", "load_control", "lc", "col", {}, [](const ControlRegisters& c, int) -> std::uint64_t { return c.col; }},
        {"lc.load", "load_control", "lc", "load_r", {"u.load", "u.icmux.load"},
         [](const ControlRegisters& c, int) -> std::uint64_t { return c.load ? 1 : 0; }},
        {"icmux.i", "input_converter_mux", "icmux", "i", {}, [](const ControlRegisters& c, int) -> std::uint64_t { return c.i; }},
        // GHDL packs an array (1 to 3) with element 1 in the top bits
        {"icmux.i_dly", "input_converter_mux", "icmux", "i_dly", {},
         [](const ControlRegisters& c, int w) -> std::uint64_t {
             const int e = w / 3;
             return (std::uint64_t(c.i_dly[0]) << (2 * e)) | (std::uint64_t(c.i_dly[1]) << e) | std::uint64_t(c.i_dly[2]);
         }},
        {"ctrl.t", "control_shift_register", "ctrl", "tt", {"u.t"}, [](const ControlRegisters& c, int) -> std::uint64_t { return c.t; }},
        {"fm.count", "find_max", "fm", "count", {}, [](const ControlRegisters& c, int) -> std::uint64_t { return c.count; }},
    };
    return regs;
}

/// The text of the first module of GHDL's Verilog whose name starts with `prefix`.
std::string module_text(const std::string& verilog, const std::string& prefix) {
    const size_t at = verilog.find("module " + prefix);
    if (at == std::string::npos) throw std::logic_error("control induction: GHDL's netlist has no module " + prefix);
    return verilog.substr(at, verilog.find("endmodule", at) - at);
}

/// A control register resolved on the netlist: its flop (yosys's name), width and reset value.
struct Flop {
    std::string name;
    int w = 0;
    std::uint64_t reset = 0;
};

/// `sig`'s flop net in `text` ("row = n933_q;" or "assign tt = n1042_q;"), "" if none.
std::string alias_of(const std::string& text, const std::string& sig) {
    std::smatch m;
    const std::regex re("(?:assign )?\\b" + sig + " = (n[0-9]+_q);");
    return std::regex_search(text, m, re) ? m[1].str() : "";
}

/// The first literal `lhs <= W'bBITS;` of `text`, if any.
bool literal_of(const std::string& text, const std::string& lhs, std::uint64_t& v) {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex("\\b" + lhs + " <= [0-9]+'b([01]+);"))) return false;
    v = std::stoull(m[1].str(), nullptr, 2);
    return true;
}

/// Each control register's flop on the flattened netlist, and its value in the reset state:
/// the reset branch's literal of its flop net, else the signal's declared initial value.
std::vector<Flop> resolve(const std::string& verilog, const std::string& smt) {
    const std::map<std::string, int> ports = yosys_smt2_ports(smt);
    std::vector<Flop> out;
    for (const ControlReg& r : control_regs()) {
        const std::string text = module_text(verilog, r.module);
        const std::string net = alias_of(text, r.signal);
        std::vector<std::string> cands = {fmt::format("u.{}.{}", r.instance, r.signal)};
        if (!net.empty()) cands.push_back(fmt::format("u.{}.{}", r.instance, net));
        cands.insert(cands.end(), r.also.begin(), r.also.end());
        Flop f;
        for (const auto& c : cands)
            if (f.name.empty() && ports.count(c + ".q") && ports.count(c + ".d")) f = {c, ports.at(c + ".q"), 0};
        if (f.name.empty()) throw std::logic_error(fmt::format("control induction: the netlist has no flop of {} (looked for {})", r.name,
                                                               fmt::join(cands, ", ")));
        if (!(!net.empty() && literal_of(text, net, f.reset)) && !literal_of(text, r.signal, f.reset))
            throw std::logic_error(fmt::format("control induction: {} has neither a reset value nor an initial value in GHDL's netlist", r.name));
        out.push_back(f);
    }
    return out;
}

/// GHDL's and yosys's commands in `dir` for the control registers' cone (top.ys, cone.ys).
std::pair<std::string, std::string> synthesise(const Formats& f, const Geometry& g, const fs::path& dir, const fs::path& rtl_dir) {
    const HarrisTopNetlist n = synthesise_harris_top(
        f, g, dir, rtl_dir,
        {.top_v = "module top(input clk, input [31:0] data, output [31:0] corner);\n"
                  "  harris_top u(.clk(clk), .rst(1'b1), .write(1'b1), .data(data), .corner(corner));\nendmodule\n",
         .script = "read_verilog harris_top.v top.v\nhierarchy -top top\nproc\nflatten\nopt -nosdff -nodffe\n"
                   "select -assert-none t:$*latch* t:$sr t:$mem* t:$*dff* t:$dff %d\n"
                   "opt_clean -purge\nexpose -evert-dff\nopt_clean\nselect -assert-none t:$dff\n"
                   "write_rtlil top.il\nwrite_smt2 -wires top.smt2\n",
         .commands = "yosys -q -s top.ys    # writes top.il and top.smt2\nyosys -q -s cone.ys   # writes cone.smt2\n"});
    return {n.verilog, n.smt};
}

/// The control state less find_max's counter: the registers whose states repeat every frame.
ControlRegisters frame_part(ControlRegisters c) {
    c.count = 0;
    return c;
}

/// The model's control, as the queries take it: the distinct frame parts from reset
/// (c_0 ... c_{prefix+period-1}, the frame part after write k+1 being c_{k+1}, or c_prefix
/// after the last) and the counter's rule at each of them, checked on the model's own run.
struct ModelControl {
    std::vector<ControlRegisters> states;   ///< frame parts (count 0)
    long prefix = 0;
    std::vector<signed char> advances;      ///< per state: the write moves the counter (1), or not (0)
    long lo = 0, hi = 0;                    ///< the counter's values seen
    long wrap_from = -1, wrap_to = -1;      ///< an advance from wrap_from goes to wrap_to (else +1)
    long count0 = 0;                        ///< the counter after reset
    long writes = 0;                        ///< writes run until the whole control state repeated
    std::string fault;                      ///< why the model does not fit this form ("": it does)
    long next_state(long k) const { return k + 1 < static_cast<long>(states.size()) ? k + 1 : prefix; }
};

/// The distinct frame parts from reset until one repeats; empty when more than `limit`.
std::vector<ControlRegisters> frame_states(const Formats& f, const Geometry& g, long limit, long& prefix) {
    HarrisTopT<DynamicFormats> m(g, DynamicFormats{f});
    std::map<ControlRegisters, long> seen;
    std::vector<ControlRegisters> seq;
    for (;;) {
        const ControlRegisters c = frame_part(m.control());
        if (const auto s = seen.find(c); s != seen.end()) {
            prefix = s->second;
            return seq;
        }
        if (static_cast<long>(seq.size()) >= limit) return {};
        seen.emplace(c, static_cast<long>(seq.size()));
        seq.push_back(c);
        m.write(0x80808080U);   // any pixels: the control registers do not read them
    }
}

/// The model's control (ModelControl), its run checked write by write until its whole control
/// state repeats (at most `max_writes` writes): the frame part after each write is the next
/// state's, and the counter moves by one rule per state: unchanged, or +1 but for one wrap.
ModelControl model_control(const Formats& f, const Geometry& g, long limit, long max_writes) {
    ModelControl mc;
    mc.states = frame_states(f, g, limit, mc.prefix);
    if (mc.states.empty()) return mc;
    mc.advances.assign(mc.states.size(), -1);
    HarrisTopT<DynamicFormats> m(g, DynamicFormats{f});
    ControlRegisters c = m.control(), back;
    mc.count0 = mc.lo = mc.hi = c.count;
    const auto fail = [&](const std::string& why) {
        mc.fault = fmt::format("the model after write {}: {}", mc.writes, why);
        return mc;
    };
    for (long k = 0;; k = mc.next_state(k)) {
        if (mc.writes == mc.prefix) back = c;
        else if (k == mc.prefix && mc.writes > mc.prefix && c == back) return mc;   // its whole control state repeats
        if (mc.writes >= max_writes) return fail(fmt::format("its control state did not repeat within {} writes", max_writes));
        m.write(0x80808080U);
        ++mc.writes;
        const ControlRegisters n = m.control();
        if (frame_part(n) != mc.states[mc.next_state(k)]) return fail("its frame part is not the next state's");
        const signed char adv = n.count != c.count;
        if (mc.advances[k] == -1) mc.advances[k] = adv;
        if (mc.advances[k] != adv) return fail(fmt::format("state {} moves find_max's counter on one visit and not on another", k));
        if (adv && n.count != c.count + 1) {
            if (mc.wrap_from == -1) std::tie(mc.wrap_from, mc.wrap_to) = std::pair{c.count, n.count};
            if (mc.wrap_from != c.count || mc.wrap_to != n.count) return fail("find_max's counter wraps at two values");
        }
        mc.lo = std::min(mc.lo, n.count);
        mc.hi = std::max(mc.hi, n.count);
        c = n;
    }
}

/// The transition cut to the cone of the control registers' next values (cone.smt2): every
/// other output stops being one and the logic that drives only those goes; every register
/// stays an input (free in the queries), so the cut keeps each next control value's function.
std::string control_cone(const std::vector<Flop>& flops, const fs::path& dir) {
    std::string keep;
    for (const auto& f : flops) keep += " w:" + f.name + ".d";
    util::write_file_atomic(dir / "cone.ys", fmt::format("read_rtlil top.il\nselect -set keep{}\nselect -assert-count {} @keep\n"
                                                         "delete -output w:* @keep %d\nopt_clean -purge\nwrite_smt2 -wires cone.smt2\n",
                                                         keep, flops.size()));
    const fs::path log = dir / "yosys-cone.log";
    fs::remove(log);
    if (util::run_process({"yosys", "-q", "-s", "cone.ys"}, {.cwd = dir, .log = log}) != 0)
        throw SimulatorError("yosys could not cut harris_top's transition to its control registers: " + util::log_tail(log, 1500));
    return util::read_file(dir / "cone.smt2");
}

std::string term(const Flop& f, const char* side) { return fmt::format("(|top_n {}.{}| s)", f.name, side); }

/// find_max's counter: the last of control_regs().
constexpr size_t kCount = 6;

/// Register r's value in state k of the frame part as an SMT literal.
std::string literal(const std::vector<Flop>& flops, const ModelControl& mc, long k, size_t r) {
    const std::uint64_t v = control_regs()[r].bits(mc.states[k], flops[r].w);
    return flops[r].w == 1 ? (v ? "true" : "false") : fmt::format("(_ bv{} {})", v, flops[r].w);
}

/// The model's next value of find_max's counter from its current one, `advances` a Bool term.
std::string next_count(const std::vector<Flop>& flops, const ModelControl& mc, const std::string& advances) {
    const Flop& n = flops[kCount];
    const std::string q = term(n, "q"), inc = fmt::format("(bvadd {} (_ bv1 {}))", q, n.w);
    const std::string moved =
        mc.wrap_from < 0 ? inc : fmt::format("(ite (= {} (_ bv{} {})) (_ bv{} {}) {})", q, mc.wrap_from, n.w, mc.wrap_to, n.w, inc);
    return fmt::format("(ite {} {} {})", advances, moved, q);
}

/// Two functions of the frame part's values, so that each state's checks name only its values:
/// `at` (the current frame part holds them, find_max's counter any value the model's takes)
/// and `step` (a next control register differs from the model's: the frame part from the
/// given next values, the counter by the model's rule).
std::string definitions(const std::vector<Flop>& flops, const ModelControl& mc) {
    std::string params, at = "(and", step = "(or";
    for (size_t r = 0; r < kCount; ++r) {
        params += fmt::format(" (v{} {})", r, flops[r].w == 1 ? std::string("Bool") : fmt::format("(_ BitVec {})", flops[r].w));
        at += fmt::format(" (= {} v{})", term(flops[r], "q"), r);
        step += fmt::format(" (not (= {} v{}))", term(flops[r], "d"), r);
    }
    const Flop& n = flops[kCount];
    at += fmt::format(" (bvule (_ bv{} {}) {}) (bvule {} (_ bv{} {})))", mc.lo, n.w, term(n, "q"), term(n, "q"), mc.hi, n.w);
    step += fmt::format(" (not (= {} {})))", term(n, "d"), next_count(flops, mc, "adv"));
    return fmt::format("(define-fun at ({}) Bool {})\n(define-fun step ({} (adv Bool)) Bool {})\n", params, at, params, step);
}

/// The frame part's values of state k, the arguments of `at` and `step`.
std::string values(const std::vector<Flop>& flops, const ModelControl& mc, long k) {
    std::string v;
    for (size_t r = 0; r < kCount; ++r) v += " " + literal(flops, mc, k, r);
    return v;
}

/// Which next control register differs at state k (a query per register); "" if none does.
std::string differing(const std::string& head, const std::vector<Flop>& flops, const ModelControl& mc, long k, const fs::path& dir) {
    std::string text = head + fmt::format("(assert (at{}))\n", values(flops, mc, k));
    const long next = mc.next_state(k);
    for (size_t r = 0; r < flops.size(); ++r) {
        const std::string model = r == kCount ? next_count(flops, mc, mc.advances[k] ? "true" : "false") : literal(flops, mc, next, r);
        text += fmt::format("(push 1)\n(assert (not (= {} {})))\n(check-sat)\n(pop 1)\n", term(flops[r], "d"), model);
    }
    util::write_file_atomic(dir / "which.smt2", text);
    util::run_process({"z3", "-smt2", "which.smt2"}, {.cwd = dir, .log = dir / "z3-which.log", .stdout_file = dir / "z3-which.txt"});
    const std::vector<std::string> a = solver_answers(dir / "z3-which.txt");
    std::string s;
    for (size_t r = 0; r < flops.size() && r < a.size(); ++r) {
        if (a[r] != "sat") continue;
        const std::string model = r != kCount ? std::to_string(control_regs()[r].bits(mc.states[next], flops[r].w))
                                  : mc.advances[k]  ? "count + 1, wrapping"
                                                    : "count, unchanged";
        s += fmt::format("{}{} (model {})", s.empty() ? "" : ", ", control_regs()[r].name, model);
    }
    return s;
}

/// cvc5 answers the states' checks again, in parts of at most kPartStates states (each part the
/// head and its states' checks, cvc5-part-N.smt2) run side by side on o.recheck_jobs cores;
/// sets p.recheck and p.rechecked (every state sat then unsat). A sat on a step where z3 said
/// unsat is a fault of one of the solvers (std::logic_error).
void recheck_with_cvc5(const std::string& head, const std::vector<std::string>& blocks, const fs::path& dir,
                       const ControlInductionOptions& o, ControlInduction& p) {
    constexpr size_t kPartStates = 20'000;
    const size_t parts = (blocks.size() + kPartStates - 1) / kPartStates;
    std::vector<long> unsat(parts, 0);
    std::vector<std::string> failed(parts), contradiction(parts);
    const auto run_part = [&](size_t j) {
        const size_t first = j * kPartStates, last = std::min(blocks.size(), first + kPartStates);
        std::string text = head;
        for (size_t k = first; k < last; ++k) text += blocks[k];
        const std::string name = fmt::format("cvc5-part-{}", j);
        util::write_file_atomic(dir / (name + ".smt2"), text);
        try {
            util::run_process({"cvc5", "--lang=smt2", "--incremental", fmt::format("--tlimit={}", o.recheck_seconds * 1000), name + ".smt2"},
                              {.cwd = dir, .log = dir / (name + ".log"), .stdout_file = dir / (name + "-answer.txt")});
        } catch (const SimulatorError& e) {
            failed[j] = e.what();
            return;
        }
        const std::vector<std::string> c = solver_answers(dir / (name + "-answer.txt"));
        for (size_t k = 0; 2 * k + 1 < c.size(); ++k) {
            if (c[2 * k + 1] == "sat" && contradiction[j].empty()) contradiction[j] = fmt::format("write {}", first + k);
            unsat[j] += c[2 * k] == "sat" && c[2 * k + 1] == "unsat";
        }
    };
    tbb::task_arena arena(o.recheck_jobs > 0 ? o.recheck_jobs : int(tbb::task_arena::automatic));
    arena.execute([&] { tbb::parallel_for(size_t{0}, parts, run_part); });
    for (size_t j = 0; j < parts; ++j) {
        if (!contradiction[j].empty())
            throw std::logic_error("control induction: z3 proves " + p.command + ", cvc5 finds a difference at " + contradiction[j]);
        if (!failed[j].empty()) {
            p.recheck = "cvc5: not run: " + failed[j];
            return;
        }
    }
    const long total = std::accumulate(unsat.begin(), unsat.end(), 0L);
    p.rechecked = total == p.queries;
    p.recheck = fmt::format("cvc5: {} unsat of {}", total, p.queries);
}

}  // namespace

HarrisTopNetlist synthesise_harris_top(const Formats& f, const Geometry& g, const fs::path& dir, const fs::path& rtl_dir,
                                       const HarrisTopScript& s) {
    fs::create_directories(dir / "work");
    std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + (dir / "work").string()};
    std::string gens, sources;
    for (const auto& [name, v] : generics(g, f)) gens += fmt::format(" -g{}={}", name, v);
    gens += " -gOBSERVE=false";
    std::istringstream gs(gens);
    for (std::string x; gs >> x;) argv.push_back(x);
    argv.push_back("--out=verilog");
    for (const auto& src : cosim::rtl_sources(rtl_dir)) {
        argv.push_back(src.string());
        sources += " " + src.string();
    }
    argv.insert(argv.end(), {"-e", "harris_top"});
    const fs::path log = dir / "synth.log";
    if (cosim::synth_verilog(argv, dir / "harris_top.v", {.log = log}) != 0)
        throw SimulatorError("ghdl --synth of harris_top failed: " + util::log_tail(log, 1500));
    util::write_file_atomic(dir / "top.v", s.top_v);
    util::write_file_atomic(dir / "top.ys", s.script);
    const fs::path ylog = dir / "yosys.log";
    fs::remove(ylog);
    if (util::run_process({"yosys", "-q", "-s", "top.ys"}, {.cwd = dir, .log = ylog}) != 0)
        throw SimulatorError("yosys could not write harris_top's transition as SMT-LIB: " + util::log_tail(ylog, 1500));
    util::write_file_atomic(dir / "commands.txt", fmt::format("ghdl --synth --std=08 --workdir=work{} --out=verilog{} -e harris_top | {} > harris_top.v\n{}",
                                                              gens, sources, cosim::kSizedBitLiteralsFilter, s.commands));
    return {util::read_file(dir / "harris_top.v"), util::read_file(dir / "top.smt2")};
}

std::vector<std::string> solver_answers(const fs::path& file) {
    std::vector<std::string> v;
    std::istringstream in(fs::exists(file) ? util::read_file(file) : "");
    for (std::string l; std::getline(in, l);)
        if (l == "sat" || l == "unsat" || l == "unknown") v.push_back(l);
    return v;
}

ControlInduction prove_control_from_reset(const Formats& f, const Geometry& g, const ControlInductionOptions& o) {
    const auto t0 = Clock::now();
    ControlInduction p;
    p.geometry = g;
    const util::ScratchDir scratch("control-induction");
    const fs::path dir = fs::absolute(o.dir.empty() ? scratch.path() : o.dir);
    fs::create_directories(dir);
    const auto done = [&] {
        p.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        return p;
    };
    const ModelControl mc = model_control(f, g, o.max_states, o.max_writes);
    if (mc.states.empty()) {
        p.detail = fmt::format("more than {} distinct control states (less find_max's counter) from reset", o.max_states);
        return done();
    }
    if (!mc.fault.empty()) {
        p.detail = mc.fault;
        return done();
    }
    p.prefix = mc.prefix;
    p.period = static_cast<long>(mc.states.size()) - p.prefix;
    p.queries = static_cast<long>(mc.states.size());
    p.model_writes = mc.writes;
    p.count_range = {mc.lo, mc.hi};
    const auto [verilog, smt] = synthesise(f, g, dir, o.rtl_dir);
    const std::vector<Flop> flops = resolve(verilog, smt);
    for (size_t r = 0; r < flops.size(); ++r)
        p.registers.push_back(fmt::format("{} = {} ({} bit{})", control_regs()[r].name, flops[r].name, flops[r].w, flops[r].w == 1 ? "" : "s"));
    // the base: the netlist's reset state is the model's
    ControlRegisters reset = mc.states[0];
    reset.count = mc.count0;
    for (size_t r = 0; r < flops.size(); ++r)
        if (flops[r].reset != control_regs()[r].bits(reset, flops[r].w)) {
            p.verdict = EqVerdict::counterexample;
            p.detail = fmt::format("reset: {} is {} on the netlist, {} in the model", control_regs()[r].name, flops[r].reset,
                                   control_regs()[r].bits(reset, flops[r].w));
            return done();
        }
    const std::string head = "(set-logic ALL)\n" + control_cone(flops, dir) + "(declare-fun s () |top_s|)\n(assert (|top_h| s))\n" +
                             definitions(flops, mc);
    std::vector<std::string> blocks;   // each state's two checks
    for (long k = 0; k < p.queries; ++k)
        // the first check (sat) shows the state is one the netlist's constraints admit, so the second's unsat is not vacuous
        blocks.push_back(fmt::format("; write {}\n(push 1)\n(assert (at{}))\n(check-sat)\n(assert (step{} {}))\n(check-sat)\n(pop 1)\n", k,
                                     values(flops, mc, k), values(flops, mc, mc.next_state(k)), mc.advances[k] ? "true" : "false"));
    std::string text = head;
    for (const auto& b : blocks) text += b;
    util::write_file_atomic(dir / "query.smt2", text);
    p.command = fmt::format("z3 -smt2 {}", (dir / "query.smt2").string());
    util::run_process({"z3", "-smt2", "query.smt2"}, {.cwd = dir, .log = dir / "z3.log", .stdout_file = dir / "z3-answer.txt"});
    const std::vector<std::string> a = solver_answers(dir / "z3-answer.txt");
    for (size_t k = 0; k < static_cast<size_t>(p.queries); ++k) {
        const std::string held = 2 * k < a.size() ? a[2 * k] : "no answer", ans = 2 * k + 1 < a.size() ? a[2 * k + 1] : "no answer";
        if (held == "sat" && ans == "unsat") continue;
        if (held == "sat" && ans == "sat") {
            p.verdict = EqVerdict::counterexample;
            p.detail = fmt::format("write {}: the netlist's next {} differs from the model's", k, differing(head, flops, mc, static_cast<long>(k), dir));
        } else {
            p.detail = fmt::format("write {}: z3 {} on the state alone (sat expected), {} on the step ({})", k, held, ans,
                                   util::log_tail(dir / "z3.log", 300));
        }
        return done();
    }
    p.verdict = EqVerdict::equal;
    if (o.recheck) recheck_with_cvc5(head, blocks, dir, o, p);
    return done();
}

std::string control_induction_markdown(const std::string& config, const std::vector<ControlInduction>& r) {
    std::string s = fmt::format("## Control registers from reset: {}\n\n"
                                "| size | verdict | prefix | period | queries | model writes | find_max's counter | second solver | seconds | detail | command |\n"
                                "|---|---|---:|---:|---:|---:|---|---|---:|---|---|\n",
                                config);
    for (const auto& p : r)
        s += fmt::format("| {}x{} | {} | {} | {} | {} | {} | {} | {} | {:.1f} | {} | `{}` |\n", p.geometry.width, p.geometry.height,
                         eq_verdict_name(p.verdict), p.prefix, p.period, p.queries, p.model_writes,
                         p.model_writes > 0 ? fmt::format("{}..{}", p.count_range.first, p.count_range.second) : std::string("-"),
                         p.recheck.empty() ? "-" : p.recheck, p.seconds, p.detail.empty() ? "-" : p.detail, p.command);
    return s;
}

}  // namespace hc::sweep

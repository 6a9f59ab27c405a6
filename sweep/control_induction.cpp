// control_induction.cpp: the control registers of GHDL's netlist of harris_top against the
// cycle model's, state by state from reset (see control_induction.hpp).
#include "sweep/control_induction.hpp"

#include <chrono>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/format.h>

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

/// GHDL's and yosys's commands in `dir`; returns (GHDL's Verilog, the SMT-LIB transition) and
/// writes commands.txt.
std::pair<std::string, std::string> synthesise(const Formats& f, const Geometry& g, const fs::path& dir, const fs::path& rtl_dir) {
    fs::create_directories(dir / "work");
    std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + (dir / "work").string()};
    std::string gens, sources;
    for (const auto& [name, v] : generics(g, f)) gens += fmt::format(" -g{}={}", name, v);
    gens += " -gOBSERVE=false";
    std::istringstream gs(gens);
    for (std::string x; gs >> x;) argv.push_back(x);
    argv.push_back("--out=verilog");
    for (const auto& s : cosim::rtl_sources(rtl_dir)) {
        argv.push_back(s.string());
        sources += " " + s.string();
    }
    argv.insert(argv.end(), {"-e", "harris_top"});
    const fs::path log = dir / "synth.log";
    if (cosim::synth_verilog(argv, dir / "harris_top.v", {.log = log}) != 0)
        throw SimulatorError("ghdl --synth of harris_top failed: " + util::log_tail(log, 1500));
    util::write_file_atomic(dir / "top.v",
                            "module top(input clk, input [31:0] data, output [31:0] corner);\n"
                            "  harris_top u(.clk(clk), .rst(1'b1), .write(1'b1), .data(data), .corner(corner));\nendmodule\n");
    util::write_file_atomic(dir / "top.ys",
                            "read_verilog harris_top.v top.v\nhierarchy -top top\nproc\nflatten\nopt -nosdff -nodffe\n"
                            "select -assert-none t:$*latch* t:$sr t:$mem* t:$*dff* t:$dff %d\n"
                            "opt_clean -purge\nexpose -evert-dff\nopt_clean\nselect -assert-none t:$dff\n"
                            "write_rtlil top.il\nwrite_smt2 -wires top.smt2\n");
    const fs::path ylog = dir / "yosys.log";
    fs::remove(ylog);
    if (util::run_process({"yosys", "-q", "-s", "top.ys"}, {.cwd = dir, .log = ylog}) != 0)
        throw SimulatorError("yosys could not write harris_top's transition as SMT-LIB: " + util::log_tail(ylog, 1500));
    util::write_file_atomic(dir / "commands.txt",
                            fmt::format("ghdl --synth --std=08 --workdir=work{} --out=verilog{} -e harris_top | {} > harris_top.v\n"
                                        "yosys -q -s top.ys    # writes top.il and top.smt2\n"
                                        "yosys -q -s cone.ys   # writes cone.smt2\n",
                                        gens, sources, cosim::kSizedBitLiteralsFilter));
    return {util::read_file(dir / "harris_top.v"), util::read_file(dir / "top.smt2")};
}

/// The model's control states from reset until one repeats: the distinct states in order
/// (prefix then period); `prefix` set. Empty when more than `limit` are distinct.
std::vector<ControlRegisters> control_states(const Formats& f, const Geometry& g, long limit, long& prefix) {
    HarrisTopT<DynamicFormats> m(g, DynamicFormats{f});
    std::map<ControlRegisters, long> seen;
    std::vector<ControlRegisters> seq;
    for (;;) {
        const ControlRegisters c = m.control();
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
/// `flop.side = v` (yosys writes a one-bit net as a Bool).
std::string equal(const Flop& f, const char* side, std::uint64_t v) {
    if (f.w == 1) return v ? term(f, side) : fmt::format("(not {})", term(f, side));
    return fmt::format("(= {} (_ bv{} {}))", term(f, side), v, f.w);
}

/// The assertions "the control registers hold c" on the current registers.
std::string at_state(const std::vector<Flop>& flops, const ControlRegisters& c) {
    std::string s = "(assert (and";
    for (size_t r = 0; r < flops.size(); ++r) s += " " + equal(flops[r], "q", control_regs()[r].bits(c, flops[r].w));
    return s + "))\n";
}

/// The answers of a solver's run of a file of checks, one word each ("unsat", "sat", ...).
std::vector<std::string> answers(const fs::path& file) {
    std::vector<std::string> v;
    std::istringstream in(fs::exists(file) ? util::read_file(file) : "");
    for (std::string l; std::getline(in, l);)
        if (l == "sat" || l == "unsat" || l == "unknown") v.push_back(l);
    return v;
}

/// Which next control register differs at state k (a query per register); "" if none does.
std::string differing(const std::string& head, const std::vector<Flop>& flops, const ControlRegisters& c, const ControlRegisters& next,
                      const fs::path& dir) {
    std::string text = head + at_state(flops, c);
    for (size_t r = 0; r < flops.size(); ++r)
        text += fmt::format("(push 1)\n(assert (not {}))\n(check-sat)\n(pop 1)\n", equal(flops[r], "d", control_regs()[r].bits(next, flops[r].w)));
    util::write_file_atomic(dir / "which.smt2", text);
    util::run_process({"z3", "-smt2", "which.smt2"}, {.cwd = dir, .log = dir / "z3-which.log", .stdout_file = dir / "z3-which.txt"});
    const std::vector<std::string> a = answers(dir / "z3-which.txt");
    std::string s;
    for (size_t r = 0; r < flops.size() && r < a.size(); ++r)
        if (a[r] == "sat")
            s += fmt::format("{}{} (model {})", s.empty() ? "" : ", ", control_regs()[r].name, control_regs()[r].bits(next, flops[r].w));
    return s;
}

}  // namespace

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
    const std::vector<ControlRegisters> states = control_states(f, g, o.max_states, p.prefix);
    if (states.empty()) {
        p.detail = fmt::format("more than {} distinct control states from reset", o.max_states);
        return done();
    }
    p.period = static_cast<long>(states.size()) - p.prefix;
    p.queries = static_cast<long>(states.size());
    const auto [verilog, smt] = synthesise(f, g, dir, o.rtl_dir);
    const std::vector<Flop> flops = resolve(verilog, smt);
    for (size_t r = 0; r < flops.size(); ++r)
        p.registers.push_back(fmt::format("{} = {} ({} bit{})", control_regs()[r].name, flops[r].name, flops[r].w, flops[r].w == 1 ? "" : "s"));
    // the base: the netlist's reset state is c_0
    for (size_t r = 0; r < flops.size(); ++r)
        if (flops[r].reset != control_regs()[r].bits(states[0], flops[r].w)) {
            p.verdict = EqVerdict::counterexample;
            p.detail = fmt::format("reset: {} is {} on the netlist, {} in the model", control_regs()[r].name, flops[r].reset,
                                   control_regs()[r].bits(states[0], flops[r].w));
            return done();
        }
    const std::string head = "(set-logic ALL)\n" + control_cone(flops, dir) + "(declare-fun s () |top_s|)\n(assert (|top_h| s))\n";
    std::string text = head;
    for (size_t k = 0; k < states.size(); ++k) {
        const ControlRegisters& next = states[k + 1 < states.size() ? k + 1 : static_cast<size_t>(p.prefix)];
        std::string differs;
        for (size_t r = 0; r < flops.size(); ++r) differs += " (not " + equal(flops[r], "d", control_regs()[r].bits(next, flops[r].w)) + ")";
        // the first check (sat) shows the state is one the netlist's constraints admit, so the second's unsat is not vacuous
        text += fmt::format("; write {}\n(push 1)\n{}(check-sat)\n(assert (or{}))\n(check-sat)\n(pop 1)\n", k, at_state(flops, states[k]),
                            differs);
    }
    util::write_file_atomic(dir / "query.smt2", text);
    p.command = fmt::format("z3 -smt2 {}", (dir / "query.smt2").string());
    util::run_process({"z3", "-smt2", "query.smt2"}, {.cwd = dir, .log = dir / "z3.log", .stdout_file = dir / "z3-answer.txt"});
    const std::vector<std::string> a = answers(dir / "z3-answer.txt");
    for (size_t k = 0; k < states.size(); ++k) {
        const std::string held = 2 * k < a.size() ? a[2 * k] : "no answer", ans = 2 * k + 1 < a.size() ? a[2 * k + 1] : "no answer";
        if (held == "sat" && ans == "unsat") continue;
        if (held == "sat" && ans == "sat") {
            p.verdict = EqVerdict::counterexample;
            const ControlRegisters& next = states[k + 1 < states.size() ? k + 1 : static_cast<size_t>(p.prefix)];
            p.detail = fmt::format("write {}: the netlist's next {} differs from the model's", k, differing(head, flops, states[k], next, dir));
        } else {
            p.detail = fmt::format("write {}: z3 {} on the state alone (sat expected), {} on the step ({})", k, held, ans,
                                   util::log_tail(dir / "z3.log", 300));
        }
        return done();
    }
    p.verdict = EqVerdict::equal;
    if (o.recheck) {
        const fs::path out = dir / "cvc5-answer.txt";
        try {
            util::run_process({"cvc5", "--lang=smt2", "--incremental", fmt::format("--tlimit={}", o.recheck_seconds * 1000), "query.smt2"},
                              {.cwd = dir, .log = dir / "cvc5.log", .stdout_file = out});
            const std::vector<std::string> c = answers(out);
            long unsat = 0;
            for (size_t k = 0; 2 * k + 1 < c.size(); ++k) {
                if (c[2 * k + 1] == "sat") throw std::logic_error("control induction: z3 proves " + p.command + ", cvc5 finds a difference");
                unsat += c[2 * k] == "sat" && c[2 * k + 1] == "unsat";
            }
            p.rechecked = unsat == p.queries;
            p.recheck = fmt::format("cvc5: {} unsat of {}", unsat, p.queries);
        } catch (const SimulatorError& e) {
            p.recheck = std::string("cvc5: not run: ") + e.what();
        }
    }
    return done();
}

std::string control_induction_markdown(const std::string& config, const std::vector<ControlInduction>& r) {
    std::string s = fmt::format("## Control registers from reset: {}\n\n"
                                "| size | verdict | prefix | period | queries | second solver | seconds | detail | command |\n"
                                "|---|---|---:|---:|---:|---|---:|---|---|\n",
                                config);
    for (const auto& p : r)
        s += fmt::format("| {}x{} | {} | {} | {} | {} | {} | {:.1f} | {} | `{}` |\n", p.geometry.width, p.geometry.height,
                         eq_verdict_name(p.verdict), p.prefix, p.period, p.queries, p.recheck.empty() ? "-" : p.recheck, p.seconds,
                         p.detail.empty() ? "-" : p.detail, p.command);
    return s;
}

}  // namespace hc::sweep

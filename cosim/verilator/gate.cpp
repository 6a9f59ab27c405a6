// gate.cpp: see gate.hpp.
#include "cosim/verilator/gate.hpp"

#include <unistd.h>

#include <chrono>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "model/harris/observation.hpp"
#include "cosim/verilator/lockstep.hpp"
#include "model/util/util.hpp"

namespace hc::vl {

namespace fs = std::filesystem;

namespace {

std::string hex(std::uint64_t v) {
    std::ostringstream s;
    s << "0x" << std::hex << v;
    return s.str();
}

void must(int rc, const std::string& what, const fs::path& log) {
    if (rc == 0) return;
    throw SimulatorError(what + " failed (exit " + std::to_string(rc) + "); log " + log.string() + ":\n" +
                         util::log_tail(log));
}

// GHDL library with the design (variants substituted) and the replay testbench analysed.
fs::path ghdl_library(const std::vector<fs::path>& sources, const fs::path& cache_dir, std::ostream& log) {
    const fs::path tb = HCVL_REPLAY_TB;   // made by CMake from ghdl_replay_tb.vhd.in
    std::uint64_t h = util::fnv1a(HCVL_TOOL_VERSIONS);
    for (const auto& p : sources) h = util::fnv1a(p.filename().string() + util::read_file(p), h);
    h = util::fnv1a(util::read_file(tb), h);
    char key[32];
    std::snprintf(key, sizeof key, "ghdl_%012llx", static_cast<unsigned long long>(h & 0xffffffffffffULL));
    const fs::path dir = cache_dir / key;
    if (fs::exists(dir / "done")) return dir;
    const fs::path tmp = cache_dir / (std::string(key) + ".tmp" + std::to_string(getpid()));
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    log << "gate: analysing the VHDL with GHDL into " << dir.string() << '\n' << std::flush;
    std::vector<std::string> a = {HCVL_GHDL, "-a", "--std=08", "--workdir=."};
    for (const auto& p : sources) a.push_back(p.string());
    a.push_back(tb.string());
    must(util::run_process(a, {.cwd = tmp, .log = tmp / "analysis.log"}), "GHDL analysis", tmp / "analysis.log");
    std::ofstream(tmp / "done") << "ok\n";
    std::error_code ec;
    fs::rename(tmp, dir, ec);
    if (ec) fs::remove_all(tmp);
    return dir;
}

// What one simulator left on its ports after a write.
struct Sample {
    std::uint32_t corner = 0;
    std::string obs;   // GHDL: std_ulogic characters, obs(0) first; empty without obs
};

struct Side {
    std::vector<Sample> ghdl;
};

std::string element_name(const ObsField& f, const ObsSlot& s) {
    return f.name + (f.elements() > 1 ? "(" + std::to_string(s.row) + "," + std::to_string(s.col) + ")" : "");
}

// Value of a slot in GHDL's obs string; nullopt when any of its bits is not '0'/'1'.
std::optional<std::uint64_t> ghdl_value(const std::string& obs, const ObsSlot& s, int obs_bits) {
    const int msb_p = obs_bits - 1 - (s.lsb + s.width - 1);   // VHDL index of the MSB
    std::uint64_t v = 0;
    for (int k = 0; k < s.width; ++k) {
        const char ch = obs[static_cast<std::size_t>(msb_p + k)];
        if (ch != '0' && ch != '1') return std::nullopt;
        v = (v << 1) | static_cast<std::uint64_t>(ch == '1');
    }
    return v;
}

}  // namespace

std::vector<GateCase> gate_cases() {
    using P = Pattern;
    return {
        {"10x10 random,extremes,checkerboard,blocks (smallest chainable size)", {10, 10},
         {P::random, P::extremes, P::checkerboard, P::blocks}},
        {"37x21 blocks,random,extremes,checkerboard (odd, several window rows)", {37, 21},
         {P::blocks, P::random, P::extremes, P::checkerboard}},
    };
}

namespace {
NetlistConfig gate_netlist(const GateCase& gc, const Formats& f, const std::vector<fs::path>& variants) {
    NetlistConfig nc{gc.g, f, true, variants};
    nc.optimise = false;
    return nc;
}
}  // namespace

const char* verdict_name(GateVerdict v) {
    switch (v) {
        case GateVerdict::pass: return "pass";
        case GateVerdict::translation_fault: return "translation fault";
        case GateVerdict::rtl_fault: return "RTL fault";
    }
    return "?";
}

namespace {

// One gate case's stream, once, shared by the three sides.
std::vector<BusEvent> case_stream(const GateCase& gc) {
    std::vector<Image> imgs;
    for (std::size_t k = 0; k < gc.patterns.size(); ++k)
        imgs.push_back(make_pattern(gc.patterns[k], gc.g.width, gc.g.height, static_cast<int>(k), 7));
    std::vector<const Image*> ptrs;
    for (const auto& im : imgs) ptrs.push_back(&im);
    HostDriver drv(gc.g, ptrs);
    std::vector<BusEvent> events;
    for (BusEvent ev; drv.next(ev);) events.push_back(ev);
    return events;
}

// GHDL: the stream replayed through the VHDL (library `lib`), one sample a write.
std::vector<Sample> ghdl_replay(const GateCase& gc, const Formats& f, const fs::path& lib, const fs::path& cache_dir,
                                const std::vector<BusEvent>& events) {
    const fs::path run_dir = cache_dir / ("gate_run" + std::to_string(getpid()));
    fs::create_directories(run_dir);
    {
        std::ofstream stim(run_dir / "stim.txt");
        char buf[16];
        for (const auto& ev : events) {
            std::snprintf(buf, sizeof buf, "%08X\n", ev.data);
            stim << buf;
        }
    }
    // mcode takes top-level generics as run options, after the unit name
    std::vector<std::string> cmd = {HCVL_GHDL, "--elab-run", "--std=08", "--workdir=" + lib.string(),
                                    "ghdl_replay_tb"};
    for (const auto& [name, value] : generics(gc.g, f)) cmd.push_back("-g" + name + "=" + std::to_string(value));
    // power-up 'U' values make numeric_std warn at time 0 only; they say nothing here
    cmd.insert(cmd.end(), {"-gOBSERVE=true", "-gSTIM=stim.txt", "-gRESULT=result.txt",
                           "--ieee-asserts=disable-at-0"});
    fs::remove(run_dir / "ghdl.log");
    must(util::run_process(cmd, {.cwd = run_dir, .log = run_dir / "ghdl.log"}), "GHDL simulation of " + gc.name, run_dir / "ghdl.log");
    std::vector<Sample> ghdl;
    {
        std::ifstream in(run_dir / "result.txt");
        std::string line;
        while (std::getline(in, line)) {
            Sample s;
            s.corner = static_cast<std::uint32_t>(std::stoul(line.substr(0, 8), nullptr, 16));
            if (line.size() > 9) s.obs = line.substr(9);
            ghdl.push_back(std::move(s));
        }
    }
    fs::remove_all(run_dir);
    if (ghdl.size() != events.size())
        throw std::runtime_error("GHDL replay of " + gc.name + " returned " + std::to_string(ghdl.size()) +
                                 " writes, expected " + std::to_string(events.size()));
    return ghdl;
}

// The first disagreements of a case: GHDL against Verilator (translation), GHDL against the
// model (RTL); empty where none.
struct CaseFaults {
    std::string translation, rtl;
    long reads = 0, obs_compared = 0;
};

// Verilator: the netlist this geometry and these formats synthesise to, in lock step with
// the model, against GHDL's samples, until both kinds of fault are found.
CaseFaults compare_case(const GateCase& gc, const Formats& f, const std::vector<fs::path>& variants,
                        const fs::path& cache_dir, std::ostream& log, const std::vector<BusEvent>& events,
                        const std::vector<Sample>& ghdl) {
    const auto layout = obs_layout(f);
    const NetlistConfig nc = gate_netlist(gc, f, variants);
    VerilatedDesign dut(build_netlist(nc, cache_dir, log), config_key(nc));
    const int nbits = dut.obs_bits();
    const auto slots = obs_slots(f, nbits);
    HarrisTop model(gc.g, f);

    CaseFaults c;
    for (std::size_t w = 0; w < events.size(); ++w) {
        model.write(events[w].data);
        dut.write(events[w].data);
        if (events[w].read) ++c.reads;
        const std::string where = gc.name + ", write " + std::to_string(w + 1) +
                                  (events[w].read ? " (a read)" : "");
        const std::uint32_t cg = ghdl[w].corner, cv = dut.corner(), cm = model.corner();
        if (c.translation.empty() && cg != cv)
            c.translation = where + ": corner GHDL " + hex(cg) + ", Verilator " + hex(cv) + ", model " + hex(cm);
        if (c.rtl.empty() && cg != cm)
            c.rtl = where + ": corner GHDL " + hex(cg) + ", model " + hex(cm);
        // observation port: GHDL vs Verilator bit by bit (defined GHDL bits only), and
        // GHDL vs model element by element
        if (ghdl[w].obs.size() != static_cast<std::size_t>(nbits))
            throw std::runtime_error("GHDL obs is " + std::to_string(ghdl[w].obs.size()) + " bits, netlist " +
                                     std::to_string(nbits));
        const auto& words = dut.obs();
        const FlatObservation flat = flatten(model.observe(), f);
        for (std::size_t k = 0; k < slots.size(); ++k) {
            if (!c.translation.empty() && !c.rtl.empty()) break;
            const auto g = ghdl_value(ghdl[w].obs, slots[k], nbits);
            if (!g) continue;
            const std::uint64_t v = obs_value(words, slots[k]);
            const std::uint64_t m = flat.bits[k] & (slots[k].width >= 64 ? ~0ULL : (1ULL << slots[k].width) - 1);
            const ObsField& fld = layout[static_cast<std::size_t>(slots[k].field)];
            const std::string sig = element_name(fld, slots[k]) + " (" + fld.stage + ")";
            if (c.translation.empty() && *g != v)
                c.translation = where + ": " + sig + " GHDL " + hex(*g) + ", Verilator " + hex(v) + ", model " +
                                (flat.defined[k] ? hex(m) : std::string("undefined")) +
                                (flat.defined[k] && m == *g ? " (GHDL agrees with the model)" : "");
            if (c.rtl.empty() && flat.defined[k] && *g != m)
                c.rtl = where + ": " + sig + " GHDL " + hex(*g) + ", model " + hex(m);
        }
        ++c.obs_compared;
        if (!c.translation.empty() && !c.rtl.empty()) break;
    }
    return c;
}

}  // namespace

GateResult run_gate(const Formats& f, const std::vector<fs::path>& variants, const fs::path& cache_dir,
                    std::ostream& log) {
    const auto t0 = std::chrono::steady_clock::now();
    GateResult res;
    std::string first_rtl;
    NetlistConfig base{Geometry{}, f, true, variants};
    const fs::path lib = ghdl_library(vhdl_sources(base), cache_dir, log);

    for (const GateCase& gc : gate_cases()) {
        const std::vector<BusEvent> events = case_stream(gc);
        const std::vector<Sample> ghdl = ghdl_replay(gc, f, lib, cache_dir, events);
        const CaseFaults c = compare_case(gc, f, variants, cache_dir, log, events, ghdl);
        res.obs_compared += c.obs_compared;
        res.writes += static_cast<long>(events.size());
        res.reads += c.reads;
        std::string line = gc.name + ": " + std::to_string(events.size()) + " writes, " + std::to_string(c.reads) +
                           " reads: ";
        if (!c.translation.empty()) {
            line += "TRANSLATION FAULT (GHDL != Verilator) at " + c.translation;
            if (res.verdict != GateVerdict::translation_fault) res.first = "translation fault: " + c.translation;
            res.verdict = GateVerdict::translation_fault;
        } else if (!c.rtl.empty()) {
            line += "RTL FAULT (GHDL == Verilator != model) at " + c.rtl;
            if (first_rtl.empty()) first_rtl = "RTL fault: " + c.rtl;
            if (res.verdict == GateVerdict::pass) res.verdict = GateVerdict::rtl_fault;
        } else {
            line += "GHDL, Verilator and model agree on every read and every observed register";
        }
        res.per_case.push_back(line);
        log << "gate: " << line << '\n' << std::flush;
        // a failed gate is failed: the remaining cases (and their netlist builds) add nothing
        if (res.verdict != GateVerdict::pass) break;
    }
    if (res.verdict == GateVerdict::rtl_fault) res.first = first_rtl;
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

std::string gate_key(const Formats& f, const std::vector<fs::path>& variants) {
    std::string keys = util::read_file(HCVL_REPLAY_TB);
    for (const GateCase& gc : gate_cases()) {
        keys += gc.name + '|' + std::to_string(gc.g.width) + 'x' + std::to_string(gc.g.height);
        for (Pattern p : gc.patterns) keys += ',' + pattern_name(p);
        keys += '|' + config_key(gate_netlist(gc, f, variants)) + '\n';
    }
    return util::hex64(util::fnv1a(keys));
}

GateResult run_gate_cached(const Formats& f, const std::vector<fs::path>& variants, const fs::path& cache_dir,
                           std::ostream& log, bool* from_cache) {
    const fs::path marker = cache_dir / ("gate_pass_" + gate_key(f, variants) + ".json");
    if (from_cache) *from_cache = false;
    if (fs::exists(marker)) {
        try {
            const auto j = nlohmann::json::parse(util::read_file(marker));
            GateResult r;
            r.writes = j.at("writes");
            r.reads = j.at("reads");
            r.obs_compared = j.at("obs_compared");
            r.seconds = j.at("seconds");
            r.per_case = j.at("cases").get<std::vector<std::string>>();
            if (from_cache) *from_cache = true;
            return r;
        } catch (const std::exception&) {
            // an unreadable record is no verdict: gate again
        }
    }
    GateResult r = run_gate(f, variants, cache_dir, log);
    if (r.verdict == GateVerdict::pass) {
        const nlohmann::json j = {{"verdict", verdict_name(r.verdict)}, {"writes", r.writes}, {"reads", r.reads},
                                  {"obs_compared", r.obs_compared}, {"seconds", r.seconds}, {"cases", r.per_case}};
        util::write_file_atomic(marker, j.dump(2) + "\n");
    }
    return r;
}

}  // namespace hc::vl

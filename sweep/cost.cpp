// cost.cpp: see cost.hpp.
#include "sweep/cost.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cosim/ghdl_verilog.hpp"
#include "model/util/util.hpp"
#include "sweep/sweep_config.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace hc::sweep {

namespace {

// Bump when the flow (commands, counting, rewrite) changes: old cache entries then miss.
constexpr const char* kFlowVersion = "hc-sweep-cost-3 synth_xilinx (hierarchical)";

/// First line a tool prints for its version flag (part of the cache key).
std::string tool_version(const std::string& tool, const std::string& flag, const fs::path& tmp) {
    const fs::path out = tmp / ("version-" + std::to_string(::getpid()) + ".txt");
    fs::remove(out);
    const int rc = util::run_process({tool, flag}, {.log = out});
    std::string first;
    if (fs::exists(out)) {
        std::ifstream in(out);
        std::getline(in, first);
        fs::remove(out);
    }
    if (rc != 0 || first.empty())
        throw SimulatorError("'" + tool + " " + flag + "' failed (status " + std::to_string(rc) + "): is it installed?");
    return first;
}

json cost_to_json(const Cost& c, const Formats& f, const Geometry& g, Variant v) {
    json gen = json::object();
    for (const auto& [name, val] : generics(g, f)) gen[name] = val;
    json j = c;   // Cost's JSON without the cache state, with what the entry was made from
    j.erase("cached");
    j["variant"] = variant_name(v);
    j["generics"] = gen;
    j["flow"] = kFlowVersion;
    return j;
}

Cost cost_from_cells(const std::map<std::string, long>& cells) {
    Cost c;
    c.cells = cells;
    for (const auto& [type, n] : cells) {
        if (type.rfind("LUT", 0) == 0) c.luts += n;
        else if (type == "INV") c.inv += n;
        else if (type == "FDRE" || type == "FDSE" || type == "FDCE" || type == "FDPE") c.ffs += n;
        else if (type.rfind("DSP48", 0) == 0) c.dsps += n;
        else if (type == "CARRY4") c.carry4 += n;
        else if (type == "MUXF7" || type == "MUXF8") c.muxf += n;
        else if (type.rfind("SRL", 0) == 0) c.srl += n;
    }
    return c;
}

}  // namespace

std::string variant_name(Variant v) { return v == Variant::signed_mul ? "signed" : "ghdl"; }

/// `tool` as a path: itself when it names a file, else its first match on $PATH.
std::string find_tool(const std::string& tool) {
    if (tool.find('/') != std::string::npos) return tool;
    const char* path = std::getenv("PATH");
    if (!path) throw SimulatorError("'" + tool + "' not found: $PATH is not set (needed for the synthesis cost)");
    std::stringstream ss(path);
    for (std::string d; std::getline(ss, d, ':');)
        if (!d.empty() && ::access((fs::path(d) / tool).c_str(), X_OK) == 0) return (fs::path(d) / tool).string();
    throw SimulatorError("'" + tool + "' not found on $PATH (needed for the synthesis cost)");
}

CostContext::CostContext(const CostOptions& o) : opt(o) {
    opt.ghdl = find_tool(opt.ghdl);
    opt.yosys = find_tool(opt.yosys);
    fs::create_directories(opt.cache_dir);
    fingerprint = kFlowVersion;
    fingerprint += std::string("\n") + cosim::kVerilogReading;
    fingerprint += "\n" + tool_version(opt.ghdl, "--version", opt.cache_dir);
    fingerprint += "\n" + tool_version(opt.yosys, "-V", opt.cache_dir);
    for (const auto& p : opt.rtl_sources) fingerprint.append("\n").append(p.filename().string()).append("\n").append(util::read_file(p));
}

std::string cost_key(const CostContext& ctx, const Formats& f, Variant v) {
    std::string s = ctx.fingerprint + "\nvariant=" + variant_name(v);
    for (const auto& [name, val] : generics(ctx.opt.geometry, f)) s += "\n" + name + "=" + std::to_string(val);
    return util::hex64(util::fnv1a(s));
}

bool cached_cost(const CostContext& ctx, const Formats& f, Variant v, Cost& out) {
    const std::string key = cost_key(ctx, f, v);
    const fs::path p = ctx.opt.cache_dir / (key + ".json");
    if (!fs::exists(p)) return false;
    try {
        const json j = json::parse(util::read_file(p));
        out = cost_from_cells(j.at("cells").get<std::map<std::string, long>>());
        out.seconds = j.at("seconds").get<double>();
        out.key = key;
        out.cached = true;
        return true;
    } catch (const std::exception&) {
        return false;   // unreadable entry: synthesise again and overwrite it
    }
}

int rewrite_signed_multiplies(std::string& v) {
    // GHDL: "assign n1134_o = {{11{ix[10]}}, ix}; // sext" then "assign n1136_o = n1134_o * n1135_o; // smul"
    static const std::regex sext(R"(assign (\w+) = \{\{\d+\{(\w+)\[\d+\]\}\}, (\w+)\}; // sext)");
    static const std::regex smul(R"(assign (\w+) = (\w+) \* (\w+); // smul)");
    std::map<std::string, std::string> ext;   // wire -> the signal it sign-extends
    for (auto it = std::sregex_iterator(v.begin(), v.end(), sext); it != std::sregex_iterator(); ++it)
        if ((*it)[2] == (*it)[3]) ext[(*it)[1]] = (*it)[3];
    std::string out;
    out.reserve(v.size());
    int n = 0;
    auto last = v.cbegin();
    for (auto it = std::sregex_iterator(v.begin(), v.end(), smul); it != std::sregex_iterator(); ++it) {
        const auto& m = *it;
        out.append(last, m[0].first);
        const auto a = ext.find(m[2]), b = ext.find(m[3]);
        if (a != ext.end() && b != ext.end()) {
            out += "assign " + m[1].str() + " = $signed(" + a->second + ") * $signed(" + b->second +
                   "); // smul, signed operands restored by harris-cosim sweep";
            ++n;
        } else {
            out += m[0].str();
        }
        last = m[0].second;
    }
    out.append(last, v.cend());
    v = std::move(out);
    return n;
}

Cost synth_cost(const CostContext& ctx, const Formats& f, Variant v) {
    Cost c;
    if (cached_cost(ctx, f, v, c)) return c;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string key = cost_key(ctx, f, v);
    const fs::path dir = ctx.opt.cache_dir / fmt::format("work-{}-{}", key, ::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
    // 1. GHDL: VHDL -> Verilog netlist
    std::vector<std::string> synth = {ctx.opt.ghdl, "--synth", "--std=08", "--workdir=" + dir.string()};
    for (const auto& [name, val] : generics(ctx.opt.geometry, f)) synth.push_back(fmt::format("-g{}={}", name, val));
    synth.insert(synth.end(), {"-gOBSERVE=false", "--out=verilog"});
    for (const auto& p : ctx.opt.rtl_sources) synth.push_back(p.string());
    synth.insert(synth.end(), {"-e", "harris_top"});
    if (int rc = cosim::synth_verilog(synth, dir / "harris_top.v", {.log = dir / "ghdl.log"}); rc != 0)
        throw SimulatorError(fmt::format("ghdl --synth failed (status {}) for {}: see {}", rc,
                                             describe_difference(f), (dir / "ghdl.log").string()));
    // 2. the signed-multiply variant
    if (v == Variant::signed_mul) {
        std::string text = util::read_file(dir / "harris_top.v");
        const int n = rewrite_signed_multiplies(text);
        std::ofstream(dir / "harris_top.v", std::ios::binary | std::ios::trunc) << text;
        std::ofstream(dir / "rewrite.txt") << n << " multiplications rewritten\n";
    }
    // 3. yosys: synth_xilinx, statistics as JSON
    const fs::path stat = dir / "stat.json";
    const std::string script = "read_verilog " + (dir / "harris_top.v").string() +
                               "; synth_xilinx -top harris_top; tee -q -o " + stat.string() + " stat -json";
    if (int rc = util::run_process({ctx.opt.yosys, "-q", "-l", (dir / "yosys.log").string(), "-p", script},
                                   {.log = dir / "yosys.out"});
        rc != 0)
        throw SimulatorError(fmt::format("yosys failed (status {}) for {}: see {}", rc, describe_difference(f),
                                             (dir / "yosys.log").string()));
    // yosys 0.23 prints the text "design hierarchy" listing into the JSON of a hierarchical
    // design (lines like "   input_converter   4"): keep only lines that can be JSON
    std::string text, line;
    std::istringstream raw(util::read_file(stat));
    while (std::getline(raw, line)) {
        const auto b = line.find_first_not_of(" \t");
        if (b == std::string::npos || std::string("\"{}[]").find(line[b]) != std::string::npos) text += line + "\n";
    }
    const json st = json::parse(text);
    std::map<std::string, long> cells;
    const json* d = st.contains("design") ? &st["design"] : nullptr;
    if (!d || !d->contains("num_cells_by_type")) {
        for (const auto& [name, m] : st.at("modules").items()) d = &m;   // flattened: one module
    }
    for (const auto& [type, n] : d->at("num_cells_by_type").items()) cells[type] = n.get<long>();
    c = cost_from_cells(cells);
    c.key = key;
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    util::write_file_atomic(ctx.opt.cache_dir / (key + ".json"), cost_to_json(c, f, ctx.opt.geometry, v).dump(2) + "\n");
    fs::remove_all(dir);
    return c;
}

long datapath_register_bits(const Formats& f, const Geometry& g) {
    const long period = (static_cast<long>(g.height / 2 - 3) * (g.width / 2 + 3)) * 4;
    const long count_bits = static_cast<long>(std::ceil(std::log2(static_cast<double>(period) + 1)));
    return 2L * 25 * f.sobel_w            // Sobel x, y registers
           + 3L * 25 * f.m_w()            // M a, b, c
           + 3L * 9 * f.bf_w()            // block sums
           + 9L * (2 * f.prod_w() + f.ktr_w + f.resp_w)   // a*c, b*b, k-term, r
           + 9L * 2 * f.resp_w            // threshold: r0_delay, r1
           + 2L * f.resp_w + count_bits;  // find-max: running, max, period counter
}

}  // namespace hc::sweep

// verilate.cpp: see verilate.hpp.
#include "cosim/verilator/verilate.hpp"

#include <ostream>

#include "model/driver/host_driver.hpp"
#include "model/harris/formats_json.hpp"
#include "model/util/errors.hpp"

namespace fs = std::filesystem;

namespace hc::vl {

std::string VerilateResult::status() const {
    if (gate && gate->verdict == GateVerdict::translation_fault) return "translation_fault";
    if (gate && gate->verdict == GateVerdict::rtl_fault) return "rtl_fault";
    if (run) return run->mismatches == 0 ? "pass" : "mismatch";
    return netlist_key.empty() ? "pass" : "built";
}

NetlistTrust netlist_trust(bool ran, bool failed, bool stages_proven) {
    if (!ran) return NetlistTrust::not_run;
    if (failed) return NetlistTrust::failed;
    return stages_proven ? NetlistTrust::stages_proven : NetlistTrust::samples;
}

const char* netlist_trust_name(NetlistTrust t) {
    switch (t) {
        case NetlistTrust::not_run: return "-";
        case NetlistTrust::failed: return "failed";
        case NetlistTrust::samples: return "samples only";
        case NetlistTrust::stages_proven: return "stages proven";
    }
    return "?";
}

NetlistTrust netlist_trust(const VerilateResult& res) {
    const std::string st = res.status();
    return netlist_trust(res.gate.has_value() || res.run.has_value(), st != "pass" && st != "built", false);
}

VerilateResult run_verilate(const VerilateRun& r, std::ostream& log) {
    std::vector<fs::path> variants;
    for (const auto& v : r.variants) {
        if (!fs::is_regular_file(v)) throw InputError("--variant '" + v.string() + "' does not exist");
        variants.push_back(fs::absolute(v));
    }
    std::string why;
    if (!toolchain_available(&why)) throw InputError("the Verilator flow needs GHDL and Verilator: " + why);
    const fs::path cache = r.cache.empty() ? default_cache_dir() : r.cache;
    VerilateResult res;
    if (r.gate) {
        res.gate = run_gate_cached(r.formats, variants, cache, log, &res.gate_cached);
        if (res.gate->verdict != GateVerdict::pass) return res;
    }
    if (r.gate_only || r.frames.empty()) return res;
    const Geometry g{r.frames[0].width, r.frames[0].height};
    std::vector<const Image*> ptrs;
    for (const auto& im : r.frames) ptrs.push_back(&im);
    res.writes_in_stream = HostDriver(g, ptrs).total_writes();
    NetlistConfig nc{g, r.formats, r.observe, variants};
    nc.optimise = res.writes_in_stream > kUnoptimisedWrites;
    res.netlist = build_netlist(nc, cache, log);
    res.netlist_key = config_key(nc);
    if (r.build_only) return res;
    VerilatedDesign dut(res.netlist, res.netlist_key);
    RunOptions opt;
    opt.compare_obs = r.observe;
    opt.keep_going = r.keep_going;
    opt.read_rows = r.read_rows;
    opt.on_frame = r.on_frame;
    res.run = run_lockstep(g, r.formats, dut, ptrs, r.frame_names, opt);
    return res;
}

nlohmann::json run_counts_json(const RunResult& r) {
    return {{"complete", !r.stopped_early},
            {"writes", r.writes},
            {"reads", r.reads},
            {"corners", r.corners},
            {"read_mismatches", r.read_mismatches}};
}

using nlohmann::json;

json mismatch_json(const Mismatch& m) {
    return {{"kind", m.kind},         {"write", m.write},     {"frame", m.frame},   {"x", m.x},
            {"y", m.y},               {"quadrant", m.quadrant}, {"signal", m.signal}, {"stage", m.stage},
            {"expected", m.expected}, {"actual", m.actual}};
}

namespace {

json gate_json(const VerilateResult& res) {
    if (!res.gate) return {{"verdict", "skipped"}};
    const GateResult& gate = *res.gate;
    json j = {{"verdict", verdict_name(gate.verdict)},
              {"cached", res.gate_cached},
              {"writes", gate.writes},
              {"reads", gate.reads},
              {"cases", gate.per_case}};
    if (!gate.first.empty()) j["first"] = gate.first;
    return j;
}

void add_run_json(json& out, const RunResult& r, const VerilateResult& res, const VerilateRun& run) {
    const int nframes = static_cast<int>(run.frames.size());
    json jf = json::array();
    for (const auto& s : r.frames)
        jf.push_back({{"index", s.index}, {"name", s.source}, {"writes", s.writes}, {"reads", s.reads},
                      {"corners_read", s.corners}, {"mismatches", s.mismatches}, {"wall_seconds", s.seconds}});
    json jm = json::array();
    for (const auto& m : r.reported) jm.push_back(mismatch_json(m));
    out["geometry"] = {{"width", run.frames[0].width}, {"height", run.frames[0].height}};
    out["frames"] = jf;
    out.update(run_counts_json(r));
    out["writes_in_stream"] = res.writes_in_stream;
    out["obs_compared"] = run.observe;
    out["mismatches"] = {{"writes", r.mismatches}, {"reported", jm}};
    out["wall_seconds"] = r.seconds;
    out["writes_per_second"] = r.seconds > 0 ? r.writes / r.seconds : 0.0;
    out["verilator_seconds"] = r.verilator_seconds;
    out["verilator_writes_per_second"] = r.verilator_seconds > 0 ? r.writes / r.verilator_seconds : 0.0;
    out["verilator_seconds_per_frame"] = r.verilator_seconds / nframes;
    out["model_seconds"] = r.model_seconds;
    if (!r.reported.empty()) {
        json fm = mismatch_json(r.reported.front());
        fm["report"] = r.reported.front().describe();
        out["first_mismatch"] = fm;
    }
}

}  // namespace

json summary_json(const VerilateRun& run, const VerilateResult& res, double wall_seconds_including_build) {
    json out = {{"command", "verilate"}, {"simulator", "verilator"},
                {"formats", fields_to_json(run.formats, format_fields())}};
    out["gate"] = gate_json(res);
    if (!res.netlist_key.empty())
        out["netlist"] = {{"key", res.netlist_key}, {"library", res.netlist.string()}, {"observe", run.observe}};
    if (res.run) add_run_json(out, *res.run, res, run);
    out["wall_seconds_including_build"] = wall_seconds_including_build;
    out["status"] = res.status();
    out["trust"] = netlist_trust_name(netlist_trust(res));
    return out;
}

}  // namespace hc::vl

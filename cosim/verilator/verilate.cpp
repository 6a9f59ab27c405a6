// verilate.cpp: see verilate.hpp.
#include "cosim/verilator/verilate.hpp"

#include <ostream>

#include "model/driver/host_driver.hpp"
#include "io/util/errors.hpp"

namespace fs = std::filesystem;

namespace hc::vl {

std::string VerilateResult::status() const {
    if (gate && gate->verdict == GateVerdict::translation_fault) return "translation_fault";
    if (gate && gate->verdict == GateVerdict::rtl_fault) return "rtl_fault";
    if (run) return run->mismatches == 0 ? "pass" : "mismatch";
    return netlist_key.empty() ? "pass" : "built";
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

}  // namespace hc::vl

// cmd_verilate.cpp: `harris-cosim verilate`, full-frame RTL verification on Verilator.
//
// Purpose: streams frames through the GHDL-synthesised, verilated netlist of harris_top and
// the cycle model in lock step (hc::vl::run_lockstep), after the three-way gate
// (hc::vl::run_gate: GHDL / Verilator / model on small frames) has shown that the
// netlist translation can be trusted for this design and these formats. Flags and JSON
// summary follow `harris-cosim rtl` where they apply. Exit status: 0 all agree,
// 1 mismatch against the model, 2 bad input, 3 internal error, 4 translation fault.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.hpp"
#include "frame_source.hpp"
#include "frames.hpp"
#include "gate.hpp"
#include "lockstep.hpp"
#include "netlist.hpp"
#include "run_config.hpp"

namespace hc::tools {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct VerilateArgs {
    FrameSourceOptions src;   ///< the frame-source flags shared with `rtl` and `model`
    std::string config;       ///< JSON formats (as `rtl --config`)
    bool keep_going = false, obs = false, no_gate = false, gate_only = false, build_only = false;
    std::string json_path, reads_path, cache;
    std::vector<std::string> variants;
};

constexpr int kStatusMismatch = 1;
constexpr int kStatusTranslationFault = 4;

json mismatch_json(const vl::Mismatch& m) {
    return {{"kind", m.kind},         {"write", m.write},     {"frame", m.frame},   {"x", m.x},
            {"y", m.y},               {"quadrant", m.quadrant}, {"signal", m.signal}, {"stage", m.stage},
            {"expected", m.expected}, {"actual", m.actual}};
}

int run_verilate(const VerilateArgs& a) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<fs::path> variants;
    for (const auto& v : a.variants) {
        if (!fs::is_regular_file(v)) throw InputError("--variant '" + v + "' does not exist");
        variants.push_back(fs::absolute(v));
    }
    std::string why;
    if (!vl::toolchain_available(&why)) throw InputError("the Verilator flow needs GHDL and Verilator: " + why);
    const fs::path cache = a.cache.empty() ? vl::default_cache_dir() : fs::path(a.cache);
    const Formats f = load_config_formats(a.config);
    json out = {{"command", "verilate"}, {"simulator", "verilator"},
                {"formats", json::parse(cosim::formats_to_json(f))}};

    // 1. the gate: GHDL, Verilator and model on the small-frame regression set
    vl::GateResult gate;
    bool gate_cached = false;
    if (!a.no_gate) {
        gate = vl::run_gate_cached(f, variants, cache, std::cerr, &gate_cached);
        out["gate"] = {{"verdict", vl::verdict_name(gate.verdict)},
                       {"cached", gate_cached},
                       {"writes", gate.writes},
                       {"reads", gate.reads},
                       {"cases", gate.per_case}};
        if (!gate.first.empty()) out["gate"]["first"] = gate.first;
        std::fprintf(stderr, "verilate: gate %s%s\n", vl::verdict_name(gate.verdict),
                     gate_cached ? " (recorded earlier for these sources)" : "");
        if (gate.verdict != vl::GateVerdict::pass) {
            std::fprintf(stderr, "verilate: %s\n", gate.first.c_str());
            out["status"] = gate.verdict == vl::GateVerdict::translation_fault ? "translation_fault" : "rtl_fault";
            if (!a.json_path.empty()) write_file_atomic(a.json_path, out.dump(2) + "\n");
            throw CLI::RuntimeError(gate.verdict == vl::GateVerdict::translation_fault ? kStatusTranslationFault
                                                                                       : kStatusMismatch);
        }
    } else {
        out["gate"] = {{"verdict", "skipped"}};
        std::fprintf(stderr, "verilate: gate skipped (--no-gate): results are not trusted\n");
    }
    if (a.gate_only) {
        out["status"] = "pass";
        if (!a.json_path.empty()) write_file_atomic(a.json_path, out.dump(2) + "\n");
        return 0;
    }

    // 2. the frames and the netlist for their size
    LoadedFrames lf = load_frames(a.src);
    const std::vector<Image>& frames = lf.frames;
    const std::vector<std::string>& names = lf.names;
    const Geometry g{frames[0].width, frames[0].height};   // validated by load_frames
    const vl::NetlistConfig nc{g, f, a.obs, variants};
    const fs::path so = vl::build_netlist(nc, cache, std::cerr);
    out["netlist"] = {{"key", vl::config_key(nc)}, {"library", so.string()}, {"observe", a.obs}};
    if (a.build_only) {
        out["status"] = "built";
        if (!a.json_path.empty()) write_file_atomic(a.json_path, out.dump(2) + "\n");
        return 0;
    }
    vl::VerilatedDesign dut(so, vl::config_key(nc));

    // 3. lock step against the model
    std::vector<const Image*> ptrs;
    for (const auto& im : frames) ptrs.push_back(&im);
    std::vector<std::string> read_rows;
    vl::RunOptions opt;
    opt.compare_obs = a.obs;
    opt.keep_going = a.keep_going;
    opt.read_rows = a.reads_path.empty() ? nullptr : &read_rows;
    const int nframes = static_cast<int>(frames.size());
    opt.on_frame = [&](const vl::FrameStats& s) {
        std::fprintf(stderr, "verilate: frame %d/%d %s: %ld writes, %ld reads, %ld corners, %ld mismatches, %.2f s\n",
                     s.index + 1, nframes, s.source.c_str(), s.writes, s.reads, s.corners, s.mismatches, s.seconds);
    };
    const vl::RunResult r = vl::run_lockstep(g, f, dut, ptrs, names, opt);
    if (!r.reported.empty()) std::fprintf(stderr, "verilate: first %s\n", r.reported.front().describe().c_str());

    // the summary mirrors `harris-cosim rtl --json` (cosim/session.cpp) where fields apply
    json jf = json::array();
    for (const auto& s : r.frames)
        jf.push_back({{"index", s.index}, {"name", s.source}, {"writes", s.writes}, {"reads", s.reads},
                      {"corners_read", s.corners}, {"mismatches", s.mismatches}, {"wall_seconds", s.seconds}});
    json jm = json::array();
    for (const auto& m : r.reported) jm.push_back(mismatch_json(m));
    out["geometry"] = {{"width", g.width}, {"height", g.height}};
    out["frames"] = jf;
    out["complete"] = !r.stopped_early;
    out["writes"] = r.writes;
    out["writes_in_stream"] = HostDriver(g, ptrs).total_writes();
    out["reads"] = r.reads;
    out["read_mismatches"] = r.read_mismatches;
    out["corners"] = r.corners;
    out["obs_compared"] = a.obs;
    out["mismatches"] = {{"writes", r.mismatches}, {"reported", jm}};
    out["wall_seconds"] = r.seconds;
    out["writes_per_second"] = r.seconds > 0 ? r.writes / r.seconds : 0.0;
    out["verilator_seconds"] = r.verilator_seconds;
    out["verilator_writes_per_second"] = r.verilator_seconds > 0 ? r.writes / r.verilator_seconds : 0.0;
    out["verilator_seconds_per_frame"] = r.verilator_seconds / nframes;
    out["model_seconds"] = r.model_seconds;
    out["wall_seconds_including_build"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.reported.empty()) {
        json fm = mismatch_json(r.reported.front());
        fm["report"] = r.reported.front().describe();
        out["first_mismatch"] = fm;
    }
    out["status"] = r.mismatches == 0 ? "pass" : "mismatch";
    std::fprintf(stderr,
                 "verilate: %d frames, %ld writes, %ld reads, %ld corners, %ld mismatches; Verilator %.3f s "
                 "(%.0f writes/s), model %.3f s, total %.3f s\n",
                 nframes, r.writes, r.reads, r.corners, r.mismatches, r.verilator_seconds,
                 r.verilator_seconds > 0 ? r.writes / r.verilator_seconds : 0.0, r.model_seconds, r.seconds);
    if (!a.reads_path.empty()) {
        std::string csv = "write,frame,x,y,value\n";   // as `rtl --reads`
        for (const auto& row : read_rows) csv += row + "\n";
        write_file_atomic(a.reads_path, csv);
    }
    if (!a.json_path.empty()) write_file_atomic(a.json_path, out.dump(2) + "\n");
    if (r.mismatches != 0) throw CLI::RuntimeError(kStatusMismatch);
    return 0;
}

}  // namespace

void add_verilate_command(CLI::App& app) {
    auto a = std::make_shared<VerilateArgs>();
    CLI::App* c = app.add_subcommand(
        "verilate",
        "Full-frame RTL verification on Verilator: the GHDL-synthesised netlist against the cycle model,\n"
        "after a three-way gate (GHDL / Verilator / model on small frames) has passed.");
    add_frame_source_options(c, a->src);
    c->add_option("--config", a->config, "JSON file of bit widths and shifts (default: the thesis's)");
    c->add_flag("--keep-going", a->keep_going, "Count all mismatches instead of stopping at the first");
    c->add_flag("--obs", a->obs,
                "Also compare every observed inter-stage register after every write (OBSERVE netlist, slower)");
    c->add_option("--json", a->json_path, "Write the JSON summary here");
    c->add_option("--reads", a->reads_path, "Write every read as CSV: write,frame,x,y,value");
    c->add_option("--cache", a->cache, "Netlist cache directory (else $HARRIS_COSIM_VL_CACHE or the build tree)");
    c->add_option("--variant", a->variants,
                  "Test-only VHDL file replacing the rtl/ file of the entity it declares (e.g. tests/rtl/*.vhd)");
    c->add_flag("--no-gate", a->no_gate, "Skip the three-way gate (results are then marked untrusted)");
    c->add_flag("--gate-only", a->gate_only, "Run the gate only");
    c->add_flag("--build-only", a->build_only, "Build (or find) the netlist for the frames' size and stop");
    c->callback([a] {
        const int rc = run_verilate(*a);
        if (rc != 0) throw CLI::RuntimeError(rc);
    });
}

}  // namespace hc::tools

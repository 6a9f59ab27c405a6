// cmd_verilate.cpp: `harris-cosim verilate`, full-frame RTL verification on Verilator.
//
// Purpose: flags and printing around vl::run_verilate (cosim/verilator/verilate.hpp): the
// three-way gate (GHDL / Verilator / model on small frames), then the frames streamed
// through the GHDL-synthesised, verilated netlist and the cycle model in lock step. Flags
// and JSON summary follow `harris-cosim rtl` where they apply. Exit status: 0 all agree,
// 1 mismatch against the model (or an RTL fault in the gate), 2 bad input, 3 a tool
// failed, 4 translation fault, 5 internal fault.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "cosim/verilator/verilate.hpp"
#include "cosim/verilator/verilate_job.hpp"
#include "eval/sequences.hpp"
#include "tools/registry.hpp"
#include "model/harris/formats_json.hpp"
#include "tools/commands.hpp"
#include "tools/frame_source.hpp"
#include "tools/runner_flags.hpp"

namespace hc::tools {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct VerilateArgs {
    frames::FrameSource src;   ///< the frame-source flags shared with `rtl` and `model`
    std::string config;        ///< JSON formats (as `rtl --config`)
    bool keep_going = false, obs = false, no_gate = false, gate_only = false, build_only = false;
    std::string json_path, reads_path, cache;
    std::vector<std::string> variants;
    std::string sequences;     ///< several KITTI sequences, each from its own reset
    RunnerFlags runner;
    bool sharded = false;      ///< a sharding flag was given
};

/// Several sequences, or a run through the runner: one shard per sequence, the summary
/// (per-sequence rows and totals) from the merged data only.
void run_verilate_job(const VerilateArgs& a) {
    if (a.no_gate || a.gate_only || a.build_only || a.obs || !a.variants.empty() || !a.reads_path.empty())
        throw InputError("--sequences and the sharding flags run the gated lock step only: leave out --no-gate, "
                         "--gate-only, --build-only, --obs, --variant and --reads");
    if (!a.src.images.empty() || !a.src.pattern.empty())
        throw InputError("--sequences and the sharding flags stream KITTI sequences: leave out images and --pattern");
    vl::VerilateJob j;
    j.kitti = frames::require_kitti_root(a.src.kitti, a.src.data, "--sequences needs KITTI data");
    j.sequences = a.sequences.empty() ? std::vector<std::string>{a.src.sequence} : eval::parse_sequences(a.sequences);
    if (!a.src.pairs.empty()) j.pairs = util::parse_range(a.src.pairs, "--pairs");
    if (a.src.frames > 0) j.pairs.last = std::min(j.pairs.last, j.pairs.first + (a.src.frames + 1) / 2);
    j.pairs_flag = "--pairs " + (a.src.pairs.empty() ? std::string("(all)") : a.src.pairs);
    j.formats = a.config.empty() ? Formats{} : formats_from_file(a.config);
    j.cache = a.cache;
    j.keep_going = a.keep_going;
    const cluster::Manifest m = vl::verilate_manifest(j);
    vl::prepare_rtl(m);
    json merged;
    if (a.sharded) {
        auto got = run_sharded(run_dir(a.runner, folder_of(a.json_path)), m, a.runner);
        if (!got) return;
        merged = std::move(*got);
    } else {
        merged = cluster::run_in_process(registry(), m);
    }
    for (const auto& s : merged.at("sequences"))
        std::fprintf(stderr, "verilate: sequence %s: %ld frames, %ld writes, %ld reads, %ld corners, %ld mismatches (%s)\n",
                     s.at("sequence").get<std::string>().c_str(), s.at("frames").get<long>(), s.value("writes", 0L),
                     s.value("reads", 0L), s.value("corners", 0L), s.value("mismatches", 0L),
                     s.at("status").get<std::string>().c_str());
    const json& t = merged.at("totals");
    std::fprintf(stderr, "verilate: total %ld frames, %ld writes, %ld reads, %ld corners, %ld mismatches: %s\n",
                 t.at("frames").get<long>(), t.at("writes").get<long>(), t.at("reads").get<long>(),
                 t.at("corners").get<long>(), t.at("mismatches").get<long>(), merged.at("status").get<std::string>().c_str());
    if (!a.json_path.empty()) util::write_file_atomic(a.json_path, merged.dump(2) + "\n");
    const std::string status = merged.at("status");
    if (status == "translation_fault") throw TranslationFault("GHDL's netlist and GHDL's simulation of the VHDL disagree");
    if (status == "rtl_fault") throw MismatchError("the RTL differs from the model in the gate");
    if (status == "mismatch")
        throw MismatchError(std::to_string(t.at("mismatches").get<long>()) + " mismatch(es) between the netlist and the model");
}

/// The gate's verdict on stderr.
void print_gate(const vl::VerilateResult& res) {
    if (!res.gate) return;
    const vl::GateResult& gate = *res.gate;
    std::fprintf(stderr, "verilate: gate %s%s\n", vl::verdict_name(gate.verdict),
                 res.gate_cached ? " (recorded earlier for these sources)" : "");
    if (gate.verdict != vl::GateVerdict::pass) std::fprintf(stderr, "verilate: %s\n", gate.first.c_str());
}

/// The lock-step run's counts on stderr, its reads in --reads.
void print_run(const vl::RunResult& r, const VerilateArgs& a, const std::vector<std::string>& read_rows, int nframes) {
    if (!r.reported.empty()) std::fprintf(stderr, "verilate: first %s\n", r.reported.front().describe().c_str());
    std::fprintf(stderr,
                 "verilate: %d frames, %ld writes, %ld reads, %ld corners, %ld mismatches; Verilator %.3f s "
                 "(%.0f writes/s), model %.3f s, total %.3f s\n",
                 nframes, r.writes, r.reads, r.corners, r.mismatches, r.verilator_seconds,
                 r.verilator_seconds > 0 ? r.writes / r.verilator_seconds : 0.0, r.model_seconds, r.seconds);
    if (!a.reads_path.empty()) {
        std::string csv = "write,frame,x,y,value\n";   // as `rtl --reads`
        for (const auto& row : read_rows) csv += row + "\n";
        util::write_file_atomic(a.reads_path, csv);
    }
}

void run_verilate(const VerilateArgs& a) {
    if (!a.sequences.empty() || a.sharded) {
        run_verilate_job(a);
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    vl::VerilateRun run;
    run.formats = a.config.empty() ? Formats{} : formats_from_file(a.config);
    for (const auto& v : a.variants) run.variants.push_back(v);
    run.cache = a.cache;
    run.gate = !a.no_gate;
    run.gate_only = a.gate_only;
    run.build_only = a.build_only;
    run.observe = a.obs;
    run.keep_going = a.keep_going;
    std::vector<std::string> read_rows;
    run.read_rows = a.reads_path.empty() ? nullptr : &read_rows;
    if (!a.gate_only) {
        frames::LoadedFrames lf = frames::load_frames(a.src);
        run.frames = std::move(lf.frames);
        run.frame_names = std::move(lf.names);
    }
    const int nframes = static_cast<int>(run.frames.size());
    run.on_frame = [&](const vl::FrameStats& s) {
        std::fprintf(stderr, "verilate: frame %d/%d %s: %ld writes, %ld reads, %ld corners, %ld mismatches, %.2f s\n",
                     s.index + 1, nframes, s.source.c_str(), s.writes, s.reads, s.corners, s.mismatches, s.seconds);
    };
    if (a.no_gate) std::fprintf(stderr, "verilate: gate skipped (--no-gate): results are not trusted\n");

    const vl::VerilateResult res = vl::run_verilate(run, std::cerr);

    print_gate(res);
    if (res.run) print_run(*res.run, a, read_rows, nframes);
    const json out = vl::summary_json(run, res, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    const std::string status = res.status();
    if (!a.json_path.empty()) util::write_file_atomic(a.json_path, out.dump(2) + "\n");
    if (status == "translation_fault")
        throw TranslationFault("GHDL's netlist and GHDL's simulation of the VHDL disagree: " + res.gate->first);
    if (status == "rtl_fault") throw MismatchError("the RTL differs from the model in the gate: " + res.gate->first);
    if (status == "mismatch")
        throw MismatchError(std::to_string(res.run->mismatches) + " mismatch(es) between the netlist and the model");
}

}  // namespace

void add_verilate_command(CLI::App& app) {
    const auto [c, a] = add_command<VerilateArgs>(app, "verilate",
        "Full-frame RTL verification on Verilator: the GHDL-synthesised netlist against the cycle model,\n"
        "after a three-way gate (GHDL / Verilator / model on small frames) has passed.\n"
        "Exit status: 0 all agree, 1 mismatch, 2 bad input, 3 a tool failed, 4 translation fault.");
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
    c->add_option("--sequences", a->sequences,
                  "KITTI sequences, each from its own reset: a range 00-21 or a list 00,01,05 (one shard per "
                  "sequence; --pairs applies to each; --json gets per-sequence rows and totals)");
    add_runner_flags(c, a->runner);
    c->callback([a, c] {
        a->sharded = sharded(c);
        run_verilate(*a);
    });
}

}  // namespace hc::tools

// verilate_command.cpp: see verilate_command.hpp.
#include "cosim/verilator/verilate_command.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "cosim/verilator/verilate.hpp"
#include "cosim/verilator/verilate_job.hpp"
#include "model/harris/formats_json.hpp"

namespace hc::vl {

namespace {

using nlohmann::json;

/// The verdict of a status, as the command's failure.
void raise(const std::string& status, const std::string& detail, long mismatches) {
    if (status == "translation_fault")
        throw TranslationFault("GHDL's netlist and GHDL's simulation of the VHDL disagree" + detail);
    if (status == "rtl_fault") throw MismatchError("the RTL differs from the model in the gate" + detail);
    if (status == "mismatch")
        throw MismatchError(std::to_string(mismatches) + " mismatch(es) between the netlist and the model");
}

/// Several sequences, or a run through the runner: one shard per sequence, the summary
/// (per-sequence rows and totals) from the merged data only.
void run_job(const VerilateCommand& a, const cluster::JobRunner& runner) {
    if (a.no_gate || a.gate_only || a.build_only || a.obs || !a.variants.empty() || !a.reads_path.empty())
        throw InputError("--sequences and the sharding flags run the gated lock step only: leave out --no-gate, "
                         "--gate-only, --build-only, --obs, --variant and --reads");
    if (!a.src.images.empty() || !a.src.pattern.empty())
        throw InputError("--sequences and the sharding flags stream KITTI sequences: leave out images and --pattern");
    VerilateJob j;
    j.kitti = frames::require_kitti_root(a.src.kitti, a.src.data, "--sequences needs KITTI data");
    j.sequences = a.sequences.empty() ? std::vector<std::string>{a.src.sequence} : frames::parse_sequences(a.sequences);
    j.pairs = frames::job_pair_range(a.src);
    j.pairs_flag = frames::pairs_flag(a.src);
    j.formats = a.config.empty() ? Formats{} : formats_from_file(a.config);
    j.cache = a.cache;
    j.keep_going = a.keep_going;
    const cluster::Manifest m = verilate_manifest(j);
    prepare_rtl(m);
    const auto got = runner.run(m, cluster::folder_of(a.json_path));
    if (!got) return;
    const json& merged = *got;
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
    raise(merged.at("status"), "", t.at("mismatches").get<long>());
}

/// The gate's verdict on stderr.
void print_gate(const VerilateResult& res) {
    if (!res.gate) return;
    const GateResult& gate = *res.gate;
    std::fprintf(stderr, "verilate: gate %s%s\n", verdict_name(gate.verdict),
                 res.gate_cached ? " (recorded earlier for these sources)" : "");
    if (gate.verdict != GateVerdict::pass) std::fprintf(stderr, "verilate: %s\n", gate.first.c_str());
}

/// The lock-step run's counts on stderr, its reads in --reads.
void print_run(const RunResult& r, const VerilateCommand& a, const std::vector<std::string>& read_rows, int nframes) {
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

}  // namespace

void run_verilate_command(const VerilateCommand& a, const cluster::JobRunner& runner) {
    if (!a.sequences.empty() || runner.sharded()) {
        run_job(a, runner);
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    VerilateRun run;
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
    run.on_frame = [&](const FrameStats& s) {
        std::fprintf(stderr, "verilate: frame %d/%d %s: %ld writes, %ld reads, %ld corners, %ld mismatches, %.2f s\n",
                     s.index + 1, nframes, s.source.c_str(), s.writes, s.reads, s.corners, s.mismatches, s.seconds);
    };
    if (a.no_gate) std::fprintf(stderr, "verilate: gate skipped (--no-gate): results are not trusted\n");

    const VerilateResult res = run_verilate(run, std::cerr);

    print_gate(res);
    if (res.run) print_run(*res.run, a, read_rows, nframes);
    std::fprintf(stderr,
                 "verilate: trust: %s (this command proves no stage; `harris-cosim ranges%s --stages` proves "
                 "each stage of the netlist for every input, and sweep --stage-proofs reports it per configuration)\n",
                 netlist_trust_name(netlist_trust(res)), a.config.empty() ? "" : (" --config " + a.config).c_str());
    const json out = summary_json(run, res, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!a.json_path.empty()) util::write_file_atomic(a.json_path, out.dump(2) + "\n");
    raise(res.status(), res.gate ? ": " + res.gate->first : "", res.run ? res.run->mismatches : 0);
}

}  // namespace hc::vl

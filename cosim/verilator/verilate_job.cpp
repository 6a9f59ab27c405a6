// verilate_job.cpp: the "verilate" job kind and the RTL preparation (verilate_job.hpp).
#include "cosim/verilator/verilate_job.hpp"

#include <cstdio>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include "cosim/verilator/verilate.hpp"
#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"

namespace hc::vl {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

Formats formats_of(const json& common) {
    return formats_from_json(common.at("formats"), "the run's formats");
}

fs::path cache_of(const json& common) {
    const std::string c = common.at("cache");
    return c.empty() ? default_cache_dir() : fs::path(c);
}

json run_verilate_shard(const json& common, const json& shard, std::size_t) {
    const fs::path kitti = common.at("kitti").get<std::string>();
    const std::string seq = shard.at("sequence");
    const int p0 = shard.at("pairs").at(0), p1 = shard.at("pairs").at(1);
    const frames::Stream s = frames::load_kitti_stream(kitti, seq, {p0, p1}, fmt::format("pairs {}:{} of sequence {}", p0, p1, seq), 1, 1);
    VerilateRun run;
    run.frames = s.frames;
    run.frame_names = s.names;
    run.formats = formats_of(common);
    run.cache = cache_of(common);
    run.keep_going = common.at("keep_going");
    const int n = static_cast<int>(run.frames.size());
    run.on_frame = [&](const FrameStats& f) {
        std::fprintf(stderr, "verilate shard: sequence %s frame %d/%d: %ld writes, %ld reads, %ld mismatches\n",
                     seq.c_str(), f.index + 1, n, f.writes, f.reads, f.mismatches);
    };
    const VerilateResult res = run_verilate(run, std::cerr);
    json d = {{"sequence", seq},
              {"pairs", {p0, p1}},
              {"frames", n},
              {"geometry", {run.frames[0].width, run.frames[0].height}},
              {"gate", res.gate ? verdict_name(res.gate->verdict) : "skipped"},
              {"status", res.status()}};
    if (res.gate && !res.gate->first.empty()) d["gate_first"] = res.gate->first;
    if (res.run) {
        const RunResult& r = *res.run;
        json reported = json::array();
        for (const auto& m : r.reported) reported.push_back(m.describe());
        d.update(run_counts_json(r));
        d["mismatches"] = r.mismatches;
        d["reported"] = reported;
    }
    return d;
}

json merge_verilate(const json&, const std::vector<json>& data) {
    long writes = 0, reads = 0, corners = 0, mismatches = 0, frames = 0;
    std::string status = "pass";
    const auto rank = [](const std::string& s) {
        return s == "translation_fault" ? 3 : s == "rtl_fault" ? 2 : s == "mismatch" ? 1 : 0;
    };
    json seqs = json::array();
    for (const auto& d : data) {
        frames += d.at("frames").get<long>();
        writes += d.value("writes", 0L);
        reads += d.value("reads", 0L);
        corners += d.value("corners", 0L);
        mismatches += d.value("mismatches", 0L);
        if (rank(d.at("status")) > rank(status)) status = d.at("status");
        seqs.push_back(d);
    }
    return {{"command", "verilate"},
            {"sequences", seqs},
            {"totals", {{"frames", frames}, {"writes", writes}, {"reads", reads}, {"corners", corners},
                        {"mismatches", mismatches}}},
            {"status", status}};
}

}  // namespace

cluster::Manifest verilate_manifest(const VerilateJob& j) {
    if (j.sequences.empty()) throw InputError("verilate: no sequence given");
    frames::check_kitti_sequences(j.kitti, j.sequences);
    cluster::Manifest m;
    m.job = "verilate";
    m.common = {{"kitti", fs::absolute(j.kitti).lexically_normal().string()},
                {"formats", json::parse(formats_to_json(j.formats))},
                {"cache", j.cache.empty() ? std::string() : fs::absolute(j.cache).lexically_normal().string()},
                {"keep_going", j.keep_going}};
    for (const auto& q : j.sequences) {
        const frames::KittiSequence k = frames::open_kitti(j.kitti, q);
        const int last = std::min(j.pairs.last, k.pairs());
        if (last - j.pairs.first < 1)
            throw InputError(fmt::format("{} gives no stereo pair of KITTI sequence {} ({} has {})", j.pairs_flag, q,
                                         k.root.string(), k.pairs()));
        const Image first = frames::load_image(k.left.at(static_cast<std::size_t>(j.pairs.first)));
        m.shards.push_back({{"sequence", q}, {"pairs", {j.pairs.first, last}}, {"geometry", {first.width, first.height}}});
    }
    return m;
}

void prepare_rtl(const cluster::Manifest& m) {
    std::string why;
    if (!toolchain_available(&why)) throw InputError("the RTL needs GHDL and Verilator: " + why);
    const bool verilate = m.job == "verilate";
    std::set<std::pair<int, int>> geometries;
    for (const auto& s : m.shards)
        geometries.insert(std::make_pair(s.at("geometry").at(0).get<int>(), s.at("geometry").at(1).get<int>()));
    for (auto [w, h] : geometries) {
        VerilateRun run;
        run.frames.emplace_back(w, h);
        run.build_only = true;
        if (verilate) {
            run.formats = formats_of(m.common);
            run.cache = cache_of(m.common);
        }
        std::fprintf(stderr, "%s: gate and netlist for %dx%d before the shards start\n", m.job.c_str(), w, h);
        const VerilateResult res = run_verilate(run, std::cerr);
        if (res.gate && res.gate->verdict != GateVerdict::pass)
            throw MismatchError("the GHDL/Verilator/model gate did not pass (" +
                                std::string(verdict_name(res.gate->verdict)) + "): " + res.gate->first);
    }
}

void add_verilate_job(cluster::JobRegistry& r) { r.add({"verilate", run_verilate_shard, merge_verilate}); }

}  // namespace hc::vl

// mutate_generated_job.cpp: the job kind "mutate-generated" (mutate_generated_job.hpp): shards of generated mutants,
// each judged by run_mutant (co-simulation, then a proof of the survivors).
#include "mutation/mutate_generated_job.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "mutation/vhdl_mutants.hpp"

namespace hc::mutation {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json stimuli_json(const std::vector<Stimulus>& v) {
    json a = json::array();
    for (const auto& s : v) a.push_back(to_json(s));
    return a;
}

json run_shard_mutants(const json& common, const json& shard, std::size_t index) {
    if (common.at("rtl_hash").get<std::string>() != rtl_hash())
        throw hc::InputError("shard " + std::to_string(index) +
                                         ": rtl/ changed since this run's manifest was written; start a new run");
    Options o;
    o.quick = stimulus_from_json(common.at("quick"));
    for (const auto& s : common.at("longer")) o.longer.push_back(stimulus_from_json(s));
    o.prove = common.at("prove").get<bool>();
    o.proof_timeout_s = common.at("proof_timeout_s").get<int>();
    o.progress = [](const std::string& s) { std::fprintf(stderr, "[mutants] %s\n", s.c_str()); };
    // each shard first runs the unmutated rtl/ the same way (on whatever node it runs), so
    // that a broken environment fails the shard instead of judging every mutant stillborn
    check_unmutated(o);
    const auto all = generate_all();
    json out = json::array();
    for (const auto& n : shard.at("names")) {
        const std::string name = n.get<std::string>();
        const Mutant* m = nullptr;
        for (const auto& c : all)
            if (c.name() == name) m = &c;
        if (!m) throw hc::InputError("shard " + std::to_string(index) + ": no generated mutant '" + name + "'");
        std::fprintf(stderr, "[mutants] %s ...\n", name.c_str());
        const Result r = run_mutant(*m, o);
        std::fprintf(stderr, "[mutants] %s: %s%s%s (%.1f s)\n", name.c_str(), fate_name(r.fate).c_str(),
                     r.killed_by.empty() ? "" : (" by " + r.killed_by).c_str(),
                     r.detail.empty() ? "" : (", " + r.detail).c_str(), r.seconds);
        out.push_back(to_json(r));
    }
    return out;
}

json merge_mutants(const json&, const std::vector<json>& data) {
    json results = json::array();
    for (const auto& d : data)
        for (const auto& r : d) results.push_back(r);
    return {{"results", results}};
}

}  // namespace

cluster::Manifest mutants_manifest(const MutantsJob& p) {
    cluster::Manifest m;
    m.job = "mutate-generated";
    m.common = {{"rtl_hash", rtl_hash()},
                {"quick", to_json(p.quick)},
                {"longer", stimuli_json(p.longer)},
                {"prove", p.prove},
                {"proof_timeout_s", p.proof_timeout_s}};
    const long n = static_cast<long>(p.names.size());
    if (n == 0) return m;
    const int k = p.shards > 0 ? p.shards : static_cast<int>((n + std::max(1, p.per_shard) - 1) / std::max(1, p.per_shard));
    for (const auto& [first, last] : cluster::split_range(0, n, k)) {
        if (first >= last) continue;
        json names = json::array();
        for (long i = first; i < last; ++i) names.push_back(p.names[static_cast<std::size_t>(i)]);
        m.shards.push_back({{"names", names}});
    }
    return m;
}

std::vector<Result> mutants_results(const json& merged) {
    std::vector<Result> v;
    if (!merged.contains("results") || !merged["results"].is_array())
        throw hc::InputError("merged data of a mutants run has no 'results' list");
    for (const auto& r : merged["results"]) v.push_back(result_from_json(r));
    return v;
}

void add_mutate_generated_job(cluster::JobRegistry& r) { r.add({"mutate-generated", run_shard_mutants, merge_mutants}); }

MutantsProgress mutants_finished(const fs::path& dir) {
    const cluster::Manifest m = cluster::read_manifest(dir);
    if (m.job != "mutate-generated")
        throw hc::InputError("run directory " + dir.string() + " holds a '" + m.job + "' run, not 'mutate-generated'");
    MutantsProgress p;
    p.quick = stimulus_from_json(m.common.at("quick"));
    for (const auto& s : m.common.at("longer")) p.longer.push_back(stimulus_from_json(s));
    p.shards = m.shards.size();
    std::vector<json> data;
    const auto start = fs::last_write_time(cluster::manifest_path(dir));
    auto last = start;
    for (std::size_t i = 0; i < m.shards.size(); ++i)
        if (const auto r = cluster::read_result(dir, m, i)) {
            data.push_back(r->data);
            last = std::max(last, fs::last_write_time(cluster::result_path(dir, i)));
        }
    p.wall_seconds = std::chrono::duration<double>(last - start).count();
    p.results = mutants_results(merge_mutants(m.common, data));
    return p;
}

}  // namespace hc::mutation

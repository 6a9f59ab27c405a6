// mutate_job.cpp: the job kind "mutate" (mutate_job.hpp).
#include "mutation/mutate_job.hpp"

#include <string>

#include "io/frames/frames.hpp"
#include "model/util/util.hpp"
#include "mutation/campaign.hpp"

namespace hc::mutation {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string file_hash(const fs::path& p) { return util::hex64(util::fnv1a(util::read_file(p, "mutation list"))); }

/// The list of the manifest, refused when it changed since the manifest was made.
SmokeList campaign_of(const json& common) {
    const fs::path list = common.at("list").get<std::string>();
    if (file_hash(list) != common.at("list_hash"))
        throw hc::InputError("mutation list '" + list.string() + "' changed since the run was prepared");
    return load_smoke_list(list);
}

const SmokeMutant& find(const SmokeList& c, const std::string& id) {
    for (const auto& m : c.mutants)
        if (m.id == id) return m;
    throw hc::InputError("mutation list has no mutant '" + id + "'");
}

json outcome_json(const std::string& id, const SmokeOutcome& o) {
    json j = o;
    j["id"] = id;
    return j;
}

}  // namespace

cluster::Manifest mutate_manifest(const MutateJob& p) {
    const SmokeList c = load_smoke_list(p.list);
    std::vector<std::string> ids;
    for (const auto& m : c.mutants)
        if (p.only.empty() || m.id == p.only) ids.push_back(m.id);
    if (!p.only.empty() && ids.empty()) throw InputError("--only " + p.only + ": no such mutant in " + p.list.string());
    cluster::Manifest m;
    m.job = "mutate";
    m.common = {{"list", fs::absolute(p.list).string()}, {"list_hash", file_hash(p.list)}, {"rtl_hash", rtl_hash()},
                {"stream", stream_flags(c.stream)}};
    // unit 0 is the baseline, unit i the i-th mutant
    for (auto [a, b] : cluster::split_items(static_cast<long>(ids.size()) + 1, p.shards)) {
        json s = {{"baseline", a == 0}, {"mutants", json::array()}};
        for (long u = std::max(a, 1L); u < b; ++u) s["mutants"].push_back(ids[u - 1]);
        m.shards.push_back(s);
    }
    return m;
}

SmokeList mutate_campaign(const cluster::Manifest& m) { return campaign_of(m.common); }

SmokeResult mutate_result(const cluster::Manifest& m, const json& merged) {
    const SmokeList c = campaign_of(m.common);
    std::vector<SmokeVerdict> verdicts;
    for (const auto& o : merged.at("mutants")) verdicts.push_back(judge_smoke(find(c, o.at("id")), o.get<SmokeOutcome>()));
    return tally_smoke(merged.at("baseline").get<SmokeOutcome>(), std::move(verdicts));
}

void add_mutate_job(cluster::JobRegistry& r) {
    r.add({"mutate",
            [](const json& common, const json& shard, std::size_t index) {
                if (rtl_hash() != common.at("rtl_hash"))
                    throw hc::InputError("rtl/ changed since the mutation run was prepared");
                const SmokeList c = campaign_of(common);
                const frames::LoadedFrames lf = frames::load_frames(c.stream);
                util::ScratchDir scratch("harris-mutate-shard-" + std::to_string(index));
                json out = {{"mutants", json::array()}};
                if (shard.at("baseline")) out["baseline"] = outcome_json("", run_smoke_mutant(nullptr, lf, scratch.path() / "baseline"));
                for (const auto& id : shard.at("mutants")) {
                    const SmokeMutant& mu = find(c, id);
                    out["mutants"].push_back(outcome_json(mu.id, run_smoke_mutant(&mu, lf, scratch.path() / mu.id)));
                }
                return out;
            },
            [](const json&, const std::vector<json>& data) {
                json out = {{"mutants", json::array()}};
                for (const auto& d : data) {
                    if (d.contains("baseline")) out["baseline"] = d.at("baseline");
                    for (const auto& o : d.at("mutants")) out["mutants"].push_back(o);
                }
                return out;
            }});
}

}  // namespace hc::mutation

// slam_job.cpp: the job kind "slam" (slam_job.hpp), Monte-Carlo seeds of the EKF-SLAM
// simulator in shards, folded in seed order.
#include "mapping/slam/slam_job.hpp"

#include <string>

namespace hc::slam {

using nlohmann::json;

cluster::Manifest slam_manifest(const SlamJob& p) {
    p.config.validate();
    if (p.runs < 1) throw InputError("--runs must be at least 1, got " + std::to_string(p.runs));
    if (!(p.confidence > 0 && p.confidence < 1)) throw InputError("the confidence must be in (0, 1)");
    cluster::Manifest m;
    m.job = "slam";
    m.common = {{"config", p.config}, {"runs", p.runs}, {"first_seed", p.first_seed},
                {"confidence", p.confidence}};
    for (auto [a, b] : cluster::split_items(p.runs, p.shards))
        m.shards.push_back({{"first_run", a}, {"last_run", b}});
    return m;
}

MonteCarlo slam_result(const cluster::Manifest& m, const json& merged) {
    std::vector<RunErrors> runs;
    for (const auto& r : merged.at("runs")) runs.push_back(r.get<RunErrors>());
    if (static_cast<int>(runs.size()) != m.common.at("runs").get<int>())
        throw hc::InputError("slam: the merged data holds " + std::to_string(runs.size()) + " runs, the manifest " +
                                         m.common.at("runs").dump());
    MonteCarlo mc = fold_monte_carlo(runs, merged.at("first").get<RunTrace>(), m.common.at("confidence"));
    mc.first_seed = m.common.at("first_seed");
    return mc;
}

void add_slam_job(cluster::JobRegistry& r) {
    r.add({"slam",
            [](const json& common, const json& shard, std::size_t) {
                const SimConfig c = common.at("config").get<SimConfig>();
                c.validate();
                const std::uint64_t seed0 = common.at("first_seed");
                json runs = json::array();
                json out;
                for (long r = shard.at("first_run"); r < shard.at("last_run").get<long>(); ++r) {
                    const RunTrace t = run_simulation(c, seed0 + r);
                    runs.push_back(run_errors(t));
                    if (r == 0) out["first"] = t;
                }
                out["runs"] = std::move(runs);
                return out;
            },
            [](const json&, const std::vector<json>& data) {
                json runs = json::array(), first;
                for (const auto& d : data) {
                    for (const auto& r : d.at("runs")) runs.push_back(r);
                    if (d.contains("first")) first = d.at("first");
                }
                return json{{"runs", std::move(runs)}, {"first", std::move(first)}};
            }});
}

}  // namespace hc::slam

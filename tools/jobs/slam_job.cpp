// slam_job.cpp: the "slam" job kind, Monte-Carlo seeds of the EKF-SLAM simulator in shards,
// folded in seed order.
#include "tools/jobs/jobs.hpp"

#include <string>

namespace hc::jobs {

namespace {

json config_json(const slam::SimConfig& c) {
    return {{"layout", c.layout == slam::Layout::Random ? "random" : "cloister"},
            {"landmarks", c.landmarks},
            {"half_size", c.half_size},
            {"radius", c.radius},
            {"step", c.step},
            {"steps", c.steps},
            {"sigma_range", c.sensor.sigma_range},
            {"sigma_bearing", c.sensor.sigma_bearing},
            {"max_range", c.sensor.max_range},
            {"fov", c.sensor.fov},
            {"sigma_dx", c.odometry.sigma_dx},
            {"sigma_dtheta", c.odometry.sigma_dtheta},
            {"filter_sigma_scale", c.filter_sigma_scale}};
}

slam::SimConfig config_from(const json& j) {
    slam::SimConfig c;
    c.layout = j.at("layout") == "random" ? slam::Layout::Random : slam::Layout::Cloister;
    c.landmarks = j.at("landmarks");
    c.half_size = j.at("half_size");
    c.radius = j.at("radius");
    c.step = j.at("step");
    c.steps = j.at("steps");
    c.sensor.sigma_range = j.at("sigma_range");
    c.sensor.sigma_bearing = j.at("sigma_bearing");
    c.sensor.max_range = j.at("max_range");
    c.sensor.fov = j.at("fov");
    c.odometry.sigma_dx = j.at("sigma_dx");
    c.odometry.sigma_dtheta = j.at("sigma_dtheta");
    c.filter_sigma_scale = j.at("filter_sigma_scale");
    return c;
}

template <class M>
json matrix_json(const M& m) {
    std::vector<double> v;
    for (int r = 0; r < m.rows(); ++r)
        for (int c = 0; c < m.cols(); ++c) v.push_back(m(r, c));
    return detail::doubles(v);
}

template <class M>
M matrix_from(const json& j) {
    const std::vector<double> v = detail::doubles(j);
    M m;
    for (int r = 0, i = 0; r < m.rows(); ++r)
        for (int c = 0; c < m.cols(); ++c) m(r, c) = v.at(i++);
    return m;
}

template <class M>
json matrices_json(const std::vector<M>& v) {
    json a = json::array();
    for (const auto& m : v) a.push_back(matrix_json(m));
    return a;
}

template <class M>
std::vector<M> matrices_from(const json& j) {
    std::vector<M> v;
    for (const auto& m : j) v.push_back(matrix_from<M>(m));
    return v;
}

json errors_json(const slam::RunErrors& e) {
    return {{"pose_nees", detail::doubles(e.pose_nees)}, {"map_nees", detail::doubles(e.map_nees)},
            {"map_dof", e.map_dof},                      {"map_rmse", detail::doubles(e.map_rmse)},
            {"position_sq", detail::doubles(e.position_sq)}, {"heading_sq", detail::doubles(e.heading_sq)}};
}

slam::RunErrors errors_from(const json& j) {
    slam::RunErrors e;
    e.pose_nees = detail::doubles(j.at("pose_nees"));
    e.map_nees = detail::doubles(j.at("map_nees"));
    e.map_dof = j.at("map_dof").get<std::vector<int>>();
    e.map_rmse = detail::doubles(j.at("map_rmse"));
    e.position_sq = detail::doubles(j.at("position_sq"));
    e.heading_sq = detail::doubles(j.at("heading_sq"));
    return e;
}

/// What the report draws of the first seed's run (the filter itself is not carried).
json trace_json(const slam::RunTrace& t) {
    return {{"truth", matrices_json(t.truth)},         {"estimate", matrices_json(t.estimate)},
            {"pose_cov", matrices_json(t.pose_cov)},   {"pose_nees", detail::doubles(t.pose_nees)},
            {"map_nees", detail::doubles(t.map_nees)}, {"map_dof", t.map_dof},
            {"map_rmse", detail::doubles(t.map_rmse)}, {"world", matrices_json(t.world.landmarks)},
            {"final_map", matrices_json(t.final_map)}, {"final_map_cov", matrices_json(t.final_map_cov)}};
}

slam::RunTrace trace_from(const json& j) {
    slam::RunTrace t;
    t.truth = matrices_from<slam::Pose>(j.at("truth"));
    t.estimate = matrices_from<slam::Pose>(j.at("estimate"));
    t.pose_cov = matrices_from<slam::Mat3>(j.at("pose_cov"));
    t.pose_nees = detail::doubles(j.at("pose_nees"));
    t.map_nees = detail::doubles(j.at("map_nees"));
    t.map_dof = j.at("map_dof").get<std::vector<int>>();
    t.map_rmse = detail::doubles(j.at("map_rmse"));
    t.world.landmarks = matrices_from<slam::Vec2>(j.at("world"));
    t.final_map = matrices_from<slam::Vec2>(j.at("final_map"));
    t.final_map_cov = matrices_from<slam::Mat2>(j.at("final_map_cov"));
    return t;
}

}  // namespace

cluster::Manifest slam_manifest(const SlamShards& p) {
    p.config.validate();
    if (p.runs < 1) throw slam::InputError("--runs must be at least 1, got " + std::to_string(p.runs));
    if (!(p.confidence > 0 && p.confidence < 1)) throw slam::InputError("the confidence must be in (0, 1)");
    cluster::Manifest m;
    m.job = "slam";
    m.common = {{"config", config_json(p.config)}, {"runs", p.runs}, {"first_seed", p.first_seed},
                {"confidence", p.confidence}};
    for (auto [a, b] : cluster::split_items(p.runs, p.shards))
        m.shards.push_back({{"first_run", a}, {"last_run", b}});
    return m;
}

slam::MonteCarlo slam_result(const cluster::Manifest& m, const json& merged) {
    std::vector<slam::RunErrors> runs;
    for (const auto& r : merged.at("runs")) runs.push_back(errors_from(r));
    if (static_cast<int>(runs.size()) != m.common.at("runs").get<int>())
        throw cluster::ClusterInputError("slam: the merged data holds " + std::to_string(runs.size()) + " runs, the manifest " +
                                         m.common.at("runs").dump());
    return slam::fold_monte_carlo(runs, trace_from(merged.at("first")), m.common.at("confidence"));
}

namespace detail {

cluster::ShardJob slam_job() {
    return {"slam",
            [](const json& common, const json& shard, std::size_t) {
                const slam::SimConfig c = config_from(common.at("config"));
                c.validate();
                const std::uint64_t seed0 = common.at("first_seed");
                json runs = json::array();
                json out;
                for (long r = shard.at("first_run"); r < shard.at("last_run").get<long>(); ++r) {
                    const slam::RunTrace t = slam::run_simulation(c, seed0 + r);
                    runs.push_back(errors_json(slam::run_errors(t)));
                    if (r == 0) out["first"] = trace_json(t);
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
            }};
}

}  // namespace detail

}  // namespace hc::jobs

// simulation_json.cpp: the JSON of the simulator's configuration and of a run's errors and
// trace (simulator.hpp, consistency.hpp), as sharded Monte-Carlo runs carry them.
#include "mapping/slam/consistency.hpp"

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

namespace hc::slam {

using nlohmann::json;

namespace {

/// A list of doubles with NaN as null (JSON has no NaN) and back, bit for bit.
json doubles(const std::vector<double>& v) {
    json a = json::array();
    for (double x : v) a.push_back(std::isnan(x) ? json(nullptr) : json(x));
    return a;
}

std::vector<double> doubles(const json& j) {
    std::vector<double> v;
    for (const auto& x : j) v.push_back(x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.get<double>());
    return v;
}

template <class M>
json matrix_json(const M& m) {
    std::vector<double> v;
    for (int r = 0; r < m.rows(); ++r)
        for (int c = 0; c < m.cols(); ++c) v.push_back(m(r, c));
    return doubles(v);
}

template <class M>
M matrix_from(const json& j) {
    const std::vector<double> v = doubles(j);
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

}  // namespace

void to_json(json& j, const SimConfig& c) {
    j = {{"layout", c.layout == Layout::Random ? "random" : "cloister"},
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

void from_json(const json& j, SimConfig& c) {
    c.layout = j.at("layout") == "random" ? Layout::Random : Layout::Cloister;
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
}

void to_json(json& j, const RunErrors& e) {
    j = {{"pose_nees", doubles(e.pose_nees)}, {"map_nees", doubles(e.map_nees)},
         {"map_dof", e.map_dof},              {"map_rmse", doubles(e.map_rmse)},
         {"position_sq", doubles(e.position_sq)}, {"heading_sq", doubles(e.heading_sq)}};
}

void from_json(const json& j, RunErrors& e) {
    e.pose_nees = doubles(j.at("pose_nees"));
    e.map_nees = doubles(j.at("map_nees"));
    e.map_dof = j.at("map_dof").get<std::vector<int>>();
    e.map_rmse = doubles(j.at("map_rmse"));
    e.position_sq = doubles(j.at("position_sq"));
    e.heading_sq = doubles(j.at("heading_sq"));
}

void to_json(json& j, const RunTrace& t) {
    j = {{"truth", matrices_json(t.truth)},         {"estimate", matrices_json(t.estimate)},
         {"pose_cov", matrices_json(t.pose_cov)},   {"pose_nees", doubles(t.pose_nees)},
         {"map_nees", doubles(t.map_nees)},         {"map_dof", t.map_dof},
         {"map_rmse", doubles(t.map_rmse)},         {"world", matrices_json(t.world.landmarks)},
         {"final_map", matrices_json(t.final_map)}, {"final_map_cov", matrices_json(t.final_map_cov)}};
}

void from_json(const json& j, RunTrace& t) {
    t.truth = matrices_from<Pose>(j.at("truth"));
    t.estimate = matrices_from<Pose>(j.at("estimate"));
    t.pose_cov = matrices_from<Mat3>(j.at("pose_cov"));
    t.pose_nees = doubles(j.at("pose_nees"));
    t.map_nees = doubles(j.at("map_nees"));
    t.map_dof = j.at("map_dof").get<std::vector<int>>();
    t.map_rmse = doubles(j.at("map_rmse"));
    t.world.landmarks = matrices_from<Vec2>(j.at("world"));
    t.final_map = matrices_from<Vec2>(j.at("final_map"));
    t.final_map_cov = matrices_from<Mat2>(j.at("final_map_cov"));
}

}  // namespace hc::slam

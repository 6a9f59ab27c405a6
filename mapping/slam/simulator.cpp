// simulator.cpp: the 2-D world, the robot on a circle, its noisy odometry and its
// range-bearing sensor (field of view, range limit, Gaussian noise), like the simulator of
// the thesis's Figure 27 (Solà's course simulator).
#include <cmath>
#include <numbers>

#include "mapping/slam/simulator.hpp"

namespace hc::slam {

namespace {
void require_positive(double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
        throw InputError(std::string(name) + " must be a positive number, got " + std::to_string(v));
}

// A point at arc length s along the perimeter of the square [-h, h]², counter-clockwise
// from (-h, -h).
Vec2 on_square(double h, double s) {
    const double side = 2 * h;
    s = std::fmod(s, 4 * side);
    if (s < side) return {-h + s, -h};
    if (s < 2 * side) return {h, -h + (s - side)};
    if (s < 3 * side) return {h - (s - 2 * side), h};
    return {-h, h - (s - 3 * side)};
}
}  // namespace

Mat2 OdometryModel::covariance() const {
    return Eigen::Vector2d(sigma_dx * sigma_dx, sigma_dtheta * sigma_dtheta).asDiagonal();
}

void SimConfig::validate() const {
    if (landmarks < 1) throw InputError("the world is empty: --landmarks must be at least 1, got " + std::to_string(landmarks));
    if (steps < 1) throw InputError("--steps must be at least 1, got " + std::to_string(steps));
    require_positive(half_size, "--half-size");
    require_positive(radius, "--radius");
    require_positive(step, "--step");
    require_positive(sensor.sigma_range, "--sigma-range");
    require_positive(sensor.sigma_bearing, "--sigma-bearing");
    require_positive(sensor.max_range, "--max-range");
    require_positive(sensor.fov, "--fov");
    if (sensor.fov > 2 * std::numbers::pi + 1e-9) throw InputError("--fov must be at most 360 degrees");
    require_positive(odometry.sigma_dx, "--sigma-dx");
    require_positive(odometry.sigma_dtheta, "--sigma-dtheta");
    require_positive(filter_sigma_scale, "the filter's noise scale");
}

World make_world(Layout layout, int count, double half_size, uint64_t seed) {
    if (count < 1) throw InputError("the world is empty: the landmark count must be at least 1, got " + std::to_string(count));
    World w;
    w.landmarks.reserve(count);
    if (layout == Layout::Random) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-half_size, half_size);
        for (int i = 0; i < count; ++i) {
            const double x = u(rng);
            w.landmarks.emplace_back(x, u(rng));
        }
        return w;
    }
    // cloister: two concentric squares; the outer (twice the perimeter) holds 2/3 of them
    const int outer = std::max(1, static_cast<int>(std::lround(count * 2.0 / 3.0)));
    const int inner = count - outer;
    for (int i = 0; i < outer; ++i) w.landmarks.push_back(on_square(half_size, 8 * half_size * i / outer));
    for (int i = 0; i < inner; ++i) w.landmarks.push_back(on_square(half_size / 2, 4 * half_size * (i + 0.5) / inner));
    return w;
}

namespace {
const SimConfig& validated(const SimConfig& c) {
    c.validate();
    return c;
}
}  // namespace

Simulator::Simulator(const SimConfig& config, uint64_t seed)
    : config_(validated(config)), world_(make_world(config.layout, config.landmarks, config.half_size, seed)),
      rng_(seed) {
    pose_ = start_pose();
}

Pose Simulator::start_pose() const { return {0.0, -config_.radius, 0.0}; }

Vec2 Simulator::step() {
    const Vec2 u(config_.step, config_.step / config_.radius);
    pose_ = move(pose_, u, Vec2::Zero());
    const double nx = gauss_(rng_), nt = gauss_(rng_);
    return {u(0) + config_.odometry.sigma_dx * nx, u(1) + config_.odometry.sigma_dtheta * nt};
}

Observation Simulator::measure(int id) {
    const Vec2 y = slam::observe(pose_, world_.landmarks[id]);
    const double nr = gauss_(rng_), nb = gauss_(rng_);
    return {id, Vec2(y(0) + config_.sensor.sigma_range * nr, wrap_angle(y(1) + config_.sensor.sigma_bearing * nb))};
}

std::vector<Observation> Simulator::observe() {
    std::vector<Observation> out;
    for (int i = 0; i < static_cast<int>(world_.landmarks.size()); ++i) {
        const Vec2 y = slam::observe(pose_, world_.landmarks[i]);
        if (y(0) > 1e-9 && y(0) <= config_.sensor.max_range && std::abs(y(1)) <= config_.sensor.fov / 2) out.push_back(measure(i));
    }
    return out;
}

std::vector<Observation> Simulator::observe_all() {
    std::vector<Observation> out;
    for (int i = 0; i < static_cast<int>(world_.landmarks.size()); ++i) out.push_back(measure(i));
    return out;
}

}  // namespace hc::slam

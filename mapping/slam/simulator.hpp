// simulator.hpp: the EKF-SLAM simulator (slam.hpp): a robot on a loop among landmarks, its
// range-bearing sensor and noisy odometry, and one run of the filter over it.
#pragma once

#include "mapping/slam/ekf.hpp"

#include <random>

#include <nlohmann/json_fwd.hpp>

namespace hc::slam {

/// A range-bearing sensor: field of view (full angle), range limit, Gaussian noise.
struct SensorModel {
    double sigma_range = 0.05;          ///< m
    double sigma_bearing = 0.01745;     ///< rad (1°)
    double max_range = 6.0;             ///< m
    double fov = 3.14159265358979;      ///< rad, full angle centred on the heading
};

/// Odometry u = (dx, dθ) read with Gaussian noise of these standard deviations.
struct OdometryModel {
    double sigma_dx = 0.01;       ///< m per step
    double sigma_dtheta = 0.005;  ///< rad per step
    Mat2 covariance() const;
};

enum class Layout { Cloister, Random };

/// A simulated run: a world of landmarks around a circular trajectory.
struct SimConfig {
    Layout layout = Layout::Cloister;
    int landmarks = 40;          ///< world landmarks (> 0)
    double half_size = 5.0;      ///< m: the world spans [-half_size, half_size]²
    double radius = 3.75;        ///< m: radius of the robot's circle (centred at the origin)
    double step = 0.1;           ///< m advanced per step
    int steps = 236;             ///< motion steps (2π·radius/step ≈ 236: one loop)
    SensorModel sensor;
    OdometryModel odometry;
    /// The filter assumes noise standard deviations this many times the simulator's
    /// (1 = matched; below 1 an over-confident filter, to show that the NEES test fails).
    double filter_sigma_scale = 1.0;
    /// Throws InputError naming the first bad value (non-positive noise, empty world, ...).
    void validate() const;
};
/// A configuration as one flat JSON object (layout "cloister" or "random", the sensor's and
/// the odometry's fields beside the others); mapping/slam/simulation_json.cpp.
void to_json(nlohmann::json& j, const SimConfig& c);
void from_json(const nlohmann::json& j, SimConfig& c);

/// A world: landmark positions (index = landmark id).
struct World {
    std::vector<Vec2> landmarks;
};

/// The cloister (landmarks on two concentric squares, half_size and half_size/2, like
/// Solà's `cloister`) or a uniform random layout in [-half_size, half_size]².
World make_world(Layout layout, int count, double half_size, uint64_t seed);

/// One measured landmark.
struct Observation {
    int id = 0;
    Vec2 y = Vec2::Zero();
};

/// The simulator: ground-truth robot on a circle through the world, noisy odometry and
/// noisy range-bearing observations of the landmarks within field of view and range.
/// Seeded: the same config and seed give the same run.
class Simulator {
public:
    Simulator(const SimConfig& config, uint64_t seed);
    const World& world() const { return world_; }
    const Pose& true_pose() const { return pose_; }
    /// The robot's start pose (on the circle, heading tangent to it).
    Pose start_pose() const;
    /// Moves the true robot one step; returns the odometry reading (with noise).
    Vec2 step();
    /// Noisy observations of the landmarks visible from the true pose.
    std::vector<Observation> observe();
    /// Noisy observations of every landmark, visible or not (the thesis's worst case).
    std::vector<Observation> observe_all();

private:
    Observation measure(int id);
    SimConfig config_;
    World world_;
    Pose pose_;
    std::mt19937_64 rng_;
    std::normal_distribution<double> gauss_{0.0, 1.0};
};

}  // namespace hc::slam

// slam_command.hpp: `harris-cosim slam` as the command line hands it over: a Monte-Carlo
// consistency run in the simulator (--simulate, in one process or its seeds in shards), or
// KITTI-layout sequences (--sequences) or a calibrated rig's pairs (--calib --left --right) with
// stereo or synthetic landmarks and visual or synthetic odometry, scored against a ground truth
// when there is one (docs/slam.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/cluster/runner.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "mapping/slam/landmark_slam.hpp"
#include "mapping/slam/odometry.hpp"
#include "mapping/slam/simulator.hpp"
#include "mapping/slam/synthetic.hpp"

namespace hc::slam {

/// The command's settings, one field per flag. Every model default is its struct's
/// (SimConfig, SensorModel, AssociationConfig, VisualOdometryConfig, SyntheticOdometry,
/// KittiRunOptions); the angles are the command's, in degrees.
struct SlamCommand {
    bool simulate = false;
    std::string command_line;   ///< the command as the user typed it (less the sharding flags), for the reports
    /// every flag's value, given or default, one `name=value` a line, for the reports
    std::string settings;
    std::string pairs;          ///< --pairs a:b of each sequence or of the rig (KittiRunOptions::pairs)
    std::string sequences, kitti, data, out = "slam-report", world = "cloister", truth,
        landmarks_from = KittiRunOptions{}.stereo_landmarks ? "stereo" : "synthetic", odometry = "visual",
        association = "jcbb", vo_residual = "pixels";
    int landmarks = SimConfig{}.landmarks, steps = SimConfig{}.steps, runs = 50,
        synthetic_count = KittiRunOptions{}.synthetic_count, flip_bits = KittiRunOptions{}.flip_bits,
        forget_after = AssociationConfig{}.forget_after, max_observations = AssociationConfig{}.max_observations,
        vo_min_inliers = VisualOdometryConfig{}.min_inliers;
    std::uint64_t seed = 1;
    bool seed_given = false;   ///< --seed was given (refused where nothing is drawn)
    double half_size = SimConfig{}.half_size, radius = SimConfig{}.radius, step = SimConfig{}.step,
           sigma_range = SensorModel{}.sigma_range, sigma_bearing_deg = 1, fov_deg = 180,
           max_range = SensorModel{}.max_range, gate = AssociationConfig{}.gate_probability,
           joint_gate = AssociationConfig{}.joint_probability,
           max_hamming_fraction = AssociationConfig{}.max_hamming_fraction,
           vo_hamming_fraction = VisualOdometryConfig{}.max_hamming_fraction,
           vo_max_range = VisualOdometryConfig{}.max_range;
    std::optional<double> sigma_dx, sigma_dtheta_deg;
    double sigma_dy = SyntheticOdometry{}.sigma_dy;
    bool descriptor = true, vo_disparity_offset = VisualOdometryConfig{}.estimate_disparity_offset;
    bool vo_offset_uncertainty = VisualOdometryConfig{}.offset_uncertainty;
    bool noise_at_prediction = AssociationConfig{}.noise_at_prediction, vo_level = VisualOdometryConfig{}.level;
    bool correct_with_odometry_inliers = AssociationConfig{}.correct_with_odometry_inliers;
    double odometry_inlier_noise_scale = AssociationConfig{}.odometry_inlier_noise_scale;
    bool vo_measured_noise = VisualOdometryConfig{}.noise_from_residuals, vo_two_view = VisualOdometryConfig{}.two_view_points;
    // --landmarks-from stereo: the landmark pipeline's options
    std::string corners = landmarks::detector_name(KittiRunOptions{}.pipeline.detector),
                descriptor_name = landmarks::descriptor_name(KittiRunOptions{}.pipeline.descriptor), config;
    int g = KittiRunOptions{}.pipeline.grid.g, h = KittiRunOptions{}.pipeline.grid.h;
    // a rig's pairs instead of a KITTI-layout sequence, the ground truth, the timestamps
    frames::RigSource rig;      ///< --calib, --left, --right
    bool score_overlap = KittiRunOptions{}.score_overlap;
    double frame_period = KittiRunOptions{}.frame_period, truth_time_tolerance = KittiRunOptions{}.truth_time_tolerance;
};

/// The options of a KITTI-layout or rig run (run_kitti_sequence, run_rig_sequence) as the command
/// fills them from its settings: kitti_options(SlamCommand{}) is the command's defaults. Parses
/// the corner source and descriptor names (InputError for unknown ones).
KittiRunOptions kitti_options(const SlamCommand& c);

/// Runs the simulation or the sequences, writes the reports into c.out and prints their
/// figures. InputError for bad input (including sharding flags without --simulate).
void run_slam_command(const SlamCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::slam

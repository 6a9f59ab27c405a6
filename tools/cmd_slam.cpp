// cmd_slam.cpp: the flags of `harris-cosim slam` (mapping/slam/slam_command.hpp): 2-D EKF-SLAM in the
// simulator (--simulate) or on KITTI sequences (--sequences) (docs/slam.md).
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "mapping/landmarks/landmarks.hpp"
#include "mapping/slam/slam_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

namespace {

std::string num(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

/// The simulator's flags.
void add_simulator_flags(CLI::App* cmd, slam::SlamCommand& o) {
    constexpr double deg = std::numbers::pi / 180;
    cmd->add_option("--world", o.world, "simulated world layout: cloister or random")->capture_default_str();
    cmd->add_option("--landmarks", o.landmarks, "simulated world landmarks")->capture_default_str();
    cmd->add_option("--half-size", o.half_size, "world half size (m)")->capture_default_str();
    cmd->add_option("--radius", o.radius, "radius of the robot's circle (m)")->capture_default_str();
    cmd->add_option("--step", o.step, "distance per step (m)")->capture_default_str();
    cmd->add_option("--steps", o.steps, "steps per run")->capture_default_str();
    cmd->add_option("--runs", o.runs, "Monte-Carlo runs")->capture_default_str();
    cmd->add_option("--sigma-range", o.sigma_range, "range noise (m)")->capture_default_str();
    cmd->add_option("--sigma-bearing", o.sigma_bearing_deg, "bearing noise (deg)")->capture_default_str();
    cmd->add_option("--fov", o.fov_deg, "sensor field of view, full angle (deg)")->capture_default_str();
    cmd->add_option("--max-range", o.max_range, "sensor range limit (m)")->capture_default_str();
    cmd->add_option("--sigma-dx", o.sigma_dx, "odometry noise on dx (m per step; default " + num(slam::OdometryModel{}.sigma_dx) +
                    " simulated, " + num(slam::SyntheticOdometry{}.sigma_dx) + " KITTI --odometry synthetic)");
    cmd->add_option("--sigma-dy", o.sigma_dy, "KITTI --odometry synthetic: noise on dy (m per frame)")->capture_default_str();
    cmd->add_option("--sigma-dtheta", o.sigma_dtheta_deg,
                    fmt::format("odometry noise on dθ (deg per step; default {:.3f} simulated, {:.3f} KITTI --odometry synthetic)",
                                slam::OdometryModel{}.sigma_dtheta / deg, slam::SyntheticOdometry{}.sigma_dtheta / deg));
}

/// The KITTI run's odometry flags: which odometry, and visual odometry's settings.
void add_odometry_flags(CLI::App* cmd, slam::SlamCommand& o) {
    cmd->add_option("--odometry", o.odometry,
                    "KITTI: visual (stereo visual odometry from the landmarks; no ground truth) or synthetic "
                    "(the ground-truth relative poses plus noise of --sigma-dx/dy/dtheta)")
        ->capture_default_str();
    cmd->add_option("--vo-hamming-fraction", o.vo_hamming_fraction,
                    "visual odometry: frame-to-frame matches up to this fraction of the descriptor's bits")
        ->capture_default_str();
    cmd->add_option("--vo-min-inliers", o.vo_min_inliers,
                    "visual odometry: fewer RANSAC inliers and the frame's estimate counts as failed")
        ->capture_default_str();
    cmd->add_option("--vo-max-range", o.vo_max_range, "visual odometry: points farther than this (m) are not used")
        ->capture_default_str();
    cmd->add_option("--vo-residual", o.vo_residual,
                    "visual odometry: pixels (6-DoF, reprojection into the rig's pixels) or top-view (3-DoF, "
                    "top-view points aligned in the plane)")
        ->capture_default_str();
    cmd->add_flag("!--no-vo-disparity-offset", o.vo_disparity_offset,
                  "visual odometry on pixels: do not estimate a disparity correction common to the rig's "
                  "measurements (estimated by default, with each motion)");
    cmd->add_flag("!--no-vo-offset-uncertainty", o.vo_offset_uncertainty,
                  "visual odometry on pixels: do not add the disparity correction's uncertainty to the motions' "
                  "covariances (added by default: the motion's sensitivity to the correction times its variance)");
    cmd->add_flag("!--no-vo-level", o.vo_level,
                  "visual odometry on pixels: motions and the filter's frames in each camera's own frame, not levelled "
                  "by the tilt of the 6-DoF steps");
    cmd->add_flag("--vo-two-view", o.vo_two_view,
                  "visual odometry on pixels: refine each motion jointly with its inliers' points, estimated from "
                  "both frames' pixels (two-view bundle adjustment; off by default)");
    cmd->add_flag("--vo-measured-noise", o.vo_measured_noise,
                  "visual odometry: scale every frame's covariance by the variance factor of the run's own inlier "
                  "residuals, for the odometry and the filter (off by default)");
}

/// The landmark source and data association flags of a KITTI run.
void add_landmark_flags(CLI::App* cmd, slam::SlamCommand& o) {
    cmd->add_option("--association", o.association, "KITTI: jcbb (joint compatibility) or nearest (individual gating)")
        ->capture_default_str();
    cmd->add_option("--joint-gate", o.joint_gate, "JCBB: joint gate probability (chi-square, 2k dof)")->capture_default_str();
    cmd->add_option("--landmarks-from", o.landmarks_from,
                    "landmark source of a KITTI run: stereo (the landmark pipeline on the sequence's stereo pairs) "
                    "or synthetic (points laid along the ground-truth trajectory)")
        ->capture_default_str();
    cmd->add_option("--corners", o.corners, "stereo: corner source: " + landmarks::detector_list(true))
        ->capture_default_str();
    cmd->add_option("--descriptor", o.descriptor_name,
                    "stereo: descriptor, a binary one (the descriptor check compares Hamming distances): " +
                    landmarks::descriptor_list(true, +[](const landmarks::DescriptorInfo& r) { return landmarks::is_binary(r.id); }))
        ->capture_default_str();
    cmd->add_option("--g", o.g, "stereo: grid side (cells)")->capture_default_str();
    cmd->add_option("--h", o.h, "stereo: grid resolution reduction 2^h")->capture_default_str();
    cmd->add_option("--config", o.config, "stereo: bit-width formats (JSON) of the spec/cycle/rtl corner sources");
    cmd->add_option("--synthetic-count", o.synthetic_count, "synthetic world points along the trajectory")->capture_default_str();
    cmd->add_option("--flip-bits", o.flip_bits, "bits flipped in each synthetic descriptor observation")->capture_default_str();
    cmd->add_option("--gate", o.gate, "Mahalanobis gate probability (chi-square, 2 dof)")->capture_default_str();
    cmd->add_option("--max-hamming-fraction", o.max_hamming_fraction,
                    "association's descriptor check: largest Hamming distance as a fraction of the descriptor's bits")
        ->capture_default_str();
    cmd->add_flag("!--no-descriptor", o.descriptor,
                  "associate by the Mahalanobis gates alone (visual odometry still matches descriptors)");
    cmd->add_flag("!--noise-at-measurement", o.noise_at_prediction,
                  "gate, associate and correct each observation with its noise where it was measured, not at the "
                  "landmark's prediction");
    cmd->add_flag("!--no-odometry-inlier-corrections", o.correct_with_odometry_inliers,
                  "visual odometry: an observation that was an inlier of the motion into its frame is associated "
                  "but does not correct the filter (its pixels used by the motion only; corrected by default)");
    cmd->add_option("--odometry-inlier-noise-scale", o.odometry_inlier_noise_scale,
                    "visual odometry: an observation that was an inlier of the motion into its frame gates, associates "
                    "and corrects the filter with its noise times this (at least 1)")
        ->capture_default_str();
    cmd->add_option("--forget-after", o.forget_after, "remove landmarks unseen for this many frames (0: keep)")->capture_default_str();
    cmd->add_option("--max-observations", o.max_observations, "observations used per frame, the most precise first (0: all)")
        ->capture_default_str();
}

}  // namespace

void add_slam_command(CLI::App& app) {
    const auto [cmd, o] = add_command<Sharded<slam::SlamCommand>>(app,
        "slam", "2-D EKF-SLAM (thesis 2.5, 5.4): Monte-Carlo consistency in the simulator, or a trajectory of a KITTI sequence or a rig's stereo pairs");
    cmd->add_flag("--simulate", o->simulate, "Monte-Carlo runs in the simulator (NEES, RMSE, plots)");
    cmd->add_option("--sequences", o->sequences,
                    "KITTI sequences, comma-separated (e.g. 01 or 01,02): stereo pairs of sequences/NN, "
                    "ground truth poses/NN.txt when present (read only to score)");
    add_pair_range_option(cmd, o->pairs, ", or of the rig's --left/--right; ground truth: the poses of these pairs");
    add_rig_options(cmd, o->rig,
                    "run on its --left/--right pairs instead of a KITTI sequence, keypoints rectified as landmarks "
                    "--calib does");
    cmd->add_option("--truth", o->truth,
                    "ground truth (KITTI: 12 numbers a line, or TUM: t tx ty tz qx qy qz qw; camera 0 in the first "
                    "camera's frame, one pose per frame in order); default: the sequence's poses/NN.txt when present, "
                    "else the run is not scored");
    cmd->add_flag("--score-overlap", o->score_overlap,
                  "a ground truth with another number of poses than stereo pairs: score the frames both cover "
                  "(refused without this flag)");
    cmd->add_option("--truth-time-tolerance", o->truth_time_tolerance,
                    "a TUM --truth on a sequence with times.txt is paired with the frames by timestamp: the nearest "
                    "pose within this (s); a frame without one is refused unless --score-overlap")
        ->capture_default_str();
    cmd->add_option("--frame-period", o->frame_period,
                    "TUM timestamps where the sequence has no times.txt (and on a rig): frame index x this (s)")
        ->capture_default_str();
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding poses/ (default: <data>/kitti)");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--seed", o->seed,
                    "first seed (runs use seed, seed+1, ...); KITTI: the synthetic world or odometry (refused with "
                    "visual odometry on stereo landmarks, which draws nothing)")
        ->capture_default_str();
    add_simulator_flags(cmd, *o);
    add_odometry_flags(cmd, *o);
    add_landmark_flags(cmd, *o);
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->seed_given = cmd->count("--seed") > 0;
        o->settings = effective_settings(cmd);
        run_quoting_command_line(cmd, *o, slam::run_slam_command);
    });
}

}  // namespace hc::tools

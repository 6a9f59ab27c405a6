// cmd_slam.cpp: `harris-cosim slam`, 2-D EKF-SLAM (slam/slam.hpp): a Monte-Carlo
// consistency run in the simulator (--simulate), or KITTI sequences (--sequences) with
// stereo landmarks and visual odometry (or synthetic odometry on the real trajectory),
// scored against the ground-truth poses. Parses flags, calls hc::slam, prints;
// hc::slam::InputError becomes exit status 2. Docs: docs/slam.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"
#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "io/util/util.hpp"
#include "slam/landmarks/landmarks.hpp"
#include "slam/landmark_frames.hpp"
#include "slam/slam.hpp"
#include "slam/slam_job.hpp"

namespace hc::tools {

namespace {

constexpr double deg = std::numbers::pi / 180;

struct SlamOptions {
    bool simulate = false;
    std::string sequences, kitti, data, out = "slam-report", world = "cloister", landmarks_from = slam::KittiRunOptions{}.stereo_landmarks ? "stereo" : "synthetic",
                odometry = "visual", association = "jcbb", vo_residual = "pixels";
    // every model default is its struct's (slam::SimConfig, SensorModel, AssociationConfig,
    // VisualOdometryConfig, SyntheticOdometry); the angles are the command's, in degrees
    int landmarks = slam::SimConfig{}.landmarks, steps = slam::SimConfig{}.steps, runs = 50,
        synthetic_count = slam::KittiRunOptions{}.synthetic_count, flip_bits = slam::KittiRunOptions{}.flip_bits,
        forget_after = slam::AssociationConfig{}.forget_after,
        max_observations = slam::AssociationConfig{}.max_observations, vo_min_inliers = slam::VisualOdometryConfig{}.min_inliers;
    uint64_t seed = 1;
    bool seed_given = false;
    double half_size = slam::SimConfig{}.half_size, radius = slam::SimConfig{}.radius, step = slam::SimConfig{}.step,
           sigma_range = slam::SensorModel{}.sigma_range, sigma_bearing_deg = 1, fov_deg = 180,
           max_range = slam::SensorModel{}.max_range, gate = slam::AssociationConfig{}.gate_probability,
           joint_gate = slam::AssociationConfig{}.joint_probability,
           max_hamming_fraction = slam::AssociationConfig{}.max_hamming_fraction,
           vo_hamming_fraction = slam::VisualOdometryConfig{}.max_hamming_fraction,
           vo_max_range = slam::VisualOdometryConfig{}.max_range;
    std::optional<double> sigma_dx, sigma_dtheta_deg;
    double sigma_dy = slam::SyntheticOdometry{}.sigma_dy;
    bool descriptor = true, vo_disparity_offset = slam::VisualOdometryConfig{}.estimate_disparity_offset;
    // --landmarks-from stereo: the landmark pipeline's options
    std::string corners = landmarks::detector_name(slam::KittiRunOptions{}.pipeline.detector),
                descriptor_name = landmarks::descriptor_name(slam::KittiRunOptions{}.pipeline.descriptor), config;
    int g = slam::KittiRunOptions{}.pipeline.grid.g, h = slam::KittiRunOptions{}.pipeline.grid.h;
    // --simulate: Monte-Carlo seeds in shards (runner_flags.hpp: sharded())
    RunnerFlags runner;
    bool sharded = false;
};

std::string num(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

/// The help of an odometry noise flag, naming its two defaults (the simulator's and the KITTI
/// synthetic odometry's, each its struct's).
std::string noise_help(const std::string& what, const std::string& simulated, const std::string& kitti) {
    return what + "; default " + simulated + " simulated, " + kitti + " KITTI --odometry synthetic)";
}

void run_simulate(const SlamOptions& o) {
    slam::SimConfig c;
    c.layout = o.world == "random" ? slam::Layout::Random : slam::Layout::Cloister;
    c.landmarks = o.landmarks;
    c.half_size = o.half_size;
    c.radius = o.radius;
    c.step = o.step;
    c.steps = o.steps;
    c.sensor.sigma_range = o.sigma_range;
    c.sensor.sigma_bearing = o.sigma_bearing_deg * deg;
    c.sensor.fov = o.fov_deg * deg;
    c.sensor.max_range = o.max_range;
    if (o.sigma_dx) c.odometry.sigma_dx = *o.sigma_dx;
    if (o.sigma_dtheta_deg) c.odometry.sigma_dtheta = *o.sigma_dtheta_deg * deg;
    c.validate();
    const std::string command =
        "harris-cosim slam --simulate --world " + o.world + " --landmarks " + std::to_string(o.landmarks) +
        " --half-size " + num(o.half_size) + " --radius " + num(o.radius) + " --step " + num(o.step) + " --steps " +
        std::to_string(o.steps) + " --runs " + std::to_string(o.runs) + " --seed " + std::to_string(o.seed) +
        " --sigma-range " + num(o.sigma_range) + " --sigma-bearing " + num(o.sigma_bearing_deg) + " --fov " +
        num(o.fov_deg) + " --max-range " + num(o.max_range) + " --sigma-dx " + num(c.odometry.sigma_dx) +
        " --sigma-dtheta " + num(c.odometry.sigma_dtheta / deg) + " --out " + o.out;
    slam::MonteCarlo mc;
    if (o.sharded) {
        slam::SlamShards p;
        p.config = c;
        p.runs = o.runs;
        p.first_seed = o.seed;
        p.shards = o.runner.shards;
        const cluster::Manifest m = slam::slam_manifest(p);
        const std::filesystem::path dir = run_dir(o.runner, o.out);
        const auto merged = run_sharded(dir, m, o.runner);
        if (!merged) return;
        mc = slam::slam_result(m, *merged);
    } else {
        mc = slam::monte_carlo(c, o.runs, o.seed, 0.95, [](int done, int total) {
            if (done % 10 == 0 || done == total) std::fprintf(stderr, "slam: run %d/%d\n", done, total);
        });
    }
    slam::write_simulation_report(o.out, c, mc, command);
    std::printf("pose NEES average %.3f, 95 %% bounds [%.3f, %.3f], %.1f %% of steps inside\n", mc.pose_nees_average,
                mc.pose_lo, mc.pose_hi, 100 * mc.pose_inside);
    std::printf("map NEES per dof average %.3f, %.1f %% of steps inside their bounds\n", mc.map_nees_per_dof_average,
                100 * mc.map_inside);
    std::printf("final RMSE: position %.4f m, heading %.4f deg, landmarks %.4f m\n", mc.position_rmse.back(),
                mc.heading_rmse.back() / deg, mc.map_rmse.back());
    std::printf("report: %s/report.md\n", o.out.c_str());
}

std::vector<std::string> split_sequences(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream ss(list);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    if (out.empty()) throw InputError("--sequences '" + list + "' names no sequence");
    return out;
}

std::string odometry_label(const SlamOptions& o) {
    return o.odometry == "visual" ? "visual odometry alone" : "synthetic odometry alone";
}

slam::SequenceRun run_one_sequence(const SlamOptions& o, const std::filesystem::path& kitti, const std::string& sequence,
                                   const std::filesystem::path& out) {
    slam::KittiRunOptions k;
    slam::AssociationConfig& ac = k.association;
    ac.method = o.association == "nearest" ? slam::AssociationMethod::Nearest : slam::AssociationMethod::Jcbb;
    ac.gate_probability = o.gate;
    ac.joint_probability = o.joint_gate;
    ac.max_hamming_fraction = o.max_hamming_fraction;
    ac.check_descriptor = o.descriptor;
    ac.forget_after = o.forget_after;
    ac.max_observations = o.max_observations;
    slam::VisualOdometryConfig& vc = k.vo;
    vc.max_hamming_fraction = o.vo_hamming_fraction;
    vc.min_inliers = o.vo_min_inliers;
    vc.max_range = o.vo_max_range;
    vc.residual = o.vo_residual == "top-view" ? slam::OdometryResidual::top_view : slam::OdometryResidual::pixels;
    vc.estimate_disparity_offset = o.vo_disparity_offset;
    slam::SyntheticOdometry& so = k.synthetic;
    if (o.sigma_dx) so.sigma_dx = *o.sigma_dx;
    so.sigma_dy = o.sigma_dy;
    if (o.sigma_dtheta_deg) so.sigma_dtheta = *o.sigma_dtheta_deg * deg;
    k.visual_odometry = o.odometry == "visual";
    k.stereo_landmarks = o.landmarks_from == "stereo";
    k.seed = o.seed;
    k.synthetic_count = o.synthetic_count;
    k.flip_bits = o.flip_bits;
    std::string source_args, title;
    if (k.stereo_landmarks) {
        k.pipeline.detector = landmarks::parse_detector(o.corners);
        k.pipeline.descriptor = landmarks::parse_descriptor(o.descriptor_name);
        k.pipeline.grid = {o.g, o.h};
        k.pipeline.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
        k.pipeline.corners.progress = true;
        source_args = " --corners " + o.corners + " --descriptor " + o.descriptor_name + " --g " + std::to_string(o.g) +
                      " --h " + std::to_string(o.h) + (o.config.empty() ? "" : " --config " + o.config);
        title = "KITTI " + sequence + " (stereo landmarks: " + o.descriptor_name + " on " + o.corners + " corners, " +
                o.odometry + " odometry)";
    } else {
        source_args = " --synthetic-count " + std::to_string(o.synthetic_count) + " --flip-bits " + std::to_string(o.flip_bits);
        title = "KITTI " + sequence + " (synthetic landmarks on the real trajectory, " + o.odometry + " odometry)";
    }
    k.progress = [](const std::string& line) { std::fprintf(stderr, "slam: %s\n", line.c_str()); };
    const slam::KittiRun kr = slam::run_kitti_sequence(kitti, sequence, k);
    const slam::SequenceRun& run = kr.run;
    const std::string odo_args = k.visual_odometry
        ? " --vo-hamming-fraction " + num(vc.max_hamming_fraction) + " --vo-min-inliers " + std::to_string(vc.min_inliers) +
              " --vo-max-range " + num(vc.max_range) + " --vo-residual " + o.vo_residual +
              (o.vo_disparity_offset ? "" : " --no-vo-disparity-offset")
        : " --sigma-dx " + num(so.sigma_dx) + " --sigma-dy " + num(so.sigma_dy) + " --sigma-dtheta " +
              num(so.sigma_dtheta / deg);
    const bool seeded = o.odometry == "synthetic" || o.landmarks_from == "synthetic";
    const std::string command = "harris-cosim slam --sequences " + sequence + " --landmarks-from " + o.landmarks_from +
                                source_args + " --odometry " + o.odometry + odo_args + " --association " +
                                o.association + " --gate " + num(o.gate) + " --joint-gate " + num(o.joint_gate) +
                                " --max-hamming-fraction " + num(o.max_hamming_fraction) +
                                (o.descriptor ? "" : " --no-descriptor") + " --forget-after " +
                                std::to_string(o.forget_after) + " --max-observations " +
                                std::to_string(o.max_observations) +
                                (seeded ? " --seed " + std::to_string(o.seed) : std::string()) + " --out " + out.string();
    slam::write_sequence_report(out, run, title, command, odometry_label(o));
    std::printf("%s: %zu frames, path %.1f m; APE: EKF-SLAM %.3f m (%.2f %%), %s %.3f m (%.2f %%)", sequence.c_str(),
                run.truth.size(), run.slam_metrics.path_length, run.slam_metrics.ape, run.slam_metrics.ape_percent(),
                odometry_label(o).c_str(), run.odometry_metrics.ape, run.odometry_metrics.ape_percent());
    if (k.visual_odometry) std::printf("; odometry failed in %d of %zu steps", kr.vo.failures, kr.vo.motions.size());
    std::printf("\nreport: %s/report.md\n", out.c_str());
    return run;
}

void run_sequences(const SlamOptions& o) {
    const std::filesystem::path kitti = frames::require_kitti_root(o.kitti, o.data, "slam --sequences needs KITTI data");
    if (o.odometry != "visual" && o.odometry != "synthetic")
        throw InputError("--odometry '" + o.odometry + "' is neither visual nor synthetic");
    if (o.vo_residual != "pixels" && o.vo_residual != "top-view")
        throw InputError("--vo-residual '" + o.vo_residual + "' is neither pixels nor top-view");
    if (o.association != "jcbb" && o.association != "nearest")
        throw InputError("--association '" + o.association + "' is neither jcbb nor nearest");
    if (o.seed_given && o.odometry == "visual" && o.landmarks_from == "stereo")
        throw InputError("--seed: visual odometry on stereo landmarks is deterministic, nothing is drawn");
    const auto list = split_sequences(o.sequences);
    if (list.size() == 1) {
        run_one_sequence(o, kitti, list[0], o.out);
        return;
    }
    std::vector<std::pair<std::string, slam::SequenceRun>> runs;
    for (const auto& s : list) runs.emplace_back(s, run_one_sequence(o, kitti, s, std::filesystem::path(o.out) / s));
    const std::string md = "# EKF-SLAM per sequence\n\nGround truth is used only to score.\n\n" +
                           slam::sequences_markdown(runs, odometry_label(o));
    landmarks::write_atomic(std::filesystem::path(o.out) / "sequences.md", md);
    std::printf("%s", md.c_str());
    std::printf("table: %s/sequences.md\n", o.out.c_str());
}

void run_slam(const SlamOptions& o) {
    if (o.simulate == !o.sequences.empty())
        throw InputError("give exactly one of --simulate and --sequences NN[,NN...]");
    if (o.world != "cloister" && o.world != "random")
        throw InputError("--world '" + o.world + "' is neither cloister nor random");
    if (o.landmarks_from != "synthetic" && o.landmarks_from != "stereo")
        throw InputError("--landmarks-from '" + o.landmarks_from + "' is neither stereo nor synthetic");
    try {
        o.simulate ? run_simulate(o) : run_sequences(o);
    } catch (const slam::InputError& e) {
        throw InputError(e.what());
    } catch (const landmarks::InputError& e) {
        throw InputError(e.what());
    }
}

}  // namespace

namespace {

/// The KITTI run's odometry flags: which odometry, and visual odometry's settings.
void add_odometry_flags(CLI::App* cmd, SlamOptions& o) {
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
}

}  // namespace

void add_slam_command(CLI::App& app) {
    const auto [cmd, o] = add_command<SlamOptions>(app,
        "slam", "2-D EKF-SLAM (thesis 2.5, 5.4): Monte-Carlo consistency in the simulator, or a KITTI trajectory");
    cmd->add_flag("--simulate", o->simulate, "Monte-Carlo runs in the simulator (NEES, RMSE, plots)");
    cmd->add_option("--sequences,--sequence", o->sequences,
                    "KITTI sequences, comma-separated (e.g. 01 or 01,02): stereo pairs of sequences/NN, "
                    "ground truth poses/NN.txt (read only to score)");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding poses/ (default: <data>/kitti)");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--seed", o->seed,
                    "first seed (runs use seed, seed+1, ...); KITTI: the synthetic world or odometry (refused with "
                    "visual odometry on stereo landmarks, which draws nothing)")
        ->capture_default_str();
    cmd->add_option("--world", o->world, "simulated world layout: cloister or random")->capture_default_str();
    cmd->add_option("--landmarks", o->landmarks, "simulated world landmarks")->capture_default_str();
    cmd->add_option("--half-size", o->half_size, "world half size (m)")->capture_default_str();
    cmd->add_option("--radius", o->radius, "radius of the robot's circle (m)")->capture_default_str();
    cmd->add_option("--step", o->step, "distance per step (m)")->capture_default_str();
    cmd->add_option("--steps", o->steps, "steps per run")->capture_default_str();
    cmd->add_option("--runs", o->runs, "Monte-Carlo runs")->capture_default_str();
    cmd->add_option("--sigma-range", o->sigma_range, "range noise (m)")->capture_default_str();
    cmd->add_option("--sigma-bearing", o->sigma_bearing_deg, "bearing noise (deg)")->capture_default_str();
    cmd->add_option("--fov", o->fov_deg, "sensor field of view, full angle (deg)")->capture_default_str();
    cmd->add_option("--max-range", o->max_range, "sensor range limit (m)")->capture_default_str();
    cmd->add_option("--sigma-dx", o->sigma_dx, noise_help("odometry noise on dx (m per step", num(slam::OdometryModel{}.sigma_dx),
                                                          num(slam::SyntheticOdometry{}.sigma_dx)));
    cmd->add_option("--sigma-dy", o->sigma_dy, "KITTI --odometry synthetic: noise on dy (m per frame)")
        ->capture_default_str();
    cmd->add_option("--sigma-dtheta", o->sigma_dtheta_deg,
                    noise_help("odometry noise on dθ (deg per step", fmt::format("{:.3f}", slam::OdometryModel{}.sigma_dtheta / deg),
                               fmt::format("{:.3f}", slam::SyntheticOdometry{}.sigma_dtheta / deg)));
    add_odometry_flags(cmd, *o);
    cmd->add_option("--association", o->association, "KITTI: jcbb (joint compatibility) or nearest (individual gating)")
        ->capture_default_str();
    cmd->add_option("--joint-gate", o->joint_gate, "JCBB: joint gate probability (chi-square, 2k dof)")
        ->capture_default_str();
    cmd->add_option("--landmarks-from", o->landmarks_from,
                    "landmark source of a KITTI run: stereo (the landmark pipeline on the sequence's stereo pairs) "
                    "or synthetic (points laid along the ground-truth trajectory)")
        ->capture_default_str();
    cmd->add_option("--corners", o->corners,
                    "stereo: corner source (opencv, sift, sift512, orb, brisk, spec, cycle, rtl)")->capture_default_str();
    cmd->add_option("--descriptor", o->descriptor_name,
                    "stereo: descriptor (grid, grid-corrected, orb, brisk, brief, freak; binary for the descriptor check)")
        ->capture_default_str();
    cmd->add_option("--g", o->g, "stereo: grid side (cells)")->capture_default_str();
    cmd->add_option("--h", o->h, "stereo: grid resolution reduction 2^h")->capture_default_str();
    cmd->add_option("--config", o->config, "stereo: bit-width formats (JSON) of the spec/cycle/rtl corner sources");
    cmd->add_option("--synthetic-count", o->synthetic_count, "synthetic world points along the trajectory")->capture_default_str();
    cmd->add_option("--flip-bits", o->flip_bits, "bits flipped in each synthetic descriptor observation")->capture_default_str();
    cmd->add_option("--gate", o->gate, "Mahalanobis gate probability (chi-square, 2 dof)")->capture_default_str();
    cmd->add_option("--max-hamming-fraction", o->max_hamming_fraction,
                    "association's descriptor check: largest Hamming distance as a fraction of the descriptor's bits")
        ->capture_default_str();
    cmd->add_flag("!--no-descriptor", o->descriptor,
                  "associate by the Mahalanobis gates alone (visual odometry still matches descriptors)");
    cmd->add_option("--forget-after", o->forget_after, "remove landmarks unseen for this many frames (0: keep)")->capture_default_str();
    cmd->add_option("--max-observations", o->max_observations,
                    "observations used per frame, the most precise first (0: all)")->capture_default_str();
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->sharded = sharded(cmd);
        o->seed_given = cmd->count("--seed") > 0;
        if (o->sharded && !o->simulate) throw InputError(sharding_flags_named() + " shard the Monte-Carlo seeds of --simulate only");
        run_slam(*o);
    });
}

}  // namespace hc::tools

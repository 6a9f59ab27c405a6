// slam_command.cpp: see slam_command.hpp.
#include "mapping/slam/slam_command.hpp"

#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "mapping/slam/slam.hpp"
#include "mapping/slam/slam_job.hpp"

namespace fs = std::filesystem;

namespace hc::slam {

namespace {

constexpr double deg = std::numbers::pi / 180;

SimConfig sim_config(const SlamCommand& o) {
    SimConfig c;
    c.layout = o.world == "random" ? Layout::Random : Layout::Cloister;
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
    return c;
}

void run_simulate(const SlamCommand& o, const cluster::JobRunner& runner) {
    const SimConfig c = sim_config(o);
    MonteCarlo mc;
    if (runner.sharded()) {
        SlamJob p;
        p.config = c;
        p.runs = o.runs;
        p.first_seed = o.seed;
        p.shards = runner.settings().shards;
        const cluster::Manifest m = slam_manifest(p);
        const auto merged = runner.run(m, o.out);
        if (!merged) return;
        mc = slam_result(m, *merged);
    } else {
        mc = monte_carlo(c, o.runs, o.seed, 0.95, [](int done, int total) {
            if (done % 10 == 0 || done == total) std::fprintf(stderr, "slam: run %d/%d\n", done, total);
        });
    }
    write_simulation_report(o.out, c, mc, o.command_line);
    std::printf("pose NEES average %.3f, 95 %% bounds [%.3f, %.3f], %.1f %% of steps inside\n", mc.pose_nees_average,
                mc.pose_lo, mc.pose_hi, 100 * mc.pose_inside);
    std::printf("map NEES per dof average %.3f, %.1f %% of steps inside their bounds\n", mc.map_nees_per_dof_average,
                100 * mc.map_inside);
    std::printf("final RMSE: position %.4f m, heading %.4f deg, landmarks %.4f m\n", mc.position_rmse.back(),
                mc.heading_rmse.back() / deg, mc.map_rmse.back());
    std::printf("report: %s/report.md\n", o.out.c_str());
}

std::string odometry_label(const SlamCommand& o) {
    return o.odometry == "visual" ? "visual odometry alone" : "synthetic odometry alone";
}


/// The command line quoted in one run's report: the command as the user typed it, with the
/// sequence the report is of when it named several.
std::string report_command(const SlamCommand& o, const std::string& sequence) {
    const bool several = !sequence.empty() && util::split_csv(o.sequences).size() > 1;
    return o.command_line + (several ? " (this report: sequence " + sequence + ")" : "");
}

/// How the ground truth entered a run of these settings (the report's first sentence).
std::string provenance(const SlamCommand& o, bool has_truth) {
    if (!has_truth) return "No ground truth: the run used the stereo pairs alone, and nothing below is scored.";
    std::string s;
    if (o.landmarks_from == "synthetic")
        s += "The landmarks are synthetic: world points laid along the ground-truth trajectory and measured from the "
             "true poses, so the ground truth enters the frames" +
             std::string(o.odometry == "visual" ? " and, through them, the visual odometry. " : ". ");
    if (o.odometry == "synthetic")
        s += "The odometry is synthetic: the ground truth's relative poses plus noise, so the ground truth enters the "
             "motions. ";
    if (s.empty())
        return "Ground truth is used only to score: the trajectories below were computed from the stereo pairs "
               "without it, then compared with it (evo's APE and RPE, pose NEES with 3 dof).";
    return s + "The scores (evo's APE and RPE, pose NEES with 3 dof) compare with the same ground truth.";
}

/// The title of a run's report.
std::string run_title(const SlamCommand& o, const KittiRunOptions& k, const std::string& sequence) {
    const std::string what = sequence.empty() ? "the rig of " + o.rig.calib : "KITTI " + sequence;   // no apostrophe: gnuplot quotes the plot titles
    return k.stereo_landmarks ? what + " (stereo landmarks: " + o.descriptor_name + " on " + o.corners + " corners, " +
                                    o.odometry + " odometry)"
                              : what + " (synthetic landmarks on the real trajectory, " + o.odometry + " odometry)";
}

/// One run (a KITTI-layout sequence, or the rig's pairs when `sequence` is empty): states.csv and
/// the trajectory files written into `out` as frames come (SequenceFiles; put in place when the
/// run succeeds), its report, and its figures on stdout. Nothing is kept per frame.
SequenceRun run_one_sequence(const SlamCommand& o, const fs::path& kitti, const std::string& sequence, const fs::path& out) {
    KittiRunOptions k = kitti_options(o);
    SequenceFiles files(out);
    k.sink = files.sink();
    k.keep_frames = false;
    const KittiRun kr = sequence.empty() ? run_rig_sequence(o.rig, k)
                                         : run_kitti_sequence(kitti, sequence, k);
    const SequenceRun& run = kr.run;
    const std::string name = sequence.empty() ? "rig" : sequence;
    files.commit(run, {run_title(o, k, sequence), report_command(o, sequence), o.settings, odometry_label(o),
                       provenance(o, run.scored_frames > 0)});
    if (run.scored_frames == 0) {
        std::printf("%s: %zu frames, no ground truth (not scored)", name.c_str(), run.frame_count);
    } else {
        std::printf("%s: %zu frames (%zu scored), path %.1f m; APE 2-D / 3-D: EKF-SLAM %.3f / %.3f m (%.2f %%), "
                    "%s %.3f / %.3f m (%.2f %%)",
                    name.c_str(), run.frame_count, run.scored_frames, run.slam_metrics.path_length,
                    run.slam_metrics.ape, run.ape_3d_slam, run.slam_metrics.ape_percent(), odometry_label(o).c_str(),
                    run.odometry_metrics.ape, run.ape_3d_dead_reckoning, run.odometry_metrics.ape_percent());
    }
    if (k.visual_odometry) std::printf("; odometry failed in %d of %zu steps", kr.vo.failures, run.frame_count - 1);
    std::printf("\nreport: %s/report.md\n", out.c_str());
    return run;
}

void check_choice(const std::string& flag, const std::string& value, const std::string& a, const std::string& b) {
    if (value != a && value != b) throw InputError(flag + " '" + value + "' is neither " + a + " nor " + b);
}

void check_run_flags(const SlamCommand& o) {
    check_choice("--odometry", o.odometry, "visual", "synthetic");
    check_choice("--vo-residual", o.vo_residual, "pixels", "top-view");
    check_choice("--association", o.association, "jcbb", "nearest");
    if (o.seed_given && o.odometry == "visual" && o.landmarks_from == "stereo")
        throw InputError("--seed: visual odometry on stereo landmarks is deterministic, nothing is drawn");
}

void run_sequences(const SlamCommand& o) {
    check_run_flags(o);
    if (o.sequences.empty()) {   // the rig's pairs
        run_one_sequence(o, {}, "", o.out);
        return;
    }
    const fs::path kitti = frames::require_kitti_root(o.kitti, o.data, "slam --sequences needs KITTI data");
    const auto list = util::split_csv(o.sequences);
    if (list.empty()) throw InputError("--sequences '" + o.sequences + "' names no sequence");
    if (list.size() > 1 && !o.truth.empty())
        throw InputError("--truth '" + o.truth + "' is the ground truth of one sequence: --sequences names " +
                         std::to_string(list.size()));
    if (list.size() == 1) {
        run_one_sequence(o, kitti, list[0], o.out);
        return;
    }
    std::vector<std::pair<std::string, SequenceRun>> runs;
    for (const auto& s : list) runs.emplace_back(s, run_one_sequence(o, kitti, s, fs::path(o.out) / s));
    int scored = 0;
    for (const auto& [name, run] : runs) scored += run.scored_frames > 0;
    const bool some_unscored = scored > 0 && scored < static_cast<int>(runs.size());
    const std::string md = "# EKF-SLAM per sequence\n\n" + provenance(o, scored > 0) +
                           (some_unscored ? " Sequences without a ground truth are not scored." : "") + "\n\n" +
                           sequences_markdown(runs, odometry_label(o));
    landmarks::write_atomic(fs::path(o.out) / "sequences.md", md);
    std::printf("%s", md.c_str());
    std::printf("table: %s/sequences.md\n", o.out.c_str());
}

}  // namespace

KittiRunOptions kitti_options(const SlamCommand& o) {
    KittiRunOptions k;
    AssociationConfig& ac = k.association;
    ac.method = o.association == "nearest" ? AssociationMethod::Nearest : AssociationMethod::Jcbb;
    ac.gate_probability = o.gate;
    ac.joint_probability = o.joint_gate;
    ac.max_hamming_fraction = o.max_hamming_fraction;
    ac.check_descriptor = o.descriptor;
    ac.forget_after = o.forget_after;
    ac.max_observations = o.max_observations;
    ac.noise_at_prediction = o.noise_at_prediction;
    ac.correct_with_odometry_inliers = o.correct_with_odometry_inliers;
    ac.odometry_inlier_noise_scale = o.odometry_inlier_noise_scale;
    VisualOdometryConfig& vc = k.vo;
    vc.max_hamming_fraction = o.vo_hamming_fraction;
    vc.min_inliers = o.vo_min_inliers;
    vc.max_range = o.vo_max_range;
    vc.residual = o.vo_residual == "top-view" ? OdometryResidual::top_view : OdometryResidual::pixels;
    vc.estimate_disparity_offset = o.vo_disparity_offset;
    vc.offset_uncertainty = o.vo_offset_uncertainty;
    vc.level = o.vo_level;
    vc.noise_from_residuals = o.vo_measured_noise;
    vc.two_view_points = o.vo_two_view;
    SyntheticOdometry& so = k.synthetic;
    if (o.sigma_dx) so.sigma_dx = *o.sigma_dx;
    so.sigma_dy = o.sigma_dy;
    if (o.sigma_dtheta_deg) so.sigma_dtheta = *o.sigma_dtheta_deg * deg;
    k.visual_odometry = o.odometry == "visual";
    k.stereo_landmarks = o.landmarks_from == "stereo";
    k.seed = o.seed;
    k.truth = o.truth;
    k.score_overlap = o.score_overlap;
    k.frame_period = o.frame_period;
    k.truth_time_tolerance = o.truth_time_tolerance;
    k.pairs = o.pairs;
    k.synthetic_count = o.synthetic_count;
    k.flip_bits = o.flip_bits;
    if (k.stereo_landmarks) {
        k.pipeline.detector = landmarks::parse_detector(o.corners);
        k.pipeline.descriptor = landmarks::parse_descriptor(o.descriptor_name);
        k.pipeline.grid = {o.g, o.h};
        k.pipeline.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
        k.pipeline.corners.progress = true;
    }
    k.progress = [](const std::string& line) { std::fprintf(stderr, "slam: %s\n", line.c_str()); };
    return k;
}

void run_slam_command(const SlamCommand& o, const cluster::JobRunner& runner) {
    if (runner.sharded() && !o.simulate)
        throw InputError(cluster::sharding_flags_named() + " shard the Monte-Carlo seeds of --simulate only");
    const bool rig = o.rig.given();
    if (int(o.simulate) + int(!o.sequences.empty()) + int(rig) != 1)
        throw InputError("give exactly one of --simulate, --sequences NN[,NN...] and --calib FILE --left ... --right ...");
    if (o.simulate && !o.pairs.empty())
        throw InputError("--pairs " + o.pairs + " picks stereo pairs of --sequences or of a rig: --simulate has none");
    check_choice("--world", o.world, "cloister", "random");
    check_choice("--landmarks-from", o.landmarks_from, "stereo", "synthetic");
    o.simulate ? run_simulate(o, runner) : run_sequences(o);
}

}  // namespace hc::slam

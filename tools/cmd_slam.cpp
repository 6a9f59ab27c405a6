// cmd_slam.cpp: `harris-cosim slam`, 2-D EKF-SLAM (slam/slam.hpp): a Monte-Carlo
// consistency run in the simulator (--simulate), or a KITTI sequence's ground-truth
// trajectory with noisy odometry and stereo landmarks (--sequence). Parses flags, calls
// hc::slam, prints; hc::slam::InputError becomes exit status 2. Docs: docs/slam.md.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"
#include "jobs/jobs.hpp"
#include "frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "util/util.hpp"
#include "landmarks/landmarks.hpp"
#include "slam/slam.hpp"

namespace hc::tools {

namespace {

constexpr double deg = std::numbers::pi / 180;

struct SlamOptions {
    bool simulate = false;
    std::string sequence, kitti, data, out = "slam-report", world = "cloister", landmarks_from = "synthetic";
    int landmarks = 40, steps = 236, runs = 50, synthetic_count = 1000, flip_bits = 8, max_hamming = 64,
        forget_after = 10, max_observations = 60;
    uint64_t seed = 1;
    double half_size = 5, radius = 3.75, step = 0.1, sigma_range = 0.05, sigma_bearing_deg = 1, fov_deg = 180,
           max_range = 6, gate = 0.99;
    std::optional<double> sigma_dx, sigma_dtheta_deg;
    double sigma_lateral = 0.03;
    bool descriptor = true;
    // --landmarks-from stereo: the landmark pipeline's options
    std::string corners = "opencv", descriptor_name = "grid", config;
    int g = 16, h = 3;
    // --simulate: Monte-Carlo seeds in shards (--runner, --shards)
    RunnerFlags runner;
    bool sharded = false;
};

std::string num(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
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
    c.odometry.sigma_dx = o.sigma_dx.value_or(0.01);
    c.odometry.sigma_dtheta = o.sigma_dtheta_deg.value_or(0.005 / deg) * deg;
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
        jobs::SlamShards p;
        p.config = c;
        p.runs = o.runs;
        p.first_seed = o.seed;
        p.shards = o.runner.shards;
        const cluster::Manifest m = jobs::slam_manifest(p);
        const std::filesystem::path dir = o.runner.run_dir.empty() ? std::filesystem::path(o.out) / "run" : std::filesystem::path(o.runner.run_dir);
        const auto merged = run_sharded(dir, m, o.runner);
        if (!merged) return;
        mc = jobs::slam_result(m, *merged);
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

/// The landmark pipeline on the sequence's stereo pairs, one frame per pose (a sequence with
/// fewer pairs than poses is cut to its pairs): camera-frame points with their covariance
/// and descriptor, as the filter's front end takes them.
std::vector<slam::StereoFrame> stereo_landmark_frames(const SlamOptions& o, const std::filesystem::path& kitti,
                                                      const std::vector<slam::Mat34>& poses) {
    landmarks::PipelineOptions po;
    po.detector = landmarks::parse_detector(o.corners);
    po.descriptor = landmarks::parse_descriptor(o.descriptor_name);
    po.grid = {o.g, o.h};
    landmarks::validate(po.grid);
    landmarks::check_combination(po.descriptor, po.detector, landmarks::Norm::automatic);
    if (o.descriptor && landmarks::make_descriptor(po.descriptor, po.grid)->descriptorType() != CV_8U)
        throw InputError("--descriptor " + o.descriptor_name +
                         " is not binary: the association's descriptor check compares Hamming distances "
                         "(use a binary descriptor or --no-descriptor)");
    po.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
    po.corners.progress = true;
    const auto ds = landmarks::kitti_dataset(kitti, o.sequence, 0, static_cast<int>(poses.size()));
    if (ds.pairs.size() < 2) throw InputError("KITTI sequence " + o.sequence + " has fewer than 2 stereo pairs");
    std::fprintf(stderr, "slam: landmarks of %zu stereo pairs (%s corners, %s descriptor)\n", ds.pairs.size(),
                 o.corners.c_str(), o.descriptor_name.c_str());
    const auto lms = landmarks::acquire_dataset(ds, po);
    std::vector<slam::StereoFrame> frames;
    for (const auto& frame : lms) {
        slam::StereoFrame f;
        for (const auto& l : frame) {
            slam::StereoLandmarkObs obs;
            obs.p_cam = Eigen::Vector3d(l.p_cam[0], l.p_cam[1], l.p_cam[2]);
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) obs.cov(r, c) = l.cov(r, c);
            if (o.descriptor) obs.descriptor = l.descriptor;
            f.push_back(std::move(obs));
        }
        frames.push_back(std::move(f));
    }
    return frames;
}

void run_sequence(const SlamOptions& o) {
    std::filesystem::path kitti = o.kitti;
    if (kitti.empty()) {
        const auto d = frames::data_dir(o.data);
        if (!d) throw InputError("no data directory: give --kitti or --data, or set HARRIS_COSIM_DATA");
        kitti = *d / "kitti";
    }
    auto poses = slam::read_kitti_poses(kitti / "poses" / (o.sequence + ".txt"));
    if (poses.size() < 2) throw InputError("sequence " + o.sequence + " has fewer than 2 poses");
    slam::OdometryModel om;
    om.sigma_dx = o.sigma_dx.value_or(0.1);
    om.sigma_dtheta = o.sigma_dtheta_deg.value_or(0.002 / deg) * deg;
    om.sigma_lateral = o.sigma_lateral;
    if (!(om.sigma_dx > 0) || !(om.sigma_dtheta > 0)) throw InputError("--sigma-dx and --sigma-dtheta must be positive");
    slam::AssociationConfig ac;
    ac.gate_probability = o.gate;
    ac.max_hamming = o.max_hamming;
    ac.check_descriptor = o.descriptor;
    ac.forget_after = o.forget_after;
    ac.max_observations = o.max_observations;
    ac.validate();
    std::vector<slam::StereoFrame> frames;
    std::string source_args, title;
    if (o.landmarks_from == "stereo") {
        frames = stereo_landmark_frames(o, kitti, poses);
        poses.resize(frames.size());
        source_args = " --corners " + o.corners + " --descriptor " + o.descriptor_name + " --g " + std::to_string(o.g) +
                      " --h " + std::to_string(o.h) + (o.config.empty() ? "" : " --config " + o.config);
        title = "KITTI " + o.sequence + " (ground-truth trajectory, stereo landmarks: " + o.descriptor_name + " on " +
                o.corners + " corners)";
    } else {
        if (o.flip_bits < 0) throw InputError("--flip-bits must not be negative");
        frames = slam::synthesize_stereo_frames(poses, slam::StereoCamera{}, o.synthetic_count, o.flip_bits, o.seed);
        source_args = " --synthetic-count " + std::to_string(o.synthetic_count) + " --flip-bits " + std::to_string(o.flip_bits);
        title = "KITTI " + o.sequence + " (ground-truth trajectory, synthetic landmarks)";
    }
    const auto run = slam::run_sequence(poses, frames, om, ac, o.seed);
    const std::string command = "harris-cosim slam --sequence " + o.sequence + " --landmarks-from " + o.landmarks_from +
                                source_args + " --sigma-dx " + num(om.sigma_dx) + " --sigma-dtheta " +
                                num(om.sigma_dtheta / deg) + " --sigma-lateral " + num(om.sigma_lateral) + " --gate " + num(o.gate) + " --max-hamming " +
                                std::to_string(o.max_hamming) + (o.descriptor ? "" : " --no-descriptor") +
                                " --forget-after " + std::to_string(o.forget_after) + " --max-observations " +
                                std::to_string(o.max_observations) + " --seed " +
                                std::to_string(o.seed) + " --out " + o.out;
    slam::write_sequence_report(o.out, run, title, command);
    std::printf("%zu frames; ATE: EKF-SLAM %.3f m, dead reckoning %.3f m; final map %d landmarks\n", run.truth.size(),
                run.ate_slam, run.ate_dead_reckoning, run.frames.back().map_size);
    std::printf("report: %s/report.md\n", o.out.c_str());
}

void run_slam(const SlamOptions& o) {
    if (o.simulate == !o.sequence.empty()) throw InputError("give exactly one of --simulate and --sequence NN");
    if (o.world != "cloister" && o.world != "random")
        throw InputError("--world '" + o.world + "' is neither cloister nor random");
    if (o.landmarks_from != "synthetic" && o.landmarks_from != "stereo")
        throw InputError("--landmarks-from '" + o.landmarks_from + "' is neither stereo nor synthetic");
    try {
        o.simulate ? run_simulate(o) : run_sequence(o);
    } catch (const slam::InputError& e) {
        throw InputError(e.what());
    } catch (const landmarks::InputError& e) {
        throw InputError(e.what());
    }
}

}  // namespace

void add_slam_command(CLI::App& app) {
    auto o = std::make_shared<SlamOptions>();
    CLI::App* cmd = app.add_subcommand(
        "slam", "2-D EKF-SLAM (thesis 2.5, 5.4): Monte-Carlo consistency in the simulator, or a KITTI trajectory");
    cmd->add_flag("--simulate", o->simulate, "Monte-Carlo runs in the simulator (NEES, RMSE, plots)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence whose poses/NN.txt is the trajectory, e.g. 01");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding poses/ (default: <data>/kitti)");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--seed", o->seed, "first seed (runs use seed, seed+1, ...)")->capture_default_str();
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
    cmd->add_option("--sigma-dx", o->sigma_dx, "odometry noise on dx (m per step; default 0.01 simulated, 0.1 KITTI)");
    cmd->add_option("--sigma-dtheta", o->sigma_dtheta_deg,
                    "odometry noise on dθ (deg per step; default 0.286 simulated, 0.115 KITTI)");
    cmd->add_option("--sigma-lateral", o->sigma_lateral,
                    "KITTI: sideways slip per frame the filter allows for (m)")->capture_default_str();
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
    cmd->add_option("--max-hamming", o->max_hamming, "descriptor check: largest Hamming distance (bits)")->capture_default_str();
    cmd->add_flag("!--no-descriptor", o->descriptor, "associate by the Mahalanobis gate alone");
    cmd->add_option("--forget-after", o->forget_after, "remove landmarks unseen for this many frames (0: keep)")->capture_default_str();
    cmd->add_option("--max-observations", o->max_observations,
                    "observations used per frame, the most precise first (0: all)")->capture_default_str();
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->sharded = cmd->count("--runner") + cmd->count("--shards") > 0;
        if (o->sharded && !o->simulate) throw InputError("--runner and --shards shard the Monte-Carlo seeds of --simulate only");
        run_slam(*o);
    });
}

}  // namespace hc::tools

// cmd_landmarks.cpp: `harris-cosim landmarks`, landmark acquisition downstream of a corner
// source (thesis Figure 1): descriptor, stereo matching, scoring against the thesis's
// definition and the ground truth, triangulation, the descriptor comparison (Tables 6-10)
// and the grid's g x h study (Figures 29-34). Logic: slam/landmarks/landmarks.hpp; docs/landmarks.md.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "tools/commands.hpp"
#include "tools/frame_source.hpp"
#include "tools/runner_flags.hpp"
#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "io/util/util.hpp"
#include "slam/landmarks/landmarks.hpp"
#include "slam/landmarks/landmarks_job.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct LandmarksOptions {
    std::string corners = "opencv", descriptor = "grid", norm = "auto", config, out = "landmarks-report";
    landmarks::DatasetChoice source;   ///< --calib, --left, --right, --dataset, --middlebury, --kitti, --data, --sequence, --pairs
    int g = 16, h = 3, overlays = 2, threads = 0;
    double ratio = 0, sigma = 0.5;
    bool drop_ties = false, compare = false, study = false, corrected = false, landmark_files = true, no_truth = false;
    bool reobservation = false, descriptor_given = false;
    RunnerFlags runner;   ///< the comparison in shards (runner_flags.hpp: sharded())
    bool sharded = false;
};

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    std::string t;
    while (std::getline(ss, t, ','))
        if (!t.empty()) v.push_back(t);
    return v;
}

/// The re-observation study: its table on stdout and in <out>/reobservation.md and .csv.
void run_reobservation(const LandmarksOptions& o) {
    landmarks::ReobservationOptions ro;
    const auto dets = split(o.corners);
    if (dets.size() != 1) throw InputError("--reobservation takes one corner source (--corners)");
    ro.detector = landmarks::parse_detector(dets[0]);
    if (o.descriptor_given) {
        ro.descriptors.clear();
        for (const auto& s : split(o.descriptor)) ro.descriptors.push_back(landmarks::parse_descriptor(s));
    }
    ro.grid = {o.g, o.h};
    landmarks::validate(ro.grid);
    ro.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
    fs::path root;
    const landmarks::Dataset ds = landmarks::open_dataset(o.source, root);
    std::fprintf(stderr, "landmarks: re-observations over %zu consecutive left images of %s...\n", ds.pairs.size(),
                 ds.name.c_str());
    const auto rows = landmarks::reobservation_study(ds, ro);
    const landmarks::ReobservationReport rep = landmarks::reobservation_report(ds, ro, rows);
    fs::create_directories(o.out);
    landmarks::write_atomic(fs::path(o.out) / "reobservation.md", rep.markdown);
    landmarks::write_atomic(fs::path(o.out) / "reobservation.csv", rep.csv);
    std::printf("%s", rep.markdown.c_str());
}

/// The comparison's detectors, descriptors, grid, matcher and corner options from the flags.
landmarks::ComparisonOptions comparison_options(const LandmarksOptions& o) {
    landmarks::ComparisonOptions co;
    co.detectors.clear();
    co.descriptors.clear();
    if (o.compare) {
        co.detectors = {landmarks::Detector::sift512, landmarks::Detector::sift, landmarks::Detector::opencv};
        co.descriptors = landmarks::comparison_descriptors();
    } else {
        for (const auto& s : split(o.corners)) co.detectors.push_back(landmarks::parse_detector(s));
        for (const auto& s : split(o.descriptor)) co.descriptors.push_back(landmarks::parse_descriptor(s));
    }
    if (co.detectors.empty() || co.descriptors.empty()) throw InputError("--corners and --descriptor name at least one each");
    co.grid = {o.g, o.h};
    landmarks::validate(co.grid);
    co.match.norm = landmarks::parse_norm(o.norm);
    co.match.ratio = o.ratio;
    co.match.drop_ties = o.drop_ties;
    for (auto det : co.detectors)
        for (auto d : co.descriptors) landmarks::check_combination(d, det, co.match.norm);
    if (o.sigma <= 0) throw InputError("--sigma must be positive");
    co.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
    co.corners.progress = true;
    co.threads = o.threads;
    co.progress = [](const std::string& line) { std::fprintf(stderr, "landmarks: %s\n", line.c_str()); };
    return co;
}

/// The comparison's rows run in shards (the run directory: --run-dir, or <out>/run); none when
/// the shards are not all done.
std::optional<std::vector<landmarks::ComparisonRow>> sharded_rows(const LandmarksOptions& o, const landmarks::Dataset& ds,
                                                                  const fs::path& root, const landmarks::ComparisonOptions& co) {
    if (o.study) throw InputError("--study runs in one process: leave out " + sharding_flags_named());
    if (!o.source.calib.empty()) throw InputError("--calib (a rig's pairs) runs in one process: leave out " + sharding_flags_named());
    landmarks::LandmarksShards p;
    p.dataset = o.source.dataset;
    p.root = root;
    p.need_truth = o.source.need_truth;
    p.sequence = o.source.sequence;
    if (o.source.dataset == "kitti") {
        const util::Range r = util::parse_range(o.source.pairs, "--pairs");
        p.first = r.first;
        p.last = r.first + static_cast<int>(ds.pairs.size());
    }
    p.options = co;
    p.pairs = ds.pairs.size();
    p.shards = o.runner.shards;
    const cluster::Manifest m = landmarks::landmarks_manifest(p);
    const fs::path dir = run_dir(o.runner, o.out);
    const auto merged = run_sharded(dir, m, o.runner);
    if (!merged) return std::nullopt;
    return landmarks::landmarks_rows(*merged);
}

void run_landmarks(const LandmarksOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::function<double()> secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    try {
        if (o.reobservation) {
            if (o.compare || o.study || o.sharded || !o.source.calib.empty())
                throw InputError("--reobservation runs alone: leave out --compare, --study, --calib and " + sharding_flags_named());
            run_reobservation(o);
            return;
        }
        const landmarks::ComparisonOptions co = comparison_options(o);

        std::fprintf(stderr, "landmarks: loading %s...\n", o.source.calib.empty() ? o.source.dataset.c_str() : o.source.calib.c_str());
        fs::path root;
        const landmarks::Dataset ds = landmarks::open_dataset(o.source, root);
        std::fprintf(stderr, "landmarks: %s, %zu pairs\n", ds.name.c_str(), ds.pairs.size());
        fs::create_directories(o.out);

        std::vector<std::vector<landmarks::PairKeypoints>> kps;
        std::vector<landmarks::ComparisonRow> rows;
        if (o.sharded) {
            auto merged = sharded_rows(o, ds, root, co);
            if (!merged) return;
            rows = std::move(*merged);
        } else {
            rows = landmarks::compare(ds, co, &kps);
        }
        landmarks::ReportOptions ro;
        ro.out = o.out;
        ro.sigma_px = o.sigma;
        ro.landmark_files = o.landmark_files;
        ro.overlays = o.overlays;
        ro.study = o.study;
        ro.corrected = o.corrected;
        ro.threads = o.threads;
        ro.calib = o.source.calib;
        ro.config = o.config;
        const auto rep = landmarks::write_comparison_report(ds, co, rows, kps, ro, secs);
        std::printf("%s", landmarks::comparison_markdown(rows).c_str());
        std::printf("landmarks: comparison %.1f s, total %.1f s; report %s\n", rep.compare_seconds, rep.total_seconds,
                    (fs::path(o.out) / "report.md").c_str());
    } catch (const landmarks::InputError& e) {
        throw InputError(e.what());
    }
}

}  // namespace

void add_landmarks_command(CLI::App& app) {
    const auto [cmd, o] = add_command<LandmarksOptions>(app,
        "landmarks", "corners -> descriptor -> stereo matches -> 3D landmarks, scored against ground truth (thesis 6.4)");
    cmd->add_option("--corners", o->corners, "corner sources, comma-separated: opencv, sift, sift512, orb, brisk, spec, cycle, rtl")
        ->capture_default_str();
    cmd->add_option("--descriptor", o->descriptor, "descriptors, comma-separated: grid, grid-corrected, sift (ratio 0.8), sift-ratio1 (SIFT at the grid's ratio 1), orb, brisk, "
                    "brief (the authors' box smoothing), brief-gaussian (the paper's Gaussian), freak")
        ->capture_default_str();
    cmd->add_option("--g", o->g, "grid side")->capture_default_str();
    cmd->add_option("--h", o->h, "grid resolution reduction 2^h")->capture_default_str();
    cmd->add_option("--norm", o->norm, "matcher norm: auto (the descriptor's), hamming or l2")->capture_default_str();
    cmd->add_option("--ratio", o->ratio, "2-NN ratio for every descriptor (0: by descriptor: 0.8 for sift, the thesis's SIFT reference after Lowe; 1 for the others)");
    cmd->add_flag("--drop-ties", o->drop_ties, "ratio test also drops d0 == d1 (the evidently intended test)");
    cmd->add_flag("--compare", o->compare, "the thesis's comparison: detectors sift512, sift, opencv x the descriptors grid, sift, sift-ratio1, orb, brisk, "
                  "brief, brief-gaussian, freak");
    cmd->add_flag("--study", o->study, "g x h study of the grid descriptor (g 4..32, h 0..5) on each detector's corners");
    cmd->add_flag("--reobservation", o->reobservation,
                  "how descriptors change between consecutive frames: corners tracked by optical flow from each left "
                  "image to the next, Hamming distance of re-observations against random pairs (default descriptors: "
                  "grid, grid-corrected, orb, brisk, brief, freak)");
    cmd->add_flag("--corrected", o->corrected, "study the corrected g x g grid instead of the thesis's");
    cmd->add_option("--dataset", o->source.dataset, "middlebury or kitti")->capture_default_str();
    cmd->add_option("--middlebury", o->source.middlebury, "Middlebury 2006 folder of scenes, or one scene (default: <data>/middlebury2006/half)");
    cmd->add_flag("--no-truth", o->no_truth, "accept Middlebury scenes without disp1.png (e.g. third/): no ground-truth scoring");
    cmd->add_option("--kitti", o->source.kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->source.sequence, "KITTI sequence")->capture_default_str();
    add_pair_range_option(cmd, o->source.pairs, "KITTI stereo pair range a:b (b excluded; default " + o->source.pairs + ")");
    cmd->add_option("--calib", o->source.calib,
                    "a rig's calibration (harris-cosim calibrate's calib.yml/.json, or a calib.txt of rectified images): "
                    "run on its unrectified pairs --left/--right, keypoints undistorted and rectified (cv::undistortPoints)");
    cmd->add_option("--left", o->source.left, "with --calib: the rig's left images (files or glob patterns, sorted)");
    cmd->add_option("--right", o->source.right, "with --calib: the rig's right images, in the order of --left");
    cmd->add_option("--data", o->source.data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--config", o->config, "formats JSON of the co-processor (spec, cycle, rtl corners)");
    cmd->add_option("--sigma", o->sigma, "corner localisation noise: standard deviation (px) of each of x_l, y_l, x_r, y_r, independent, "
                    "in the landmark covariance (an assumed value; integer rounding alone would be 1/sqrt(12) = 0.29 px)")->capture_default_str();
    cmd->add_option("--overlays", o->overlays, "match overlay PNGs per row (first N pairs)")->capture_default_str();
    cmd->add_flag("!--no-landmark-files", o->landmark_files, "skip the per-pair landmark CSV/PLY files");
    cmd->add_option("--threads", o->threads,
                    "worker threads of the comparison and the study (0: all cores); each pair's extraction and matching "
                    "runs on one thread either way");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->sharded = sharded(cmd);
        o->descriptor_given = cmd->count("--descriptor") > 0;
        o->source.need_truth = !o->no_truth;
        run_landmarks(*o);
    });
}

}  // namespace hc::tools

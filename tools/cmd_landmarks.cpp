// cmd_landmarks.cpp: `harris-cosim landmarks`, landmark acquisition downstream of a corner
// source (thesis Figure 1): descriptor, stereo matching, scoring against the thesis's
// definition and the ground truth, triangulation, the descriptor comparison (Tables 6-10)
// and the grid's g x h study (Figures 29-34). Logic: landmarks/landmarks.hpp; docs/landmarks.md.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "jobs/jobs.hpp"
#include "tools/commands.hpp"
#include "tools/runner_flags.hpp"
#include "frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "util/util.hpp"
#include "landmarks/landmarks.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct LandmarksOptions {
    std::string corners = "opencv", descriptor = "grid", norm = "auto", config, out = "landmarks-report";
    std::string dataset = "middlebury", middlebury, kitti, sequence = "01", frames = "0:10", data, calib;
    std::vector<std::string> left, right;
    int g = 16, h = 3, overlays = 2, threads = 0;
    double ratio = 0, sigma = 0.5;
    bool drop_ties = false, compare = false, study = false, corrected = false, landmark_files = true, no_truth = false;
    RunnerFlags runner;   ///< the comparison in shards (--runner, --shards)
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

std::pair<int, int> pair_range(const std::string& s) {
    const auto c = s.find(':');
    try {
        if (c == std::string::npos) throw std::invalid_argument(s);
        const int a = std::stoi(s.substr(0, c)), b = std::stoi(s.substr(c + 1));
        if (a < 0 || b <= a) throw std::invalid_argument(s);
        return {a, b};
    } catch (const std::exception&) {
        throw InputError("--frames '" + s + "' is not a stereo pair range a:b with 0 <= a < b");
    }
}

std::string safe(const std::string& s) {
    std::string r = s;
    for (char& c : r)
        if (c == '/' || c == ' ') c = '_';
    return r;
}

/// The dataset of the flags; `root` receives its folder.
landmarks::Dataset load_dataset(const LandmarksOptions& o, fs::path& root) {
    if (!o.calib.empty()) {
        if (o.left.empty() || o.right.empty()) throw InputError("--calib needs the rig's images: --left and --right");
        return landmarks::rig_dataset(calib::expand_image_list(o.left, "--left"), calib::expand_image_list(o.right, "--right"),
                                      landmarks::read_rig_calibration(o.calib));
    }
    if (!o.left.empty() || !o.right.empty()) throw InputError("--left and --right are the images of a rig: give its --calib");
    const auto data = frames::data_dir(o.data);
    if (o.dataset == "middlebury") {
        root = o.middlebury;
        if (root.empty()) {
            if (!data) throw InputError("no --middlebury folder and no data directory (--data, $HARRIS_COSIM_DATA)");
            root = *data / "middlebury2006" / "half";
        }
        return landmarks::middlebury_dataset(root, !o.no_truth);
    }
    if (o.dataset == "kitti") {
        root = o.kitti;
        if (root.empty()) {
            if (!data) throw InputError("no --kitti root and no data directory (--data, $HARRIS_COSIM_DATA)");
            root = *data / "kitti";
        }
        const auto [a, b] = pair_range(o.frames);
        return landmarks::kitti_dataset(root, o.sequence, a, b);
    }
    throw InputError("--dataset '" + o.dataset + "' (middlebury or kitti)");
}

void run_landmarks(const LandmarksOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    try {
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

        std::fprintf(stderr, "landmarks: loading %s...\n", o.calib.empty() ? o.dataset.c_str() : o.calib.c_str());
        fs::path root;
        const landmarks::Dataset ds = load_dataset(o, root);
        std::fprintf(stderr, "landmarks: %s, %zu pairs\n", ds.name.c_str(), ds.pairs.size());
        fs::create_directories(o.out);

        std::vector<std::vector<landmarks::PairKeypoints>> kps;
        std::vector<landmarks::ComparisonRow> rows;
        if (o.sharded) {
            if (o.study) throw InputError("--study runs in one process: leave out --runner and --shards");
            if (!o.calib.empty()) throw InputError("--calib (a rig's pairs) runs in one process: leave out --runner and --shards");
            jobs::LandmarksShards p;
            p.dataset = o.dataset;
            p.root = root;
            p.need_truth = !o.no_truth;
            p.sequence = o.sequence;
            std::tie(p.first, p.last) = o.dataset == "kitti" ? pair_range(o.frames) : std::pair<int, int>{0, 0};
            p.options = co;
            p.pairs = ds.pairs.size();
            p.shards = o.runner.shards;
            const cluster::Manifest m = jobs::landmarks_manifest(p);
            const fs::path dir = o.runner.run_dir.empty() ? fs::path(o.out) / "run" : fs::path(o.runner.run_dir);
            const auto merged = run_sharded(dir, m, o.runner);
            if (!merged) return;
            rows = jobs::landmarks_rows(*merged);
        } else {
            rows = landmarks::compare(ds, co, &kps);
        }
        const double t_compare = secs();

        // landmarks and overlays of every row
        landmarks::PipelineOptions po;
        po.noise.sigma_px = o.sigma;
        std::ostringstream depth;
        bool any_truth = false;
        for (const auto& row : rows) {
            const std::string dir = landmarks::detector_name(row.detector) + "-" + landmarks::descriptor_name(row.descriptor);
            for (size_t k = 0; k < row.pairs.size(); ++k) {
                const auto& pr = row.pairs[k];
                if (o.landmark_files) {
                    const auto lm = landmarks::landmarks_from(pr, ds.calib[k], po);
                    landmarks::write_atomic(fs::path(o.out) / dir / "landmarks" / (safe(pr.name) + ".csv"), landmarks::landmarks_csv(lm));
                    landmarks::write_atomic(fs::path(o.out) / dir / "landmarks" / (safe(pr.name) + ".ply"), landmarks::landmarks_ply(lm));
                }
                if (static_cast<int>(k) < o.overlays)
                    landmarks::write_png(fs::path(o.out) / dir / (safe(pr.name) + "-matches.png"),
                                         landmarks::match_overlay(ds.pairs[k], pr));
            }
            const auto de = landmarks::depth_error(row, ds);
            if (de.n) {
                any_truth = true;
                depth << fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} |\n", landmarks::descriptor_name(row.descriptor),
                                     landmarks::detector_name(row.detector), de.n, de.median, de.mean, de.p90);
            }
        }

        // the g x h study
        std::ostringstream study_md, study_plots;
        std::string study_csv;
        if (o.study) {
            landmarks::StudyOptions so;
            so.corrected = o.corrected;
            so.match = co.match;
            so.threads = o.threads;
            study_md << fmt::format("Grid descriptor ({}), g {}..{}, h {}..{}, summed over the dataset's pairs.\n\n",
                                    o.corrected ? "corrected g x g" : "thesis", so.g_min, so.g_max, so.h_min, so.h_max)
                     << "| detector | best (g, h), thesis-correct | correct | best (g, h), ground truth | correct (truth) | seconds |\n"
                        "|---|---|---:|---|---:|---:|\n";
            for (size_t i = 0; i < co.detectors.size(); ++i) {
                const auto det = co.detectors[i];
                const std::string dn = landmarks::detector_name(det);
                const double ts = secs();
                const auto st = landmarks::study(ds, det, kps[i], so);
                const double t_study = secs() - ts;
                std::fprintf(stderr, "landmarks: study on %s corners: %zu cells in %.1f s\n", dn.c_str(), st.cells.size(), t_study);
                double ref = -1, ref_truth = -1;   // the SIFT descriptor on the same corners, as the thesis's dashed line
                for (const auto& r : rows)
                    if (r.detector == det && r.descriptor == landmarks::Descriptor::sift) {
                        ref = static_cast<double>(r.totals.correct);
                        ref_truth = r.totals.truth_known ? static_cast<double>(r.totals.truth_correct) : -1;
                    }
                const std::string csv = landmarks::study_csv(ds.name, st);
                study_csv += study_csv.empty() ? csv : csv.substr(csv.find('\n') + 1);
                if (landmarks::plot_study(st, false, ref, ds.name + ": grid on " + dn + " corners, thesis-correct matches",
                                          fs::path(o.out) / ("study-" + dn + ".png")))
                    study_plots << "![" << dn << "](study-" << dn << ".png)\n";
                if (st.best_truth().truth_correct > 0 &&
                    landmarks::plot_study(st, true, ref_truth, ds.name + ": grid on " + dn + " corners, ground-truth-correct matches",
                                          fs::path(o.out) / ("study-" + dn + "-truth.png")))
                    study_plots << "![" << dn << " ground truth](study-" << dn << "-truth.png)\n";
                const auto bc = st.best_correct(), bt = st.best_truth();
                study_md << fmt::format("| {} | ({}, {}) | {} | {} | {} | {:.1f} |\n", dn, bc.g, bc.h, bc.correct,
                                        bt.truth_correct ? fmt::format("({}, {})", bt.g, bt.h) : "n/a", bt.truth_correct, t_study);
            }
            study_md << "\n" << study_plots.str();
            landmarks::write_atomic(fs::path(o.out) / "study.csv", study_csv);
        }
        const double t_total = secs();

        // report
        std::ostringstream md;
        md << "# Landmark acquisition: " << ds.name << "\n\n";
        md << fmt::format("{} stereo pairs. Matches pass the cross-check and the 2-NN ratio test (thesis: ratio {} for binary "
                          "descriptors{}, 0.8 for SIFT); *correct (thesis)* adds the epipolar test |y_r - y_l| < 5; *correct "
                          "(ground truth)* counts, of those with a known disparity, the ones with |x_l - x_r - d| <= 1 px. "
                          "Time: extraction of both images + matching, one thread.\n\n",
                          ds.pairs.size(), o.ratio > 0 ? o.ratio : 1.0, o.drop_ties ? ", ties dropped" : " as printed");
        if (ds.rig)
            md << "A rig's unrectified pairs (`--calib " << o.calib
               << "`): keypoints undistorted and rectified by cv::undistortPoints with the calibration's intrinsics, "
                  "distortion, rectifying rotations and projections (no image warped); the epipolar test, the triangulation "
                  "(its rectified projections) and the overlays use the rectified positions.\n\n";
        md << fmt::format("Co-processor formats (spec, cycle, rtl corners): {}.\n\n",
                          o.config.empty() ? "the thesis's" : "--config " + o.config);
        md << landmarks::comparison_markdown(rows) << "\n";
        if (any_truth)
            md << "## Depth error against the ground truth\n\nRelative |Z - Z_gt| / Z_gt of correct (thesis) matches with a "
                  "known disparity.\n\n| descriptor | detector | n | median | mean | 90th percentile |\n|---|---|---:|---:|---:|---:|\n"
               << depth.str() << "\n";
        if (o.study) md << "## Grid parameter study (g x h)\n\n" << study_md.str() << "\n";
        md << fmt::format("Wall time: comparison {:.1f} s, total {:.1f} s.\n", t_compare, t_total);
        landmarks::write_atomic(fs::path(o.out) / "report.md", md.str());
        landmarks::write_atomic(fs::path(o.out) / "results.csv", landmarks::comparison_csv(ds.name, rows));
        landmarks::write_atomic(fs::path(o.out) / "results.json", landmarks::comparison_json(ds.name, rows));
        std::printf("%s", landmarks::comparison_markdown(rows).c_str());
        std::printf("landmarks: comparison %.1f s, total %.1f s; report %s\n", t_compare, t_total,
                    (fs::path(o.out) / "report.md").c_str());
    } catch (const landmarks::InputError& e) {
        throw InputError(e.what());
    }
}

}  // namespace

void add_landmarks_command(CLI::App& app) {
    auto o = std::make_shared<LandmarksOptions>();
    CLI::App* cmd = app.add_subcommand(
        "landmarks", "corners -> descriptor -> stereo matches -> 3D landmarks, scored against ground truth (thesis 6.4)");
    cmd->add_option("--corners", o->corners, "corner sources, comma-separated: opencv, sift, sift512, orb, brisk, spec, cycle, rtl")
        ->capture_default_str();
    cmd->add_option("--descriptor", o->descriptor, "descriptors, comma-separated: grid, grid-corrected, sift, orb, brisk, brief, freak")
        ->capture_default_str();
    cmd->add_option("--g", o->g, "grid side")->capture_default_str();
    cmd->add_option("--h", o->h, "grid resolution reduction 2^h")->capture_default_str();
    cmd->add_option("--norm", o->norm, "matcher norm: auto (the descriptor's), hamming or l2")->capture_default_str();
    cmd->add_option("--ratio", o->ratio, "2-NN ratio (0: thesis, 1 for binary, 0.8 for SIFT)");
    cmd->add_flag("--drop-ties", o->drop_ties, "ratio test also drops d0 == d1 (the evidently intended test)");
    cmd->add_flag("--compare", o->compare, "the thesis's comparison: detectors sift512, sift, opencv x all six descriptors");
    cmd->add_flag("--study", o->study, "g x h study of the grid descriptor (g 4..32, h 0..5) on each detector's corners");
    cmd->add_flag("--corrected", o->corrected, "study the corrected g x g grid instead of the thesis's");
    cmd->add_option("--dataset", o->dataset, "middlebury or kitti")->capture_default_str();
    cmd->add_option("--middlebury", o->middlebury, "Middlebury 2006 folder of scenes, or one scene (default: <data>/middlebury2006/half)");
    cmd->add_flag("--no-truth", o->no_truth, "accept Middlebury scenes without disp1.png (e.g. third/): no ground-truth scoring");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence")->capture_default_str();
    cmd->add_option("--frames", o->frames, "KITTI stereo pair range a:b (b excluded)")->capture_default_str();
    cmd->add_option("--calib", o->calib,
                    "a rig's calibration (harris-cosim calibrate's calib.yml/.json, or a calib.txt of rectified images): "
                    "run on its unrectified pairs --left/--right, keypoints undistorted and rectified (cv::undistortPoints)");
    cmd->add_option("--left", o->left, "with --calib: the rig's left images (files or glob patterns, sorted)");
    cmd->add_option("--right", o->right, "with --calib: the rig's right images, in the order of --left");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--config", o->config, "formats JSON of the co-processor (spec, cycle, rtl corners)");
    cmd->add_option("--sigma", o->sigma, "pixel noise (px, each coordinate) of the landmark covariance")->capture_default_str();
    cmd->add_option("--overlays", o->overlays, "match overlay PNGs per row (first N pairs)")->capture_default_str();
    cmd->add_flag("!--no-landmark-files", o->landmark_files, "skip the per-pair landmark CSV/PLY files");
    cmd->add_option("--threads", o->threads,
                    "worker threads of the comparison and the study (0: all cores); each pair's extraction and matching "
                    "runs on one thread either way");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->sharded = cmd->count("--runner") + cmd->count("--shards") > 0;
        run_landmarks(*o);
    });
}

}  // namespace hc::tools

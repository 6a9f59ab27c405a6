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

#include "tools/jobs/jobs.hpp"
#include "tools/commands.hpp"
#include "tools/frame_source.hpp"
#include "tools/runner_flags.hpp"
#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "io/util/util.hpp"
#include "slam/landmarks/landmarks.hpp"

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
    bool reobservation = false, descriptor_given = false;
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
        throw InputError("--pairs '" + s + "' is not a stereo pair range a:b with 0 <= a < b");
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
        root = frames::require_kitti_root(o.kitti, o.data, "--dataset kitti needs KITTI data");
        const auto [a, b] = pair_range(o.frames);
        return landmarks::kitti_dataset(root, o.sequence, a, b);
    }
    throw InputError("--dataset '" + o.dataset + "' (middlebury or kitti)");
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
    const landmarks::Dataset ds = load_dataset(o, root);
    std::fprintf(stderr, "landmarks: re-observations over %zu consecutive left images of %s...\n", ds.pairs.size(),
                 ds.name.c_str());
    const auto rows = landmarks::reobservation_study(ds, ro);
    std::ostringstream md, csv;
    md << fmt::format("# Re-observations between consecutive frames: {} ({} left images, {} corners)\n\n", ds.name,
                      ds.pairs.size(), landmarks::detector_name(ro.detector))
       << fmt::format("Corners of frame k tracked into frame k+1 by Lucas-Kanade optical flow (forward-backward error <= "
                      "{} px, a corner of frame k+1 within {} px of the tracked point); Hamming distances as a fraction of "
                      "the descriptor's bits; a random pair is the same corner against a random other corner of frame "
                      "k+1. Grid g = {}, h = {}.\n\n",
                      ro.max_fb_px, ro.max_corner_px, ro.grid.g, ro.grid.h)
       << "| descriptor | bits | re-observations | median, re-observed | median, random | mean, re-observed | mean, "
          "random | re-observed below the random median | own descriptor nearest |\n"
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    csv << "dataset,detector,descriptor,bits,frames,reobservations,same_median,random_median,same_mean,random_mean,"
           "below_random_median,nearest\n";
    for (const auto& r : rows) {
        const double n = r.reobservations ? double(r.reobservations) : 1.0;
        md << fmt::format("| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n",
                          landmarks::descriptor_name(r.descriptor), r.bits, r.reobservations, r.same_median,
                          r.random_median, r.same_mean, r.random_mean, double(r.below_random_median) / n,
                          double(r.nearest) / n);
        csv << fmt::format("{},{},{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{},{}\n", ds.name,
                           landmarks::detector_name(ro.detector), landmarks::descriptor_name(r.descriptor), r.bits,
                           r.frames, r.reobservations, r.same_median, r.random_median, r.same_mean, r.random_mean,
                           r.below_random_median, r.nearest);
    }
    fs::create_directories(o.out);
    landmarks::write_atomic(fs::path(o.out) / "reobservation.md", md.str());
    landmarks::write_atomic(fs::path(o.out) / "reobservation.csv", csv.str());
    std::printf("%s", md.str().c_str());
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
    if (!merged) return std::nullopt;
    return jobs::landmarks_rows(*merged);
}

/// The landmark files and match overlays of every row under <out>; the depth error table's
/// rows (empty when no pair has a known disparity).
std::string write_row_files(const LandmarksOptions& o, const landmarks::Dataset& ds,
                            const std::vector<landmarks::ComparisonRow>& rows) {
    landmarks::PipelineOptions po;
    po.noise.sigma_px = o.sigma;
    std::ostringstream depth;
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
            depth << fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} |\n", landmarks::descriptor_name(row.descriptor),
                                 landmarks::detector_name(row.detector), de.n, de.median, de.mean, de.p90);
        }
    }
    return depth.str();
}

/// The g x h study of every detector: its Markdown section (with the held-out choice), its
/// plots and <out>/study.csv. `secs` is the run's clock.
std::string study_markdown(const LandmarksOptions& o, const landmarks::Dataset& ds, const landmarks::ComparisonOptions& co,
                           const std::vector<std::vector<landmarks::PairKeypoints>>& kps,
                           const std::vector<landmarks::ComparisonRow>& rows, const std::function<double()>& secs) {
    std::ostringstream study_md, study_plots, held_out_md;
    bool held_out_by_truth = true;
    std::string study_csv;
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
        // (g, h) chosen on half of the pairs, scored on the other half, both ways
        if (ds.pairs.size() >= 2) {
            const bool by_truth = bt.truth_correct > 0;
            std::vector<size_t> even, odd;
            for (size_t k = 0; k < ds.pairs.size(); ++k) (k % 2 ? odd : even).push_back(k);
            const auto names = [&](const std::vector<size_t>& v) {
                std::string out;
                for (size_t k : v) out += (out.empty() ? "" : ", ") + ds.pairs[k].name;
                return out;
            };
            const auto count = [&](const landmarks::StudyCell& c) { return by_truth ? c.truth_correct : c.correct; };
            for (const auto& [choose, report] : {std::pair{even, odd}, std::pair{odd, even}}) {
                const auto ho = landmarks::held_out_choice(st, choose, report, by_truth);
                held_out_md << fmt::format("| {} | {} | {} | ({}, {}) | {} | {} | ({}, {}) | {} |\n", dn, names(choose),
                                           names(report), ho.chosen.g, ho.chosen.h, count(ho.chosen),
                                           count(ho.on_report), ho.report_best.g, ho.report_best.h,
                                           count(ho.report_best));
            }
            held_out_by_truth = held_out_by_truth && by_truth;
        }
    }
    if (!held_out_md.str().empty())
        study_md << "\n(g, h) chosen on the pairs of one half and scored on the other ("
                 << (held_out_by_truth ? "ground-truth-correct" : "thesis-correct")
                 << " matches; 'best on scored' is what choosing on the scored pairs themselves would claim):\n\n"
                    "| detector | chosen on | scored on | chosen (g, h) | count on chosen | count on scored | best on scored "
                    "| its count |\n|---|---|---|---|---:|---:|---|---:|\n"
                 << held_out_md.str();
    study_md << "\n" << study_plots.str();
    landmarks::write_atomic(fs::path(o.out) / "study.csv", study_csv);
    return study_md.str();
}

/// The report's Markdown: the matching rules, the comparison table, the depth error and the study.
std::string report_markdown(const LandmarksOptions& o, const landmarks::Dataset& ds,
                            const std::vector<landmarks::ComparisonRow>& rows, const std::string& depth,
                            const std::string& study, double t_compare, double t_total) {
    std::ostringstream md;
    md << "# Landmark acquisition: " << ds.name << "\n\n";
    md << fmt::format("{} stereo pairs. Matches pass the cross-check and the 2-NN ratio test ({}{}); *correct (thesis)* "
                      "adds the epipolar test |y_r - y_l| < 5; *correct (ground truth)* counts, of those with a known "
                      "disparity, the ones with |x_l - x_r - d| <= 1 px and |y_r - y_l| <= 1 px; *x only* the ones with "
                      "|x_l - x_r - d| <= 1 px whatever their rows. Time: extraction of both images + matching, one thread.\n\n",
                      ds.pairs.size(),
                      o.ratio > 0 ? fmt::format("ratio {} for every descriptor", o.ratio)
                                  : std::string("ratio 1, the thesis's test of the grid, for every descriptor but "
                                                "sift, which uses 0.8 as the thesis's SIFT reference (after Lowe); "
                                                "sift-ratio1 is SIFT at ratio 1"),
                      o.drop_ties ? "; ties dropped" : "; the test as printed");
    if (ds.rig)
        md << "A rig's unrectified pairs (`--calib " << o.calib
           << "`): keypoints undistorted and rectified by cv::undistortPoints with the calibration's intrinsics, "
              "distortion, rectifying rotations and projections (no image warped); the epipolar test, the triangulation "
              "(its rectified projections) and the overlays use the rectified positions.\n\n";
    md << fmt::format("Co-processor formats (spec, cycle, rtl corners): {}.\n\n",
                      o.config.empty() ? "the thesis's" : "--config " + o.config);
    md << landmarks::comparison_markdown(rows) << "\n";
    if (!depth.empty())
        md << "## Depth error against the ground truth\n\nRelative |Z - Z_gt| / Z_gt of correct (thesis) matches with a "
              "known disparity.\n\n| descriptor | detector | n | median | mean | 90th percentile |\n|---|---|---:|---:|---:|---:|\n"
           << depth << "\n";
    if (o.study) md << "## Grid parameter study (g x h)\n\n" << study << "\n";
    md << fmt::format("Wall time: comparison {:.1f} s, total {:.1f} s.\n", t_compare, t_total);
    return md.str();
}

void run_landmarks(const LandmarksOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::function<double()> secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    try {
        if (o.reobservation) {
            if (o.compare || o.study || o.sharded || !o.calib.empty())
                throw InputError("--reobservation runs alone: leave out --compare, --study, --calib, --runner and --shards");
            run_reobservation(o);
            return;
        }
        const landmarks::ComparisonOptions co = comparison_options(o);

        std::fprintf(stderr, "landmarks: loading %s...\n", o.calib.empty() ? o.dataset.c_str() : o.calib.c_str());
        fs::path root;
        const landmarks::Dataset ds = load_dataset(o, root);
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
        const double t_compare = secs();
        const std::string depth = write_row_files(o, ds, rows);   // landmarks and overlays of every row
        const std::string study = o.study ? study_markdown(o, ds, co, kps, rows, secs) : std::string();
        const double t_total = secs();

        const std::string md = report_markdown(o, ds, rows, depth, study, t_compare, t_total);
        landmarks::write_atomic(fs::path(o.out) / "report.md", md);
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
    cmd->add_option("--dataset", o->dataset, "middlebury or kitti")->capture_default_str();
    cmd->add_option("--middlebury", o->middlebury, "Middlebury 2006 folder of scenes, or one scene (default: <data>/middlebury2006/half)");
    cmd->add_flag("--no-truth", o->no_truth, "accept Middlebury scenes without disp1.png (e.g. third/): no ground-truth scoring");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence")->capture_default_str();
    add_pair_range_option(cmd, o->frames, "KITTI stereo pair range a:b (b excluded; default " + o->frames + ")");
    cmd->add_option("--calib", o->calib,
                    "a rig's calibration (harris-cosim calibrate's calib.yml/.json, or a calib.txt of rectified images): "
                    "run on its unrectified pairs --left/--right, keypoints undistorted and rectified (cv::undistortPoints)");
    cmd->add_option("--left", o->left, "with --calib: the rig's left images (files or glob patterns, sorted)");
    cmd->add_option("--right", o->right, "with --calib: the rig's right images, in the order of --left");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
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
        o->sharded = cmd->count("--runner") + cmd->count("--shards") > 0;
        o->descriptor_given = cmd->count("--descriptor") > 0;
        run_landmarks(*o);
    });
}

}  // namespace hc::tools

// report_files.cpp: the landmarks command's report as the library writes it: report.md (the
// matching rules, the comparison, the depth errors, the g x h study with its held-out choice),
// results.csv/.json, each row's landmark files and overlays; the re-observation tables.
#include <cstdio>
#include <sstream>
#include <utility>

#include <fmt/format.h>

#include "mapping/landmarks/report.hpp"

namespace fs = std::filesystem;

namespace hc::landmarks {

namespace {

std::string safe(const std::string& s) {
    std::string r = s;
    for (char& c : r)
        if (c == '/' || c == ' ') c = '_';
    return r;
}

/// The landmark files and match overlays of every row under <out>; the depth error table's
/// rows (empty when no pair has a known disparity).
std::string write_row_files(const ReportOptions& ro, const Dataset& ds,
                            const std::vector<ComparisonRow>& rows) {
    PipelineOptions po;
    po.noise.sigma_px = ro.sigma_px;
    std::ostringstream depth;
    for (const auto& row : rows) {
        const std::string dir = detector_name(row.detector) + "-" + descriptor_name(row.descriptor);
        for (size_t k = 0; k < row.pairs.size(); ++k) {
            const auto& pr = row.pairs[k];
            if (ro.landmark_files) {
                const auto lm = landmarks_from(pr, ds.calib[k], po);
                write_atomic(ro.out / dir / "landmarks" / (safe(pr.name) + ".csv"), landmarks_csv(lm));
                write_atomic(ro.out / dir / "landmarks" / (safe(pr.name) + ".ply"), landmarks_ply(lm));
            }
            if (static_cast<int>(k) < ro.overlays)
                write_png(ro.out / dir / (safe(pr.name) + "-matches.png"),
                                     match_overlay(ds.pairs[k], pr));
        }
        const auto de = depth_error(row, ds);
        if (de.n) {
            depth << fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} |\n", descriptor_name(row.descriptor),
                                 detector_name(row.detector), de.n, de.median, de.mean, de.p90);
        }
    }
    return depth.str();
}

/// The g x h study of every detector: its Markdown section (with the held-out choice), its
/// plots and <out>/study.csv. `secs` is the run's clock.
std::string study_markdown(const ReportOptions& ro, const Dataset& ds, const ComparisonOptions& co,
                           const std::vector<std::vector<PairKeypoints>>& kps,
                           const std::vector<ComparisonRow>& rows, const std::function<double()>& secs) {
    std::ostringstream study_md, study_plots, held_out_md;
    bool held_out_by_truth = true;
    std::string study_csv;
    StudyOptions so;
    so.corrected = ro.corrected;
    so.match = co.match;
    so.threads = ro.threads;
    study_md << fmt::format("Grid descriptor ({}), g {}..{}, h {}..{}, summed over the dataset's pairs.\n\n",
                            ro.corrected ? "corrected g x g" : "thesis", so.g_min, so.g_max, so.h_min, so.h_max)
             << "| detector | best (g, h), thesis-correct | correct | best (g, h), ground truth | correct (truth) | seconds |\n"
                "|---|---|---:|---|---:|---:|\n";
    for (size_t i = 0; i < co.detectors.size(); ++i) {
        const auto det = co.detectors[i];
        const std::string dn = detector_name(det);
        const double ts = secs();
        const auto st = study(ds, det, kps[i], so);
        const double t_study = secs() - ts;
        std::fprintf(stderr, "landmarks: study on %s corners: %zu cells in %.1f s\n", dn.c_str(), st.cells.size(), t_study);
        double ref = -1, ref_truth = -1;   // the SIFT descriptor on the same corners, as the thesis's dashed line
        for (const auto& r : rows)
            if (r.detector == det && r.descriptor == Descriptor::sift) {
                ref = static_cast<double>(r.totals.correct);
                ref_truth = r.totals.truth_known ? static_cast<double>(r.totals.truth_correct) : -1;
            }
        const std::string csv = landmarks::study_csv(ds.name, st);
        study_csv += study_csv.empty() ? csv : csv.substr(csv.find('\n') + 1);
        if (plot_study(st, false, ref, ds.name + ": grid on " + dn + " corners, thesis-correct matches",
                                  ro.out / ("study-" + dn + ".png")))
            study_plots << "![" << dn << "](study-" << dn << ".png)\n";
        if (st.best_truth().truth_correct > 0 &&
            plot_study(st, true, ref_truth, ds.name + ": grid on " + dn + " corners, ground-truth-correct matches",
                                  ro.out / ("study-" + dn + "-truth.png")))
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
            const auto count = [&](const StudyCell& c) { return by_truth ? c.truth_correct : c.correct; };
            for (const auto& [choose, report] : {std::pair{even, odd}, std::pair{odd, even}}) {
                const auto ho = held_out_choice(st, choose, report, by_truth);
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
    write_atomic(ro.out / "study.csv", study_csv);
    return study_md.str();
}

/// The report's Markdown: the matching rules, the comparison table, the depth error and the study.
std::string report_markdown(const ReportOptions& ro, const ComparisonOptions& co, const Dataset& ds,
                            const std::vector<ComparisonRow>& rows, const std::string& depth,
                            const std::string& study, double t_compare, double t_total) {
    std::ostringstream md;
    md << "# Landmark acquisition: " << ds.name << "\n\n";
    md << fmt::format("{} stereo pairs. Matches pass the cross-check and the 2-NN ratio test ({}{}); *correct (thesis)* "
                      "adds the epipolar test |y_r - y_l| < 5; *correct (ground truth)* counts, of those with a known "
                      "disparity, the ones with |x_l - x_r - d| <= 1 px and |y_r - y_l| <= 1 px; *x only* the ones with "
                      "|x_l - x_r - d| <= 1 px whatever their rows. Time: extraction of both images + matching, one thread.\n\n",
                      ds.pairs.size(),
                      co.match.ratio > 0 ? fmt::format("ratio {} for every descriptor", co.match.ratio)
                                  : std::string("ratio 1, the thesis's test of the grid, for every descriptor but "
                                                "sift, which uses 0.8 as the thesis's SIFT reference (after Lowe); "
                                                "sift-ratio1 is SIFT at ratio 1"),
                      co.match.drop_ties ? "; ties dropped" : "; the test as printed");
    if (ds.rig)
        md << "A rig's unrectified pairs (`--calib " << ro.calib
           << "`): keypoints undistorted and rectified by cv::undistortPoints with the calibration's intrinsics, "
              "distortion, rectifying rotations and projections (no image warped); the epipolar test, the triangulation "
              "(its rectified projections) and the overlays use the rectified positions.\n\n";
    md << fmt::format("Co-processor formats (spec, cycle, rtl corners): {}.\n\n",
                      ro.config.empty() ? "the thesis's" : "--config " + ro.config);
    md << comparison_markdown(rows) << "\n";
    if (!depth.empty())
        md << "## Depth error against the ground truth\n\nRelative |Z - Z_gt| / Z_gt of correct (thesis) matches with a "
              "known disparity.\n\n| descriptor | detector | n | median | mean | 90th percentile |\n|---|---|---:|---:|---:|---:|\n"
           << depth << "\n";
    if (ro.study) md << "## Grid parameter study (g x h)\n\n" << study << "\n";
    md << fmt::format("Wall time: comparison {:.1f} s, total {:.1f} s.\n", t_compare, t_total);
    return md.str();
}

}  // namespace

ComparisonReport write_comparison_report(const Dataset& ds, const ComparisonOptions& co,
                                         const std::vector<ComparisonRow>& rows,
                                         const std::vector<std::vector<PairKeypoints>>& keypoints, const ReportOptions& ro,
                                         const std::function<double()>& secs) {
    if (ro.study && keypoints.size() != co.detectors.size())
        throw InputError("the g x h study needs the corners of every detector (compare()'s keypoints)");
    ComparisonReport r;
    r.compare_seconds = secs();
    const std::string depth = write_row_files(ro, ds, rows);   // landmarks and overlays of every row
    const std::string study = ro.study ? study_markdown(ro, ds, co, keypoints, rows, secs) : std::string();
    r.total_seconds = secs();
    r.markdown = report_markdown(ro, co, ds, rows, depth, study, r.compare_seconds, r.total_seconds);
    write_atomic(ro.out / "report.md", r.markdown);
    write_atomic(ro.out / "results.csv", comparison_csv(ds.name, rows));
    write_atomic(ro.out / "results.json", comparison_json(ds.name, rows));
    return r;
}

ReobservationReport reobservation_report(const Dataset& ds, const ReobservationOptions& ro,
                                         const std::vector<ReobservationRow>& rows) {
    std::ostringstream md, csv;
    md << fmt::format("# Re-observations between consecutive frames: {} ({} left images, {} corners)\n\n", ds.name,
                      ds.pairs.size(), detector_name(ro.detector))
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
                          descriptor_name(r.descriptor), r.bits, r.reobservations, r.same_median,
                          r.random_median, r.same_mean, r.random_mean, double(r.below_random_median) / n,
                          double(r.nearest) / n);
        csv << fmt::format("{},{},{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{},{}\n", ds.name,
                           detector_name(ro.detector), descriptor_name(r.descriptor), r.bits,
                           r.frames, r.reobservations, r.same_median, r.random_median, r.same_mean, r.random_mean,
                           r.below_random_median, r.nearest);
    }
    return {md.str(), csv.str()};
}

}  // namespace hc::landmarks

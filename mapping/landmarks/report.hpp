// report.hpp: the landmark chain's files (part of mapping/landmarks/landmarks.hpp): atomic writes,
// match overlays, the comparison and study tables and plots.
#pragma once

#include "mapping/landmarks/pipeline.hpp"
#include "mapping/landmarks/reobservation.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hc::landmarks {

// ---- reports -----------------------------------------------------------------------------

/// Writes `bytes` to `target` through a temporary beside it and a rename (never half a file).
void write_atomic(const std::filesystem::path& target, const std::string& bytes);
/// Left and right images side by side, each match a line: green when correct (within 1 px of
/// the ground truth, or without ground truth passing the epipolar test), red when wrong,
/// yellow when the ground truth is unknown at the left pixel. Unmatched keypoints grey.
cv::Mat match_overlay(const StereoImages& img, const PairResult& r);
void write_png(const std::filesystem::path& target, const cv::Mat& img);   ///< atomic

/// The comparison as CSV (one row per detector x descriptor, summed over pairs; plus the
/// SURF row marked unavailable), Markdown and JSON (per pair as well).
std::string comparison_csv(const std::string& dataset, const std::vector<ComparisonRow>& rows);
std::string comparison_markdown(const std::vector<ComparisonRow>& rows);
std::string comparison_json(const std::string& dataset, const std::vector<ComparisonRow>& rows);

std::string study_csv(const std::string& dataset, const StudyResult& s);
/// Correct matches over g, one curve per h (as the thesis's Figures 29-34), `reference` a
/// dashed line (e.g. the SIFT descriptor's count on the same corners; < 0: none), through
/// gnuplot (false when gnuplot is not installed). `truth` plots ground-truth-correct counts.
bool plot_study(const StudyResult& s, bool truth, double reference, const std::string& title,
                const std::filesystem::path& png);

/// The landmarks command's report: what it writes besides the tables, and how it names its inputs.
struct ReportOptions {
    std::filesystem::path out;      ///< output directory (made by the caller)
    double sigma_px = 0.5;          ///< pixel noise of the landmark files' covariances (PixelNoise)
    bool landmark_files = true;     ///< <out>/<detector>-<descriptor>/landmarks/<pair>.csv and .ply
    int overlays = 2;               ///< match overlay PNGs of each row's first N pairs
    bool study = false;             ///< the grid's g x h study on each detector's corners
    bool corrected = false;         ///< study the corrected g x g grid instead of the thesis's
    int threads = 0;                ///< the study's threads (0: all cores)
    std::string calib, config;      ///< the rig's calibration file and the formats file as given (empty: none)
};
struct ComparisonReport {
    std::string markdown;           ///< report.md
    double compare_seconds = 0, total_seconds = 0;   ///< the run's clock when the comparison and the report ended
};
/// Writes the report of a comparison under ro.out: report.md (the matching rules of co.match,
/// the comparison, the depth errors against ground truth, with ro.study the g x h study and its
/// held-out choice of (g, h)), results.csv, results.json, each row's landmark files and overlays,
/// study.csv and the study's plots. `keypoints` are compare()'s (needed by the study, one entry
/// per detector of co); `secs` is the run's clock in seconds.
ComparisonReport write_comparison_report(const Dataset& ds, const ComparisonOptions& co,
                                         const std::vector<ComparisonRow>& rows,
                                         const std::vector<std::vector<PairKeypoints>>& keypoints, const ReportOptions& ro,
                                         const std::function<double()>& secs);

/// The re-observation study's tables: Markdown (with its method) and CSV.
struct ReobservationReport {
    std::string markdown, csv;
};
ReobservationReport reobservation_report(const Dataset& ds, const ReobservationOptions& o,
                                         const std::vector<ReobservationRow>& rows);

}  // namespace hc::landmarks

// report.cpp: the files of a landmarks run: comparison tables (CSV, Markdown, JSON), the
// g x h study (CSV, gnuplot PNG), match overlays (PNG), all written atomically.
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mapping/landmarks/report.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::landmarks {

void write_atomic(const fs::path& target, const std::string& bytes) { util::write_file_atomic(target, bytes); }

void write_png(const fs::path& target, const cv::Mat& img) {
    std::vector<std::uint8_t> buf;
    if (!cv::imencode(".png", img, buf)) throw std::runtime_error("cannot encode '" + target.string() + "'");
    write_atomic(target, std::string(buf.begin(), buf.end()));
}

cv::Mat match_overlay(const StereoImages& img, const PairResult& r) {
    cv::Mat canvas(img.left.rows, img.left.cols + img.right.cols, CV_8UC3);
    cv::Mat l = canvas(cv::Rect(0, 0, img.left.cols, img.left.rows));
    cv::Mat rr = canvas(cv::Rect(img.left.cols, 0, img.right.cols, img.right.rows));
    cv::cvtColor(img.left, l, cv::COLOR_GRAY2BGR);
    cv::cvtColor(img.right, rr, cv::COLOR_GRAY2BGR);
    const cv::Point2f off(static_cast<float>(img.left.cols), 0.f);
    const cv::Scalar grey(150, 150, 150), green(0, 200, 0), red(0, 0, 255), yellow(0, 220, 255);
    for (const auto& k : r.kp_left) cv::circle(canvas, k.pt, 1, grey, -1);
    for (const auto& k : r.kp_right) cv::circle(canvas, k.pt + off, 1, grey, -1);
    for (const auto& m : r.matches) {
        const cv::Scalar c = !m.epipolar                ? red
                             : m.truth == truth_right   ? green
                             : m.truth != truth_unknown ? red
                             : r.has_truth              ? yellow
                                                        : green;
        cv::line(canvas, m.left, m.right + off, c, 1, cv::LINE_AA);
        cv::circle(canvas, m.left, 2, c, 1);
        cv::circle(canvas, m.right + off, 2, c, 1);
    }
    return canvas;
}

// ---- comparison tables -----------------------------------------------------------------------

namespace {

double ratio(long a, long b) { return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0; }

std::string row_label(const ComparisonRow& r) {
    if (descriptor_info(r.descriptor).grid)
        return fmt::format("{} (g={}, h={})", descriptor_name(r.descriptor), r.grid.g, r.grid.h);
    return descriptor_name(r.descriptor);
}

}  // namespace

std::string comparison_csv(const std::string& dataset, const std::vector<ComparisonRow>& rows) {
    std::ostringstream o;
    o << "dataset,descriptor,g,h,detector,pairs,keypoints,all_matches,correct_thesis,truth_known,correct_truth,"
         "truth_precision,correct_truth_x_only,descriptor_bytes,ms_per_pair,available\n";
    std::vector<Detector> seen;
    for (const auto& r : rows) {
        const bool grid = descriptor_info(r.descriptor).grid;
        o << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{:.4f},{},{},{:.3f},yes\n", dataset, descriptor_name(r.descriptor),
                         grid ? std::to_string(r.grid.g) : "", grid ? std::to_string(r.grid.h) : "",
                         detector_name(r.detector), r.totals.pairs, r.totals.keypoints, r.totals.all, r.totals.correct,
                         r.totals.truth_known, r.totals.truth_correct, ratio(r.totals.truth_correct, r.totals.truth_known),
                         r.totals.truth_correct_x, r.descriptor_bytes, r.totals.pairs ? 1e3 * r.totals.seconds / r.totals.pairs : 0.0);
        if (std::find(seen.begin(), seen.end(), r.detector) == seen.end()) seen.push_back(r.detector);
    }
    for (Detector d : seen) o << fmt::format("{},surf,,,{},,,,,,,,,,,no (nonfree; absent from Debian's OpenCV)\n", dataset, detector_name(d));
    return o.str();
}

std::string comparison_markdown(const std::vector<ComparisonRow>& rows) {
    std::ostringstream o;
    o << "| descriptor | detector | keypoints | all matches | correct (thesis) | ratio | correct (ground truth) | "
         "x only | of known | bytes | ms / pair |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::vector<Detector> seen;
    for (const auto& r : rows) {
        const Totals& t = r.totals;
        o << fmt::format("| {} | {} | {} | {} | {} | {:.3f} | {} | {} | {} | {} | {:.2f} |\n", row_label(r),
                         detector_name(r.detector), t.keypoints, t.all, t.correct, ratio(t.correct, t.all),
                         t.truth_known ? fmt::format("{} ({:.3f})", t.truth_correct, ratio(t.truth_correct, t.truth_known)) : "n/a",
                         t.truth_known ? fmt::format("{} ({:.3f})", t.truth_correct_x, ratio(t.truth_correct_x, t.truth_known))
                                       : "n/a",
                         t.truth_known, r.descriptor_bytes, t.pairs ? 1e3 * t.seconds / t.pairs : 0.0);
        if (std::find(seen.begin(), seen.end(), r.detector) == seen.end()) seen.push_back(r.detector);
    }
    for (Detector d : seen)
        o << fmt::format("| surf | {} | unavailable: nonfree, absent from Debian's OpenCV 4.6 | | | | | | | | |\n", detector_name(d));
    return o.str();
}

std::string comparison_json(const std::string& dataset, const std::vector<ComparisonRow>& rows) {
    nlohmann::json j;
    j["dataset"] = dataset;
    j["rows"] = nlohmann::json::array();
    for (const auto& r : rows) {
        nlohmann::json row{{"descriptor", descriptor_name(r.descriptor)},
                           {"detector", detector_name(r.detector)},
                           {"descriptor_bytes", r.descriptor_bytes},
                           {"all", r.totals.all},
                           {"correct_thesis", r.totals.correct},
                           {"truth_known", r.totals.truth_known},
                           {"correct_truth", r.totals.truth_correct},
                           {"correct_truth_x_only", r.totals.truth_correct_x},
                           {"keypoints", r.totals.keypoints},
                           {"seconds", r.totals.seconds}};
        if (descriptor_info(r.descriptor).grid) {
            row["g"] = r.grid.g;
            row["h"] = r.grid.h;
        }
        for (const auto& p : r.pairs)
            row["pairs"].push_back({{"name", p.name},
                                    {"keypoints_left", p.keypoints_left},
                                    {"keypoints_right", p.keypoints_right},
                                    {"all", p.all()},
                                    {"correct_thesis", p.correct()},
                                    {"truth_known", p.truth_known()},
                                    {"correct_truth", p.truth_correct()},
                                    {"correct_truth_x_only", p.truth_correct_x()},
                                    {"seconds", p.seconds}});
        j["rows"].push_back(row);
    }
    j["unavailable"] = {{"surf", "nonfree module, absent from Debian's OpenCV 4.6"}};
    return j.dump(1) + "\n";
}

// ---- study ----------------------------------------------------------------------------------

std::string study_csv(const std::string& dataset, const StudyResult& s) {
    std::ostringstream o;
    o << "dataset,detector,g,h,all_matches,correct_thesis,correct_truth\n";
    for (const auto& c : s.cells)
        o << fmt::format("{},{},{},{},{},{},{}\n", dataset, detector_name(s.detector), c.g, c.h, c.all, c.correct, c.truth_correct);
    return o.str();
}

bool plot_study(const StudyResult& s, bool truth, double reference, const std::string& title, const fs::path& png) {
    const std::string gnuplot = HC_GNUPLOT;
    if (gnuplot.empty() || !fs::exists(gnuplot)) return false;
    if (png.has_parent_path()) fs::create_directories(png.parent_path());
    int h_min = 1 << 30, h_max = -1, g_min = 1 << 30, g_max = -1;
    for (const auto& c : s.cells) {
        h_min = std::min(h_min, c.h), h_max = std::max(h_max, c.h);
        g_min = std::min(g_min, c.g), g_max = std::max(g_max, c.g);
    }
    std::ostringstream sc;
    const fs::path tmp = png.string() + ".tmp.png";
    sc << "set terminal pngcairo size 900,560 noenhanced\n"   // falls back below if pngcairo is missing
       << "set output '" << tmp.string() << "'\n"
       << "set title '" << title << "'\nset xlabel 'g (grid side)'\nset ylabel '"
       << (truth ? "correct matches (ground truth)" : "correct matches (thesis)") << "'\n"
       << "set key outside right\nset grid\nset xrange [" << g_min << ":" << g_max << "]\n";
    sc << "plot ";
    for (int h = h_min; h <= h_max; ++h) sc << "'-' using 1:2 with linespoints title 'h = " << h << "', ";
    if (reference >= 0) sc << reference << " with lines dashtype 2 lc rgb 'black' title 'SIFT descriptor'";
    else sc << "1/0 notitle";
    sc << "\n";
    for (int h = h_min; h <= h_max; ++h) {
        for (const auto& c : s.cells)
            if (c.h == h) sc << c.g << ' ' << (truth ? c.truth_correct : c.correct) << '\n';
        sc << "e\n";
    }
    std::string script = sc.str();
    for (const char* term : {"pngcairo", "png"}) {
        if (std::string(term) == "png") script.replace(script.find("pngcairo"), 8, "png");
        const fs::path gp = png.string() + ".gp";
        write_atomic(gp, script);
        const std::string cmd = "'" + gnuplot + "' '" + gp.string() + "' 2>/dev/null";
        const int rc = std::system(cmd.c_str());
        fs::remove(gp);
        if (rc == 0 && fs::exists(tmp) && fs::file_size(tmp) > 0) {
            fs::rename(tmp, png);
            return true;
        }
    }
    fs::remove(tmp);
    return false;
}

}  // namespace hc::landmarks

// report.cpp: see report.hpp.
#include "eval/report.hpp"
#include "model/util/errors.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

#include "io/frames/frames.hpp"

namespace fs = std::filesystem;

namespace hc::eval {

namespace {

// Thesis Table 5 (KITTI sequence 00, 4541 stereo pairs; Schulz 2015, section 6.3.2).
constexpr std::uint64_t kTp = 10437007, kTn = 4224750170ULL, kFp = 372423, kFn = 380448;

std::string num(std::uint64_t v) {
    std::string s = std::to_string(v), o;
    for (size_t i = 0; i < s.size(); ++i) {
        if (i && (s.size() - i) % 3 == 0) o += ',';
        o += s[i];
    }
    return o;
}

std::string markdown(const Report& r) {
    Confusion th;
    th.tp = kTp; th.tn = kTn; th.fp = kFp; th.fn = kFn;
    std::ostringstream m;
    m << "# Harris co-processor vs OpenCV: " << r.source << " source\n\n";
    m << "Stream: " << r.stream << "  \nCommand: `" << r.command << "`  \n";
    if (r.seconds_total > 0)
        m << fmt::format("Time: source {:.2f} s, OpenCV reference {:.2f} s, total {:.2f} s ({} threads)\n\n",
                         r.seconds_source, r.seconds_reference, r.seconds_total, r.threads);
    else
        m << "\n";
    m << "Metrics, reference and protocol: docs/metrics.md. Scored frames: "
      << std::count_if(r.frames.begin(), r.frames.end(), [](const FrameRow& f) { return f.scored; }) << " of "
      << r.frames.size() << ".\n\n";
    m << "| | this run (" << r.source << ") | thesis Table 5 (KITTI 00, hardware) |\n|---|---:|---:|\n";
    m << "| True positives | " << num(r.total.tp) << " | " << num(th.tp) << " |\n";
    m << "| True negatives | " << num(r.total.tn) << " | " << num(th.tn) << " |\n";
    m << "| False positives | " << num(r.total.fp) << " | " << num(th.fp) << " |\n";
    m << "| False negatives | " << num(r.total.fn) << " | " << num(th.fn) << " |\n";
    m << "| Total points | " << num(r.total.total()) << " | " << num(th.total()) << " |\n";
    m << fmt::format("| Recall | {:.6f} | {:.6f} |\n", r.total.recall(), th.recall());
    m << fmt::format("| Specificity | {:.6f} | {:.6f} |\n", r.total.specificity(), th.specificity());
    m << fmt::format("| Precision | {:.6f} | {:.6f} |\n", r.total.precision(), th.precision());
    m << fmt::format("| F1 | {:.6f} | {:.6f} |\n\n", r.total.f1(), th.f1());
    m << "The thesis scored KITTI sequence 00 (4541 pairs); only one stereo pair of 00 is available here, so "
         "the figures are not directly comparable.\n\n";
    if (!r.sequences.empty()) {
        m << "## Per sequence (each streamed from its own reset)\n\n";
        m << "| sequence | pairs | frames | scored | TP | FP | FN | recall | precision |\n"
             "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const auto& q : r.sequences)
            m << fmt::format("| {} | {}..{} | {} | {} | {} | {} | {} | {:.6f} | {:.6f} |\n", q.sequence, q.first_pair,
                             q.last_pair, q.frames, q.scored, num(q.c.tp), num(q.c.fp), num(q.c.fn), q.c.recall(),
                             q.c.precision());
        m << fmt::format("| total | | {} | {} | {} | {} | {} | {:.6f} | {:.6f} |\n\n", r.frames.size(),
                         std::count_if(r.frames.begin(), r.frames.end(), [](const FrameRow& f) { return f.scored; }),
                         num(r.total.tp), num(r.total.fp), num(r.total.fn), r.total.recall(), r.total.precision());
    }
    if (!r.ablation.empty()) {
        m << "## Ablation: one approximation switched back to ideal at a time (spec model)\n\n";
        m << "| variant | recall | precision | F1 | TP | FP | FN | options |\n|---|---:|---:|---:|---:|---:|---:|---|\n";
        for (const auto& a : r.ablation)
            m << fmt::format("| {} | {:.6f} | {:.6f} | {:.6f} | {} | {} | {} | `{}` |\n", a.name, a.c.recall(),
                             a.c.precision(), a.c.f1(), num(a.c.tp), num(a.c.fp), num(a.c.fn), a.options);
        m << "\n";
    }
    if (!r.deviations.empty()) {
        m << "## Cycle model vs spec model: deviations on these frames\n\n";
        m << "| cause | pixels | corners | measured by |\n|---|---|---:|---|\n";
        for (const auto& d : r.deviations)
            m << "| " << d.cause << " | " << d.pixels << " | " << d.corners << " | " << d.measured << " |\n";
        m << "\n";
    }
    for (const auto& n : r.notes) m << "- " << n << "\n";
    m << "\nFiles: `frames.csv` (per frame), " << (r.sequences.empty() ? "" : "`sequences.csv` (per sequence), ")
      << "`totals.json`";
    if (!r.overlays.empty()) {
        m << ", overlays (green both, red " << r.source << " only, blue OpenCV only):";
        for (const auto& f : r.overlays) m << " `" << f << "`";
    }
    m << ", `recall_precision.png`.\n";
    return m.str();
}

}  // namespace

void write_reports(const fs::path& out, const Report& r) {
    std::ostringstream csv;
    csv << "frame,name,pair,scored,tp,tn,fp,fn,recall,precision,source_corners,reference_corners,thr,max\n";
    for (const auto& f : r.frames)
        csv << fmt::format("{},{},{},{},{},{},{},{},{:.6f},{:.6f},{},{},{},{}\n", f.frame, f.name, f.pair,
                           f.scored ? 1 : 0, f.c.tp, f.c.tn, f.c.fp, f.c.fn, f.c.recall(), f.c.precision(),
                           f.source_corners, f.reference_corners, f.thr, f.max);
    nlohmann::json j;
    j["source"] = r.source;
    j["stream"] = r.stream;
    j["command"] = r.command;
    auto conf = [](const Confusion& c) {
        return nlohmann::json{{"tp", c.tp},         {"tn", c.tn},
                              {"fp", c.fp},         {"fn", c.fn},
                              {"total", c.total()}, {"recall", c.recall()},
                              {"specificity", c.specificity()}, {"precision", c.precision()},
                              {"f1", c.f1()}};
    };
    j["totals"] = conf(r.total);
    j["scored_frames"] = std::count_if(r.frames.begin(), r.frames.end(), [](const FrameRow& f) { return f.scored; });
    if (r.seconds_total > 0)
        j["seconds"] = {{"source", r.seconds_source}, {"reference", r.seconds_reference}, {"total", r.seconds_total}};
    std::ostringstream seq_csv;
    seq_csv << "sequence,first_pair,last_pair,frames,scored,tp,tn,fp,fn,recall,precision\n";
    for (const auto& q : r.sequences) {
        j["sequences"].push_back({{"sequence", q.sequence}, {"first_pair", q.first_pair}, {"last_pair", q.last_pair},
                                  {"frames", q.frames}, {"scored_frames", q.scored}, {"metrics", conf(q.c)}});
        seq_csv << fmt::format("{},{},{},{},{},{},{},{},{},{:.6f},{:.6f}\n", q.sequence, q.first_pair, q.last_pair,
                               q.frames, q.scored, q.c.tp, q.c.tn, q.c.fp, q.c.fn, q.c.recall(), q.c.precision());
    }
    if (!r.sequences.empty()) util::write_file_atomic(out / "sequences.csv", seq_csv.str());
    j["thesis_table5"] = {{"tp", kTp}, {"tn", kTn}, {"fp", kFp}, {"fn", kFn},
                          {"recall", 0.964830}, {"specificity", 0.999912}, {"precision", 0.965546}};
    for (const auto& a : r.ablation) j["ablation"].push_back({{"variant", a.name}, {"options", a.options}, {"metrics", conf(a.c)}});
    for (const auto& d : r.deviations)
        j["deviations"].push_back({{"cause", d.cause}, {"pixels", d.pixels}, {"corners", d.corners}, {"measured", d.measured}});
    util::write_file_atomic(out / "frames.csv", csv.str());
    util::write_file_atomic(out / "totals.json", j.dump(2) + "\n");
    util::write_file_atomic(out / "summary.md", markdown(r));
}

void write_overlay(const fs::path& file, const Image& img, const std::vector<std::uint8_t>& src,
                   const std::vector<std::uint8_t>& ref) {
    cv::Mat grey(img.height, img.width, CV_8UC1, const_cast<std::uint8_t*>(img.pixels.data())), bgr;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    bgr = bgr * 0.6;   // dim the picture so the marks stand out
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const size_t i = static_cast<size_t>(y) * img.width + x;
            if (!src[i] && !ref[i]) continue;
            const cv::Scalar col = src[i] && ref[i] ? cv::Scalar(0, 255, 0)        // both: green
                                   : src[i]       ? cv::Scalar(0, 0, 255)          // source only: red
                                                  : cv::Scalar(255, 96, 0);        // OpenCV only: blue
            cv::circle(bgr, {x, y}, 3, col, 1, cv::LINE_AA);
        }
    std::vector<std::uint8_t> buf;
    if (!cv::imencode(".png", bgr, buf)) throw InternalError("cannot encode overlay " + file.string());
    util::write_file_atomic(file, std::string(buf.begin(), buf.end()));
}

void require_rtl_agreement(const Report& r, const fs::path& out) {
    if (r.rtl_mismatches > 0)
        throw MismatchError(fmt::format("eval --source rtl: {} reads of the netlist disagree with the cycle model "
                                        "run in lock step (report in {})", r.rtl_mismatches, out.string()));
}

bool write_plot(const fs::path& out, const Report& r) {
    // gnuplot's output goes to a log beside the plot's temporaries, removed with them
    const fs::path log = out / fmt::format(".plot.{}.log", ::getpid());
    const auto gnuplot = [&](const fs::path& script) {
        try {
            return util::run_process({"gnuplot", script.string()}, {.log = log});
        } catch (const SimulatorError&) {
            return 127;   // not installed
        }
    };
    const fs::path dat = out / fmt::format(".plot.{}.dat", ::getpid());
    const fs::path png_tmp = out / fmt::format(".recall_precision.{}.png", ::getpid());
    std::vector<double> values, frames;
    {
        std::ofstream d(dat);
        for (const auto& f : r.frames)
            if (f.scored) {
                d << f.frame << ' ' << f.c.recall() << ' ' << f.c.precision() << '\n';
                values.insert(values.end(), {f.c.recall(), f.c.precision()});
                frames.push_back(f.frame);
            }
    }
    // framed on the data: the rates' extent with a margin (not below 0; a margin above 1 keeps
    // rates of 1 off the frame), the frames' extent
    const std::string axes = "set yrange " + util::axis_range(values, 0.08, 0.0, 1e300, 0.01).gnuplot() +
                             "\nset xrange " + util::axis_range(frames, 0.02, -1e300, 1e300, 1.0).gnuplot() + "\n";
    const fs::path gp = out / fmt::format(".plot.{}.gp", ::getpid());
    {
        std::ofstream g(gp);
        g << "set terminal pngcairo size 1000,400\n" << "set output '" << png_tmp.string() << "'\n"
          << "set title 'recall and precision per frame (" << r.source << " vs OpenCV)'\n"
          << "set xlabel 'frame in stream (L0 R0 L1 R1 ...)'\n" << axes << "set key outside right\nset grid\n"
          << "plot '" << dat.string() << "' using 1:2 with linespoints title 'recall', '' using 1:3 with linespoints title 'precision'\n";
    }
    const int rc = gnuplot(gp);
    fs::remove(dat);
    fs::remove(gp);
    if (rc != 0 || !fs::exists(png_tmp)) {
        // pngcairo may be absent from gnuplot-nox builds: fall back to the plain png terminal
        std::ofstream g(gp);
        g << "set terminal png size 1000,400\nset output '" << png_tmp.string() << "'\n"
          << "set title 'recall and precision per frame'\n" << axes << "set key outside right\nset grid\n"
          << "plot '-' using 1:2 with linespoints title 'recall', '-' using 1:2 with linespoints title 'precision'\n";
        for (int k = 0; k < 2; ++k) {
            for (const auto& f : r.frames)
                if (f.scored) g << f.frame << ' ' << (k == 0 ? f.c.recall() : f.c.precision()) << '\n';
            g << "e\n";
        }
        g.close();
        const int rc2 = gnuplot(gp);
        fs::remove(gp);
        fs::remove(log);
        if (rc2 != 0 || !fs::exists(png_tmp)) {
            std::fprintf(stderr, "harris-cosim eval: warning: gnuplot missing or failed, recall_precision.png not drawn\n");
            fs::remove(png_tmp);
            return false;
        }
    }
    fs::remove(log);
    fs::rename(png_tmp, out / "recall_precision.png");
    return true;
}

}  // namespace hc::eval

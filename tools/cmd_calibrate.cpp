// cmd_calibrate.cpp: `harris-cosim calibrate`, stereo calibration of a user's rig from
// chessboard pairs (thesis 4.3) into a KITTI-style calib.txt, the OpenCV YAML/JSON with the
// distortion model and Q, per-view errors (CSV) and a Markdown report. The work is in
// slam/landmarks/calib.hpp; docs/calibration.md describes the files.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/landmarks/calib.hpp"
#include "tools/commands.hpp"
#include "io/frames/frames.hpp"
#include "model/harris/formats_json.hpp"
#include "io/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct CalibrateOptions {
    std::vector<std::string> left, right;
    std::string board = "9x6", out = "calib";
    double square = 1.0, alpha = 0;
    int min_pairs = 5, subpix_window = 0;
    bool fix_intrinsic = false;
};

void run_calibrate(const CalibrateOptions& o) {
    try {
        const calib::Board board = calib::parse_board(o.board, o.square);
        if (o.min_pairs < 1) throw InputError(fmt::format("--min-pairs {}: must be >= 1", o.min_pairs));
        if (o.alpha != -1 && (o.alpha < 0 || o.alpha > 1))
            throw InputError(fmt::format("--alpha {}: must be -1 or within [0, 1]", o.alpha));
        const auto left = calib::expand_image_list(o.left, "--left");
        const auto right = calib::expand_image_list(o.right, "--right");
        const auto d = calib::detect_boards(left, right, board, calib::DetectOptions{o.min_pairs, o.subpix_window},
                                            [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); });
        calib::CalibOptions opt;
        opt.alpha = o.alpha;
        opt.refine_intrinsics = !o.fix_intrinsic;
        const auto c = calib::calibrate(d, board, opt);
        const auto check = calib::check_rectification(c, d);
        if (check.mean_abs_dy > calib::kUsableMeanDy)
            std::fprintf(stderr, "warning: rectified rows differ by %.2f px on average: this calibration is not "
                                 "usable (see report.md)\n", check.mean_abs_dy);

        const fs::path out(o.out);
        fs::create_directories(out);
        util::write_file_atomic(out / "calib.txt", calib::to_kitti_calib(c));
        util::write_file_atomic(out / "calib.yml", calib::to_opencv_storage(c, false));
        util::write_file_atomic(out / "calib.json", calib::to_opencv_storage(c, true));
        std::string csv = "pair,left_rms_px,right_rms_px\n";
        for (size_t i = 0; i < c.per_view_errors.size(); ++i)
            csv += fmt::format("\"{}\",{:.6f},{:.6f}\n", c.view_names[i], c.per_view_errors[i][0],
                               c.per_view_errors[i][1]);
        util::write_file_atomic(out / "views.csv", csv);
        // The picture shows the view with the largest reprojection error, where a bad
        // calibration would show first.
        size_t worst = 0;
        for (size_t i = 1; i < c.per_view_errors.size(); ++i)
            if (std::max(c.per_view_errors[i][0], c.per_view_errors[i][1]) >
                std::max(c.per_view_errors[worst][0], c.per_view_errors[worst][1]))
                worst = i;
        const auto& wv = d.views[worst];
        std::vector<uchar> png;
        cv::imencode(".png",
                     calib::rectified_pair_figure(c, cv::imread(wv.left_file.string(), cv::IMREAD_GRAYSCALE),
                                                  cv::imread(wv.right_file.string(), cv::IMREAD_GRAYSCALE), wv),
                     png);
        util::write_file_atomic(out / "rectified.png", std::string(png.begin(), png.end()));
        util::write_file_atomic(out / "report.md", calib::report_markdown(c, d, board, check, "rectified.png", wv.name));
        std::printf("%zu pairs used, %zu skipped; RMS %.4f px; left fx %.3f fy %.3f cx %.3f cy %.3f; "
                    "baseline %.6g; rectified mean |y_l - y_r| %.4f px\n",
                    d.views.size(), d.skipped.size(), c.rms, c.K1.at<double>(0, 0), c.K1.at<double>(1, 1),
                    c.K1.at<double>(0, 2), c.K1.at<double>(1, 2), c.rectified.baseline(), check.mean_abs_dy);
        std::printf("wrote %s/{calib.txt, calib.yml, calib.json, views.csv, rectified.png, report.md}\n",
                    out.string().c_str());
    } catch (const calib::InputError& e) {
        throw InputError(e.what());
    }
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
    const auto [cmd, o] = add_command<CalibrateOptions>(app,
        "calibrate", "stereo calibration from chessboard pairs (thesis 4.3): KITTI calib.txt, YAML/JSON with "
                     "distortion and Q, report");
    cmd->add_option("--left", o->left, "left images: files or quoted glob patterns, paired in sorted order")
        ->required();
    cmd->add_option("--right", o->right, "right images: files or quoted glob patterns")->required();
    cmd->add_option("--board", o->board, "inner corners per row x per column")->capture_default_str();
    cmd->add_option("--square", o->square, "side of a square (unit of T and of the baseline)")
        ->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--min-pairs", o->min_pairs, "fewest pairs with the board in both images")
        ->capture_default_str();
    cmd->add_option("--subpix-window", o->subpix_window,
                    "cornerSubPix half window, px (0: a third of the corner spacing, within 2..11)")
        ->capture_default_str();
    cmd->add_option("--alpha", o->alpha, "stereoRectify scaling: 0 valid pixels only, 1 all pixels, -1 OpenCV's")
        ->capture_default_str();
    cmd->add_flag("--fix-intrinsic", o->fix_intrinsic,
                  "keep each camera's own intrinsics in the stereo optimisation");
    cmd->callback([o] { run_calibrate(*o); });
}

}  // namespace hc::tools

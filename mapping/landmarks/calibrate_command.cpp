// calibrate_command.cpp: see calibrate_command.hpp.
#include "mapping/landmarks/calibrate_command.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "io/frames/frames.hpp"
#include "mapping/landmarks/calib.hpp"

namespace fs = std::filesystem;

namespace hc::landmarks {

namespace {

/// The view with the largest reprojection error, where a bad calibration would show first.
size_t worst_view(const Calibration& c) {
    size_t worst = 0;
    for (size_t i = 1; i < c.per_view_errors.size(); ++i)
        if (std::max(c.per_view_errors[i][0], c.per_view_errors[i][1]) >
            std::max(c.per_view_errors[worst][0], c.per_view_errors[worst][1]))
            worst = i;
    return worst;
}

void write_files(const fs::path& out, const Calibration& c, const Detection& d, const Board& board,
                 const RectificationCheck& check) {
    fs::create_directories(out);
    util::write_file_atomic(out / "calib.txt", to_kitti_calib(c));
    util::write_file_atomic(out / "calib.yml", to_opencv_storage(c, false));
    util::write_file_atomic(out / "calib.json", to_opencv_storage(c, true));
    std::string csv = "pair,left_rms_px,right_rms_px\n";
    for (size_t i = 0; i < c.per_view_errors.size(); ++i)
        csv += fmt::format("\"{}\",{:.6f},{:.6f}\n", c.view_names[i], c.per_view_errors[i][0], c.per_view_errors[i][1]);
    util::write_file_atomic(out / "views.csv", csv);
    const auto& wv = d.views[worst_view(c)];
    std::vector<uchar> png;
    cv::imencode(".png",
                 rectified_pair_figure(c, cv::imread(wv.left_file.string(), cv::IMREAD_GRAYSCALE),
                                       cv::imread(wv.right_file.string(), cv::IMREAD_GRAYSCALE), wv),
                 png);
    util::write_file_atomic(out / "rectified.png", std::string(png.begin(), png.end()));
    util::write_file_atomic(out / "report.md", report_markdown(c, d, board, check, "rectified.png", wv.name));
}

}  // namespace

void run_calibrate_command(const CalibrateCommand& o) {
    const Board board = parse_board(o.board, o.square);
    if (o.min_pairs < 1) throw InputError(fmt::format("--min-pairs {}: must be >= 1", o.min_pairs));
    if (o.alpha != -1 && (o.alpha < 0 || o.alpha > 1))
        throw InputError(fmt::format("--alpha {}: must be -1 or within [0, 1]", o.alpha));
    const auto left = frames::expand_image_list(o.left, "--left");
    const auto right = frames::expand_image_list(o.right, "--right");
    const auto d = detect_boards(left, right, board, DetectOptions{o.min_pairs, o.subpix_window},
                                 [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); });
    CalibOptions opt;
    opt.alpha = o.alpha;
    opt.refine_intrinsics = !o.fix_intrinsic;
    const auto c = calibrate(d, board, opt);
    const auto check = check_rectification(c, d);
    if (check.mean_abs_dy > kUsableMeanDy)
        std::fprintf(stderr, "warning: rectified rows differ by %.2f px on average: this calibration is not "
                             "usable (see report.md)\n", check.mean_abs_dy);
    write_files(o.out, c, d, board, check);
    std::printf("%zu pairs used, %zu skipped; RMS %.4f px; left fx %.3f fy %.3f cx %.3f cy %.3f; "
                "baseline %.6g; rectified mean |y_l - y_r| %.4f px\n",
                d.views.size(), d.skipped.size(), c.rms, c.K1.at<double>(0, 0), c.K1.at<double>(1, 1),
                c.K1.at<double>(0, 2), c.K1.at<double>(1, 2), c.rectified.baseline(), check.mean_abs_dy);
    std::printf("wrote %s/{calib.txt, calib.yml, calib.json, views.csv, rectified.png, report.md}\n", o.out.c_str());
}

}  // namespace hc::landmarks

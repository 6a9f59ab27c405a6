// calib.cpp: chessboard detection over stereo pairs, stereo calibration and rectification
// through OpenCV's calib3d, the calibration files, and the rectification of keypoints.
#include "mapping/landmarks/calib.hpp"

#include <fmt/format.h>
#include <glob.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace hc::landmarks {

namespace fs = std::filesystem;

Board parse_board(const std::string& spec, double square) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    std::istringstream in(spec);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w < 2 || h < 2 ||
        w > 100 || h > 100)
        throw InputError(fmt::format("--board '{}': expected WxH inner corners, each 2..100 "
                                     "(for example 9x6)", spec));
    if (!(square > 0) || !std::isfinite(square))
        throw InputError(fmt::format("--square {}: the side of a square must be > 0", square));
    return Board{cv::Size(w, h), square};
}

std::vector<cv::Point2f> find_board(const cv::Mat& grey, const Board& board, int subpix_half,
                                    int* used_half) {
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCorners(grey, board.inner, corners,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
        return {};
    // Sub-pixel refinement (stop after 30 steps or a move < 0.01 px). The window's half side
    // is subpix_half, else a third of the smallest spacing s of adjacent corners, so that a
    // window of side 2s/3 stays well inside the four squares meeting at the corner even where
    // perspective shortens them; the samples' fixed 11 px measured worse on their own boards
    // (docs/calibration.md).
    float spacing = std::numeric_limits<float>::max();
    const int w = board.inner.width;
    for (int i = 0; i < board.inner.height; ++i)
        for (int j = 0; j < w; ++j) {
            const auto k = static_cast<size_t>(i * w + j);
            if (j + 1 < w) spacing = std::min(spacing, static_cast<float>(cv::norm(corners[k + 1] - corners[k])));
            if (i + 1 < board.inner.height)
                spacing = std::min(spacing, static_cast<float>(cv::norm(corners[k + static_cast<size_t>(w)] - corners[k])));
        }
    const int half = subpix_half > 0 ? subpix_half : std::clamp(static_cast<int>(spacing / 3), 2, 11);
    if (used_half) *used_half = half;
    cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
    return corners;
}

namespace {

cv::Mat read_grey(const fs::path& p) {
    if (!fs::is_regular_file(p)) throw InputError(fmt::format("no such image file '{}'", p.string()));
    cv::Mat img = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
    if (img.empty()) throw InputError(fmt::format("cannot read image '{}'", p.string()));
    return img;
}

// findChessboardCorners may start a board at either end; a pair whose two images disagree
// would pair each corner with its point reflection. When the first-to-last corner directions
// of the two images point opposite ways, the right image's order is reversed.
void align_order(const std::vector<cv::Point2f>& l, std::vector<cv::Point2f>& r) {
    const cv::Point2f dl = l.back() - l.front(), dr = r.back() - r.front();
    if (dl.dot(dr) < 0) std::reverse(r.begin(), r.end());
}

}  // namespace

Detection detect_boards(const std::vector<fs::path>& left, const std::vector<fs::path>& right,
                        const Board& board, const DetectOptions& opt, const Progress& progress) {
    if (left.size() != right.size())
        throw InputError(fmt::format("{} left images but {} right images: stereo pairs are "
                                     "taken in order and must be as many", left.size(), right.size()));
    if (opt.min_views < 0) throw InputError(fmt::format("minimum number of pairs {} is negative", opt.min_views));
    if (opt.subpix_half < 0 || opt.subpix_half > 50)
        throw InputError(fmt::format("sub-pixel half window {} px: must be within 0..50 (0: per image)",
                                     opt.subpix_half));
    Detection d;
    for (size_t i = 0; i < left.size(); ++i) {
        const std::string name = left[i].filename().string() + " + " + right[i].filename().string();
        const cv::Mat l = read_grey(left[i]);
        const cv::Mat r = read_grey(right[i]);
        if (l.size() != r.size())
            throw InputError(fmt::format("image '{}' is {}x{}, its left partner '{}' is {}x{}", right[i].string(),
                                         r.cols, r.rows, left[i].string(), l.cols, l.rows));
        StereoView v;
        v.name = name;
        v.left_file = left[i];
        v.right_file = right[i];
        v.left = find_board(l, board, opt.subpix_half, &v.window_left);
        v.right = find_board(r, board, opt.subpix_half, &v.window_right);
        std::string missing;
        if (v.left.empty() && v.right.empty()) missing = "both images";
        else if (v.left.empty()) missing = "the left image";
        else if (v.right.empty()) missing = "the right image";
        if (!missing.empty()) {
            d.skipped.push_back(fmt::format("{}: {}x{} board not found in {}", name,
                                            board.inner.width, board.inner.height, missing));
            if (progress) progress("warning: skipping " + d.skipped.back());
            continue;
        }
        // only pairs that are used fix the image size: a skipped pair may be of any size
        if (d.views.empty())
            d.image_size = l.size();
        else if (l.size() != d.image_size)
            throw InputError(fmt::format("image '{}' is {}x{}, the first pair used ({}) is {}x{}", left[i].string(),
                                         l.cols, l.rows, d.views.front().name, d.image_size.width,
                                         d.image_size.height));
        align_order(v.left, v.right);
        d.views.push_back(std::move(v));
        if (progress) progress(fmt::format("pair {}/{}: {}: board found", i + 1, left.size(), name));
    }
    if (static_cast<int>(d.views.size()) < opt.min_views) {
        std::string list;
        for (const auto& s : d.skipped) list += "\n  " + s;
        throw InputError(fmt::format("the {}x{} board was found in both images of {} of {} pairs; "
                                     "at least {} are needed{}",
                                     board.inner.width, board.inner.height, d.views.size(),
                                     left.size(), opt.min_views, list));
    }
    return d;
}

namespace {

std::vector<cv::Point3f> board_points(const Board& b) {
    std::vector<cv::Point3f> pts;
    for (int i = 0; i < b.inner.height; ++i)
        for (int j = 0; j < b.inner.width; ++j)
            pts.emplace_back(static_cast<float>(j * b.square), static_cast<float>(i * b.square), 0.f);
    return pts;
}

// Each camera alone, then the pair, then the rectification (calibrate without the checks).
Calibration calibrate_views(const Detection& d, const std::vector<std::vector<cv::Point3f>>& obj,
                            const std::vector<std::vector<cv::Point2f>>& il,
                            const std::vector<std::vector<cv::Point2f>>& ir, const CalibOptions& opt) {
    Calibration c;
    c.K1 = cv::Mat::eye(3, 3, CV_64F);
    c.K2 = cv::Mat::eye(3, 3, CV_64F);
    c.D1 = cv::Mat::zeros(1, 5, CV_64F);
    c.D2 = cv::Mat::zeros(1, 5, CV_64F);
    // Each camera alone first (Zhang's initialisation needs no stereo), model k1 k2 p1 p2 k3.
    std::vector<cv::Mat> rv, tv;
    cv::Mat sd, sde, pve;
    cv::calibrateCamera(obj, il, d.image_size, c.K1, c.D1, rv, tv, sd, sde, pve);
    c.sigma1 = cv::Vec4d(sd.at<double>(0), sd.at<double>(1), sd.at<double>(2), sd.at<double>(3));
    cv::calibrateCamera(obj, ir, d.image_size, c.K2, c.D2, rv, tv, sd, sde, pve);
    c.sigma2 = cv::Vec4d(sd.at<double>(0), sd.at<double>(1), sd.at<double>(2), sd.at<double>(3));
    cv::Mat E, F, errs;
    const int flags = opt.refine_intrinsics ? cv::CALIB_USE_INTRINSIC_GUESS : cv::CALIB_FIX_INTRINSIC;
    c.rms = cv::stereoCalibrate(obj, il, ir, c.K1, c.D1, c.K2, c.D2, d.image_size, c.R, c.T, E, F,
                                errs, flags,
                                cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-10));
    for (int i = 0; i < errs.rows; ++i) {
        c.per_view_errors.emplace_back(errs.at<double>(i, 0), errs.at<double>(i, 1));
        c.view_names.push_back(d.views[static_cast<size_t>(i)].name);
    }
    cv::Mat P1, P2;
    cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, d.image_size, c.R, c.T, c.R1, c.R2, P1, P2, c.Q,
                      cv::CALIB_ZERO_DISPARITY, opt.alpha);
    if (std::abs(P2.at<double>(1, 3)) > std::abs(P2.at<double>(0, 3)))
        throw InputError("the cameras are stacked vertically: rectified rows would be columns; "
                         "only side-by-side rigs are supported");
    c.rectified = landmarks::rig_from_projections(P1.ptr<double>(), P2.ptr<double>(), d.image_size.width,
                                               d.image_size.height);
    return c;
}

}  // namespace

Calibration calibrate(const Detection& d, const Board& board, const CalibOptions& opt) {
    if (d.views.size() < 3)
        throw InputError(fmt::format("{} stereo pairs show the board; the calibration needs at least 3 "
                                     "(Zhang's method solves a general camera's intrinsics from 3 or more "
                                     "views of the plane)", d.views.size()));
    const std::vector<std::vector<cv::Point3f>> obj(d.views.size(), board_points(board));
    std::vector<std::vector<cv::Point2f>> il, ir;
    for (const auto& v : d.views) {
        il.push_back(v.left);
        ir.push_back(v.right);
    }
    try {
        return calibrate_views(d, obj, il, ir, opt);
    } catch (const cv::Exception& e) {
        throw InputError(fmt::format("the calibration of {} pairs failed (too few or degenerate views?): {}",
                                     d.views.size(), e.what()));
    }
}

std::vector<cv::Point2f> rectify_points(const Calibration& c, Side side,
                                        const std::vector<cv::Point2f>& pts) {
    if (c.rectified_input || pts.empty()) return pts;
    const bool l = side == Side::left;
    std::vector<cv::Point2f> out;
    cv::undistortPoints(pts, out, l ? c.K1 : c.K2, l ? c.D1 : c.D2, l ? c.R1 : c.R2,
                        projection(c.rectified, side),
                        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-10));
    return out;
}

RectificationCheck check_rectification(const Calibration& c, const Detection& d) {
    RectificationCheck r;
    double sum = 0;
    for (const auto& v : d.views) {
        const auto l = rectify_points(c, Side::left, v.left);
        const auto rr = rectify_points(c, Side::right, v.right);
        for (size_t i = 0; i < l.size(); ++i) {
            const double dy = std::abs(static_cast<double>(l[i].y) - rr[i].y);
            sum += dy;
            r.max_abs_dy = std::max(r.max_abs_dy, dy);
            ++r.corners;
        }
    }
    r.mean_abs_dy = r.corners ? sum / static_cast<double>(r.corners) : 0;
    return r;
}

cv::Mat rectified_pair_figure(const Calibration& c, const cv::Mat& left, const cv::Mat& right,
                              const StereoView& view) {
    const cv::Size size = image_size(c);
    if (left.size() != size || right.size() != size)
        throw InputError(fmt::format("images of {}x{} for a calibration of {}x{}", left.cols, left.rows,
                                     size.width, size.height));
    const int W = size.width, H = size.height;
    cv::Mat fig(H, 2 * W, CV_8UC3);
    for (int k = 0; k < 2; ++k) {
        cv::Mat mx, my, rect, bgr;
        cv::initUndistortRectifyMap(k ? c.K2 : c.K1, k ? c.D2 : c.D1, k ? c.R2 : c.R1,
                                    projection(c.rectified, k ? Side::right : Side::left), size, CV_32FC1, mx, my);
        cv::remap(k ? right : left, rect, mx, my, cv::INTER_LINEAR);
        cv::cvtColor(rect, bgr, cv::COLOR_GRAY2BGR);
        bgr.copyTo(fig(cv::Rect(k * W, 0, W, H)));
    }
    for (int y = 0; y < H; y += 20) cv::line(fig, {0, y}, {2 * W - 1, y}, cv::Scalar(255, 160, 0), 1);
    for (const auto& p : rectify_points(c, Side::left, view.left))
        cv::circle(fig, p, 3, cv::Scalar(0, 200, 0), 1, cv::LINE_AA);
    for (const auto& p : rectify_points(c, Side::right, view.right))
        cv::circle(fig, p + cv::Point2f(static_cast<float>(W), 0), 3, cv::Scalar(0, 0, 230), 1, cv::LINE_AA);
    return fig;
}

cv::Mat projection(const landmarks::RectifiedRig& rig, Side side) {
    double P0[12], P1[12];
    rig.projections(P0, P1);
    return cv::Mat(3, 4, CV_64F, side == Side::left ? P0 : P1).clone();
}

cv::Mat disparity_to_depth(const landmarks::RectifiedRig& rig) {
    // stereoRectify's Q for a horizontal rig: Tx = tx1 / f is the right camera's offset
    // (negative); W = (d + cx2 - cx1) / (-Tx), so Z = f / W = f b / d when cx1 = cx2.
    const double f = rig.fx, cx1 = rig.cx0, cy = rig.cy;
    const double cx2 = rig.cx1, tx = rig.tx1 / rig.fx;
    cv::Mat Q = cv::Mat::zeros(4, 4, CV_64F);
    Q.at<double>(0, 0) = 1;
    Q.at<double>(0, 3) = -cx1;
    Q.at<double>(1, 1) = 1;
    Q.at<double>(1, 3) = -cy;
    Q.at<double>(2, 3) = f;
    Q.at<double>(3, 2) = -1 / tx;
    Q.at<double>(3, 3) = (cx1 - cx2) / tx;
    return Q;
}

// ---- KITTI calib.txt --------------------------------------------------------------------

namespace {

std::string shortest(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
    return std::string(buf, r.ptr);
}

std::string kitti_row(const char* key, const double P[12]) {
    std::string s = key;
    s += ':';
    for (int i = 0; i < 12; ++i) s += ' ' + shortest(P[i]);
    return s + '\n';
}

}  // namespace

std::string to_kitti_calib(const Calibration& c) {
    double P0[12], P1[12];
    c.rectified.projections(P0, P1);
    return kitti_row("P0", P0) + kitti_row("P1", P1);
}

Calibration parse_kitti_calib(const std::string& text, const std::string& name) {
    std::map<std::string, cv::Mat> rows;
    std::istringstream in(text);
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        const auto colon = line.find(':');
        if (colon == std::string::npos) continue;   // blank or foreign lines: not a row
        const std::string key = line.substr(0, colon);
        if (key != "P0" && key != "P1") continue;   // P2, P3, Tr, ...: not needed here
        if (rows.count(key))
            throw InputError(fmt::format("{}:{}: row {} appears twice", name, lineno, key));
        cv::Mat P(3, 4, CV_64F);
        const char* p = line.data() + colon + 1;
        const char* end = line.data() + line.size();
        int n = 0;
        for (;; ++n) {
            while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
            if (p == end) break;
            double v = 0;
            const auto r = std::from_chars(p, end, v);
            if (r.ec != std::errc() || n >= 12 || !std::isfinite(v))
                throw InputError(fmt::format("{}:{}: row {} must hold 12 finite numbers", name,
                                             lineno, key));
            P.at<double>(n / 4, n % 4) = v;
            p = r.ptr;
        }
        if (n != 12)
            throw InputError(fmt::format("{}:{}: row {} holds {} numbers, expected 12", name,
                                         lineno, key, n));
        rows[key] = P;
    }
    for (const char* k : {"P0", "P1"})
        if (!rows.count(k)) throw InputError(fmt::format("{}: no row {}", name, k));
    const cv::Mat P0 = rows["P0"], P1 = rows["P1"];
    if (!(P0.at<double>(0, 0) > 0) || !(P1.at<double>(0, 0) > 0))
        throw InputError(fmt::format("{}: P0 and P1 need a positive focal length", name));
    if (P1.at<double>(0, 3) == 0)
        throw InputError(fmt::format("{}: P1 has no baseline (P1[3] = 0)", name));
    Calibration c;
    try {
        c.rectified = landmarks::rig_from_projections(P0.ptr<double>(), P1.ptr<double>());
    } catch (const hc::InputError& e) {
        throw InputError(fmt::format("{}: {}", name, e.what()));
    }
    c.K1 = P0(cv::Rect(0, 0, 3, 3)).clone();
    c.K2 = P1(cv::Rect(0, 0, 3, 3)).clone();
    c.D1 = cv::Mat::zeros(1, 5, CV_64F);
    c.D2 = cv::Mat::zeros(1, 5, CV_64F);
    c.R = cv::Mat::eye(3, 3, CV_64F);
    c.R1 = cv::Mat::eye(3, 3, CV_64F);
    c.R2 = cv::Mat::eye(3, 3, CV_64F);
    c.T = (cv::Mat_<double>(3, 1) << c.rectified.tx1 / c.rectified.fx - c.rectified.tx0 / c.rectified.fx, 0, 0);
    c.Q = disparity_to_depth(c.rectified);
    c.rectified_input = true;
    return c;
}

Calibration read_kitti_calib(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    if (!f) throw InputError(fmt::format("cannot read calibration file '{}'", p.string()));
    std::ostringstream s;
    s << f.rdbuf();
    return parse_kitti_calib(s.str(), p.string());
}

// ---- OpenCV FileStorage -----------------------------------------------------------------

namespace {
constexpr const char* kDistortionModel = "opencv k1 k2 p1 p2 k3";
}

std::string to_opencv_storage(const Calibration& c, bool json) {
    cv::FileStorage fs(json ? ".json" : ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    fs << "image_width" << c.rectified.width << "image_height" << c.rectified.height;
    fs << "distortion_model" << kDistortionModel;
    fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2;
    fs << "R" << c.R << "T" << c.T << "R1" << c.R1 << "R2" << c.R2;
    fs << "P1" << projection(c.rectified, Side::left) << "P2" << projection(c.rectified, Side::right) << "Q" << c.Q;
    fs << "rms" << c.rms;
    cv::Mat errs(static_cast<int>(c.per_view_errors.size()), 2, CV_64F);
    for (int i = 0; i < errs.rows; ++i)
        for (int j = 0; j < 2; ++j) errs.at<double>(i, j) = c.per_view_errors[static_cast<size_t>(i)][j];
    fs << "per_view_errors" << errs;
    fs << "view_names" << "[";
    for (const auto& n : c.view_names) fs << n;
    fs << "]";
    fs << "sigma1" << cv::Mat(c.sigma1).reshape(1, 1) << "sigma2" << cv::Mat(c.sigma2).reshape(1, 1);
    fs << "rectified_input" << (c.rectified_input ? 1 : 0);
    return fs.releaseAndGetString();
}

Calibration read_opencv_storage(const fs::path& p) {
    if (!fs::is_regular_file(p))
        throw InputError(fmt::format("no such calibration file '{}'", p.string()));
    Calibration c;
    try {
        cv::FileStorage f(p.string(), cv::FileStorage::READ);
        if (!f.isOpened()) throw InputError(fmt::format("cannot read calibration file '{}'", p.string()));
        auto node = [&](const char* key) {
            cv::FileNode n = f[key];
            if (n.empty()) throw InputError(fmt::format("{}: no key '{}'", p.string(), key));
            return n;
        };
        auto mat = [&](const char* key, int rows, int cols) {
            cv::Mat m;
            node(key) >> m;
            if (m.rows != rows || m.cols != cols || m.type() != CV_64F)
                throw InputError(fmt::format("{}: '{}' is not a {}x{} matrix of doubles",
                                             p.string(), key, rows, cols));
            return m;
        };
        if (static_cast<std::string>(node("distortion_model")) != kDistortionModel)
            throw InputError(fmt::format("{}: distortion_model is not '{}'", p.string(), kDistortionModel));
        const int width = static_cast<int>(node("image_width")), height = static_cast<int>(node("image_height"));
        c.K1 = mat("K1", 3, 3);
        c.D1 = mat("D1", 1, 5);
        c.K2 = mat("K2", 3, 3);
        c.D2 = mat("D2", 1, 5);
        c.R = mat("R", 3, 3);
        c.T = mat("T", 3, 1);
        c.R1 = mat("R1", 3, 3);
        c.R2 = mat("R2", 3, 3);
        const cv::Mat P1 = mat("P1", 3, 4), P2 = mat("P2", 3, 4);
        try {
            c.rectified = landmarks::rig_from_projections(P1.ptr<double>(), P2.ptr<double>(), width, height);
        } catch (const hc::InputError& e) {
            throw InputError(fmt::format("{}: {}", p.string(), e.what()));
        }
        c.Q = mat("Q", 4, 4);
        c.rms = static_cast<double>(node("rms"));
        cv::Mat errs;
        node("per_view_errors") >> errs;
        for (int i = 0; i < errs.rows; ++i)
            c.per_view_errors.emplace_back(errs.at<double>(i, 0), errs.at<double>(i, 1));
        for (const auto& n : node("view_names")) c.view_names.push_back(static_cast<std::string>(n));
        const cv::Mat s1 = mat("sigma1", 1, 4), s2 = mat("sigma2", 1, 4);
        for (int i = 0; i < 4; ++i) {
            c.sigma1[i] = s1.at<double>(i);
            c.sigma2[i] = s2.at<double>(i);
        }
        c.rectified_input = static_cast<int>(node("rectified_input")) != 0;
    } catch (const cv::Exception& e) {
        throw InputError(fmt::format("cannot parse calibration file '{}': {}", p.string(), e.what()));
    }
    return c;
}

// ---- report -----------------------------------------------------------------------------

namespace {

std::string mat_md(const cv::Mat& m) {
    std::string s = "|";
    for (int j = 0; j < m.cols; ++j) s += fmt::format(" {} |", j);
    s += "\n|";
    for (int j = 0; j < m.cols; ++j) s += "---:|";
    s += "\n";
    for (int i = 0; i < m.rows; ++i) {
        s += "|";
        for (int j = 0; j < m.cols; ++j) s += fmt::format(" {:.6g} |", m.at<double>(i, j) + 0.0);   // -0 -> 0
        s += "\n";
    }
    return s;
}

}  // namespace

std::string report_markdown(const Calibration& c, const Detection& d, const Board& board,
                            const RectificationCheck& check, const std::string& figure,
                            const std::string& figure_view) {
    std::string s = "# Stereo calibration\n\n";
    s += fmt::format("Board {}x{} inner corners, square {}; images {}x{}; {} pairs used, {} skipped.\n\n",
                     board.inner.width, board.inner.height, board.square, c.rectified.width,
                     c.rectified.height, d.views.size(), d.skipped.size());
    s += fmt::format("- stereo reprojection RMS: **{:.4f} px** (cv::stereoCalibrate, both images of every pair)\n",
                     c.rms);
    s += fmt::format("- rectified focal length: {:.3f} px; baseline: {:.6g} (unit of the square)\n",
                     c.rectified.fx, c.rectified.baseline());
    s += fmt::format("- rectification check over {} corner pairs: mean |y_l - y_r| = **{:.4f} px**, "
                     "largest {:.4f} px\n\n", check.corners, check.mean_abs_dy, check.max_abs_dy);
    if (check.mean_abs_dy > kUsableMeanDy)
        s += fmt::format("**Warning: rectified rows differ by {:.2f} px on average (more than {} px): this "
                         "calibration is not usable; take more views, at various angles and distances.**\n\n",
                         check.mean_abs_dy, kUsableMeanDy);
    if (!figure.empty())
        s += fmt::format("![{0} rectified]({1})\n\n{0}, warped for this picture only (the pipeline moves "
                         "keypoints, not pixels): left and right rectified side by side, board corners "
                         "through rectify_points (green left, red right), a line every 20 px.\n\n",
                         figure_view, figure);
    s += "## Per-view reprojection error\n\nRMS per image (px) and the half side of the sub-pixel "
         "window its corners were refined in (px).\n\n| pair | left | right | window left | window right |\n"
         "|---|---:|---:|---:|---:|\n";
    for (size_t i = 0; i < c.per_view_errors.size(); ++i) {
        const StereoView* v = i < d.views.size() && d.views[i].name == c.view_names[i] ? &d.views[i] : nullptr;
        s += fmt::format("| {} | {:.4f} | {:.4f} | {} | {} |\n", c.view_names[i], c.per_view_errors[i][0],
                         c.per_view_errors[i][1], v ? std::to_string(v->window_left) : "-",
                         v ? std::to_string(v->window_right) : "-");
    }
    if (!d.skipped.empty()) {
        s += "\n## Skipped pairs\n\n";
        for (const auto& k : d.skipped) s += "- " + k + "\n";
    }
    s += "\n## Intrinsics\n\nAfter the stereo optimisation; the standard deviations (sd, px) are each camera's own "
         "calibration's (cv::calibrateCamera).\n\n| camera | fx | fy | cx | cy | sd fx | sd fy | sd cx | sd cy | k1 | "
         "k2 | p1 | p2 | k3 |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (int k = 0; k < 2; ++k) {
        const cv::Mat& K = k ? c.K2 : c.K1;
        const cv::Mat& D = k ? c.D2 : c.D1;
        const cv::Vec4d& sd = k ? c.sigma2 : c.sigma1;
        s += fmt::format("| {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f}",
                         k ? "right" : "left", K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2),
                         K.at<double>(1, 2), sd[0], sd[1], sd[2], sd[3]);
        for (int i = 0; i < 5; ++i) s += fmt::format(" | {:.5g}", D.at<double>(0, i));
        s += " |\n";
    }
    s += "\n## Extrinsics (X_r = R X_l + T)\n\nR:\n\n" + mat_md(c.R) + "\nT:\n\n" + mat_md(c.T.t());
    s += "\n## Rectification\n\ncalib.txt P0 (left):\n\n" + mat_md(projection(c.rectified, Side::left)) +
         "\ncalib.txt P1 (right):\n\n" + mat_md(projection(c.rectified, Side::right)) +
         "\nQ (x, y, x_l - x_r, 1 -> X, Y, Z, W):\n\n" + mat_md(c.Q);
    return s;
}

}  // namespace hc::landmarks

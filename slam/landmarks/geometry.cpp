// geometry.cpp: triangulation through a rectified pair's projection matrices (thesis 4.3;
// the formulas are hc::stereo's, slam/landmarks/stereo.hpp), covariance by first-order propagation of
// pixel noise, landmark files and the depth error against ground-truth disparity.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <fmt/format.h>

#include "slam/landmarks/landmarks.hpp"
#include "slam/landmarks/stereo.hpp"

namespace hc::landmarks {

void StereoCalib::validate() const {
    const auto bad = [](const std::string& why) { throw InputError("stereo calibration: " + why); };
    for (const auto* P : {&P0, &P1}) {
        if ((*P)(0, 1) != 0 || (*P)(1, 0) != 0 || (*P)(2, 0) != 0 || (*P)(2, 1) != 0 || (*P)(2, 2) != 1 || (*P)(2, 3) != 0)
            bad("P0 and P1 must be rectified projection matrices [fx 0 cx tx; 0 fy cy ty; 0 0 1 0]");
        if ((*P)(0, 0) <= 0 || (*P)(1, 1) <= 0) bad("focal lengths must be positive");
    }
    if (P0(0, 0) != P1(0, 0) || P0(1, 1) != P1(1, 1) || P0(1, 2) != P1(1, 2) || P0(1, 3) != P1(1, 3))
        bad("P0 and P1 differ in fx, fy, cy or ty: the pair is not rectified");
    if (!(P0(0, 3) - P1(0, 3) > 0)) bad("P1's x translation must put the right camera to the right (P0[0][3] > P1[0][3])");
}

StereoCalib middlebury_calib(double scale, double dmin_full, cv::Size image) {
    // Middlebury 2006: focal length 3740 px, baseline 160 mm at full size; Z = b f / (d + dmin)
    // with d in full-size pixels. At scale s: f s, and the offset dmin s enters as cx1 - cx0.
    const double f = 3740.0 * scale, b = 0.160;
    const double cx = (image.width - 1) / 2.0, cy = (image.height - 1) / 2.0;
    StereoCalib c;
    c.P0 = cv::Matx34d(f, 0, cx, 0, 0, f, cy, 0, 0, 0, 1, 0);
    c.P1 = cv::Matx34d(f, 0, cx + dmin_full * scale, -f * b, 0, f, cy, 0, 0, 0, 1, 0);
    c.validate();
    return c;
}

namespace {

stereo::RectifiedRig rig(const StereoCalib& c) {
    stereo::RectifiedRig r;
    r.fx = c.P0(0, 0);
    r.fy = c.P0(1, 1);
    r.cx0 = c.P0(0, 2);
    r.cx1 = c.P1(0, 2);
    r.cy = c.P0(1, 2);
    r.tx0 = c.P0(0, 3);
    r.tx1 = c.P1(0, 3);
    r.ty = c.P0(1, 3);
    return r;
}

}  // namespace

Triangulated triangulate(const StereoCalib& c, cv::Point2d l, cv::Point2d r, const PixelNoise& n) {
    const stereo::Point3 s = stereo::triangulate(rig(c), l.x, l.y, r.x, r.y);
    Triangulated t;
    if (!s.valid) return t;
    t.p = cv::Vec3d(s.p[0], s.p[1], s.p[2]);
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) t.J(i, k) = s.J[i][k];
    double cov[3][3];
    n.covariance(s, cov);
    t.cov = cv::Matx33d(&cov[0][0]);
    t.valid = true;
    return t;
}

std::string landmarks_csv(const std::vector<Landmark>& ls) {
    std::ostringstream o;
    o << "x,y,z,cov_xx,cov_xy,cov_xz,cov_yy,cov_yz,cov_zz,u_left,v_left,u_right,v_right,match_distance,descriptor_hex\n";
    o << std::setprecision(10);
    for (const auto& l : ls) {
        o << l.p_cam[0] << ',' << l.p_cam[1] << ',' << l.p_cam[2] << ',' << l.cov(0, 0) << ',' << l.cov(0, 1) << ','
          << l.cov(0, 2) << ',' << l.cov(1, 1) << ',' << l.cov(1, 2) << ',' << l.cov(2, 2) << ',' << l.left.x << ','
          << l.left.y << ',' << l.right.x << ',' << l.right.y << ',' << l.match_distance << ',';
        for (std::uint8_t b : l.descriptor) o << fmt::format("{:02x}", b);
        o << '\n';
    }
    return o.str();
}

std::string landmarks_ply(const std::vector<Landmark>& ls) {
    std::ostringstream o;
    o << "ply\nformat ascii 1.0\ncomment harris-cosim landmarks: left rectified camera frame, metres\n"
      << "element vertex " << ls.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property float sigma_z\nend_header\n";
    o << std::setprecision(8);
    for (const auto& l : ls)
        o << l.p_cam[0] << ' ' << l.p_cam[1] << ' ' << l.p_cam[2] << ' ' << std::sqrt(l.cov(2, 2)) << '\n';
    return o.str();
}

namespace {

void collect_depth_errors(const PairResult& r, const cv::Mat& disparity, const StereoCalib& calib, std::vector<double>& e) {
    if (disparity.empty()) return;
    for (const auto& m : r.matches) {
        if (!m.epipolar) continue;
        const int x = static_cast<int>(std::lround(m.left.x)), y = static_cast<int>(std::lround(m.left.y));
        if (x < 0 || y < 0 || x >= disparity.cols || y >= disparity.rows) continue;
        const float d = disparity.at<float>(y, x);
        if (d <= 0) continue;
        const Triangulated est = triangulate(calib, m.left, m.right);
        const Triangulated gt = triangulate(calib, m.left, cv::Point2d(m.left.x - d, m.left.y));
        if (!est.valid || !gt.valid) continue;
        e.push_back(std::abs(est.p[2] - gt.p[2]) / gt.p[2]);
    }
}

DepthError summarise(std::vector<double>& e) {
    DepthError de;
    de.n = static_cast<long>(e.size());
    if (e.empty()) return de;
    std::sort(e.begin(), e.end());
    double s = 0;
    for (double v : e) s += v;
    de.mean = s / static_cast<double>(e.size());
    de.median = e[e.size() / 2];
    de.p90 = e[std::min(e.size() - 1, static_cast<size_t>(0.9 * static_cast<double>(e.size())))];
    return de;
}

}  // namespace

DepthError depth_error(const PairResult& r, const cv::Mat& disparity, const StereoCalib& calib) {
    std::vector<double> e;
    collect_depth_errors(r, disparity, calib, e);
    return summarise(e);
}

DepthError depth_error(const ComparisonRow& row, const Dataset& ds) {
    std::vector<double> e;
    for (size_t k = 0; k < row.pairs.size() && k < ds.pairs.size(); ++k)
        if (k < ds.disparity.size() && k < ds.calib.size()) collect_depth_errors(row.pairs[k], ds.disparity[k], ds.calib[k], e);
    return summarise(e);
}

}  // namespace hc::landmarks

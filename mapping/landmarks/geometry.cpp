// geometry.cpp: the Middlebury rig, landmark files and the depth error against ground-truth
// disparity (triangulation and covariance: landmarks::triangulate, mapping/landmarks/stereo.hpp).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <fmt/format.h>

#include "mapping/landmarks/geometry.hpp"
#include "mapping/landmarks/pipeline.hpp"
#include "mapping/landmarks/stereo.hpp"

namespace hc::landmarks {

landmarks::RectifiedRig middlebury_calib(double scale, double dmin_full, cv::Size image) {
    // Middlebury 2006: focal length 3740 px, baseline 160 mm at full size; Z = b f / (d + dmin)
    // with d in full-size pixels. At scale s: f s, and the offset dmin s enters as cx1 - cx0.
    const double f = 3740.0 * scale, b = 0.160;
    const double cx = (image.width - 1) / 2.0, cy = (image.height - 1) / 2.0;
    landmarks::RectifiedRig c;
    c.fx = c.fy = f;
    c.cx0 = cx;
    c.cx1 = cx + dmin_full * scale;
    c.cy = cy;
    c.tx1 = -f * b;
    c.width = image.width;
    c.height = image.height;
    c.validate();
    return c;
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

void collect_depth_errors(const PairResult& r, const cv::Mat& disparity, const landmarks::RectifiedRig& calib,
                          std::vector<double>& e) {
    if (disparity.empty()) return;
    for (const auto& m : r.matches) {
        if (!m.epipolar) continue;
        const int x = static_cast<int>(std::lround(m.left.x)), y = static_cast<int>(std::lround(m.left.y));
        if (x < 0 || y < 0 || x >= disparity.cols || y >= disparity.rows) continue;
        const float d = disparity.at<float>(y, x);
        if (d <= 0) continue;
        const landmarks::Point3 est = landmarks::triangulate(calib, pixels(m.left, m.right));
        const landmarks::Point3 gt = landmarks::triangulate(calib, pixels(m.left, cv::Point2f(m.left.x - d, m.left.y)));
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

DepthError depth_error(const PairResult& r, const cv::Mat& disparity, const landmarks::RectifiedRig& calib) {
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

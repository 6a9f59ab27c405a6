// opencv_reference.cpp: see opencv_reference.hpp and docs/metrics.md.
#include "model/spec/opencv_reference.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace hc::spec {

double hw_to_opencv_response_scale(const Formats& f) {
    const double sobel_scale = 1.0 / ((1 << (3 - 1)) * 3 * 255.0);   // OpenCV: 1/3060
    const double m_units = std::ldexp(1.0, f.m_drop + f.bf_drop);    // hw: floor(/2^m_drop), floor(/2^bf_drop)
    const double a_scale = m_units * sobel_scale * sobel_scale;       // A_cv per unit of A_hw
    return a_scale * a_scale;                                         // R is quadratic in A
}

void opencv_response(const Image& img, const ReferenceOptions& o, cv::Mat& out) {
    const cv::Mat src(img.height, img.width, CV_8UC1, const_cast<std::uint8_t*>(img.pixels.data()));
    cv::cornerHarris(src, out, o.block_size, o.ksize, o.k, cv::BORDER_DEFAULT);
}

double opencv_corners(const Image& img, const ReferenceOptions& o, std::vector<std::uint8_t>& mask) {
    cv::Mat r;
    opencv_response(img, o, r);
    double mx = 0;
    cv::minMaxLoc(r, nullptr, &mx);
    const float thr = static_cast<float>(o.rel_threshold * mx);
    const int W = img.width, H = img.height;
    mask.assign(static_cast<size_t>(W) * H, 0);
    if (!o.strict) {
        cv::Mat d;
        cv::dilate(r, d, cv::Mat());   // 3x3, default border: outside pixels never win
        for (int y = 0; y < H; ++y) {
            const float* rr = r.ptr<float>(y);
            const float* dd = d.ptr<float>(y);
            std::uint8_t* m = mask.data() + static_cast<size_t>(y) * W;
            for (int x = 0; x < W; ++x) m[x] = rr[x] > thr && rr[x] == dd[x];
        }
        return mx;
    }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float c = r.at<float>(y, x);
            if (!(c > thr)) continue;
            bool corner = true;
            for (int dy = -1; dy <= 1 && corner; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int yy = y + dy, xx = x + dx;
                    if ((dx || dy) && yy >= 0 && xx >= 0 && yy < H && xx < W && !(c > r.at<float>(yy, xx))) {
                        corner = false;
                        break;
                    }
                }
            mask[static_cast<size_t>(y) * W + x] = corner;
        }
    return mx;
}

}  // namespace hc::spec

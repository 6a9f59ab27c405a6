// opencv_reference.hpp: the reference detector the co-processor is measured against
// (docs/metrics.md, "OpenCV reference"): OpenCV's Harris response, a threshold relative to
// the current frame's maximum, and 3x3 non-maximum suppression.
//
//   R     = cv::cornerHarris(img, blockSize 3, ksize 3, k 0.04, BORDER_DEFAULT) (CV_32F)
//   thr   = 0.01 * max(R over the frame)
//   corner(x,y) = R(x,y) > thr  and  R(x,y) == dilate(R, 3x3)(x,y)       (non-strict, default)
//              or R(x,y) > thr  and  R(x,y) >  all 8 neighbours in the image (strict)
#pragma once

#include <cstdint>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace cv { class Mat; }

namespace hc::spec {

struct ReferenceOptions {
    int block_size = 3;
    int ksize = 3;
    double k = 0.04;
    double rel_threshold = 0.01;
    bool strict = false;   ///< strict NMS instead of R == dilate(R)
};

/// The scale from the hardware's integer response (formats f, k aside) to OpenCV's float
/// response: OpenCV divides the Sobel output by 2^(ksize-1)*blockSize*255 = 3060
/// (cornerEigenValsVecs) and sums M unnormalised; the hardware keeps ix in units of the
/// Sobel kernel and divides M by 2^m_drop and the block sum by 2^bf_drop, so with
/// u = 2^(m_drop + bf_drop) (thesis: 512)
///   A_cv = A_hw * u / 3060^2   and   R_cv = R_hw * (u / 3060^2)^2 (up to the floors).
double hw_to_opencv_response_scale(const Formats& f = {});

/// OpenCV's Harris response of an 8-bit image (CV_32F, same size).
void opencv_response(const Image& img, const ReferenceOptions& o, cv::Mat& out);

/// The reference corner mask (row-major, 1 = corner). Returns the frame's maximum.
double opencv_corners(const Image& img, const ReferenceOptions& o, std::vector<std::uint8_t>& mask);

}  // namespace hc::spec

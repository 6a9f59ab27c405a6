// The stereo pair that the features data test and benchmark measure on: KITTI sequence 01
// pair 0 from the data directory, else opencv-doc's aloeL/aloeR, with the strongest Harris
// corners (cv::goodFeaturesToTrack, Harris score k = 0.04, 3 x 3 blocks, at least 3 px
// apart) of each image as keypoints.
#pragma once

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/frames/frames.hpp"

namespace hc::features_test {

struct StereoSample {
    std::string name;  ///< "KITTI 01 pair 0" or "aloe"
    cv::Mat left, right;
    std::vector<cv::KeyPoint> kp_l, kp_r;
};

/// The `count` strongest Harris corners at least `border` pixels inside the image.
inline std::vector<cv::KeyPoint> strongest_harris(const cv::Mat& grey, int count, int border) {
    std::vector<cv::Point2f> pts;
    cv::Mat mask = cv::Mat::zeros(grey.size(), CV_8U);
    mask(cv::Rect(border, border, grey.cols - 2 * border, grey.rows - 2 * border)).setTo(255);
    cv::goodFeaturesToTrack(grey, pts, count, 1e-4, 3, mask, 3, true, 0.04);
    std::vector<cv::KeyPoint> k;
    for (const auto& p : pts) k.emplace_back(p, 7.f);
    return k;
}

/// The KITTI pair when the data directory has it, else aloe (HC_OPENCV_SAMPLES_DIR), else
/// nothing. `corners` keypoints per image, at least `border` pixels inside it.
inline std::optional<StereoSample> load_stereo_sample(int corners, int border = 0) {
    namespace fs = std::filesystem;
    StereoSample s;
    const auto data = frames::data_dir("");
    const fs::path kitti = data ? *data / "kitti/sequences/01" : fs::path();
    if (data && fs::exists(kitti / "image_0/000000.png") && fs::exists(kitti / "image_1/000000.png")) {
        s.name = "KITTI 01 pair 0";
        s.left = cv::imread((kitti / "image_0/000000.png").string(), cv::IMREAD_GRAYSCALE);
        s.right = cv::imread((kitti / "image_1/000000.png").string(), cv::IMREAD_GRAYSCALE);
    } else {
#ifdef HC_OPENCV_SAMPLES_DIR
        const fs::path dir = HC_OPENCV_SAMPLES_DIR;
        s.name = "aloe";
        s.left = cv::imread((dir / "aloeL.jpg").string(), cv::IMREAD_GRAYSCALE);
        s.right = cv::imread((dir / "aloeR.jpg").string(), cv::IMREAD_GRAYSCALE);
#endif
    }
    if (s.left.empty() || s.right.empty()) return std::nullopt;
    s.kp_l = strongest_harris(s.left, corners, border);
    s.kp_r = strongest_harris(s.right, corners, border);
    return s;
}

}  // namespace hc::landmarks_test

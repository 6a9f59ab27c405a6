// calib_doc_test.cpp: calibration of OpenCV's sample stereo rig from its chessboard pairs
// left01..14.jpg, right01..14.jpg (13 pairs: there is no 10), checked against the sample's
// own single-camera result left_intrinsics.yml. The directory is HC_OPENCV_SAMPLES (found by
// CMake in Debian's opencv-doc) or $HARRIS_COSIM_OPENCV_SAMPLES; without it the test exits 77
// (CTest: skipped) with a message.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <opencv2/calib3d.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "mapping/landmarks/calib.hpp"

using namespace hc::landmarks;
namespace fs = std::filesystem;

namespace {

fs::path g_dir;

// The 9x6 board of the samples, 25 mm squares (left_intrinsics.yml's square_size): T and
// the baseline come out in metres.
const Board kBoard{cv::Size(9, 6), 0.025};

std::vector<fs::path> sample_images(const char* side) {
    std::vector<fs::path> v;
    for (int i = 1; i <= 14; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "%s%02d.jpg", side, i);
        if (fs::exists(g_dir / name)) v.push_back(g_dir / name);   // the samples have no 10
    }
    return v;
}

const Detection& detection(int subpix_half = 0) {
    static std::map<int, Detection> cache;
    auto it = cache.find(subpix_half);
    if (it == cache.end())
        it = cache.emplace(subpix_half, detect_boards(sample_images("left"), sample_images("right"), kBoard,
                                                      DetectOptions{10, subpix_half})).first;
    return it->second;
}

const Calibration& calibration() {
    static const Calibration c = calibrate(detection(), kBoard);
    return c;
}

struct Intrinsics {
    double fx, fy, cx, cy, rms;
};

Intrinsics shipped_left_intrinsics() {
    cv::FileStorage f((g_dir / "left_intrinsics.yml").string(), cv::FileStorage::READ);
    REQUIRE(f.isOpened());
    cv::Mat K;
    f["camera_matrix"] >> K;
    REQUIRE(K.rows == 3);
    return {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2), K.at<double>(1, 2),
            static_cast<double>(f["avg_reprojection_error"])};
}

}  // namespace

TEST_CASE("the board is found in both images of all 13 sample pairs", "[calib][opencv-doc]") {
    const Detection& d = detection();
    CHECK(d.image_size == cv::Size(640, 480));
    CHECK(d.views.size() == 13);
    CHECK(d.skipped.empty());
}

TEST_CASE("the sample rig calibrates to a stereo reprojection RMS below 0.25 px", "[calib][opencv-doc]") {
    const Calibration& c = calibration();
    INFO("RMS " << c.rms);
    // Measured 0.196 px (docs/calibration.md); the bound leaves 25 % for other OpenCV
    // versions' corner detection. With the samples' fixed 11 px sub-pixel window the same
    // calibration measured 0.444 px, and OpenCV's own single-camera sample reports 0.393 px
    // on the left images alone (left_intrinsics.yml): the bound separates the two.
    CHECK(c.rms < 0.25);
    CHECK(c.rms > 0.05);   // real images: an RMS near zero would mean the residuals are not computed
    REQUIRE(c.per_view_errors.size() == 13);
    for (size_t i = 0; i < 13; ++i) {
        INFO(c.view_names[i] << ": " << c.per_view_errors[i][0] << ", " << c.per_view_errors[i][1]);
        CHECK(c.per_view_errors[i][0] < 0.35);   // measured at most 0.303 px (left08)
        CHECK(c.per_view_errors[i][1] < 0.35);
    }
}

TEST_CASE("the left camera's intrinsics agree with the sample's left_intrinsics.yml", "[calib][opencv-doc]") {
    const Intrinsics s = shipped_left_intrinsics();
    const cv::Mat& K = calibration().K1;
    INFO("ours fx " << K.at<double>(0, 0) << " fy " << K.at<double>(1, 1) << " cx " << K.at<double>(0, 2)
                    << " cy " << K.at<double>(1, 2) << "; shipped fx " << s.fx << " fy " << s.fy << " cx "
                    << s.cx << " cy " << s.cy);
    // Tolerance 5 px on each of fx, fy, cx, cy: three standard deviations of the difference of
    // two estimates taken as independent (the same images correlate them, which only narrows
    // the difference), 3 sqrt(0.68^2 + 1.56^2) = 5.1 px, with cv::calibrateCamera's
    // largest deviation of the four on these 13 views: 0.68 px with our corners, 1.56 px with
    // the samples' 11 px sub-pixel window that left_intrinsics.yml was made with (both in the
    // reports of docs/calibration.md). Measured differences: 2.21, 2.22, 0.16, 0.57 px.
    const double tol = 5.0;
    CHECK(std::abs(K.at<double>(0, 0) - s.fx) < tol);
    CHECK(std::abs(K.at<double>(1, 1) - s.fy) < tol);
    CHECK(std::abs(K.at<double>(0, 2) - s.cx) < tol);
    CHECK(std::abs(K.at<double>(1, 2) - s.cy) < tol);
}

TEST_CASE("with the sample's window and flags the left images reproduce left_intrinsics.yml", "[calib][opencv-doc]") {
    // Same images, same 11 px sub-pixel window, same model as the shipped file (one camera,
    // CALIB_FIX_ASPECT_RATIO with fx/fy = 1, k1 k2 p1 p2 k3): the result must be the file's,
    // up to the OpenCV version's corner detection. Measured: 0.18 px off in fx, 0.09 in cx,
    // 0.02 in cy, RMS 0.408 against 0.393.
    const Intrinsics s = shipped_left_intrinsics();
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    std::vector<cv::Point3f> b;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 9; ++j) b.emplace_back(static_cast<float>(j * kBoard.square), static_cast<float>(i * kBoard.square), 0.f);
    for (const auto& v : detection(11).views) {
        obj.push_back(b);
        img.push_back(v.left);
    }
    cv::Mat K = cv::Mat::eye(3, 3, CV_64F), D;
    std::vector<cv::Mat> rv, tv;
    const double rms = cv::calibrateCamera(obj, img, cv::Size(640, 480), K, D, rv, tv, cv::CALIB_FIX_ASPECT_RATIO);
    INFO("rms " << rms << " fx " << K.at<double>(0, 0) << " cx " << K.at<double>(0, 2) << " cy " << K.at<double>(1, 2));
    CHECK(std::abs(K.at<double>(0, 0) - s.fx) < 0.5);   // a third of the estimate's deviation (1.36 px in fx)
    CHECK(std::abs(K.at<double>(0, 2) - s.cx) < 0.5);
    CHECK(std::abs(K.at<double>(1, 2) - s.cy) < 0.5);
    CHECK(std::abs(rms - s.rms) < 0.03);
}

TEST_CASE("rectified board corners of the sample pairs lie on the same row", "[calib][opencv-doc]") {
    const RectificationCheck r = check_rectification(calibration(), detection());
    INFO("mean " << r.mean_abs_dy << " max " << r.max_abs_dy);
    CHECK(r.corners == 13u * 54u);
    CHECK(r.mean_abs_dy < 0.15);   // measured 0.101 px: half the reprojection RMS
    CHECK(r.max_abs_dy < 1.0);     // measured 0.620 px; the thesis's epipolar test accepts |dy| < 5 px
}

TEST_CASE("the sample rig's baseline is about 8 cm and its calib.txt round trip is exact", "[calib][opencv-doc]") {
    const Calibration& c = calibration();
    INFO("baseline " << c.rectified.baseline() << " T " << c.T);
    CHECK(c.rectified.baseline() == Approx(0.0832).margin(0.001));   // measured 0.08317 m with 25 mm squares
    const Calibration r = parse_kitti_calib(to_kitti_calib(c), "round trip");
    for (const Side side : {Side::left, Side::right})
        CHECK(cv::norm(projection(r.rectified, side), projection(c.rectified, side), cv::NORM_INF) == 0);
    CHECK(r.rectified.baseline() == c.rectified.baseline());
}

int main(int argc, char** argv) {
    const char* env = std::getenv("HARRIS_COSIM_OPENCV_SAMPLES");
    g_dir = env ? fs::path(env) : fs::path(HC_OPENCV_SAMPLES);
    if (g_dir.empty() || !fs::exists(g_dir / "left01.jpg") || !fs::exists(g_dir / "left_intrinsics.yml")) {
        std::printf("SKIPPED: no OpenCV stereo samples (left01.jpg, left_intrinsics.yml) in '%s': install "
                    "Debian's opencv-doc or set HARRIS_COSIM_OPENCV_SAMPLES to a directory holding them\n",
                    g_dir.string().c_str());
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

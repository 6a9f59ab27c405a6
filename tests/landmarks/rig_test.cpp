// rig_test.cpp: the landmark pipeline on a user's own rig, end to end on OpenCV's stereo
// chessboard samples (Debian opencv-doc, left01..14.jpg, right01..14.jpg, 13 pairs): calibrate, write
// and read back the calibration, then run the pipeline on one unrectified pair with its
// keypoints undistorted and rectified. The board's corners, rectified and triangulated, lie
// one square apart on one plane and share a rectified row; the pipeline's matches share a
// row too, and outnumber those of the same pair taken as rectified.
// Exits 77 (CTest: skipped) without the samples.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/frames/frames.hpp"
#include "mapping/landmarks/landmarks.hpp"

namespace fs = std::filesystem;
using namespace hc::landmarks;
namespace landmarks = hc::landmarks;

namespace {
fs::path g_samples;
}

int main(int argc, char** argv) {
    const char* env = std::getenv("HARRIS_COSIM_OPENCV_SAMPLES");
    g_samples = env && *env ? fs::path(env) : fs::path(HC_OPENCV_SAMPLES);
    if (!fs::exists(g_samples / "left01.jpg") || !fs::exists(g_samples / "right14.jpg")) {
        std::printf("SKIP: OpenCV's stereo samples (left01..14.jpg, right01..14.jpg) not in '%s' "
                    "(install opencv-doc or set HARRIS_COSIM_OPENCV_SAMPLES)\n",
                    g_samples.string().c_str());
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

TEST_CASE("on a calibrated rig's unrectified pair, the chessboard's landmarks are flat, one square apart, on one row",
          "[landmarks][calib]") {
    // the 13 pairs of the samples (there is no left10/right10)
    const auto left = hc::frames::expand_image_list({(g_samples / "left[0-9]*.jpg").string()}, "left");
    const auto right = hc::frames::expand_image_list({(g_samples / "right[0-9]*.jpg").string()}, "right");
    REQUIRE(left.size() == 13);
    const landmarks::Board board{{9, 6}, 1.0};   // unit: one square
    const landmarks::Detection det = landmarks::detect_boards(left, right, board);
    const landmarks::Calibration rig = landmarks::calibrate(det, board);
    // through the file `harris-cosim calibrate` writes
    const fs::path file = fs::temp_directory_path() / ("hc_rig_test_" + std::to_string(::getpid()) + ".yml");
    write_atomic(file, landmarks::to_opencv_storage(rig, false));
    const landmarks::Calibration read = read_rig_calibration(file);
    fs::remove(file);

    const fs::path l3 = g_samples / "left03.jpg", r3 = g_samples / "right03.jpg";
    const Dataset ds = rig_dataset({l3}, {r3}, read);
    REQUIRE(ds.rig);
    PipelineOptions o;
    o.detector = Detector::opencv;
    o.descriptor = Descriptor::brief;
    const std::vector<Landmark> lm = acquire_dataset(ds, o).at(0);
    REQUIRE(lm.size() > 20);
    // the same from the corners detected beforehand; corners of another number of pairs refused
    const std::vector<PairKeypoints> kp = detect_dataset(ds, o.detector, o.corners);
    const std::vector<Landmark> again = acquire_dataset(ds, kp, o).at(0);
    REQUIRE(again.size() == lm.size());
    for (size_t i = 0; i < lm.size(); ++i) CHECK(again[i].p_cam == lm[i].p_cam);
    CHECK_THROWS_AS(acquire_dataset(ds, std::vector<PairKeypoints>{}, o), hc::InputError);

    // the board's corners in both raw images, and where rectification puts them
    const cv::Mat gl = cv::imread(l3.string(), cv::IMREAD_GRAYSCALE), gr = cv::imread(r3.string(), cv::IMREAD_GRAYSCALE);
    const auto bl = landmarks::find_board(gl, board), br = landmarks::find_board(gr, board);
    REQUIRE(bl.size() == 54);
    REQUIRE(br.size() == 54);
    const auto rl = landmarks::rectify_points(read, landmarks::Side::left, bl), rr = landmarks::rectify_points(read, landmarks::Side::right, br);
    double raw_dy = 0, rect_dy = 0;
    for (size_t i = 0; i < bl.size(); ++i) {
        raw_dy += std::abs(bl[i].y - br[i].y) / 54.0;
        rect_dy += std::abs(rl[i].y - rr[i].y) / 54.0;
    }
    // the board's corners triangulated through the rectified rig: one square apart, flat
    const hc::landmarks::RectifiedRig rect = ds.calib.at(0);
    std::vector<cv::Vec3d> corners;
    for (size_t i = 0; i < 54; ++i) {
        const hc::landmarks::Point3 t = hc::landmarks::triangulate(rect, pixels(rl[i], rr[i]));
        REQUIRE(t.valid);
        corners.emplace_back(t.p[0], t.p[1], t.p[2]);
    }
    std::vector<double> sides;
    for (int i = 0; i < 54; ++i) {
        if (i % 9 + 1 < 9) sides.push_back(cv::norm(corners[static_cast<size_t>(i)] - corners[static_cast<size_t>(i + 1)]));
        if (i / 9 + 1 < 6) sides.push_back(cv::norm(corners[static_cast<size_t>(i)] - corners[static_cast<size_t>(i + 9)]));
    }
    std::sort(sides.begin(), sides.end());
    // their plane (least squares: the normal is the smallest singular vector)
    cv::Vec3d mean(0, 0, 0);
    for (const auto& p : corners) mean += p / 54.0;
    cv::Mat A(54, 3, CV_64F);
    for (int i = 0; i < 54; ++i)
        for (int j = 0; j < 3; ++j) A.at<double>(i, j) = corners[static_cast<size_t>(i)][j] - mean[j];
    cv::Mat w, u, vt;
    cv::SVD::compute(A, w, u, vt);
    const cv::Vec3d normal(vt.at<double>(2, 0), vt.at<double>(2, 1), vt.at<double>(2, 2));
    double corner_off_plane = 0;
    for (const auto& p : corners) corner_off_plane = std::max(corner_off_plane, std::abs((p - mean).dot(normal)));
    // the pipeline's matches: on rectified keypoints they share a row; the same pair taken as
    // rectified (raw keypoints) loses most of them to the epipolar test
    std::vector<double> dy;
    for (const auto& l : lm) dy.push_back(std::abs(l.left.y - l.right.y));
    std::sort(dy.begin(), dy.end());
    Dataset raw = ds;
    raw.rig.reset();
    ComparisonOptions co;
    co.detectors = {Detector::opencv};
    co.descriptors = {Descriptor::brief};
    const long rectified_correct = compare(ds, co).at(0).totals.correct, raw_correct = compare(raw, co).at(0).totals.correct;
    WARN(lm.size() << " landmarks, median rectified |dy| " << dy[dy.size() / 2] << " px; correct (thesis) matches "
                   << rectified_correct << " rectified, " << raw_correct << " on the raw keypoints; board corners: mean |dy| raw "
                   << raw_dy << " px, rectified " << rect_dy << " px, depth " << mean[2]
                   << " squares, largest distance from their plane " << corner_off_plane << " squares, neighbour distances "
                   << sides.front() << " .. " << sides.back() << ", median " << sides[sides.size() / 2]);
    CHECK(raw_dy > 2.0);    // the raw pair is not rectified
    CHECK(rect_dy < 0.5);   // its rectified corners share a row
    CHECK(sides[sides.size() / 2] == Approx(1.0).epsilon(0.02));
    CHECK(corner_off_plane < 0.05);
    CHECK(dy[dy.size() / 2] < 1.0);
    CHECK(static_cast<long>(lm.size()) <= rectified_correct);
    CHECK(rectified_correct > 2 * raw_correct);
}

TEST_CASE("a bad rig calibration file is an input error naming it", "[landmarks][calib]") {
    const fs::path bad = fs::temp_directory_path() / ("hc_rig_test_bad_" + std::to_string(::getpid()) + ".yml");
    write_atomic(bad, "%YAML:1.0\n---\nimage_width: 640\n");
    CHECK_THROWS_WITH(read_rig_calibration(bad), Catch::Contains(bad.string()));
    fs::remove(bad);
    CHECK_THROWS_WITH(read_rig_calibration("no/such/calib.yml"), Catch::Contains("no/such/calib.yml"));
    CHECK_THROWS_WITH(read_rig_calibration("no/such/calib.txt"), Catch::Contains("no/such/calib.txt"));
    const landmarks::Calibration kitti = landmarks::parse_kitti_calib(
        "P0: 700 0 320 0 0 700 240 0 0 0 1 0\nP1: 700 0 320 -350 0 700 240 0 0 0 1 0\n", "t");
    CHECK_THROWS_WITH(rig_dataset({g_samples / "left01.jpg"}, {}, kitti), Catch::Contains("1 left images but 0 right"));
    CHECK_THROWS_WITH(rig_dataset({g_samples / "left01.jpg"}, {g_samples / "nothere.jpg"}, kitti), Catch::Contains("nothere.jpg"));
}

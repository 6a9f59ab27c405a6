// calib_kitti_test.cpp: the KITTI reader on the sequence 01 calib.txt of the data directory
// (io/frames/frames.hpp data_dir). Exits 77 (CTest: skipped) with a message when it is absent.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <filesystem>

#include "tests/frames/data_dir_holding.hpp"
#include "mapping/landmarks/calib.hpp"

using namespace hc::landmarks;

namespace {
std::filesystem::path g_calib;
}

TEST_CASE("KITTI 01's calib.txt gives fx 718.856 px and a 0.537 m baseline", "[calib][kitti]") {
    const Calibration c = read_kitti_calib(g_calib);
    CHECK(c.rectified_input);
    CHECK(c.rectified.fx == 718.856);
    CHECK(c.rectified.cx0 == 607.1928);
    CHECK(c.rectified.cy == 185.2157);
    CHECK(c.rectified.tx1 == -386.1448);
    CHECK(c.rectified.baseline() == Approx(0.537).margin(0.0005));   // 386.1448 / 718.856 = 0.53716 m
    // 1 px of disparity at the far end: Z = f b / d = 386.1448 m.
    const cv::Mat X = c.Q * (cv::Mat_<double>(4, 1) << 607.1928, 185.2157, 1, 1);
    CHECK(X.at<double>(2) / X.at<double>(3) == Approx(386.1448).epsilon(1e-12));
}

int main(int argc, char** argv) {
    const auto d = hc::frames::test::data_dir_holding("kitti/sequences/01/calib.txt");
    if (!d) return 77;
    g_calib = *d / "kitti/sequences/01/calib.txt";
    return hc::test::run_catch(argc, argv);
}

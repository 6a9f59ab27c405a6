// slam_trajectory_test.cpp: the 6-DoF trajectory files without data: a hand-made sequence of
// 6-DoF steps written in the KITTI and TUM formats and read back, its 3-D APE computed by hand,
// visual odometry's 6-DoF steps integrated into height and tilt (spatial_track), and the
// ground-truth and timestamp readers' refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "tests/slam/temp_file.hpp"
#include "mapping/slam/slam.hpp"

using namespace hc::slam;
using hc::slam::test::temp_file;
namespace fs = std::filesystem;

namespace {

Mat3 rot_x(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Mat3 rot_y(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }

/// Poses of camera 0 from 6-DoF steps: T_k = T_{k-1} · [R | t].
std::vector<Mat34> integrate(const std::vector<std::pair<Mat3, Eigen::Vector3d>>& steps) {
    Mat3 M = Mat3::Identity();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    std::vector<Mat34> out;
    Mat34 T;
    T << M, p;
    out.push_back(T);
    for (const auto& [R, t] : steps) {
        p += M * t;
        M = M * R;
        T << M, p;
        out.push_back(T);
    }
    return out;
}
}  // namespace

TEST_CASE("a 6-DoF trajectory written and read back in both formats gives the 3-D APE computed by hand", "[slam]") {
    // three steps of 1 m forward, each climbing 0.2 m (y down: -0.2), pitching, rolling and turning
    const Mat3 R = rot_y(0.05) * rot_x(0.02) * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const auto truth = integrate({{R, {0, -0.2, 1}}, {R, {0, -0.2, 1}}, {R, {0, -0.2, 1}}});
    // the estimate: the truth moved by known offsets (0; 0.3, 0.4; 1, 2, 2; 0, 0, 0.5)
    std::vector<Mat34> estimate = truth;
    estimate[1].col(3) += Eigen::Vector3d(0, 0.3, 0.4);
    estimate[2].col(3) += Eigen::Vector3d(1, 2, 2);
    estimate[3].col(3) += Eigen::Vector3d(0, 0, 0.5);
    const double by_hand = std::sqrt((0 + 0.25 + 9 + 0.25) / 4.0);
    CHECK(absolute_trajectory_error_3d(estimate, truth) == Approx(by_hand).epsilon(1e-12));

    const fs::path kitti_file = temp_file("est_kitti.txt", kitti_trajectory(estimate));
    const fs::path tum_file = temp_file("est_tum.txt", "# t tx ty tz qx qy qz qw\n" +
                                                           tum_trajectory(estimate, {0.0, 0.1036, 0.2073, 0.3109}));
    const fs::path truth_file = temp_file("truth_kitti.txt", kitti_trajectory(truth));
    const auto est_k = read_trajectory_file(kitti_file), est_t = read_trajectory_file(tum_file),
               tru = read_trajectory_file(truth_file);
    REQUIRE(est_k.size() == 4);
    REQUIRE(est_t.size() == 4);
    for (size_t k = 0; k < 4; ++k) {
        INFO("pose " << k);
        CHECK((est_k[k] - estimate[k]).cwiseAbs().maxCoeff() < 1e-8);   // 9 significant digits
        CHECK((est_t[k] - estimate[k]).cwiseAbs().maxCoeff() < 1e-8);
    }
    // the height, roll and pitch the steps gave are in the file: the last pose climbed 3 × 0.2 m
    // in a frame pitched by the steps, not 0
    CHECK(tru[3](1, 3) < -0.5);
    CHECK(absolute_trajectory_error_3d(est_k, tru) == Approx(by_hand).epsilon(1e-8));
    CHECK(absolute_trajectory_error_3d(est_t, tru) == Approx(by_hand).epsilon(1e-8));
    for (const auto& f : {kitti_file, tum_file, truth_file}) fs::remove(f);
}

TEST_CASE("visual odometry's 6-DoF steps give each frame's height and tilt, a failed step neither", "[slam]") {
    VisualOdometry vo;
    const double a = 0.1;   // each step pitches by a about the camera's x axis and climbs 0.2 m
    for (bool ok : {true, false, true}) {
        MotionEstimate e;
        e.ok = ok;
        e.rotation = rot_x(a);
        e.translation = Eigen::Vector3d(0, -0.2, 1);
        vo.estimates.push_back(e);
    }
    const SpatialTrack s = spatial_track(vo);
    REQUIRE(s.height.size() == 4);
    REQUIRE(s.tilt.size() == 4);
    CHECK(s.height[0] == 0);
    CHECK(s.height[1] == Approx(-0.2));
    CHECK(s.height[2] == Approx(-0.2));   // the failed step moves nothing
    // the third step's translation seen in the once-pitched camera: y = -0.2 cos a - sin a
    CHECK(s.height[3] == Approx(-0.2 - 0.2 * std::cos(a) - std::sin(a)));
    CHECK((s.tilt[3] - rot_x(2 * a)).cwiseAbs().maxCoeff() < 1e-12);   // heading 0: the tilt is the pitch
    // the 6-DoF pose of a top-view pose (x forward 2, y left 1, heading 0.3) with that tilt and height
    const auto p = spatial_poses({Pose(2, 1, 0.3)}, {s.tilt[3]}, {s.height[3]});
    CHECK(p[0](0, 3) == Approx(-1));
    CHECK(p[0](1, 3) == Approx(s.height[3]));
    CHECK(p[0](2, 3) == Approx(2));
    CHECK(planar_pose(p[0])(2) == Approx(0.3));
    CHECK(tilt_of(p[0].leftCols<3>()).isApprox(s.tilt[3], 1e-12));
    CHECK_THROWS_AS(spatial_poses({Pose::Zero(), Pose::Zero()}, {Mat3::Identity()}), std::invalid_argument);
}

TEST_CASE("ground-truth and timestamp files are read or refused naming the file and line", "[slam]") {
    CHECK(read_trajectory_file(temp_file("tum.txt", "0 1 2 3 0 0 0 1\n"))[0].col(3) == Eigen::Vector3d(1, 2, 3));
    CHECK_THROWS_WITH(read_trajectory_file(temp_file("seven.txt", "1 2 3 4 5 6 7\n")),
                      Catch::Contains("line 1") && Catch::Contains("neither a KITTI pose"));
    CHECK_THROWS_WITH(read_trajectory_file(temp_file("mixed.txt", "0 1 2 3 0 0 0 1\n1 0 0 0 0 1 0 0 0 0 1 0\n")),
                      Catch::Contains("line 2") && Catch::Contains("have 8"));
    CHECK_THROWS_WITH(read_trajectory_file(temp_file("zero_q.txt", "0 1 2 3 0 0 0 0\n")),
                      Catch::Contains("quaternion"));
    CHECK_THROWS_WITH(read_trajectory_file(temp_file("words.txt", "0 1 2 3 a 0 0 1\n")), Catch::Contains("not a number"));
    CHECK_THROWS_WITH(read_trajectory_file(temp_file("comments.txt", "# nothing\n")), Catch::Contains("holds no pose"));
    CHECK_THROWS_AS(read_trajectory_file("/nonexistent/truth.txt"), hc::InputError);
    CHECK(read_timestamps(temp_file("times.txt", "0.000000e+00\n1.036000e-01\n")) == std::vector<double>{0, 0.1036});
    CHECK_THROWS_WITH(read_timestamps(temp_file("times2.txt", "0\n1 2\n")), Catch::Contains("line 2"));
    CHECK_THROWS_AS(read_timestamps(temp_file("times3.txt", "")), hc::InputError);
}

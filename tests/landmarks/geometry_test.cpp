// geometry_test.cpp: triangulation through a rectified rig (landmarks::triangulate), its Jacobian and
// covariance, calibration files and landmark files, on synthetic scenes of known depth.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "mapping/landmarks/landmarks.hpp"

using namespace hc::landmarks;

namespace {

// KITTI odometry sequences 00-02, calib.txt rows P0 and P1 (fx 718.856, baseline 0.537 m).
const double kKittiP0[12] = {718.856, 0, 607.1928, 0, 0, 718.856, 185.2157, 0, 0, 0, 1, 0};
const double kKittiP1[12] = {718.856, 0, 607.1928, -386.1448, 0, 718.856, 185.2157, 0, 0, 0, 1, 0};

hc::landmarks::RectifiedRig kitti_calib() { return hc::landmarks::rig_from_projections(kKittiP0, kKittiP1); }

// the projection of X through the 3x4 matrix P (row-major)
cv::Point2d project(const double P[12], const cv::Vec3d& X) {
    const cv::Vec3d p = cv::Matx34d(P) * cv::Vec4d(X[0], X[1], X[2], 1.0);
    return {p[0] / p[2], p[1] / p[2]};
}

hc::landmarks::Point3 triangulate(const hc::landmarks::RectifiedRig& c, cv::Point2d l, cv::Point2d r,
                               const PixelNoise& n = {}) {
    return hc::landmarks::triangulate(c, {l.x, l.y, r.x, r.y}, n);
}

cv::Vec3d vec(const hc::landmarks::Point3& t) { return {t.p[0], t.p[1], t.p[2]}; }

}  // namespace

TEST_CASE("points of a synthetic scene triangulate back to their known position within 1e-9 relative", "[landmarks]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ux(-15, 15), uy(-3, 3), uz(2, 90);
    for (const hc::landmarks::RectifiedRig& c : {kitti_calib(), middlebury_calib(0.5, 270, cv::Size(641, 555))}) {
        c.validate();
        double P0[12], P1[12];
        c.projections(P0, P1);
        for (int i = 0; i < 1000; ++i) {
            const cv::Vec3d X(ux(rng), uy(rng), uz(rng));
            const hc::landmarks::Point3 t = triangulate(c, project(P0, X), project(P1, X));
            REQUIRE(t.valid);
            INFO("point " << X << " triangulated " << vec(t));
            CHECK(cv::norm(vec(t) - X) / cv::norm(X) <= 1e-9);
        }
    }
}

TEST_CASE("a KITTI match of 8 px disparity lies at fx * baseline / 8 = 48.268 m", "[landmarks]") {
    const hc::landmarks::RectifiedRig c = kitti_calib();
    CHECK(c.baseline() == Approx(386.1448 / 718.856).epsilon(1e-15));
    const hc::landmarks::Point3 t = triangulate(c, {700.0, 200.0}, {692.0, 200.0});
    REQUIRE(t.valid);
    CHECK(t.p[2] == Approx(386.1448 / 8.0).epsilon(1e-15));
    CHECK(t.p[0] == Approx((700.0 - 607.1928) * t.p[2] / 718.856).epsilon(1e-14));
    CHECK(t.p[1] == Approx((200.0 - 185.2157) * t.p[2] / 718.856).epsilon(1e-14));
    CHECK_FALSE(triangulate(c, {700.0, 200.0}, {700.0, 200.0}).valid);   // zero disparity: at infinity
    CHECK_FALSE(triangulate(c, {700.0, 200.0}, {705.0, 200.0}).valid);   // negative: behind the cameras
}

TEST_CASE("the triangulation Jacobian equals central differences on every input coordinate", "[landmarks]") {
    const hc::landmarks::RectifiedRig c = kitti_calib();
    const double in[4] = {812.3, 240.7, 771.9, 241.4};
    const hc::landmarks::Point3 t = triangulate(c, {in[0], in[1]}, {in[2], in[3]});
    for (int k = 0; k < 4; ++k) {
        double a[4], b[4];
        std::copy(in, in + 4, a);
        std::copy(in, in + 4, b);
        const double e = 1e-4;
        a[k] += e;
        b[k] -= e;
        const cv::Vec3d num = (vec(triangulate(c, {a[0], a[1]}, {a[2], a[3]})) - vec(triangulate(c, {b[0], b[1]}, {b[2], b[3]}))) / (2 * e);
        for (int r = 0; r < 3; ++r) {
            INFO("d p[" << r << "] / d input[" << k << "]");
            CHECK(t.J[r][k] == Approx(num[r]).epsilon(1e-6).margin(1e-9));
        }
    }
}

TEST_CASE("the landmark covariance is sigma^2 J J^T: depth variance 2 sigma^2 Z^2 / d^2", "[landmarks]") {
    const hc::landmarks::RectifiedRig c = kitti_calib();
    const hc::landmarks::Point3 t = triangulate(c, {650.0, 190.0}, {640.0, 190.0}, PixelNoise{0.5});
    const double Z = 386.1448 / 10.0;
    CHECK(t.cov[2][2] == Approx(2 * 0.25 * Z * Z / 100.0).epsilon(1e-12));
    CHECK(t.cov[0][2] == Approx(t.cov[2][0]).epsilon(1e-15));
    const hc::landmarks::Point3 far = triangulate(c, {650.0, 190.0}, {649.0, 190.0}, PixelNoise{0.5});
    CHECK(far.cov[2][2] / t.cov[2][2] == Approx(10000.0).epsilon(1e-9));   // sigma_Z grows with Z^2
}

TEST_CASE("a rig that is not rectified is refused with a message", "[landmarks]") {
    double P1[12];
    std::copy(kKittiP1, kKittiP1 + 12, P1);
    P1[5] = 700;   // fy differs from P0's
    CHECK_THROWS_WITH(hc::landmarks::rig_from_projections(kKittiP0, P1), Catch::Contains("not rectified"));
    hc::landmarks::RectifiedRig c = kitti_calib();
    c.tx1 = 386.1448;   // right camera to the left
    CHECK_THROWS_AS(c.validate(), hc::InputError);
    CHECK_THROWS_WITH(c.validate(), Catch::Contains("right camera to the right"));
}

TEST_CASE("a KITTI calib.txt gives the rig of its P0 and P1, a file without P1 is refused", "[landmarks]") {
    const auto dir = std::filesystem::temp_directory_path() / "hc_landmarks_calib_test";
    std::filesystem::create_directories(dir);
    {
        std::ofstream f(dir / "calib.txt");
        f << "P0: 7.188560000000e+02 0 6.071928000000e+02 0 0 7.188560000000e+02 1.852157000000e+02 0 0 0 1 0\n"
          << "P1: 7.188560000000e+02 0 6.071928000000e+02 -3.861448000000e+02 0 7.188560000000e+02 1.852157000000e+02 0 0 0 1 0\n";
    }
    const hc::landmarks::RectifiedRig c = hc::landmarks::read_kitti_calib(dir / "calib.txt").rectified;
    CHECK(c.tx1 == -386.1448);
    CHECK(c.fx == 718.856);
    {
        std::ofstream f(dir / "calib.txt");
        f << "P0: 7.188560000000e+02 0 6.071928000000e+02 0 0 7.188560000000e+02 1.852157000000e+02 0 0 0 1 0\n";
    }
    CHECK_THROWS_WITH(hc::landmarks::read_kitti_calib(dir / "calib.txt"), Catch::Contains("no row P1"));
    std::filesystem::remove_all(dir);
}

TEST_CASE("landmark files: CSV names its columns, PLY counts its vertices", "[landmarks]") {
    Landmark l;
    l.p_cam = {1.5, -0.25, 12};
    l.cov = cv::Matx33d::eye();
    l.descriptor = {0x0f, 0xa0};
    l.left = {10, 20};
    l.right = {4, 20};
    const std::string csv = landmarks_csv({l});
    CHECK(csv.rfind("x,y,z,cov_xx,cov_xy,cov_xz,cov_yy,cov_yz,cov_zz,u_left,v_left,u_right,v_right,match_distance,descriptor_hex\n", 0) == 0);
    CHECK(csv.find("\n1.5,-0.25,12,1,0,0,1,0,1,10,20,4,20,0,0fa0\n") != std::string::npos);
    const std::string ply = landmarks_ply({l, l});
    CHECK(ply.find("element vertex 2\n") != std::string::npos);
    CHECK(ply.find("1.5 -0.25 12 1\n") != std::string::npos);
}

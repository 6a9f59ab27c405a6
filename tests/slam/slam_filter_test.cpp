// slam_filter_test.cpp: the events of the EKF-SLAM filter: angle wrapping, every Jacobian
// against central finite differences (tolerance 1e-6 absolute), a one-landmark scenario
// computed by hand, the three covariance forms against each other, landmark removal as
// marginalisation, and a symmetric positive semi-definite covariance over 10,000 steps.
#include <catch2/catch.hpp>

#include <cmath>
#include <initializer_list>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "tests/slam/numeric_jacobian.hpp"
#include "mapping/slam/slam.hpp"

using namespace hc::slam;
using hc::slam::test::numeric_jacobian;

namespace {
constexpr double pi = std::numbers::pi;
constexpr double tol = 1e-6;

// A few poses and points in every quadrant, angles near ±π included.
const std::vector<Pose> poses = {Pose(0, 0, 0), Pose(1.5, -2, 0.7), Pose(-3, 1, -2.9), Pose(2, 2, 3.1)};
const std::vector<Vec2> points = {Vec2(3, 1), Vec2(-2, 4), Vec2(0.5, -3), Vec2(-4, -0.2)};

/// A point function of a pose and its inverse (to_frame and from_frame, observe and
/// inv_observe), each with its Jacobians by the pose and by the point: at every pose and
/// point above, g(r, f(r, p)) = p and the four Jacobians equal finite differences; `angles`
/// lists f's output components that are angles.
using PosePointFn = Vec2 (*)(const Pose&, const Vec2&, Mat23*, Mat2*);
void check_inverse_pair(PosePointFn f, PosePointFn g, std::initializer_list<int> angles) {
    for (const auto& r : poses)
        for (const auto& p : points) {
            Mat23 Q_r, P_r;
            Mat2 Q_p, P_q;
            const Vec2 q = f(r, p, &Q_r, &Q_p);
            CHECK((g(r, q, &P_r, &P_q) - p).norm() < 1e-12);
            CHECK((Q_r - numeric_jacobian<2, 3>([&](const Pose& x) { return f(x, p, nullptr, nullptr); }, r, angles)).norm() < tol);
            CHECK((Q_p - numeric_jacobian<2, 2>([&](const Vec2& x) { return f(r, x, nullptr, nullptr); }, p, angles)).norm() < tol);
            CHECK((P_r - numeric_jacobian<2, 3>([&](const Pose& x) { return g(x, q, nullptr, nullptr); }, r)).norm() < tol);
            CHECK((P_q - numeric_jacobian<2, 2>([&](const Vec2& x) { return g(r, x, nullptr, nullptr); }, q)).norm() < tol);
        }
}
}  // namespace

TEST_CASE("angles are wrapped into the interval from -pi excluded to pi included", "[slam]") {
    CHECK(wrap_angle(0) == 0);
    CHECK(wrap_angle(pi) == Approx(pi));
    CHECK(wrap_angle(-pi) == Approx(pi));
    CHECK(wrap_angle(3 * pi / 2) == Approx(-pi / 2));
    CHECK(wrap_angle(-3 * pi / 2) == Approx(pi / 2));
    CHECK(wrap_angle(7 * pi + 0.25) == Approx(-pi + 0.25));
    CHECK(wrap_angle(-0.5) == Approx(-0.5));
}

TEST_CASE("to_frame and from_frame Jacobians equal finite differences", "[slam]") {
    check_inverse_pair(to_frame, from_frame, {});
}

TEST_CASE("scan and inv_scan Jacobians equal finite differences and invert each other", "[slam]") {
    for (const auto& p : points) {
        Mat2 Y_p, P_y;
        const Vec2 y = scan(p, &Y_p);
        CHECK((inv_scan(y, &P_y) - p).norm() < 1e-12);
        CHECK((Y_p - numeric_jacobian<2, 2>([](const Vec2& x) { return scan(x); }, p, {1})).norm() < tol);
        CHECK((P_y - numeric_jacobian<2, 2>([](const Vec2& x) { return inv_scan(x); }, y)).norm() < tol);
        CHECK((Y_p * P_y - Mat2::Identity()).norm() < 1e-12);
    }
    CHECK(scan(Vec2(0, -2))(1) == Approx(-pi / 2));
}

TEST_CASE("move's Jacobians equal finite differences, including across the ±pi cut", "[slam]") {
    const std::vector<Vec2> us = {Vec2(0.1, 0.05), Vec2(1.2, -0.3), Vec2(-0.4, 0.9), Vec2(0.5, 0)};
    for (const auto& r : poses)
        for (const auto& u : us) {
            const Vec2 n(0.01, -0.02);
            Mat3 R_r;
            Mat32 R_n;
            const Pose r1 = move(r, u, n, &R_r, &R_n);
            CHECK(r1(2) > -pi);
            CHECK(r1(2) <= pi);
            CHECK((R_r - numeric_jacobian<3, 3>([&](const Pose& x) { return move(x, u, n); }, r, {2})).norm() < tol);
            CHECK((R_n - numeric_jacobian<3, 2>([&](const Vec2& x) { return move(r, u, x); }, n, {2})).norm() < tol);
        }
}

TEST_CASE("move along an arc ends where the arc ends", "[slam]") {
    // a circle of radius 2 from (0, -2) heading 0: a quarter turn ends at (2, 0) heading π/2
    Pose r(0, -2, 0);
    for (int k = 0; k < 10; ++k) r = move(r, Vec2(2 * std::sin(pi / 40) * 2, pi / 20), Vec2::Zero());
    CHECK(r(0) == Approx(2).margin(1e-12));
    CHECK(r(1) == Approx(0).margin(1e-12));
    CHECK(r(2) == Approx(pi / 2));
}

TEST_CASE("observe and inv_observe Jacobians equal finite differences and invert each other", "[slam]") {
    check_inverse_pair(observe, inv_observe, {1});
}

TEST_CASE("the camera-to-range-bearing Jacobian equals finite differences and propagates the covariance", "[slam]") {
    const Eigen::Vector3d p(-3.0, 1.2, 12.0);
    Eigen::Matrix3d cov;
    cov << 0.04, 0.01, 0.02, 0.01, 0.03, 0.0, 0.02, 0.0, 0.5;
    Eigen::Matrix<double, 2, 3> J;
    const RangeBearing rb = camera_to_range_bearing(p, cov, &J);
    CHECK(rb.y(0) == Approx(std::sqrt(9.0 + 144.0)));
    CHECK(rb.y(1) == Approx(std::atan2(3.0, 12.0)));   // 3 m to the left of the forward axis
    const auto f = [&](const Eigen::Vector3d& x) { return camera_to_range_bearing(x, cov).y; };
    CHECK((J - numeric_jacobian<2, 3>(f, p, {1})).norm() < tol);
    CHECK((rb.R - J * cov * J.transpose()).norm() < 1e-15);
    CHECK(rb.R(0, 1) == rb.R(1, 0));
}

TEST_CASE("a one-landmark scenario gives the values computed by hand", "[slam]") {
    // Map at the origin with P = 0 (eq. 2.11). Landmark seen at (range 2, bearing 0) with
    // R = diag(0.01, 1e-4): at (2, 0), covariance diag(0.01, 2²·1e-4 = 4e-4), uncorrelated.
    // Move u = (1, 0), N = diag(0.01, 4e-4): R_n = [1 0; 0 1/2; 0 1], so
    // P_rr = [0.01 0 0; 0 1e-4 2e-4; 0 2e-4 4e-4]. Observe (1.1, 0): z = (0.1, 0),
    // H_r = [-1 0 0; 0 -1 -1], H_l = I, Z = diag(0.03, 9e-4 + 4e-4 + 1e-4 = 1.4e-3),
    // K's range column = (-1/3, 0, 0, 1/3, 0).
    const Mat2 R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
    const Mat2 N = Eigen::Vector2d(0.01, 4e-4).asDiagonal();
    for (auto form : {UpdateForm::Structured, UpdateForm::DenseKzk, UpdateForm::Dense}) {
        Ekf ekf;
        ekf.add_landmark(7, Vec2(2, 0), R);
        CHECK(ekf.landmark(7).isApprox(Vec2(2, 0)));
        CHECK(ekf.landmark_covariance(7).isApprox(Mat2(Eigen::Vector2d(0.01, 4e-4).asDiagonal())));
        ekf.predict(Vec2(1, 0), N);
        Mat3 Prr;
        Prr << 0.01, 0, 0, 0, 1e-4, 2e-4, 0, 2e-4, 4e-4;
        CHECK((ekf.pose_covariance() - Prr).norm() < 1e-15);
        // before the correction, for gating: h = (1, 0), H P Hᵀ = Z − R = diag(0.02, 1.3e-3)
        const PredictedObservation predicted = ekf.predicted_observation(7);
        CHECK((predicted.y - Vec2(1, 0)).norm() < 1e-15);
        CHECK((predicted.HPHt - Mat2(Eigen::Vector2d(0.02, 1.3e-3).asDiagonal())).norm() < 1e-15);
        const Innovation gated = ekf.innovation(7, Vec2(1.1, 0), R);
        CHECK(gated.mahalanobis2 == Approx(0.01 / 0.03));
        CHECK(Ekf::innovation(predicted, Vec2(1.1, 0), R).mahalanobis2 == gated.mahalanobis2);
        const Innovation inn = ekf.correct(7, Vec2(1.1, 0), R, form);
        CHECK(inn.z(0) == Approx(0.1));
        CHECK(inn.Z(0, 0) == Approx(0.03));
        CHECK(inn.Z(1, 1) == Approx(1.4e-3));
        CHECK(inn.Z(0, 1) == Approx(0).margin(1e-15));
        CHECK(inn.mahalanobis2 == Approx(0.01 / 0.03));
        CHECK(ekf.pose()(0) == Approx(1 - 0.1 / 3));
        CHECK(ekf.pose()(1) == Approx(0).margin(1e-15));
        CHECK(ekf.landmark(7)(0) == Approx(2 + 0.1 / 3));
        const Eigen::MatrixXd P = ekf.covariance();
        CHECK(P(0, 0) == Approx(0.01 - 0.01 * 0.01 / 0.03));
        CHECK(P(3, 3) == Approx(0.01 - 0.01 * 0.01 / 0.03));
        CHECK(P(0, 3) == Approx(0.01 * 0.01 / 0.03));
        CHECK(P(3, 0) == Approx(0.01 * 0.01 / 0.03));
    }
}

TEST_CASE("compose's Jacobians equal finite differences and between() inverts it", "[slam]") {
    const std::vector<Motion> us = {Motion(0.1, 0.02, 0.05), Motion(1.2, -0.4, -0.3), Motion(-0.4, 0.3, 3.0)};
    for (const auto& r : poses)
        for (const auto& u : us) {
            Mat3 R_r, R_u;
            const Pose r1 = compose(r, u, &R_r, &R_u);
            CHECK(r1(2) > -pi);
            CHECK(r1(2) <= pi);
            CHECK((R_r - numeric_jacobian<3, 3>([&](const Pose& x) { return compose(x, u); }, r, {2})).norm() < tol);
            CHECK((R_u - numeric_jacobian<3, 3>([&](const Motion& x) { return compose(r, x); }, u, {2})).norm() < tol);
            const Motion b = between(r, r1);
            CHECK((b.head<2>() - u.head<2>()).norm() < 1e-12);
            CHECK(std::abs(wrap_angle(b(2) - u(2))) < 1e-12);
        }
}

TEST_CASE("a 3-DoF prediction moves the pose by compose and adds R_u Q R_u'", "[slam]") {
    const Pose r0(1, 2, 0.4);
    Ekf a(r0, Mat3::Zero());
    const Motion u(1.0, 0.1, 0.2);
    const Mat3 Q = Eigen::Vector3d(0.01, 0.004, 1e-4).asDiagonal();
    a.predict_motion(u, Q);
    Mat3 R_u;
    CHECK((a.pose() - compose(r0, u, nullptr, &R_u)).norm() < 1e-15);
    CHECK((a.pose_covariance() - R_u * Q * R_u.transpose()).norm() < 1e-15);
}

TEST_CASE("the structured, P-KZK' and (I-KH)P updates give the same state and covariance", "[slam]") {
    SimConfig c;
    c.steps = 60;
    const RunTrace a = run_simulation(c, 3, UpdateForm::Structured);
    const RunTrace b = run_simulation(c, 3, UpdateForm::DenseKzk);
    const RunTrace d = run_simulation(c, 3, UpdateForm::Dense);
    REQUIRE(a.final_filter.dimension() == d.final_filter.dimension());
    REQUIRE(a.final_filter.dimension() > 30);
    CHECK((a.final_filter.mean() - b.final_filter.mean()).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((a.final_filter.mean() - d.final_filter.mean()).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((a.final_filter.covariance() - b.final_filter.covariance()).cwiseAbs().maxCoeff() < 1e-10);
    CHECK((a.final_filter.covariance() - d.final_filter.covariance()).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("removing a landmark leaves the marginal of the others", "[slam]") {
    SimConfig c;
    c.steps = 30;
    const RunTrace t = run_simulation(c, 5);
    Ekf ekf = t.final_filter;
    const auto ids = ekf.landmark_ids();
    REQUIRE(ids.size() >= 3);
    const int victim = ids[1], l = ekf.state_index(victim);
    const Eigen::VectorXd x = ekf.mean();
    const Eigen::MatrixXd P = ekf.covariance();
    ekf.remove_landmark(victim);
    CHECK_FALSE(ekf.has_landmark(victim));
    CHECK(ekf.dimension() == x.size() - 2);
    CHECK(ekf.landmark_ids().size() == ids.size() - 1);
    std::vector<int> keep;
    for (int i = 0; i < x.size(); ++i)
        if (i != l && i != l + 1) keep.push_back(i);
    CHECK((ekf.mean() - x(keep)).norm() == 0);
    CHECK((ekf.covariance() - P(keep, keep)).norm() == 0);
    CHECK(ekf.landmark(ids[2]) == x.segment<2>(l + 2));
    ekf.remove_landmark(victim);   // absent: no effect
    CHECK(ekf.dimension() == x.size() - 2);
}

TEST_CASE("adding a landmark twice is refused and unknown landmarks are reported", "[slam]") {
    Ekf ekf;
    ekf.add_landmark(1, Vec2(2, 0.3), Mat2::Identity() * 0.01);
    CHECK_THROWS_AS(ekf.add_landmark(1, Vec2(2, 0.3), Mat2::Identity()), std::invalid_argument);
    CHECK_THROWS_AS(ekf.correct(2, Vec2(2, 0.3), Mat2::Identity()), std::out_of_range);
}

TEST_CASE("the map grows past its reserved capacity without changing its values", "[slam]") {
    Ekf small(Pose(1, 2, 0.3), Mat3::Identity() * 0.01, 1), big(Pose(1, 2, 0.3), Mat3::Identity() * 0.01, 100);
    for (int i = 0; i < 20; ++i) {
        const Vec2 y(1 + 0.1 * i, -1 + 0.1 * i);
        small.add_landmark(i, y, Mat2::Identity() * 0.02);
        big.add_landmark(i, y, Mat2::Identity() * 0.02);
    }
    CHECK(small.dimension() == 43);
    CHECK((small.covariance() - big.covariance()).norm() == 0);
    CHECK((small.mean() - big.mean()).norm() == 0);
}

TEST_CASE("the covariance stays symmetric positive semi-definite over 10,000 steps", "[slam]") {
    SimConfig c;
    c.steps = 10000;
    c.landmarks = 24;
    const RunTrace t = run_simulation(c, 11);
    const Eigen::MatrixXd P = t.final_filter.covariance();
    CHECK((P - P.transpose()).norm() == 0);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(P);
    INFO("eigenvalues " << es.eigenvalues().minCoeff() << " .. " << es.eigenvalues().maxCoeff());
    CHECK(es.eigenvalues().minCoeff() > -1e-12 * es.eigenvalues().maxCoeff());
    for (const auto& Prr : t.pose_cov) {   // every step's pose block
        const Eigen::SelfAdjointEigenSolver<Mat3> e3(Prr);
        REQUIRE(e3.eigenvalues().minCoeff() > -1e-15);
    }
    // 10,000 steps of 0.1 m on a circle of 3.75 m: about 42 loops, heading bounded
    CHECK(t.estimate.size() == 10001);
    CHECK((t.estimate.back() - t.truth.back()).head<2>().norm() < 0.5);
}

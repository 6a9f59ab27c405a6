// slam_stereo_test.cpp: the stereo-landmark front end without data: KITTI pose files,
// top-view poses and odometry, trajectory writers, triangulation covariance, Hamming
// distance, association by Mahalanobis gate and descriptor, and a synthetic sequence.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include <unistd.h>

#include "tests/slam/numeric_jacobian.hpp"
#include "tests/slam/temp_file.hpp"
#include "mapping/slam/slam.hpp"

using namespace hc::slam;
using hc::slam::test::numeric_jacobian;
using hc::slam::test::temp_file;
namespace fs = std::filesystem;

namespace {

const Mat3 Q0 = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();   // a small motion covariance

// KITTI-like poses: straight ahead 1 m a frame, turning left by `turn` rad a frame.
std::vector<Mat34> arc_poses(int count, double turn) {
    std::vector<Mat34> out;
    Pose r(0, 0, 0);
    for (int k = 0; k < count; ++k) {
        out.push_back(kitti_pose(r));
        r = move(r, Vec2(1.0, turn), Vec2::Zero());
    }
    return out;
}
}  // namespace

TEST_CASE("a KITTI poses file is read line by line and bad files name file and line", "[slam]") {
    const fs::path good = temp_file("good.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n\n1 0 0 0.5 0 1 0 -0.1 0 0 1 2\n");
    const auto poses = read_kitti_poses(good);
    REQUIRE(poses.size() == 2);
    CHECK(poses[1](0, 3) == 0.5);
    CHECK(poses[1](1, 3) == -0.1);
    CHECK(poses[1](2, 3) == 2);
    const fs::path short_line = temp_file("short.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1\n");
    CHECK_THROWS_WITH(read_kitti_poses(short_line), Catch::Contains("line 2") && Catch::Contains("12 numbers"));
    const fs::path long_line = temp_file("long.txt", "1 0 0 0 0 1 0 0 0 0 1 0 7\n");
    CHECK_THROWS_WITH(read_kitti_poses(long_line), Catch::Contains("more than 12"));
    const fs::path empty = temp_file("empty.txt", "");
    CHECK_THROWS_WITH(read_kitti_poses(empty), Catch::Contains("holds no pose"));
    CHECK_THROWS_AS(read_kitti_poses("/nonexistent/poses/01.txt"), hc::InputError);
    for (const auto& p : {good, short_line, long_line, empty}) fs::remove(p);
}

TEST_CASE("a top-view pose survives the round trip through a KITTI pose", "[slam]") {
    for (const Pose& r : {Pose(3, -2, 0.4), Pose(-1, 5, -2.8), Pose(0, 0, 0)}) {
        const Mat34 T = kitti_pose(r);
        CHECK((T.leftCols<3>().transpose() * T.leftCols<3>() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
        CHECK((planar_pose(T) - r).norm() < 1e-14);
    }
    // forward (camera z) is the top view's x, the camera's left (−x) its y
    const Mat34 T = kitti_pose(Pose(2, 1, std::numbers::pi / 2));
    CHECK(T(2, 3) == 2);
    CHECK(T(0, 3) == -1);
    CHECK(T.col(2).dot(Eigen::Vector3d(-1, 0, 0)) == Approx(1));   // heading π/2 = the camera looks left
}

TEST_CASE("exact synthetic odometry on a trajectory gives exact dead reckoning", "[slam]") {
    // a drive with sideways slip as well as turns: (dx, dθ) alone could not follow it
    std::vector<Pose> truth{Pose(0, 0, 0)};
    for (int k = 1; k < 20; ++k) truth.push_back(compose(truth.back(), Motion(1.0, 0.03 * std::sin(k), 0.05)));
    std::vector<Motion> u;
    for (size_t k = 1; k < truth.size(); ++k) {
        u.push_back(between(truth[k - 1], truth[k]));
        CHECK(u.back()(0) == Approx(1.0));
        CHECK(u.back()(1) == Approx(0.03 * std::sin(k)));
        CHECK(u.back()(2) == Approx(0.05));
    }
    const auto dr = dead_reckoning(truth[0], u);
    CHECK(absolute_trajectory_error(dr, truth) < 1e-12);
    SyntheticOdometry m;
    m.sigma_dx = 0.1;
    const auto noisy = noisy_odometry(truth, m, 1);
    REQUIRE(noisy.size() == 19);
    CHECK(noisy == noisy_odometry(truth, m, 1));
    CHECK(noisy != noisy_odometry(truth, m, 2));
    CHECK(absolute_trajectory_error(dead_reckoning(truth[0], noisy), truth) > 0.01);
}

TEST_CASE("trajectories are written in the KITTI and TUM formats", "[slam]") {
    const std::vector<Pose> p = {Pose(0, 0, 0), Pose(2, -1, std::numbers::pi / 2)};
    CHECK(kitti_trajectory(p) == "1 0 -0 -0 0 1 0 0 0 0 1 0\n6.123234e-17 0 -1 1 0 1 0 0 1 0 6.123234e-17 2\n");
    CHECK(tum_trajectory(std::vector<Mat34>{kitti_pose(p[1])}, {0.1}) == "0.1 1 0 2 0 -0.707106781 0 0.707106781\n");
    CHECK_THROWS_AS(tum_trajectory(std::vector<Mat34>{kitti_pose(p[0]), kitti_pose(p[1])}, {0.0}), std::invalid_argument);
    CHECK(absolute_trajectory_error({Pose(0, 0, 0), Pose(3, 4, 0)}, {Pose(0, 0, 1), Pose(0, 0, 0)}) ==
          Approx(std::sqrt(25.0 / 2)));
}

TEST_CASE("triangulation covariance is the pixel noise on u_l, v_l, u_r, v_r through the Jacobian", "[slam]") {
    const hc::landmarks::RectifiedRig cam = synthetic_rig();
    const Eigen::Vector4d m(800, 150, 780, 151);   // disparity 20 px, rows one apart
    const auto f = [&](const Eigen::Vector4d& x) {
        return to_observation(hc::landmarks::triangulate(cam, {x(0), x(1), x(2), x(3)})).p_cam;
    };
    const StereoLandmarkObs o = to_observation(hc::landmarks::triangulate(cam, {m(0), m(1), m(2), m(3)}));
    const double z = cam.fx * cam.baseline() / 20, s = hc::landmarks::PixelNoise{}.sigma_px;
    CHECK(o.p_cam.z() == Approx(z));
    CHECK(o.p_cam.y() == Approx((150.5 - cam.cy) * z / cam.fx));   // v = (v_l + v_r) / 2
    const Eigen::Matrix<double, 3, 4> J = numeric_jacobian<3, 4>(f, m);
    CHECK((o.cov - s * s * J * J.transpose()).norm() < 1e-6 * o.cov.norm());
    // the disparity u_l - u_r has variance 2 σ²: σ_z = √2 z²/(f b) σ (σ on the disparity
    // itself would give z²/(f b) σ); y from the mean of two rows and from z:
    // σ_y² = σ² (z²/(2 f²) + 2 ((v - cy)/f)² z⁴/(f b)²)
    CHECK(std::sqrt(o.cov(2, 2)) == Approx(std::sqrt(2.0) * z * z / (cam.fx * cam.baseline()) * s).epsilon(1e-12));
    const double yv = o.p_cam.y() / z;   // (v - cy) / f
    CHECK(o.cov(1, 1) == Approx(s * s * (z * z / (2 * cam.fx * cam.fx) + 2 * yv * yv * z * z * z * z /
                                                                            (cam.fx * cam.baseline() * cam.fx * cam.baseline())))
                             .epsilon(1e-12));
}

TEST_CASE("the pixel noise is σ on each of u_l, v_l, u_r, v_r: Σ(u, v, d) = σ² [[1,0,1],[0,½,0],[1,0,2]]",
          "[slam]") {
    hc::landmarks::PixelNoise noise{0.7};
    const hc::landmarks::StereoPixels exact{600, 200, 580, 200};
    std::mt19937_64 rng(5);
    const int n = 200000;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (int k = 0; k < n; ++k) {
        const hc::landmarks::StereoPixels m = noise.perturb(exact, rng);
        // error of (u, v, d) = (u_l, (v_l + v_r)/2, u_l - u_r)
        const Eigen::Vector3d e(m.u_l - exact.u_l, (m.v_l + m.v_r) / 2 - 200, (m.u_l - m.u_r) - 20);
        mean += e;
        second += e * e.transpose();
    }
    mean /= n;
    const Eigen::Matrix3d C = second / n - mean * mean.transpose();
    Eigen::Matrix3d model;
    model << 1, 0, 1, 0, 0.5, 0, 1, 0, 2;
    model *= 0.49;
    INFO("sample covariance\n" << C);
    CHECK(mean.norm() < 0.01);
    // 200,000 draws: each entry within 0.01 (its standard error is below 0.0045)
    CHECK((C - model).cwiseAbs().maxCoeff() < 0.01);
    // a zero σ leaves the pixels exact
    noise.sigma_px = 0;
    const hc::landmarks::StereoPixels same = noise.perturb(exact, rng);
    CHECK((same.u_l == exact.u_l && same.v_l == exact.v_l && same.u_r == exact.u_r && same.v_r == exact.v_r));
}

TEST_CASE("the Hamming distance counts differing bits and extra bytes", "[slam]") {
    CHECK(hamming_distance({0xff, 0x00}, {0x0f, 0x01}) == 5);
    CHECK(hamming_distance({0xff}, {0xff, 0x00}) == 8);
    CHECK(hamming_distance({}, {}) == 0);
}

TEST_CASE("association matches inside the gate and refuses a descriptor that differs", "[slam]") {
    AssociationConfig ac;
    ac.forget_after = 0;
    LandmarkSlam s(Pose::Zero(), ac);
    StereoFrame f0;
    const hc::landmarks::RectifiedRig cam = synthetic_rig();
    StereoLandmarkObs a = to_observation(hc::landmarks::triangulate(cam, {700, 200, 670, 200})), b = to_observation(hc::landmarks::triangulate(cam, {400, 200, 375, 200}));
    a.descriptor = std::vector<uint8_t>(32, 0x00);
    b.descriptor = std::vector<uint8_t>(32, 0xff);
    f0 = {a, b};
    const FrameStats s0 = s.first_frame(f0);
    CHECK(s0.observed == 2);
    CHECK(s0.added == 2);
    CHECK(s0.matched == 0);
    // the same two points after no motion: both matched
    const FrameStats s1 = s.next_frame(Motion::Zero(), Q0, f0);
    CHECK(s1.matched == 2);
    CHECK(s1.added == 0);
    CHECK(s1.map_size == 2);
    // point a with b's descriptor: inside the gate, refused by the descriptor, added as new
    StereoLandmarkObs a2 = a;
    a2.descriptor = b.descriptor;
    const FrameStats s2 = s.next_frame(Motion::Zero(), Q0, {a2});
    CHECK(s2.matched == 0);
    CHECK(s2.rejected_by_descriptor == 1);
    CHECK(s2.added == 1);
    CHECK(s2.map_size == 3);
    // without the descriptor check the same observation is matched
    ac.check_descriptor = false;
    LandmarkSlam t(Pose::Zero(), ac);
    t.first_frame(f0);
    CHECK(t.next_frame(Motion::Zero(), Q0, {a2}).matched == 1);
}

TEST_CASE("an odometry inlier corrects the filter with its noise scaled, or not at all", "[slam]") {
    const hc::landmarks::RectifiedRig cam = synthetic_rig();
    const StereoLandmarkObs a = to_observation(hc::landmarks::triangulate(cam, {700, 200, 670, 200}));
    StereoLandmarkObs inlier = a;
    inlier.odometry_inlier = true;
    // the pose variance after a motion and one observation of a landmark mapped in frame 0
    const auto pose_variance = [&](const AssociationConfig& ac, const StereoLandmarkObs& seen, FrameStats* st = nullptr) {
        LandmarkSlam s(Pose::Zero(), ac);
        s.first_frame({a});
        const FrameStats f = s.next_frame(Motion::Zero(), Q0, {seen});
        if (st) *st = f;
        return s.filter().pose_covariance().trace();
    };
    const AssociationConfig plain;
    const double predicted = Q0.trace() + LandmarkSlam(Pose::Zero(), plain).filter().pose_covariance().trace();
    const double corrected = pose_variance(plain, a);
    CHECK(corrected < predicted);
    CHECK(pose_variance(plain, inlier) == corrected);   // the mark alone changes nothing
    AssociationConfig scaled;
    scaled.odometry_inlier_noise_scale = 4;
    const double weaker = pose_variance(scaled, inlier);
    CHECK(weaker > corrected);
    CHECK(weaker < predicted);
    CHECK(pose_variance(scaled, a) == corrected);       // an observation not marked is as measured
    AssociationConfig skip;
    skip.correct_with_odometry_inliers = false;
    FrameStats st;
    CHECK(pose_variance(skip, inlier, &st) == Approx(predicted).epsilon(1e-12));
    CHECK(st.matched == 1);                              // associated, not added again
    CHECK(st.added == 0);
    CHECK(st.matched_not_corrected == 1);
    CHECK(pose_variance(skip, a) == corrected);
    scaled.odometry_inlier_noise_scale = 0.5;
    CHECK_THROWS_WITH(scaled.validate(), Catch::Contains("--odometry-inlier-noise-scale"));
}

TEST_CASE("landmarks unseen for forget_after frames are removed", "[slam]") {
    AssociationConfig ac;
    ac.forget_after = 2;
    LandmarkSlam s(Pose::Zero(), ac);
    const hc::landmarks::RectifiedRig cam = synthetic_rig();
    StereoLandmarkObs a = to_observation(hc::landmarks::triangulate(cam, {700, 200, 670, 200}));
    s.first_frame({a});
    CHECK(s.next_frame(Motion::Zero(), Q0, {}).removed == 0);
    const FrameStats f = s.next_frame(Motion::Zero(), Q0, {});
    CHECK(f.removed == 1);
    CHECK(f.map_size == 0);
}

TEST_CASE("bad association settings and sequences are refused with InputError", "[slam]") {
    AssociationConfig ac;
    ac.gate_probability = 1.5;
    CHECK_THROWS_AS(ac.validate(), hc::InputError);
    SyntheticOdometry om;
    om.sigma_dy = 0;
    CHECK_THROWS_AS(om.validate(), hc::InputError);
    ac = AssociationConfig{};
    ac.max_hamming_fraction = 1.5;
    CHECK_THROWS_AS(LandmarkSlam(Pose::Zero(), ac), hc::InputError);
    const auto poses = arc_poses(3, 0);
    CHECK_THROWS_WITH(run_sequence(poses, std::vector<StereoFrame>(2), SyntheticOdometry{}, AssociationConfig{}, 1),
                      Catch::Contains("one landmark frame per pose"));
    CHECK_THROWS_AS(run_sequence({poses[0]}, std::vector<StereoFrame>(1), SyntheticOdometry{}, AssociationConfig{}, 1),
                    hc::InputError);
    CHECK_THROWS_AS(synthesize_stereo_frames(poses, synthetic_rig(), {}, 0, 0, 1), hc::InputError);
}

TEST_CASE("on a synthetic curved drive EKF-SLAM beats dead reckoning with the same odometry", "[slam]") {
    const auto poses = arc_poses(80, 0.01);
    const auto frames = synthesize_stereo_frames(poses, synthetic_rig(), {}, 300, 8, 3);
    SyntheticOdometry om;
    om.sigma_dx = 0.05;
    om.sigma_dy = 0.01;
    om.sigma_dtheta = 0.005;
    const SequenceRun r = run_sequence(poses, frames, om, AssociationConfig{}, 7);
    int matched = 0, observed = 0;
    for (const auto& f : r.frames) {
        matched += f.matched;
        observed += f.observed;
    }
    INFO("ATE slam " << r.ate_slam << " m, dead reckoning " << r.ate_dead_reckoning << " m; " << matched << " of "
         << observed << " observations matched");
    CHECK(observed > 80 * 20);
    CHECK(matched > observed / 2);
    CHECK(r.ate_slam < 0.5 * r.ate_dead_reckoning);
    CHECK(r.estimate.size() == 80);
}

namespace {
/// Every field of two metrics equal to the last bit (NaN equal to NaN in the per-frame NEES), but
/// the SE(2)-aligned APE: running sums against a pass over the poses, relative 1e-9.
void check_same_metrics(const TrajectoryMetrics& a, const TrajectoryMetrics& b) {
    CHECK(a.ape == b.ape);
    CHECK(a.ape_se2 > 0);
    CHECK(std::abs(a.ape_se2 - b.ape_se2) <= 1e-9 * b.ape_se2);
    CHECK(a.rpe == b.rpe);
    CHECK(a.rpe_heading == b.rpe_heading);
    CHECK(a.path_length == b.path_length);
    CHECK(a.final_error == b.final_error);
    CHECK(a.nees_mean == b.nees_mean);
    CHECK(a.nees_frames == b.nees_frames);
    CHECK(a.nees_lo == b.nees_lo);
    CHECK(a.nees_hi == b.nees_hi);
    CHECK(a.nees_within_95 == b.nees_within_95);
    REQUIRE(a.nees.size() == b.nees.size());
    for (size_t k = 0; k < a.nees.size(); ++k) {
        INFO("frame " << k);
        CHECK(((std::isnan(a.nees[k]) && std::isnan(b.nees[k])) || a.nees[k] == b.nees[k]));
    }
}
}  // namespace

TEST_CASE("a run's metrics summed as frames come are score_trajectory's on its poses to the last bit, the aligned APE to 1e-9", "[slam]") {
    const auto poses = arc_poses(60, 0.01);
    const auto frames = synthesize_stereo_frames(poses, synthetic_rig(), {}, 300, 8, 3);
    const SequenceRun r = run_sequence(poses, frames, SyntheticOdometry{}, AssociationConfig{}, 5);
    REQUIRE(r.truth.size() == 60);
    check_same_metrics(r.slam_metrics, score_trajectory(r.estimate, r.truth, r.pose_cov));
    // the odometry alone, with its covariance integrated from the motions' (zero at the start)
    std::vector<Mat3> dr_cov{Mat3::Zero()};
    for (size_t k = 0; k + 1 < r.truth.size(); ++k) {
        Mat3 R_r, R_u;
        compose(r.dead_reckoning[k], r.odometry[k], &R_r, &R_u);
        dr_cov.push_back(R_r * dr_cov.back() * R_r.transpose() + R_u * r.odometry_cov[k] * R_u.transpose());
    }
    check_same_metrics(r.odometry_metrics, score_trajectory(r.dead_reckoning, r.truth, dr_cov));
    // both start at the true pose with P = 0: frame 0 has no NEES
    CHECK(r.slam_metrics.nees_frames == 59);
    CHECK(std::isnan(r.slam_metrics.nees.front()));
    CHECK(std::isnan(r.odometry_metrics.nees.front()));
    // the running sums alone: the run's bits, no per-frame NEES; nothing before a frame
    TrajectoryScore score;
    CHECK_THROWS_AS(score.metrics(), std::invalid_argument);
    for (size_t k = 0; k < r.truth.size(); ++k) score.add(r.estimate[k], r.truth[k], &r.pose_cov[k]);
    CHECK(score.metrics().ape == r.slam_metrics.ape);
    CHECK(score.metrics().ape_se2 == r.slam_metrics.ape_se2);
    CHECK(score.metrics().nees.empty());
}

TEST_CASE("the SE(2)-aligned APE from running sums is aligned_ape's to relative 1e-9", "[slam]") {
    // by hand: a unit square turned by 90° and moved by (10, -5), one corner 0.3 m off away from
    // the centre. The square stays symmetric about that diagonal, so the best rotation is the
    // 90° and the translation takes the mean error, 0.3 / 4: left are 0.3 · 3/4 at that corner
    // and 0.3 / 4 at the three others, Σ = 0.09 · 3/4, RMS over four 0.3 · √3 / 4.
    const std::vector<Pose> truth{Pose(0, 0, 0), Pose(1, 0, 0), Pose(1, 1, 0), Pose(0, 1, 0)};
    std::vector<Pose> estimate;
    for (const Pose& t : truth) estimate.push_back(Pose(10 - t.y(), -5 + t.x(), 0));
    estimate[2].head<2>() += 0.3 * Vec2(-1, 1) / std::sqrt(2.0);   // corner (9, -4), centre (9.5, -4.5)
    AlignedApeSums sums;
    CHECK_THROWS_AS(sums.ape(), std::invalid_argument);
    for (size_t k = 0; k < truth.size(); ++k) sums.add(estimate[k].head<2>(), truth[k].head<2>());
    const double pass = aligned_ape(estimate, truth);
    INFO("sums " << sums.ape() << ", pass " << pass);
    CHECK(sums.count() == 4);
    CHECK(std::abs(pass - 0.3 * std::sqrt(3.0) / 4) < 1e-12);
    CHECK(std::abs(sums.ape() - pass) <= 1e-9 * pass);
    // a long run: 1,500 frames of synthetic landmarks on a 1.5 km drive, its kept poses
    const auto poses = arc_poses(1500, 0.004);
    SyntheticOdometry om;
    om.sigma_dtheta = 0.004;
    const SequenceRun r = run_sequence(poses, synthesize_stereo_frames(poses, synthetic_rig(), {}, 3000, 8, 9), om,
                                       AssociationConfig{}, 11);
    const double slam_pass = aligned_ape(r.estimate, r.truth), odometry_pass = aligned_ape(r.dead_reckoning, r.truth);
    INFO("EKF-SLAM " << r.slam_metrics.ape_se2 << " against " << slam_pass << " m; odometry alone "
         << r.odometry_metrics.ape_se2 << " against " << odometry_pass << " m");
    CHECK(slam_pass > 0.01);
    CHECK(odometry_pass > slam_pass);
    CHECK(std::abs(r.slam_metrics.ape_se2 - slam_pass) <= 1e-9 * slam_pass);
    CHECK(std::abs(r.odometry_metrics.ape_se2 - odometry_pass) <= 1e-9 * odometry_pass);
}

namespace {
/// The files of a folder and their text.
std::map<std::string, std::string> folder_text(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::ifstream f(e.path(), std::ios::binary);
        out[e.path().filename().string()] = std::string(std::istreambuf_iterator<char>(f), {});
    }
    return out;
}
}  // namespace

TEST_CASE("a run's files written as frames come are write_sequence_report's, and a failed run leaves the folder as it was", "[slam]") {
    const auto poses = arc_poses(40, 0.01);
    const auto frames = synthesize_stereo_frames(poses, synthetic_rig(), {}, 300, 8, 3);
    const SequenceReportText text{"test", "none", "synthetic odometry alone", "provenance"};
    const fs::path root = fs::temp_directory_path() / ("slam_test_files_" + std::to_string(::getpid()));
    fs::remove_all(root);
    // kept, then written at the end; and written row by row, nothing kept
    SequenceRun kept = run_sequence(poses, frames, SyntheticOdometry{}, AssociationConfig{}, 5);
    for (size_t k = 0; k < kept.frame_count; ++k) kept.timestamps.push_back(0.1 * static_cast<double>(k));
    write_sequence_report(root / "kept", kept, text);
    SequenceRun streamed;
    {
        SequenceFiles files(root / "streamed");
        RunRecord record{[&files](const FrameRecord& f) {
                             FrameRecord stamped = f;
                             stamped.timestamp = 0.1 * static_cast<double>(f.frame);
                             files.add(stamped);
                         },
                         false, {}};
        streamed = run_sequence(poses, frames_of(frames), SyntheticOdometry{}, AssociationConfig{}, 5, record);
        files.commit(streamed, text);
    }
    CHECK(streamed.estimate.empty());
    CHECK(streamed.frames.empty());
    CHECK(streamed.frame_count == 40);
    CHECK(streamed.scored_frames == 40);
    CHECK(streamed.slam_metrics.ape == kept.slam_metrics.ape);
    CHECK(streamed.ape_3d_slam == kept.ape_3d_slam);
    CHECK(streamed.ape_3d_slam > 0);
    const auto a = folder_text(root / "kept"), b = folder_text(root / "streamed");
    for (const char* name : {"states.csv", "estimate_kitti.txt", "estimate_planar_kitti.txt", "dead_reckoning_kitti.txt",
                             "truth_kitti.txt", "estimate_tum.txt", "summary.json", "report.md"}) {
        INFO(name);
        REQUIRE(a.count(name));
        REQUIRE(b.count(name));
        CHECK(a.at(name) == b.at(name));
    }
    CHECK(std::count(b.at("states.csv").begin(), b.at("states.csv").end(), '\n') == 41);
    // a run failing at frame 30 into the folder of the first: its files untouched, no temporaries
    // left; into a new folder: the folder is removed
    const auto failing = [&frames, k = size_t{0}](StereoFrame& f) mutable {
        if (k == 30) throw hc::InputError("frame 30 unreadable");
        f = frames[k++];
        return true;
    };
    for (const fs::path& dir : {root / "kept", root / "new"}) {
        {
            SequenceFiles files(dir);
            CHECK_THROWS_WITH(run_sequence(poses, failing, SyntheticOdometry{}, AssociationConfig{}, 5,
                                           RunRecord{files.sink(), false, {}}),
                              Catch::Contains("frame 30"));
        }
        if (dir == root / "kept") CHECK(folder_text(dir) == a);
        else CHECK_FALSE(fs::exists(dir));
    }
    fs::remove_all(root);
}

// slam_kitti_test.cpp: the KITTI path end to end on the real ground-truth trajectory of
// sequence 01 (poses/01.txt) with synthetic stereo landmarks along it (the landmark
// pipeline's output is not used here). Exits 77 (CTest: skipped) with a message when the
// data directory holds no poses/01.txt.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>

#include "frames/frames.hpp"
#include "slam/slam.hpp"

using namespace hc::slam;

namespace {
std::filesystem::path g_poses;
}

TEST_CASE("on KITTI 01's trajectory with synthetic landmarks EKF-SLAM beats dead reckoning", "[slam][kitti]") {
    const auto poses = read_kitti_poses(g_poses);
    REQUIRE(poses.size() >= 51);
    // the top-view odometry model fits the real motion: lateral offsets stay small
    double lateral = 0;
    for (size_t k = 1; k < poses.size(); ++k) {
        const Pose a = planar_pose(poses[k - 1]), b = planar_pose(poses[k]);
        const Pose m = move(a, odometry_between(a, b), Vec2::Zero());
        lateral = std::max(lateral, (m - b).head<2>().norm());
    }
    INFO("largest lateral residual of the motion model " << lateral << " m");
    CHECK(lateral < 0.05);
    CHECK(lateral > 0.02);   // real motion is not exactly (dx, dθ): measured 0.033 m
    const auto frames = synthesize_stereo_frames(poses, StereoCamera{}, 1000, 8, 1);
    OdometryModel om;
    om.sigma_dx = 0.1;
    om.sigma_dtheta = 0.002;
    om.sigma_lateral = 0.03;   // the sideways slip measured above
    double slam_sum = 0, dr_sum = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        const SequenceRun r = run_sequence(poses, frames, om, AssociationConfig{}, seed);
        REQUIRE(r.estimate.size() == poses.size());
        slam_sum += r.ate_slam;
        dr_sum += r.ate_dead_reckoning;
        int matched = 0, observed = 0;
        for (const auto& f : r.frames) {
            matched += f.matched;
            observed += f.observed;
        }
        INFO("seed " << seed << ": ATE slam " << r.ate_slam << " m, dead reckoning " << r.ate_dead_reckoning << " m, "
             << matched << " of " << observed << " observations matched");
        CHECK(matched > observed / 2);
        int hinted = 0, agreeing = 0;
        for (const auto& f : r.frames) {
            hinted += f.matched_with_hints;
            agreeing += f.matched_agreeing;
        }
        CHECK(hinted == matched);
        CHECK(agreeing >= 0.99 * hinted);   // matches to the synthetic point that made the landmark
    }
    INFO("mean ATE over 10 odometry seeds: slam " << slam_sum / 10 << " m, dead reckoning " << dr_sum / 10 << " m");
    CHECK(slam_sum < 0.25 * dr_sum);   // measured 0.09 m against 0.55..1.07 m on seeds 1..4
    CHECK(slam_sum / 10 < 0.15);
}

int main(int argc, char** argv) {
    const auto d = hc::frames::data_dir("");
    if (!d || !std::filesystem::exists(*d / "kitti/poses/01.txt")) {
        std::printf("SKIPPED: no kitti/poses/01.txt in the data directory (set HARRIS_COSIM_DATA)\n");
        return 77;
    }
    g_poses = *d / "kitti/poses/01.txt";
    return Catch::Session().run(argc, argv);
}

// slam_kitti_test.cpp: KITTI sequence 01 end to end: synthetic landmarks along the real
// ground-truth trajectory with synthetic odometry, and the goal from the stereo camera
// alone with the command's defaults (kitti_options of a default SlamCommand: OpenCV Harris
// corners, BRIEF, visual odometry on pixel residuals with the disparity correction, EKF-SLAM;
// the poses read only to score): APE of EKF-SLAM at most visual odometry's and at most 1.5 %
// of the path, one frame per stereo pair of the data. Exits 77 (CTest: skipped) with a message when the
// data directory holds no poses/01.txt.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "io/frames/frames.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/slam/slam.hpp"
#include "mapping/slam/slam_command.hpp"

using namespace hc::slam;

namespace {
std::filesystem::path g_kitti;
}

TEST_CASE("on KITTI 01's trajectory with synthetic landmarks EKF-SLAM beats synthetic odometry alone", "[slam][kitti]") {
    const auto poses = read_kitti_poses(g_kitti / "poses/01.txt");
    REQUIRE(poses.size() >= 51);
    std::vector<Pose> truth;
    for (const auto& T : poses) truth.push_back(planar_pose(T));
    // exact 3-DoF odometry integrates to the exact trajectory
    std::vector<Motion> exact;
    for (size_t k = 1; k < truth.size(); ++k) exact.push_back(between(truth[k - 1], truth[k]));
    CHECK(absolute_trajectory_error(dead_reckoning(truth[0], exact), truth) < 1e-9);
    const auto frames = synthesize_stereo_frames(poses, synthetic_rig(), {}, 1000, 8, 1);
    double slam_sum = 0, dr_sum = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        const SequenceRun r = run_sequence(poses, frames, SyntheticOdometry{}, AssociationConfig{}, seed);
        REQUIRE(r.estimate.size() == poses.size());
        slam_sum += r.ate_slam;
        dr_sum += r.ate_dead_reckoning;
        int matched = 0, observed = 0, hinted = 0, agreeing = 0;
        for (const auto& f : r.frames) {
            matched += f.matched;
            observed += f.observed;
            hinted += f.matched_with_hints;
            agreeing += f.matched_agreeing;
        }
        INFO("seed " << seed << ": ATE slam " << r.ate_slam << " m, odometry alone " << r.ate_dead_reckoning << " m, "
             << matched << " of " << observed << " observations matched");
        CHECK(matched > observed / 2);
        CHECK(hinted == matched);
        CHECK(agreeing >= 0.99 * hinted);   // matches to the synthetic point that made the landmark
    }
    INFO("mean ATE over 10 odometry seeds: slam " << slam_sum / 10 << " m, odometry alone " << dr_sum / 10 << " m");
    CHECK(slam_sum < 0.5 * dr_sum);
}

namespace {
/// The command's defaults as the command fills them (kitti_options of a default SlamCommand:
/// OpenCV's corners, BRIEF, visual odometry on pixel residuals), without its progress lines.
KittiRunOptions command_defaults() {
    KittiRunOptions o = kitti_options(SlamCommand{});
    o.progress = nullptr;
    o.pipeline.corners.progress = false;
    return o;
}
/// The number of stereo pairs of KITTI 01 in the data.
int pairs_01() { return hc::frames::open_kitti(g_kitti, "01").pairs(); }
/// `harris-cosim slam --sequences 01` through the library: run_kitti_sequence with the command's
/// defaults, frame by frame; computed once for the test cases below.
const KittiRun& command_run_01() {
    static std::optional<KittiRun> run;
    if (!run) run = run_kitti_sequence(g_kitti, "01", command_defaults());
    return *run;
}
bool have_stereo_01() { return std::filesystem::exists(g_kitti / "sequences/01/image_1"); }
}  // namespace

TEST_CASE("on KITTI 01 from the stereo camera alone EKF-SLAM ends closer to the truth than visual odometry",
          "[slam][kitti][stereo]") {
    if (!have_stereo_01()) {
        WARN("SKIPPED: no KITTI 01 stereo pairs");
        return;
    }
    const KittiRun& kr = command_run_01();
    const SequenceRun& r = kr.run;
    const size_t pairs = static_cast<size_t>(pairs_01());
    const size_t poses = read_kitti_poses(g_kitti / "poses/01.txt").size();
    INFO("APE EKF-SLAM " << r.slam_metrics.ape << " m (" << r.slam_metrics.ape_percent() << " % of the path), visual "
         << "odometry alone " << r.odometry_metrics.ape << " m; odometry failures " << kr.vo.failures << "; disparity "
         << "correction " << (r.disparity_offset.empty() ? 0.0 : r.disparity_offset.back()) << " px; " << pairs
         << " pairs, " << poses << " poses");
    // every pair of the data is a frame; each one with a true pose is scored (the command
    // refuses a poses file of another length, so the data's two counts agree)
    CHECK(r.estimate.size() == pairs);
    CHECK(r.truth.size() == std::min(pairs, poses));
    CHECK(kr.vo.failures == 0);
    CHECK(r.slam_metrics.ape <= r.odometry_metrics.ape);
    // the goal's second half: at most 1.5 % of the path
    CHECK(r.slam_metrics.ape_percent() <= 1.5);
    // the disparity correction the odometry found without ground truth
    REQUIRE_FALSE(r.disparity_offset.empty());
    CHECK(r.disparity_offset.back() > 0.5);
}

TEST_CASE("a KITTI run frame by frame equals the run on all its pairs read at once",
          "[slam][kitti][stereo]") {
    if (!have_stereo_01()) {
        WARN("SKIPPED: no KITTI 01 stereo pairs");
        return;
    }
    const KittiRunOptions o = command_defaults();
    const auto ds = hc::landmarks::kitti_dataset(g_kitti, "01", {0, pairs_01()});
    std::vector<Pose> truth;
    for (const auto& T : read_kitti_poses(g_kitti / "poses/01.txt")) truth.push_back(planar_pose(T));
    truth.resize(std::min(truth.size(), ds.pairs.size()));
    VisualOdometryConfig vc = o.vo;
    vc.rig = ds.calib.front();
    const SequenceRun whole = run_visual_sequence(landmark_frames(ds, o.pipeline), truth, vc, o.association);
    const SequenceRun& parts = command_run_01().run;
    REQUIRE(parts.estimate.size() == whole.estimate.size());
    for (size_t k = 0; k < whole.estimate.size(); ++k) {
        INFO("frame " << k);
        CHECK(parts.estimate[k] == whole.estimate[k]);
        CHECK(parts.frames[k].matched == whole.frames[k].matched);
    }
    CHECK(parts.dead_reckoning == whole.dead_reckoning);
    CHECK(parts.slam_metrics.ape == whole.slam_metrics.ape);
}

int main(int argc, char** argv) {
    const auto d = hc::frames::data_dir("");
    if (!d || !std::filesystem::exists(*d / "kitti/poses/01.txt")) {
        std::printf("SKIPPED: no kitti/poses/01.txt in the data directory (set HARRIS_COSIM_DATA)\n");
        return 77;
    }
    g_kitti = *d / "kitti";
    return hc::test::run_catch(argc, argv);
}

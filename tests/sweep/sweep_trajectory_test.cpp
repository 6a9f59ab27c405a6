// sweep_trajectory_test.cpp: the sweep's trajectory column (visual odometry and EKF-SLAM on
// KITTI 01 from each configuration's spec-model corners) equals slam::run_kitti_sequence
// called directly, and the reports carry it. Exits 77 (CTest: skipped) with a message without
// KITTI 01's stereo pairs under the data directory ($HARRIS_COSIM_DATA, else ../shared/data).
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "mapping/slam/landmark_frames.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_report.hpp"

namespace fs = std::filesystem;
using namespace hc;
using namespace hc::sweep;

namespace {
fs::path g_kitti;
}

TEST_CASE("the sweep's trajectory column is run_kitti_sequence of each configuration, in every report", "[sweep][slam]") {
    SweepResult r;
    r.spec = parse_sweep_spec(R"({"configs": [{"name": "thesis"}, {"name": "tight-m7-b6", "m_drop": 7, "bf_sum_w": 21,
                                 "bf_drop": 6, "ktr_w": 29, "resp_w": 32}], "trajectory": {"sequence": "01"}})",
                              "t");
    REQUIRE(r.spec.trajectory.enabled);
    for (const auto& c : r.spec.configs) r.points.push_back(PointResult{c});
    r.trajectory_run = score_trajectories(r.points, g_kitti, r.spec.trajectory, false);
    CHECK_THAT(r.trajectory_run, Catch::Contains("KITTI 01: 51 stereo pairs") && Catch::Contains("orb descriptor"));
    const nlohmann::json js = nlohmann::json::parse(to_json(r));
    const std::string csv = to_csv(r), md = to_markdown(r);
    for (size_t i = 0; i < r.points.size(); ++i) {
        const PointResult& p = r.points[i];
        slam::KittiRunOptions k;
        k.stereo_landmarks = true;
        k.pipeline.detector = landmarks::Detector::spec;
        k.pipeline.descriptor = landmarks::Descriptor::orb;
        k.pipeline.corners.formats = p.config.formats;
        const slam::KittiRun direct = slam::run_kitti_sequence(g_kitti, "01", k);
        INFO(p.config.name);
        REQUIRE(p.has_trajectory);
        CHECK(p.trajectory.ape_slam == direct.run.slam_metrics.ape);
        CHECK(p.trajectory.ape_odometry == direct.run.odometry_metrics.ape);
        CHECK(p.trajectory.path_length == direct.run.slam_metrics.path_length);
        CHECK(p.trajectory.frames == 51);
        CHECK(p.trajectory.odometry_failures == direct.vo.failures);
        CHECK(js["points"][i]["trajectory"]["ape_slam_m"] == p.trajectory.ape_slam);
        CHECK(js["points"][i]["trajectory"].get<Trajectory>().odometry_failures == p.trajectory.odometry_failures);
        CHECK_THAT(csv, Catch::Contains(fmt::format("{:.6f},{:.6f},{:.6f},{},,,-\n", p.trajectory.ape_slam,
                                                    p.trajectory.ape_odometry, p.trajectory.path_length,
                                                    p.trajectory.odometry_failures)));
        CHECK_THAT(md, Catch::Contains(fmt::format(" | no | {:.3f} | {:.2f} | {:.3f} | {} |\n", p.trajectory.ape_slam,
                                                   p.trajectory.ape_percent(), p.trajectory.ape_odometry,
                                                   p.trajectory.odometry_failures)));
    }
    // the two widths give different corners, so different trajectories
    CHECK(r.points[0].trajectory.ape_slam != r.points[1].trajectory.ape_slam);
}

int main(int argc, char** argv) {
    const char* env = std::getenv("HARRIS_COSIM_DATA");
    g_kitti = (env && *env ? fs::path(env) : fs::path(HC_TEST_DATA_DIR)) / "kitti";
    if (!fs::is_directory(g_kitti / "sequences" / "01" / "image_1") || !fs::exists(g_kitti / "poses" / "01.txt")) {
        std::printf("SKIP: no KITTI 01 stereo pairs and poses under '%s' (set HARRIS_COSIM_DATA)\n", g_kitti.string().c_str());
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

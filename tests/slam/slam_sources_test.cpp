// slam_sources_test.cpp: where a run's pairs and ground truth come from, on KITTI 01's first
// six stereo pairs laid out in a temporary folder: a KITTI-layout sequence without poses (the
// trajectory written, nothing scored), with a ground truth of another length (refused naming
// both counts, or scored on the overlap with score_overlap), with a times.txt (the TUM
// timestamps), a range of its pairs (scored against their poses), and the same pairs as a
// rig's plain images with a rig file converted from calib.txt (zero distortion). Exits 77 (CTest: skipped) with a message without KITTI 01.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "io/frames/frames.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/landmarks/calib.hpp"
#include "mapping/slam/slam.hpp"

using namespace hc::slam;
namespace fs = std::filesystem;

namespace {

constexpr int kPairs = 6;
fs::path g_kitti;   // the data's KITTI root
fs::path g_work;    // this run's temporary folder

std::string text_of(const fs::path& p) {
    std::ifstream f(p);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

int lines_of(const fs::path& p) {
    std::ifstream f(p);
    std::string line;
    int n = 0;
    while (std::getline(f, line)) ++n;
    return n;
}

/// The first `lines` lines of KITTI 01's poses.
std::string poses_text(int lines) {
    std::ifstream f(g_kitti / "poses/01.txt");
    std::string line, out;
    for (int k = 0; k < lines && std::getline(f, line); ++k) out += line + "\n";
    return out;
}

/// A KITTI root `name` holding sequence 01's first kPairs pairs (links to the data's images)
/// and its calib.txt, with `poses` as poses/01.txt and `times` as times.txt when not empty.
fs::path kitti_layout(const std::string& name, const std::string& poses, const std::string& times) {
    const fs::path root = g_work / name, seq = root / "sequences/01";
    for (const char* cam : {"image_0", "image_1"}) {
        fs::create_directories(seq / cam);
        const auto src = g_kitti / "sequences/01" / cam;
        for (int k = 0; k < kPairs; ++k) {
            char file[16];
            std::snprintf(file, sizeof file, "%06d.png", k);
            fs::create_symlink(src / file, seq / cam / file);
        }
    }
    fs::copy_file(g_kitti / "sequences/01/calib.txt", seq / "calib.txt");
    if (!poses.empty()) {
        fs::create_directories(root / "poses");
        std::ofstream(root / "poses/01.txt") << poses;
    }
    if (!times.empty()) std::ofstream(seq / "times.txt") << times;
    return root;
}

/// The command's defaults (OpenCV's corners, BRIEF, visual odometry on pixels).
KittiRunOptions defaults() { return KittiRunOptions{}; }

/// The run on the kPairs pairs with the first kPairs poses, computed once.
const KittiRun& scored_run() {
    static std::optional<KittiRun> r;
    if (!r) r = run_kitti_sequence(kitti_layout("scored", poses_text(kPairs), ""), "01", defaults());
    return *r;
}

fs::path report_of(const SequenceRun& run, const std::string& name) {
    const fs::path out = g_work / ("out_" + name);
    write_sequence_report(out, run, {"test " + name, "none", "visual odometry alone", "provenance"});
    return out;
}

}  // namespace

TEST_CASE("without a ground truth the run writes its trajectory, map and report, and scores nothing", "[slam][kitti]") {
    const KittiRun r = run_kitti_sequence(kitti_layout("no_truth", "", ""), "01", defaults());
    CHECK(r.run.truth.empty());
    CHECK(r.run.estimate.size() == kPairs);
    CHECK(r.run.slam_metrics.ape == 0);
    CHECK(r.run.ape_3d_slam == 0);
    CHECK_FALSE(r.run.map.empty());
    // the estimate does not depend on the ground truth
    CHECK(r.run.estimate == scored_run().run.estimate);
    const fs::path out = report_of(r.run, "no_truth");
    CHECK(lines_of(out / "estimate_kitti.txt") == kPairs);
    CHECK(lines_of(out / "estimate_tum.txt") == kPairs);
    CHECK_FALSE(fs::exists(out / "truth_kitti.txt"));
    const auto j = nlohmann::json::parse(text_of(out / "summary.json"));
    CHECK(j["ground_truth"] == false);
    CHECK_FALSE(j.contains("ate_m"));
    CHECK(text_of(out / "report.md").find("No ground truth") != std::string::npos);
}

TEST_CASE("a ground truth of another length than the pairs is refused naming both counts", "[slam][kitti]") {
    const fs::path root = kitti_layout("short_truth", poses_text(4), "");
    CHECK_THROWS_AS(run_kitti_sequence(root, "01", defaults()), hc::InputError);
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", defaults()),
                      Catch::Contains("4 poses") && Catch::Contains("6 stereo pairs") &&
                          Catch::Contains("--score-overlap"));
    KittiRunOptions o = defaults();   // a longer --truth file, in TUM's format
    std::ostringstream tum;
    for (int k = 0; k < 9; ++k) tum << k << " 0 0 " << k << " 0 0 0 1\n";
    o.truth = g_work / "long_truth_tum.txt";
    std::ofstream(o.truth) << tum.str();
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o), Catch::Contains("9 poses") && Catch::Contains("6 stereo pairs"));
}

TEST_CASE("with score_overlap a shorter ground truth scores the frames it covers", "[slam][kitti]") {
    KittiRunOptions o = defaults();
    o.score_overlap = true;
    const KittiRun r = run_kitti_sequence(kitti_layout("overlap", poses_text(4), ""), "01", o);
    REQUIRE(r.run.estimate.size() == kPairs);   // the run is not cut
    REQUIRE(r.run.truth.size() == 4);
    const SequenceRun& full = scored_run().run;
    CHECK(r.run.estimate == full.estimate);
    const std::vector<Pose> est4(full.estimate.begin(), full.estimate.begin() + 4), truth4(full.truth.begin(), full.truth.begin() + 4);
    CHECK(r.run.slam_metrics.ape == Approx(absolute_trajectory_error(est4, truth4)).epsilon(1e-12));
    CHECK(r.run.slam_metrics.ape > 0);
    CHECK(r.run.truth_3d.size() == 4);
    const fs::path out = report_of(r.run, "overlap");
    CHECK(lines_of(out / "truth_kitti.txt") == 4);
    CHECK(lines_of(out / "estimate_kitti.txt") == kPairs);
    CHECK(text_of(out / "report.md").find("first 4 of the 6 frames") != std::string::npos);
}

TEST_CASE("pairs a:b run those stereo pairs, scored against their poses; past the sequence is refused", "[slam][kitti]") {
    KittiRunOptions o = defaults();
    o.pairs = "1:5";
    const KittiRun r = run_kitti_sequence(kitti_layout("pairs", poses_text(kPairs), ""), "01", o);
    const SequenceRun& full = scored_run().run;
    REQUIRE(full.truth.size() == kPairs);
    REQUIRE(r.run.estimate.size() == 4);
    REQUIRE(r.run.truth.size() == 4);
    // poses[1..5) in pair 1's camera frame, where the run's estimate starts (to 1e-6: the file's
    // rotations are orthonormal to its 7 digits)
    const auto poses = read_kitti_poses(g_kitti / "poses/01.txt");
    const Mat3 R1 = poses[1].leftCols<3>();
    REQUIRE(r.run.truth_3d.size() == 4);
    for (int k = 0; k < 4; ++k) {
        INFO("frame " << k);
        const Mat34& T = r.run.truth_3d[k];
        CHECK((R1 * T.leftCols<3>() - poses[k + 1].leftCols<3>()).norm() < 1e-6);
        CHECK((R1 * T.col(3) + poses[1].col(3) - poses[k + 1].col(3)).norm() < 1e-6);
        CHECK(r.run.truth[k] == planar_pose(T));
    }
    CHECK(r.run.truth_3d.front().col(3).norm() < 1e-12);
    CHECK(r.run.estimate.front().norm() == 0);   // the run starts at its first camera, as the truth now does
    CHECK(r.run.timestamps[0] == Approx(0.1));   // pair 1's time: its index times the period
    CHECK(r.run.slam_metrics.ape > 0);
    const fs::path root = g_work / "pairs";
    o.pairs = "2:";
    CHECK(run_kitti_sequence(root, "01", o).run.truth.size() == kPairs - 2);
    o.pairs = "1:9";
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o),
                      Catch::Contains("--pairs 1:9 reaches past the data") && Catch::Contains("has 6 stereo pairs"));
    o.pairs = "5:6";
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o), Catch::Contains("fewer than 2 stereo pairs in --pairs 5:6"));
    o.pairs = "4:2";
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o), Catch::Contains("--pairs '4:2' is not FIRST:LAST"));
}

TEST_CASE("the 3-D APE of the written KITTI files equals the report's, and differs from the 2-D one", "[slam][kitti]") {
    const SequenceRun& r = scored_run().run;
    REQUIRE(r.truth.size() == kPairs);
    CHECK(r.spatial_from_odometry);
    const fs::path out = report_of(r, "scored");
    const double from_files = absolute_trajectory_error_3d(read_trajectory_file(out / "estimate_kitti.txt"),
                                                           read_trajectory_file(out / "truth_kitti.txt"));
    CHECK(from_files == Approx(r.ape_3d_slam).epsilon(1e-6));
    const auto j = nlohmann::json::parse(text_of(out / "summary.json"));
    CHECK(j["ape_3d_m"]["slam"].get<double>() == Approx(from_files).epsilon(1e-6));
    CHECK(r.ape_3d_slam != r.slam_metrics.ape);
    // the estimate's height comes from the odometry: not level at height 0
    double max_height = 0;
    for (const auto& T : r.estimate_3d) max_height = std::max(max_height, std::abs(T(1, 3)));
    CHECK(max_height > 0);
}

TEST_CASE("TUM timestamps are the sequence's times.txt, or frame index times the period", "[slam][kitti]") {
    const std::vector<double> times = {0, 0.103634, 0.207269, 0.310904, 0.414538, 0.518173};
    std::ostringstream t;
    t << std::scientific;
    for (double v : times) t << v << "\n";
    const KittiRun r = run_kitti_sequence(kitti_layout("times", "", t.str()), "01", defaults());
    REQUIRE(r.run.timestamps.size() == kPairs);
    for (int k = 0; k < kPairs; ++k) CHECK(r.run.timestamps[k] == Approx(times[k]).epsilon(1e-12));
    CHECK(r.run.timestamps_from == "the sequence's times.txt");
    std::ifstream tum(report_of(r.run, "times") / "estimate_tum.txt");
    for (int k = 0; k < kPairs; ++k) {
        double stamp = -1;
        std::string rest;
        tum >> stamp;
        std::getline(tum, rest);
        CHECK(stamp == Approx(times[k]).epsilon(1e-8));
    }
    const SequenceRun& no_times = scored_run().run;
    CHECK(no_times.timestamps[3] == Approx(0.3));
    CHECK(no_times.timestamps_from.find("frame index") != std::string::npos);
    const fs::path short_times = kitti_layout("short_times", "", "0\n0.1\n");
    CHECK_THROWS_WITH(run_kitti_sequence(short_times, "01", defaults()),
                      Catch::Contains("2 timestamps") && Catch::Contains("6 frames"));
}

TEST_CASE("a TUM ground truth is paired with the frames by timestamp when the sequence has a times.txt", "[slam][kitti]") {
    const std::vector<double> times = {0, 0.103634, 0.207269, 0.310904, 0.414538, 0.518173};
    std::ostringstream t;
    t << std::setprecision(9);
    for (double v : times) t << v << "\n";
    const fs::path root = kitti_layout("tum_by_time", "", t.str());
    // KITTI 01's first poses at the frames' times give or take 4 ms, a decoy 100 m off 50 ms after
    // each, and the lines in reverse order: only the timestamps can pair them
    const auto poses = read_kitti_poses(g_kitti / "poses/01.txt");
    std::vector<Mat34> tum_poses;
    std::vector<double> tum_times;
    for (int k = 0; k < kPairs; ++k) {
        tum_poses.push_back(poses[static_cast<size_t>(k)]);
        tum_times.push_back(times[static_cast<size_t>(k)] + (k % 2 ? 0.004 : -0.004));
        Mat34 decoy = poses[static_cast<size_t>(k)];
        decoy(0, 3) += 100;
        tum_poses.push_back(decoy);
        tum_times.push_back(times[static_cast<size_t>(k)] + 0.05);
    }
    std::istringstream lines(tum_trajectory(tum_poses, tum_times));
    std::vector<std::string> rows;
    for (std::string line; std::getline(lines, line);) rows.push_back(line);
    KittiRunOptions o = defaults();
    o.truth = g_work / "tum_by_time.txt";
    {
        std::ofstream f(o.truth);
        f << "# timestamp tx ty tz qx qy qz qw\n";
        for (auto it = rows.rbegin(); it != rows.rend(); ++it) f << *it << "\n";
    }
    const KittiRun r = run_kitti_sequence(root, "01", o);
    const SequenceRun& by_file = scored_run().run;   // the same poses from poses/01.txt in file order
    REQUIRE(r.run.truth.size() == kPairs);
    CHECK(r.run.truth_pairing.find("by timestamp") != std::string::npos);
    CHECK(by_file.truth_pairing == "in file order");
    for (int k = 0; k < kPairs; ++k) {
        INFO("frame " << k);
        CHECK((r.run.truth[k] - by_file.truth[k]).norm() < 1e-6);
    }
    CHECK(r.run.slam_metrics.ape == Approx(by_file.slam_metrics.ape).margin(1e-6));
    CHECK(nlohmann::json::parse(text_of(report_of(r.run, "tum_by_time") / "summary.json"))["truth_pairing"] ==
          r.run.truth_pairing);
    // a tolerance below the 4 ms: frame 0 has no pose within it
    o.truth_time_tolerance = 0.003;
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o),
                      Catch::Contains("tum_by_time.txt") && Catch::Contains("frame 0") && Catch::Contains("0.003 s"));
    // a ground truth that ends after frame 3 (4 ms tolerance kept): frame 4 refused, or the
    // first 4 frames scored with score_overlap
    o.truth_time_tolerance = 0.02;
    o.truth = g_work / "tum_first_four.txt";
    std::ofstream(o.truth) << tum_trajectory(std::vector<Mat34>(tum_poses.begin(), tum_poses.begin() + 8),
                                             std::vector<double>(tum_times.begin(), tum_times.begin() + 8));
    CHECK_THROWS_WITH(run_kitti_sequence(root, "01", o), Catch::Contains("frame 4") && Catch::Contains("--score-overlap"));
    o.score_overlap = true;
    const KittiRun four = run_kitti_sequence(root, "01", o);
    CHECK(four.run.truth.size() == 4);
    CHECK(four.run.estimate.size() == kPairs);
    // without a times.txt the same TUM file is paired in file order: 12 poses for 6 pairs
    o.score_overlap = false;
    o.truth = g_work / "tum_by_time.txt";
    CHECK_THROWS_WITH(run_kitti_sequence(kitti_layout("tum_no_times", "", ""), "01", o),
                      Catch::Contains("12 poses") && Catch::Contains("6 stereo pairs"));
}

TEST_CASE("a rig's plain images with a rig file from calib.txt give the KITTI-layout run, pair by pair", "[slam][kitti]") {
    // the rig: calib.txt's rectified pair as calibrate's YAML, zero distortion, identity
    // rotations, marked unrectified so that every keypoint goes through cv::undistortPoints
    hc::landmarks::Calibration c = hc::landmarks::read_kitti_calib(g_kitti / "sequences/01/calib.txt");
    c.rectified_input = false;
    c.rectified.width = 1241;
    c.rectified.height = 376;
    const fs::path rig_file = g_work / "rig.yml";
    std::ofstream(rig_file) << hc::landmarks::to_opencv_storage(c, false);
    const fs::path left = g_work / "rig_left", right = g_work / "rig_right";
    fs::create_directories(left);
    fs::create_directories(right);
    for (int k = 0; k < kPairs; ++k) {
        char file[16];
        std::snprintf(file, sizeof file, "%06d.png", k);
        fs::copy_file(g_kitti / "sequences/01/image_0" / file, left / file);
        fs::copy_file(g_kitti / "sequences/01/image_1" / file, right / file);
    }
    KittiRunOptions o = defaults();
    o.truth = g_work / "rig_truth.txt";
    std::ofstream(o.truth) << poses_text(kPairs);
    const KittiRun rig = run_rig_sequence({rig_file.string(), {left.string()}, {(right / "*.png").string()}}, o);
    const SequenceRun& kitti = scored_run().run;
    REQUIRE(rig.run.estimate.size() == kitti.estimate.size());
    REQUIRE(rig.run.truth.size() == kPairs);
    // undistortPoints with zero distortion moves a keypoint by float rounding only (cv::Point2f):
    // the landmarks, and with them the poses, agree to well under a millimetre
    double worst = 0;
    for (size_t k = 0; k < kitti.estimate.size(); ++k)
        worst = std::max(worst, (rig.run.estimate[k] - kitti.estimate[k]).head<2>().norm());
    INFO("largest position difference " << worst << " m; APE rig " << rig.run.slam_metrics.ape << " m, KITTI layout "
         << kitti.slam_metrics.ape << " m");
    CHECK(worst < 1e-3);
    CHECK(rig.run.slam_metrics.ape == Approx(kitti.slam_metrics.ape).margin(1e-3));
    CHECK(rig.run.timestamps_from.find("frame index") != std::string::npos);
    // read pair by pair, the same bits as the pairs read all at once (landmarks::open_dataset)
    // and run through the filter held (run_visual_sequence), on OpenCV's corners and the spec
    // model's (whose threshold is carried from pair to pair)
    for (const auto corners : {hc::landmarks::Detector::opencv, hc::landmarks::Detector::spec}) {
        KittiRunOptions oc = o;
        oc.pipeline.detector = corners;
        hc::landmarks::DatasetChoice choice;
        choice.rig.calib = rig_file.string();
        choice.rig.left = {left.string()};
        choice.rig.right = {(right / "*.png").string()};
        fs::path root;
        const hc::landmarks::Dataset ds = hc::landmarks::open_dataset(choice, root);
        VisualOdometryConfig vo = oc.vo;
        vo.rig = ds.calib.front();
        std::vector<Pose> planar;
        for (const auto& T : read_trajectory_file(oc.truth)) planar.push_back(planar_pose(T));
        const SequenceRun held = run_visual_sequence(landmark_frames(ds, oc.pipeline), planar, vo, oc.association);
        const SequenceRun streamed = run_rig_sequence({rig_file.string(), {left.string()}, {(right / "*.png").string()}}, oc).run;
        INFO("corners " << hc::landmarks::detector_name(corners));
        REQUIRE(streamed.estimate.size() == held.estimate.size());
        for (size_t k = 0; k < held.estimate.size(); ++k) {
            CHECK(streamed.estimate[k] == held.estimate[k]);
            CHECK(streamed.pose_cov[k] == held.pose_cov[k]);
            CHECK(streamed.estimate_3d[k] == held.estimate_3d[k]);
            CHECK(streamed.frames[k].observed == held.frames[k].observed);
        }
        CHECK(streamed.slam_metrics.ape == held.slam_metrics.ape);
        CHECK(streamed.odometry_metrics.ape == held.odometry_metrics.ape);
    }
    // pairs a:b of the rig's lists, scored against the poses of those pairs
    KittiRunOptions op = o;
    op.pairs = "2:6";
    const KittiRun part = run_rig_sequence({rig_file.string(), {left.string()}, {right.string()}}, op);
    REQUIRE(part.run.truth_3d.size() == 4);
    REQUIRE(rig.run.truth_3d.size() == kPairs);
    const Mat34& P2 = rig.run.truth_3d[2];
    for (int k = 0; k < 4; ++k) {   // poses[2..6) in pair 2's camera frame
        const Mat34& T = part.run.truth_3d[k];
        CHECK((P2.leftCols<3>() * T.col(3) + P2.col(3) - rig.run.truth_3d[k + 2].col(3)).norm() < 1e-6);
    }
    op.pairs = "0:7";
    CHECK_THROWS_WITH(run_rig_sequence({rig_file.string(), {left.string()}, {right.string()}}, op),
                      Catch::Contains("--pairs 0:7 reaches past the data: the rig's --left/--right has 6 stereo pairs"));
    // the rig without its calibration, and a left list of another length, are refused
    CHECK_THROWS_WITH(run_rig_sequence({"", {left.string()}, {right.string()}}, o), Catch::Contains("--calib"));
    CHECK_THROWS_WITH(run_rig_sequence({rig_file.string(), {left.string()}, {(right / "00000[0-2].png").string()}}, o),
                      Catch::Contains("6 left images but 3 right images"));
}

int main(int argc, char** argv) {
    const auto d = hc::frames::data_dir("");
    if (!d || !fs::exists(*d / "kitti/poses/01.txt") || !fs::exists(*d / "kitti/sequences/01/image_1/000005.png")) {
        std::printf("SKIPPED: no KITTI 01 stereo pairs and poses in the data directory (set HARRIS_COSIM_DATA)\n");
        return 77;
    }
    g_kitti = *d / "kitti";
    g_work = fs::temp_directory_path() / ("slam_sources_test_" + std::to_string(::getpid()));
    fs::remove_all(g_work);
    fs::create_directories(g_work);
    const int rc = hc::test::run_catch(argc, argv);
    fs::remove_all(g_work);
    return rc;
}

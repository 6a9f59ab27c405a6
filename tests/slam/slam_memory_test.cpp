// slam_memory_test.cpp: the frame-by-frame SLAM run's memory on long streams (label slow).
// A stream of 2N frames runs through the library (visual odometry and the filter,
// run_visual_stream) with a source that reads this process's resident set (/proc/self/status
// VmRSS) when frame N and frame 2N are asked for; at the end the peak (VmHWM) must be under
// 512 MB and the resident set after 2N frames within kFlatMb of the one after N. The run keeps
// no per-frame record (RunRecord::keep false, as the command runs): its metrics and counts are
// running sums.
//  - real pairs: KITTI 01's stereo pairs cycled (pair k is pair k mod the sequence's pair count,
//    loaded as reached), the command's defaults with the spec corner source (1,600 pairs) and
//    the cycle model's (200 pairs: one host-driver stream, its threshold carried across frames),
//    and, run by hand (`slam_memory_tests "[memory][rtl]"`), the netlist's (200 pairs);
//  - synthetic: sequence 00's 4,541 poses with synthetic landmarks (N = 2,270).
// Each case runs alone in its own ctest process (the peak is the process's). Exits 77 (skipped)
// without the data.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include "io/frames/frames.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/slam/trajectory.hpp"

using namespace hc;

namespace {

constexpr double kBoundMb = 512;
constexpr double kFlatMb = 16;

/// A field of /proc/self/status in MB (VmRSS: now, VmHWM: the peak).
double status_mb(const std::string& field) {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind(field + ":", 0) == 0) {
            std::istringstream ss(line.substr(field.size() + 1));
            double kb = 0;
            ss >> kb;
            return kb / 1024.0;
        }
    FAIL("no " << field << " in /proc/self/status");
    return 0;
}

struct Sampled {
    double at_n = 0, at_2n = 0;
    size_t frames = 0;
};

/// `source` with the resident set read when frame n and frame 2n (1-based) have been given out.
slam::FrameSource sampled(slam::FrameSource source, size_t n, Sampled& s) {
    return [source = std::move(source), n, &s](slam::StereoFrame& f) {
        if (!source(f)) return false;
        ++s.frames;
        if (s.frames == n) s.at_n = status_mb("VmRSS");
        if (s.frames == 2 * n) s.at_2n = status_mb("VmRSS");
        return true;
    };
}

void check_flat(const Sampled& s, size_t n, const char* what) {
    const double peak = status_mb("VmHWM");
    std::printf("%s: %zu frames; resident after %zu frames %.1f MB, after %zu %.1f MB; peak %.1f MB\n", what, s.frames, n,
                s.at_n, 2 * n, s.at_2n, peak);
    CHECK(s.frames == 2 * n);
    CHECK(peak <= kBoundMb);
    CHECK(s.at_2n - s.at_n <= kFlatMb);
}

std::filesystem::path kitti_root() {
    const auto d = frames::data_dir("");
    return d ? *d / "kitti" : std::filesystem::path();
}

slam::VisualOdometryConfig odometry(const landmarks::RectifiedRig& rig) {
    slam::VisualOdometryConfig vc;
    vc.rig = rig;
    return vc;
}


/// KITTI 01's stereo pairs cycled to 2n pairs (pair k is pair k mod the sequence's pair count,
/// loaded as reached) through corner source `d` and the command's defaults otherwise.
void check_cycled_kitti(landmarks::Detector d, size_t n) {
    const auto kitti = kitti_root();
    const int pairs = frames::open_kitti(kitti, "01").pairs();
    REQUIRE(pairs > 1);
    const landmarks::RectifiedRig rig = landmarks::kitti_dataset(kitti, "01", {0, 1}).calib.front();
    landmarks::PipelineOptions po = slam::kitti_pipeline_defaults();
    po.detector = d;
    slam::FrameSource source = slam::landmark_stream(
        static_cast<int>(2 * n),
        [kitti, pairs](int k) { return landmarks::kitti_dataset(kitti, "01", {k % pairs, k % pairs + 1}).pairs.front(); },
        rig, po);
    Sampled s;
    const slam::SequenceRun run = slam::run_visual_stream(sampled(std::move(source), n, s), {}, odometry(rig),
                                                          slam::AssociationConfig{}, nullptr, {{}, false, {}});
    CHECK(run.frame_count == 2 * n);
    CHECK(run.estimate.empty());
    const std::string what = landmarks::detector_name(d) + " source, KITTI 01 cycled";
    check_flat(s, n, what.c_str());
}

}  // namespace

TEST_CASE("spec corners on KITTI 01's pairs cycled: peak under 512 MB, flat from N to 2N frames", "[memory][real]") {
    check_cycled_kitti(landmarks::Detector::spec, 800);
}

TEST_CASE("cycle-model corners on KITTI 01's pairs cycled: peak under 512 MB, flat from N to 2N frames",
          "[memory][cycle]") {
    // the cycle model streams about 5 pairs a second: 200 pairs, N = 100
    check_cycled_kitti(landmarks::Detector::cycle, 100);
}

// Not in the test suite (hidden, "[.]"; run it by its tags): the netlist streams about 0.5 pairs
// a second, so its 2N = 200 pairs take about 7 minutes beside the suite's time budget.
TEST_CASE("rtl corners on KITTI 01's pairs cycled: peak under 512 MB, flat from N to 2N frames", "[.][memory][rtl]") {
    check_cycled_kitti(landmarks::Detector::rtl, 100);
}

TEST_CASE("synthetic landmarks on sequence 00's 4,541 poses: peak under 512 MB, flat from N to 2N frames",
          "[memory][synthetic]") {
    const std::vector<slam::Mat34> poses = slam::read_kitti_poses(frames::kitti_poses_file(kitti_root(), "00"));
    REQUIRE(poses.size() == 4541);
    const size_t n = poses.size() / 2;
    std::vector<slam::Mat34> used(poses.begin(), poses.begin() + static_cast<long>(2 * n));
    auto synthetic = std::make_shared<slam::SyntheticFrames>(used, slam::synthetic_rig(), landmarks::PixelNoise{}, 1000, 8, 1);
    std::vector<slam::Pose> truth;
    for (const auto& T : used) truth.push_back(slam::planar_pose(T));
    Sampled s;
    const slam::SequenceRun run = slam::run_visual_stream(
        sampled([synthetic](slam::StereoFrame& f) { return synthetic->next(f); }, n, s), truth,
        odometry(slam::synthetic_rig()), slam::AssociationConfig{}, nullptr, {{}, false, used});
    CHECK(run.slam_metrics.path_length > 0);
    CHECK(run.ape_3d_slam > 0);
    CHECK(run.estimate.empty());
    check_flat(s, n, "synthetic landmarks, sequence 00");
}

int main(int argc, char** argv) {
    const auto kitti = kitti_root();
    if (kitti.empty() || !std::filesystem::exists(kitti / "sequences/01/image_1") ||
        !std::filesystem::exists(frames::kitti_poses_file(kitti, "00"))) {
        std::printf("SKIPPED: no KITTI 01 stereo pairs or sequence 00's poses in the data directory\n");
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

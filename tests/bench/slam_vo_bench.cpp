// slam_vo_bench.cpp: one frame of the stereo SLAM front and back end after corner detection,
// on KITTI 01's 1241x376 stereo pairs (ORB and the grid descriptor on OpenCV's Harris
// corners, computed once before timing): description and stereo matching of the pair
// (landmarks::match_pair), triangulation (landmarks_from), visual odometry against the
// previous frame (estimate_motion) and the filter step (prediction, gating, association,
// corrections, new landmarks). One thread (cv::setNumThreads(1)). The filter's own part is
// also timed with nearest-neighbour association, the peer of JCBB in the same run, and with
// visual odometry on the top view, the peer of the pixel residuals.
// Without the data (HARRIS_COSIM_DATA or the build's data directory holding kitti/) the
// benchmarks report an error and skip.
#include <benchmark/benchmark.h>

#include <chrono>
#include <optional>

#include <opencv2/core/utility.hpp>

#include "io/frames/frames.hpp"
#include "slam/landmarks/landmarks.hpp"
#include "slam/landmark_frames.hpp"
#include "slam/slam.hpp"

using namespace hc;

namespace {

struct Kitti {
    landmarks::Dataset ds;
    std::vector<landmarks::PairKeypoints> kp;
};

const Kitti* kitti() {
    static std::optional<Kitti> k;
    static bool tried = false;
    if (!tried) {
        tried = true;
        const auto d = frames::data_dir("");
        if (d && std::filesystem::exists(*d / "kitti/sequences/01/image_1")) {
            Kitti x;
            x.ds = landmarks::kitti_dataset(*d / "kitti", "01", {0, 51});
            x.kp = landmarks::detect_dataset(x.ds, landmarks::Detector::opencv);
            k = std::move(x);
        }
    }
    return k ? &*k : nullptr;
}

/// The data on one thread, or an error on `state` (nullptr) without it.
const Kitti* setup(benchmark::State& state) {
    cv::setNumThreads(1);
    const Kitti* k = kitti();
    if (!k) state.SkipWithError("no KITTI 01 stereo pairs in the data directory");
    return k;
}

/// Pair f described, matched and triangulated: the filter's frame.
slam::StereoFrame landmark_frame(const Kitti& k, size_t f, const landmarks::PipelineOptions& po) {
    const auto r = landmarks::match_pair(k.ds.pairs[f], k.kp[f], po.descriptor, po.grid, po.match);
    slam::StereoFrame cur;
    for (const auto& l : landmarks::landmarks_from(r, k.ds.calib[f], po)) cur.push_back(slam::to_observation(l));
    return cur;
}

/// Frames 0..n: everything after corner detection, frame by frame, timed per frame.
void BM_frame_after_corners(benchmark::State& state, landmarks::Descriptor descriptor,
                            slam::AssociationMethod method, slam::OdometryResidual residual) {
    const Kitti* k = setup(state);
    if (!k) return;
    landmarks::PipelineOptions po;
    po.descriptor = descriptor;
    slam::AssociationConfig ac;
    ac.method = method;
    slam::VisualOdometryConfig vc;
    vc.residual = residual;
    vc.rig = k->ds.calib.front();
    const int n = static_cast<int>(k->ds.pairs.size());
    double frames = 0;
    for (auto _ : state) {
        slam::LandmarkSlam filter(slam::Pose::Zero(), ac);
        slam::StereoFrame prev;
        slam::Motion last = slam::Motion::Zero();
        for (int f = 0; f < n; ++f) {
            slam::StereoFrame cur = landmark_frame(*k, static_cast<size_t>(f), po);
            if (f == 0) {
                filter.first_frame(cur);
            } else {
                const slam::MotionEstimate e = slam::estimate_motion(prev, cur, vc);
                if (e.ok) last = e.u;
                filter.next_frame(last, e.ok ? e.cov : slam::Mat3::Identity(), cur);
            }
            prev = std::move(cur);
        }
        benchmark::DoNotOptimize(filter.filter().pose());
        frames += n;
    }
    state.counters["ms_per_frame"] = benchmark::Counter(frames / 1000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// The filter and odometry alone on the frames' landmarks (description and matching done
/// before timing): visual odometry + prediction + association + corrections.
void BM_vo_and_filter(benchmark::State& state, landmarks::Descriptor descriptor, slam::AssociationMethod method,
                      slam::OdometryResidual residual) {
    const Kitti* k = setup(state);
    if (!k) return;
    landmarks::PipelineOptions po;
    po.descriptor = descriptor;
    std::vector<slam::StereoFrame> frames;
    for (size_t f = 0; f < k->ds.pairs.size(); ++f) frames.push_back(landmark_frame(*k, f, po));
    slam::AssociationConfig ac;
    ac.method = method;
    slam::VisualOdometryConfig vc;
    vc.residual = residual;
    vc.rig = k->ds.calib.front();
    double count = 0;
    for (auto _ : state) {
        slam::LandmarkSlam filter(slam::Pose::Zero(), ac);
        filter.first_frame(frames[0]);
        slam::Motion last = slam::Motion::Zero();
        for (size_t f = 1; f < frames.size(); ++f) {
            const slam::MotionEstimate e = slam::estimate_motion(frames[f - 1], frames[f], vc);
            if (e.ok) last = e.u;
            filter.next_frame(last, e.ok ? e.cov : slam::Mat3::Identity(), frames[f]);
        }
        benchmark::DoNotOptimize(filter.filter().pose());
        count += static_cast<double>(frames.size() - 1);
    }
    state.counters["ms_per_frame"] = benchmark::Counter(count / 1000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(BM_frame_after_corners, orb_jcbb, landmarks::Descriptor::orb, slam::AssociationMethod::Jcbb,
                  slam::OdometryResidual::pixels)
    ->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_frame_after_corners, grid_jcbb, landmarks::Descriptor::grid, slam::AssociationMethod::Jcbb,
                  slam::OdometryResidual::pixels)
    ->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_vo_and_filter, orb_jcbb, landmarks::Descriptor::orb, slam::AssociationMethod::Jcbb, slam::OdometryResidual::pixels)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_vo_and_filter, orb_jcbb_top_view, landmarks::Descriptor::orb, slam::AssociationMethod::Jcbb, slam::OdometryResidual::top_view)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_vo_and_filter, orb_nearest, landmarks::Descriptor::orb, slam::AssociationMethod::Nearest,
                  slam::OdometryResidual::pixels)
    ->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_vo_and_filter, grid_jcbb, landmarks::Descriptor::grid, slam::AssociationMethod::Jcbb, slam::OdometryResidual::pixels)
    ->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();

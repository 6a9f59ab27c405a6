// slam_vo_bench.cpp: the stereo SLAM front and back end after corner detection, per frame,
// on KITTI 01's 51 stereo pairs (1241x376), with OpenCV's Harris corners computed once before
// timing: description and stereo matching of each pair (landmarks::match_pair),
// triangulation (landmarks_from), then the `slam` command's run (run_visual_sequence at its
// configurations' defaults: visual odometry, disparity correction, levelled frames, the
// filter's prediction, gating, association, corrections and new landmarks). One thread
// (cv::setNumThreads(1)). Peers in the same run: the descriptors (the command's BRIEF, ORB,
// the thesis's grid), nearest-neighbour association against JCBB, and visual odometry on
// the top view against the pixel residuals. Long streams, frame by frame: sequence 00's 4,541
// poses with synthetic landmarks streamed against the same frames held (the peer), and KITTI
// 01's pairs cycled to 510 through the spec corner source (its model on all cores) against 51
// (the peer: per-frame time that does not grow with the stream).
// Without the data (HARRIS_COSIM_DATA or the build's data directory holding kitti/) the
// benchmarks report an error and skip.
#include <benchmark/benchmark.h>

#include <initializer_list>
#include <optional>
#include <string>

#include <opencv2/core/utility.hpp>

#include "io/frames/frames.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/slam/slam.hpp"

using namespace hc;

namespace {

struct Kitti {
    landmarks::Dataset ds;
    std::vector<landmarks::PairKeypoints> kp;
    std::vector<slam::Pose> truth;   ///< the run's scores need it; nothing timed reads it
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
            const auto poses = slam::read_kitti_poses(frames::kitti_poses_file(*d / "kitti", "01"));
            for (size_t f = 0; f < x.ds.pairs.size() && f < poses.size(); ++f) x.truth.push_back(slam::planar_pose(poses[f]));
            if (x.truth.size() == x.ds.pairs.size()) k = std::move(x);
        }
    }
    return k ? &*k : nullptr;
}

/// The data on one thread, or an error on `state` (nullptr) without it.
const Kitti* setup(benchmark::State& state) {
    cv::setNumThreads(1);
    const Kitti* k = kitti();
    if (!k) state.SkipWithError("no KITTI 01 stereo pairs and poses in the data directory");
    return k;
}

/// Every pair described, matched and triangulated from its corners: the filter's frames.
std::vector<slam::StereoFrame> landmark_frames(const Kitti& k, const landmarks::PipelineOptions& po) {
    return slam::landmark_frames(k.ds, k.kp, po);
}

slam::AssociationConfig association(slam::AssociationMethod method) {
    slam::AssociationConfig ac;
    ac.method = method;
    return ac;
}

slam::VisualOdometryConfig odometry(const Kitti& k, slam::OdometryResidual residual) {
    slam::VisualOdometryConfig vc;
    vc.residual = residual;
    vc.rig = k.ds.calib.front();
    return vc;
}

void report_per_frame(benchmark::State& state, double frames) {
    state.counters["ms_per_frame"] = benchmark::Counter(frames / 1000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// Everything after corner detection for the 51 frames: description and stereo matching,
/// triangulation, then the command's run (run_visual_sequence: visual odometry, disparity
/// correction, levelling, the filter's steps); per frame.
void BM_frame_after_corners(benchmark::State& state, landmarks::Descriptor descriptor,
                            slam::AssociationMethod method, slam::OdometryResidual residual) {
    const Kitti* k = setup(state);
    if (!k) return;
    landmarks::PipelineOptions po = slam::kitti_pipeline_defaults();
    po.descriptor = descriptor;
    const slam::AssociationConfig ac = association(method);
    const slam::VisualOdometryConfig vc = odometry(*k, residual);
    double frames = 0;
    for (auto _ : state) {
        const slam::SequenceRun run = slam::run_visual_sequence(landmark_frames(*k, po), k->truth, vc, ac);
        benchmark::DoNotOptimize(run.estimate.back());
        frames += static_cast<double>(k->truth.size());
    }
    report_per_frame(state, frames);
}

/// The command's run alone on the frames' landmarks (description and matching done before
/// timing): visual odometry, disparity correction, levelling, prediction, association,
/// corrections, per step.
void BM_vo_and_filter(benchmark::State& state, landmarks::Descriptor descriptor, slam::AssociationMethod method,
                      slam::OdometryResidual residual) {
    const Kitti* k = setup(state);
    if (!k) return;
    landmarks::PipelineOptions po = slam::kitti_pipeline_defaults();
    po.descriptor = descriptor;
    const std::vector<slam::StereoFrame> frames = landmark_frames(*k, po);
    const slam::AssociationConfig ac = association(method);
    const slam::VisualOdometryConfig vc = odometry(*k, residual);
    double steps = 0;
    for (auto _ : state) {
        const slam::SequenceRun run = slam::run_visual_sequence(frames, k->truth, vc, ac);
        benchmark::DoNotOptimize(run.estimate.back());
        steps += static_cast<double>(frames.size() - 1);
    }
    report_per_frame(state, steps);
}

/// The frame-by-frame run on a long stream, per frame: sequence 00's first `range(0)` poses with
/// synthetic landmarks, visual odometry and the filter; streamed (frames drawn as read,
/// SyntheticFrames, run_visual_stream), or with `range(1)` set the peer that holds them (all
/// frames drawn first, synthesize_stereo_frames, then run_visual_sequence).
void BM_synthetic_00(benchmark::State& state) {
    cv::setNumThreads(1);
    const auto d = frames::data_dir("");
    const auto poses_file = d ? frames::kitti_poses_file(*d / "kitti", "00") : std::filesystem::path();
    if (!d || !std::filesystem::exists(poses_file)) {
        state.SkipWithError("no sequence 00 poses in the data directory");
        return;
    }
    std::vector<slam::Mat34> poses = slam::read_kitti_poses(poses_file);
    poses.resize(std::min(poses.size(), static_cast<size_t>(state.range(0))));
    std::vector<slam::Pose> truth;
    for (const auto& T : poses) truth.push_back(slam::planar_pose(T));
    slam::VisualOdometryConfig vc;
    vc.rig = slam::synthetic_rig();
    double frames = 0;
    for (auto _ : state) {
        if (state.range(1)) {
            const auto held = slam::synthesize_stereo_frames(poses, *vc.rig, landmarks::PixelNoise{}, 1000, 8, 1);
            benchmark::DoNotOptimize(slam::run_visual_sequence(held, truth, vc, slam::AssociationConfig{}).estimate.back());
        } else {
            slam::SyntheticFrames synthetic(poses, *vc.rig, landmarks::PixelNoise{}, 1000, 8, 1);
            const slam::SequenceRun run = slam::run_visual_stream(
                [&](slam::StereoFrame& f) { return synthetic.next(f); }, truth, vc, slam::AssociationConfig{});
            benchmark::DoNotOptimize(run.estimate.back());
        }
        frames += static_cast<double>(poses.size());
    }
    report_per_frame(state, frames);
}

/// The streamed run on real pairs, per frame: KITTI 01's 51 pairs cycled to `range(0)` pairs (51:
/// the peer of 510, the same pairs once) (pair k is pair k mod
/// 51, loaded as reached), the spec corner source (its threshold carried across pairs) and
/// everything after it (landmark_stream, run_visual_stream); per frame.
void BM_stream_spec_01_cycled(benchmark::State& state) {
    const Kitti* k = setup(state);
    if (!k) return;
    const auto root = *frames::data_dir("") / "kitti";
    landmarks::PipelineOptions po = slam::kitti_pipeline_defaults();
    po.detector = landmarks::Detector::spec;
    const int n = static_cast<int>(state.range(0));
    const slam::VisualOdometryConfig vc = odometry(*k, slam::OdometryResidual::pixels);
    double frames = 0;
    for (auto _ : state) {
        const slam::FrameSource pairs = slam::landmark_stream(
            n, [root](int p) { return landmarks::kitti_dataset(root, "01", {p % 51, p % 51 + 1}).pairs.front(); },
            *vc.rig, po);
        const slam::SequenceRun run = slam::run_visual_stream(pairs, {}, vc, slam::AssociationConfig{});
        benchmark::DoNotOptimize(run.estimate.back());
        frames += n;
    }
    report_per_frame(state, frames);
}

/// A peer of the benchmarks after corners: its name after the benchmark's and a slash, its
/// descriptor, association and odometry residual.
struct Peer {
    const char* name;
    landmarks::Descriptor descriptor;
    slam::AssociationMethod method;
    slam::OdometryResidual residual;
};
using AfterCorners = void (*)(benchmark::State&, landmarks::Descriptor, slam::AssociationMethod,
                              slam::OdometryResidual);

/// Registers `bench` once per peer as `<name>/<peer>`, `iterations` iterations each, in ms.
void register_peers(const char* name, AfterCorners bench, std::initializer_list<Peer> peers, int iterations) {
    for (const Peer& p : peers)
        benchmark::RegisterBenchmark((std::string(name) + "/" + p.name).c_str(),
                                     [bench, p](benchmark::State& st) { bench(st, p.descriptor, p.method, p.residual); })
            ->Unit(benchmark::kMillisecond)
            ->Iterations(iterations);
}

}  // namespace

BENCHMARK(BM_synthetic_00)->Args({4541, 0})->Args({4541, 1})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_stream_spec_01_cycled)->Arg(51)->Arg(510)->Unit(benchmark::kMillisecond)->Iterations(1);

// The descriptor, association and residual peers, after the two streams above.
int main(int argc, char** argv) {
    using D = landmarks::Descriptor;
    using A = slam::AssociationMethod;
    using R = slam::OdometryResidual;
    register_peers("BM_frame_after_corners", BM_frame_after_corners,
                   {{"orb_jcbb", D::orb, A::Jcbb, R::pixels}, {"grid_jcbb", D::grid, A::Jcbb, R::pixels}}, 2);
    register_peers("BM_vo_and_filter", BM_vo_and_filter,
                   {{"brief_jcbb", D::brief, A::Jcbb, R::pixels},
                    {"orb_jcbb", D::orb, A::Jcbb, R::pixels},
                    {"orb_jcbb_top_view", D::orb, A::Jcbb, R::top_view},
                    {"orb_nearest", D::orb, A::Nearest, R::pixels},
                    {"grid_jcbb", D::grid, A::Jcbb, R::pixels}},
                   3);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

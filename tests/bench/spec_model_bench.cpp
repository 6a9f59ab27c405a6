// spec_model_bench.cpp: time per frame of the spec model (response + threshold + strict
// NMS) against OpenCV's reference (cornerHarris + threshold + dilate NMS) on the same
// 1241x376 frame, one thread each, and the ratio spec/OpenCV (goal: <= 0.5).
// Frame: KITTI 01 image_0/000000.png from the data directory (--data via
// $HARRIS_COSIM_DATA, else the build default); a generated 1241x376 frame when absent.
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include <cstdio>
#include <filesystem>

#include "io/frames/frames.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/spec/spec_model.hpp"

namespace {

hc::Image g_frame;
std::string g_frame_name;

void load_frame() {
    if (auto d = hc::frames::data_dir(""); d) {
        const auto p = *d / "kitti/sequences/01/image_0/000000.png";
        if (std::filesystem::exists(p)) {
            g_frame = hc::frames::load_image(p);
            g_frame_name = p.string();
            return;
        }
    }
    g_frame = hc::make_pattern(hc::Pattern::blocks, 1241, 376, 0);
    g_frame_name = "generated 1241x376 'blocks' pattern (no KITTI data found)";
}

void BM_spec_model(benchmark::State& st) {
    const hc::spec::SpecModel m;
    hc::spec::Response r;
    std::vector<std::uint8_t> mask;
    for (auto _ : st) {
        m.response(g_frame, r);
        m.corners(r, m.threshold_for(r.max), mask);
        benchmark::DoNotOptimize(mask.data());
    }
}

void BM_opencv_reference(benchmark::State& st) {
    const hc::spec::ReferenceOptions o;
    std::vector<std::uint8_t> mask;
    for (auto _ : st) {
        hc::spec::opencv_corners(g_frame, o, mask);
        benchmark::DoNotOptimize(mask.data());
    }
}

BENCHMARK(BM_spec_model)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_opencv_reference)->Unit(benchmark::kMillisecond)->UseRealTime();

// Collects the two timings to print their ratio after the run.
class RatioReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const auto& r : runs)
            if (r.run_type == Run::RT_Iteration && r.iterations > 0) {
                const double t = r.GetAdjustedRealTime();
                if (r.benchmark_name().find("spec") != std::string::npos) spec_ = t;
                else if (r.benchmark_name().find("opencv") != std::string::npos) cv_ = t;
            }
        ConsoleReporter::ReportRuns(runs);
    }
    double spec_ = 0, cv_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    cv::setNumThreads(1);   // one thread each (the spec model's per-frame calls are serial)
    load_frame();
    std::printf("frame: %s (%dx%d)\n", g_frame_name.c_str(), g_frame.width, g_frame.height);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    RatioReporter rep;
    benchmark::RunSpecifiedBenchmarks(&rep);
    benchmark::Shutdown();
    if (rep.spec_ > 0 && rep.cv_ > 0)
        std::printf("spec/OpenCV time per frame: %.3f ms / %.3f ms = %.3f (goal <= 0.5)\n", rep.spec_,
                    rep.cv_, rep.spec_ / rep.cv_);
    return 0;
}

// features_bench.cpp: descriptor extraction + stereo matching per stereo pair, one thread:
// the grid descriptor (thesis variant, g = 16, h = 3: the thesis's Harris choice; and the
// corrected variant) against BRIEF (the authors' 9 x 9 box smoothing over an integral image,
// and the paper's 9 x 9 Gaussian), each followed by the same brute-force Hamming matcher
// (hc::landmarks::match_stereo: 2-NN both ways, symmetry, printed ratio test, |dy| < 5), on
// the same keypoints, in the same run. Goal: grid + matching faster than BRIEF + matching
// (thesis Tables 9-10: 1.72-1.88 times slower on a PC), measured by BM_grid_vs_brief_interleaved
// (the three chains one after the other in every iteration: robust to a changing machine
// load). Also each chain and stage alone, FREAK, and grid extraction against the keypoint count.
// Pair: KITTI 01 pair 0 from the data directory ($HARRIS_COSIM_DATA, else the build
// default), else opencv-doc's aloeL/aloeR; keypoints: the 1,000 strongest Harris corners
// per image at least 28 px inside it (BRIEF's margin), so every descriptor sees the same ones.
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "mapping/landmarks/descriptors.hpp"
#include "tests/landmarks/stereo_sample.hpp"

namespace {

using namespace hc::landmarks;

hc::features_test::StereoSample g_pair;

struct Described {
    cv::Mat l, r;
};

Described describe(cv::Feature2D& f) {
    Described d;
    auto kl = g_pair.kp_l, kr = g_pair.kp_r;
    f.compute(g_pair.left, kl, d.l);
    f.compute(g_pair.right, kr, d.r);
    return d;
}

void run_describe_and_match(benchmark::State& st, const cv::Ptr<cv::Feature2D>& f) {
    MatchOptions o;
    o.norm = f->defaultNorm();
    size_t matches = 0;
    for (auto _ : st) {
        const Described d = describe(*f);
        const auto m = match_stereo(d.l, g_pair.kp_l, d.r, g_pair.kp_r, o);
        matches = m.size();
        benchmark::DoNotOptimize(m.data());
    }
    st.counters["matches"] = double(matches);
    st.counters["bytes"] = f->descriptorSize();
}

void run_describe(benchmark::State& st, const cv::Ptr<cv::Feature2D>& f) {
    for (auto _ : st) {
        const Described d = describe(*f);
        benchmark::DoNotOptimize(d.l.data);
    }
}

void run_match(benchmark::State& st, const cv::Ptr<cv::Feature2D>& f) {
    const Described d = describe(*f);
    MatchOptions o;
    o.norm = f->defaultNorm();
    for (auto _ : st) {
        const auto m = match_stereo(d.l, g_pair.kp_l, d.r, g_pair.kp_r, o);
        benchmark::DoNotOptimize(m.data());
    }
}

/// This thread's CPU time in ms.
double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/// Describe both images and match, once.
size_t describe_and_match_once(cv::Feature2D& f) {
    MatchOptions o;
    o.norm = f.defaultNorm();
    const Described d = describe(f);
    return match_stereo(d.l, g_pair.kp_l, d.r, g_pair.kp_r, o).size();
}

cv::Ptr<cv::Feature2D> grid_thesis() { return GridDescriptor::create(16, 3, GridVariant::thesis); }
cv::Ptr<cv::Feature2D> grid_corrected() { return GridDescriptor::create(16, 3, GridVariant::corrected); }
cv::Ptr<cv::Feature2D> brief() { return BriefDescriptor::create(BorderPolicy::drop, BriefSmoothing::box); }
cv::Ptr<cv::Feature2D> brief_gaussian() {
    return BriefDescriptor::create(BorderPolicy::drop, BriefSmoothing::gaussian);
}
cv::Ptr<cv::Feature2D> freak() { return FreakDescriptor::create(); }

/// The descriptors benchmarked chain by chain: BM_<name>_describe_and_match for each, and
/// BM_<name>_describe, BM_<name>_match for those marked.
struct Chain {
    const char* name;
    cv::Ptr<cv::Feature2D> (*make)();
    bool describe;
    bool match;
};
const Chain kChains[] = {{"grid_thesis", grid_thesis, true, true},
                         {"grid_corrected", grid_corrected, true, true},
                         {"brief", brief, true, true},
                         {"brief_gaussian", brief_gaussian, true, false},
                         {"freak", freak, false, false}};

/// Registers the chains' benchmarks (kChains): describe and match, then describe alone, then
/// match alone, in kChains' order, after those the BENCHMARK macros register.
void register_chain_benchmarks() {
    using Run = void (*)(benchmark::State&, const cv::Ptr<cv::Feature2D>&);
    const struct {
        const char* stage;
        Run run;
        bool Chain::*has;   ///< null: every chain
    } stages[] = {{"describe_and_match", run_describe_and_match, nullptr},
                  {"describe", run_describe, &Chain::describe},
                  {"match", run_match, &Chain::match}};
    for (const auto& k : stages)
        for (const Chain& c : kChains) {
            if (k.has && !(c.*k.has)) continue;
            const std::string name = std::string("BM_") + c.name + "_" + k.stage;
            benchmark::RegisterBenchmark(name.c_str(), [run = k.run, make = c.make](benchmark::State& st) { run(st, make()); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        }
}

/// Grid (thesis) + matching, BRIEF (box) + matching and BRIEF (Gaussian) + matching one after
/// the other in every iteration, each timed (real and thread CPU time), so that a changing
/// machine load hits all alike; counters: the mean times per pair and the grid's ratios to
/// each BRIEF.
void BM_grid_vs_brief_interleaved(benchmark::State& st) {
    const cv::Ptr<cv::Feature2D> chains[3] = {grid_thesis(), brief(), brief_gaussian()};
    const char* names[3] = {"grid", "brief", "brief_gaussian"};
    double real[3] = {0, 0, 0}, cpu[3] = {0, 0, 0};
    size_t sink = 0;
    using clock = std::chrono::steady_clock;
    for (auto _ : st) {
        for (int i = 0; i < 3; ++i) {
            const auto r0 = clock::now();
            const double c0 = thread_cpu_ms();
            sink += describe_and_match_once(*chains[i]);
            real[i] += std::chrono::duration<double, std::milli>(clock::now() - r0).count();
            cpu[i] += thread_cpu_ms() - c0;
        }
    }
    benchmark::DoNotOptimize(sink);
    const double n = double(st.iterations());
    for (int i = 0; i < 3; ++i) {
        st.counters[std::string(names[i]) + "_real_ms"] = real[i] / n;
        st.counters[std::string(names[i]) + "_cpu_ms"] = cpu[i] / n;
    }
    st.counters["real_ratio"] = real[0] / real[1];
    st.counters["cpu_ratio"] = cpu[0] / cpu[1];
    st.counters["real_ratio_gaussian"] = real[0] / real[2];
    st.counters["cpu_ratio_gaussian"] = cpu[0] / cpu[2];
}
BENCHMARK(BM_grid_vs_brief_interleaved)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

/// Grid extraction of n keypoints spread uniformly at KITTI's density (1,000 per 1241 x 376
/// image): time per keypoint stays flat as n grows when extraction is O(n (g + k)), not O(n^2).
void BM_grid_thesis_describe_n_keypoints(benchmark::State& st) {
    const int n = static_cast<int>(st.range(0));
    const double side = std::sqrt(1241.0 * 376.0 * n / 1000.0);
    cv::RNG rng(12345);
    std::vector<cv::KeyPoint> k(static_cast<size_t>(n));
    for (auto& p : k) p = cv::KeyPoint(float(rng.uniform(0.0, side)), float(rng.uniform(0.0, side)), 7.f);
    for (auto _ : st) {
        const cv::Mat d = grid_describe(k, 16, 3, GridVariant::thesis);
        benchmark::DoNotOptimize(d.data);
    }
    st.SetItemsProcessed(st.iterations() * n);
}
BENCHMARK(BM_grid_thesis_describe_n_keypoints)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

/// BRIEF's smoothing alone on both images, padded by the 28-px margin as BriefDescriptor
/// does: the paper's 9 x 9 Gaussian of sigma 2 over the whole image (BM_brief_smoothing_only)
/// against the integral image the authors' box filter reads (BM_brief_integral_only).
void BM_brief_smoothing_only(benchmark::State& st) {
    cv::Mat padded, smooth;
    for (auto _ : st) {
        for (const cv::Mat* img : {&g_pair.left, &g_pair.right}) {
            cv::copyMakeBorder(*img, padded, 28, 28, 28, 28, cv::BORDER_REFLECT_101);
            cv::GaussianBlur(padded, smooth, cv::Size(9, 9), 2.0, 2.0, cv::BORDER_REFLECT_101);
            benchmark::DoNotOptimize(smooth.data);
        }
    }
}
void BM_brief_integral_only(benchmark::State& st) {
    cv::Mat padded, sum;
    for (auto _ : st) {
        for (const cv::Mat* img : {&g_pair.left, &g_pair.right}) {
            cv::copyMakeBorder(*img, padded, 28, 28, 28, 28, cv::BORDER_REFLECT_101);
            cv::integral(padded, sum, CV_32S);
            benchmark::DoNotOptimize(sum.data);
        }
    }
}
BENCHMARK(BM_brief_integral_only)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_brief_smoothing_only)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Keeps every benchmark's real time per iteration (the median over repetitions when
/// --benchmark_repetitions is given) to print the ratios after the run.
class RatioReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const auto& r : runs) {
            const std::string name = r.run_name.function_name;
            if (r.run_type == Run::RT_Aggregate && r.aggregate_name == "median") {
                ms[name] = r.GetAdjustedRealTime();
                cpu[name] = r.GetAdjustedCPUTime();
                median.insert(name);
            } else if (r.run_type == Run::RT_Iteration && r.iterations > 0 && !median.count(name)) {
                ms[name] = r.GetAdjustedRealTime();
                cpu[name] = r.GetAdjustedCPUTime();
            }
        }
        for (const auto& r : runs)
            if (r.run_name.function_name == "BM_grid_vs_brief_interleaved" &&
                (r.run_type == Run::RT_Iteration || r.aggregate_name == "median"))
                for (const auto& [k, v] : r.counters) interleaved[k] = v.value;
        ConsoleReporter::ReportRuns(runs);
    }
    std::set<std::string> median;
    std::map<std::string, double> interleaved;
    /// Real-time ratio a / b, and the CPU-time ratio (the fairer one on a loaded machine).
    void ratio(const char* what, const std::string& a, const std::string& b) const {
        const auto x = ms.find(a), y = ms.find(b);
        if (x == ms.end() || y == ms.end() || y->second <= 0) return;
        const double ca = cpu.at(a), cb = cpu.at(b);
        std::printf("%s: real %.3f ms / %.3f ms = %.3f; CPU %.3f ms / %.3f ms = %.3f\n", what, x->second,
                    y->second, x->second / y->second, ca, cb, cb > 0 ? ca / cb : 0.0);
    }
    std::map<std::string, double> ms, cpu;
};

}  // namespace

int main(int argc, char** argv) {
    cv::setNumThreads(1);
    // the strongest 1,000 corners at least BRIEF's margin (28 px) inside each image, so that
    // BRIEF keeps them all and every descriptor describes the same ones
    auto s = hc::features_test::load_stereo_sample(1000, 28);
    if (!s) {
        std::fprintf(stderr, "features_bench: no KITTI 01 pair 0 and no opencv-doc aloe pair\n");
        return 2;
    }
    g_pair = std::move(*s);
    {
        const size_t l = g_pair.kp_l.size(), r = g_pair.kp_r.size();
        cv::Mat unused;
        BriefDescriptor::create()->compute(g_pair.left, g_pair.kp_l, unused);
        BriefDescriptor::create()->compute(g_pair.right, g_pair.kp_r, unused);
        if (g_pair.kp_l.size() != l || g_pair.kp_r.size() != r) {
            std::fprintf(stderr, "features_bench: BRIEF dropped keypoints inside its margin\n");
            return 1;
        }
    }
    std::printf("pair: %s (%dx%d), keypoints %zu left, %zu right\n", g_pair.name.c_str(), g_pair.left.cols,
                g_pair.left.rows, g_pair.kp_l.size(), g_pair.kp_r.size());
    register_chain_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    RatioReporter rep;
    benchmark::RunSpecifiedBenchmarks(&rep);
    benchmark::Shutdown();
    if (!rep.interleaved.empty()) {
        auto& v = rep.interleaved;
        std::printf("interleaved, grid (thesis) + matching / BRIEF (box) + matching (goal < 1): real %.3f ms / %.3f ms = "
                    "%.3f; CPU %.3f ms / %.3f ms = %.3f\n",
                    v["grid_real_ms"], v["brief_real_ms"], v["real_ratio"], v["grid_cpu_ms"], v["brief_cpu_ms"],
                    v["cpu_ratio"]);
        std::printf("interleaved, grid (thesis) + matching / BRIEF (Gaussian) + matching: real %.3f ms / %.3f ms = "
                    "%.3f; CPU %.3f ms / %.3f ms = %.3f\n",
                    v["grid_real_ms"], v["brief_gaussian_real_ms"], v["real_ratio_gaussian"], v["grid_cpu_ms"],
                    v["brief_gaussian_cpu_ms"], v["cpu_ratio_gaussian"]);
    }
    rep.ratio("grid (thesis) + matching / BRIEF (box) + matching (goal < 1)", "BM_grid_thesis_describe_and_match",
              "BM_brief_describe_and_match");
    rep.ratio("grid (thesis) + matching / BRIEF (Gaussian) + matching", "BM_grid_thesis_describe_and_match",
              "BM_brief_gaussian_describe_and_match");
    rep.ratio("grid (corrected) + matching / BRIEF + matching", "BM_grid_corrected_describe_and_match",
              "BM_brief_describe_and_match");
    rep.ratio("grid (thesis) extraction / BRIEF (box) extraction", "BM_grid_thesis_describe", "BM_brief_describe");
    rep.ratio("grid (thesis) extraction / BRIEF (Gaussian) extraction", "BM_grid_thesis_describe",
              "BM_brief_gaussian_describe");
    rep.ratio("matching 35-byte grid / matching 32-byte BRIEF", "BM_grid_thesis_match", "BM_brief_match");
    return 0;
}

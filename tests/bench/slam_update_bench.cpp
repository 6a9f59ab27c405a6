// slam_update_bench.cpp: the EKF-SLAM landmark update in the thesis's worst case (Table 3):
// a map of k landmarks (state 3 + 2k), every landmark observed and updated in one step.
// One step = k sequential corrections. Three covariance forms in the same run (one thread):
//   structured  P·Hᵀ from 5 columns + symmetric rank-2 update   O(k·n²)
//   dense_kzk   dense H, P ← P − K Z Kᵀ (thesis eq. 2.18)       O(k·n²)
//   dense       dense H, P ← (I − K H) P                         O(k·n³)
// The dense (I − KH)P step is measured up to 200 landmarks (the thesis's range); beyond,
// its single update (BM_update) is measured and the step is k times it.
// `--plot=DIR` writes DIR/timing.csv and DIR/timing.png (log-log, with the thesis's ARM
// figures) from the CPU times of this run.
#include <benchmark/benchmark.h>

#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "mapping/slam/slam.hpp"

using namespace hc::slam;

namespace {

struct Scene {
    Ekf ekf;
    std::vector<Vec2> y;   ///< one observation per landmark, in state order
    Mat2 R;
};

// A robot at the origin after a few motions, k landmarks in a ring 2..10 m around it,
// each initialised from a noisy observation; y holds a second noisy observation of each.
Scene make_scene(int k) {
    std::mt19937_64 rng(k);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> range(2, 10), bearing(-3.1, 3.1);
    Scene s{Ekf(Pose::Zero(), Mat3::Zero(), k), {}, Mat2::Zero()};
    s.R = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
    const Mat2 N = Eigen::Vector2d(0.01 * 0.01, 0.005 * 0.005).asDiagonal();
    for (int i = 0; i < 3; ++i) s.ekf.predict(Vec2(0.1, 0.01), N);
    for (int i = 0; i < k; ++i) {
        const Vec2 y(range(rng), bearing(rng));
        s.ekf.add_landmark(i, y, s.R);
        s.y.push_back(y + Vec2(0.05 * g(rng), 0.01 * g(rng)));
    }
    s.ekf.predict(Vec2(0.1, 0.01), N);
    return s;
}

template <UpdateForm F>
void BM_step(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    const Scene scene = make_scene(k);
    for (auto _ : state) {
        state.PauseTiming();
        Ekf ekf = scene.ekf;
        state.ResumeTiming();
        for (int i = 0; i < k; ++i) ekf.correct(i, scene.y[i], scene.R, F);
        benchmark::DoNotOptimize(ekf);
    }
    state.counters["landmarks"] = k;
}

template <UpdateForm F>
void BM_update(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    Scene scene = make_scene(k);
    int i = 0;
    for (auto _ : state) {
        scene.ekf.correct(i, scene.y[i], scene.R, F);
        benchmark::DoNotOptimize(scene.ekf);
        i = (i + 1) % k;
    }
    state.counters["landmarks"] = k;
}

void sizes(benchmark::internal::Benchmark* b, int max_k) {
    for (int k : {50, 100, 150, 200, 300, 500, 700, 1000})
        if (k <= max_k) b->Arg(k);
    b->Unit(benchmark::kMillisecond);
}

BENCHMARK_TEMPLATE(BM_step, UpdateForm::Structured)->Apply([](auto* b) { sizes(b, 1000); });
BENCHMARK_TEMPLATE(BM_step, UpdateForm::DenseKzk)->Apply([](auto* b) { sizes(b, 1000); });
BENCHMARK_TEMPLATE(BM_step, UpdateForm::Dense)->Apply([](auto* b) { sizes(b, 200); });
BENCHMARK_TEMPLATE(BM_update, UpdateForm::Structured)->Apply([](auto* b) { sizes(b, 1000); });
BENCHMARK_TEMPLATE(BM_update, UpdateForm::Dense)->Apply([](auto* b) { sizes(b, 1000); });

// Collects the mean CPU time per iteration of every run, by name, for the plot (CPU time:
// the machine may be shared, and the update runs on one thread).
class Collector : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const auto& r : runs)
            if (r.run_type == Run::RT_Iteration && r.iterations > 0)
                ms[r.benchmark_name()] = r.cpu_accumulated_time / static_cast<double>(r.iterations) * 1e3;
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> ms;
};

}  // namespace

int main(int argc, char** argv) {
    std::string plot_dir;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strncmp(argv[i], "--plot=", 7) == 0)
            plot_dir = argv[i] + 7;
        else
            args.push_back(argv[i]);
    }
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
    Collector collector;
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::Shutdown();
    if (plot_dir.empty()) return 0;
    std::vector<TimingRow> rows;
    for (int k : {50, 100, 150, 200, 300, 500, 700, 1000}) {
        const std::string arg = "/" + std::to_string(k);
        const auto get = [&](const std::string& name) {
            const auto it = collector.ms.find(name + arg);
            return it == collector.ms.end() ? 0.0 : it->second;
        };
        TimingRow r;
        r.landmarks = k;
        r.structured_ms = get("BM_step<UpdateForm::Structured>");
        r.dense_kzk_ms = get("BM_step<UpdateForm::DenseKzk>");
        r.dense_ms = get("BM_step<UpdateForm::Dense>");
        if (r.dense_ms == 0) {
            r.dense_ms = k * get("BM_update<UpdateForm::Dense>");   // k single updates
            r.dense_from_single_update = r.dense_ms > 0;
        }
        if (r.structured_ms > 0 || r.dense_ms > 0) rows.push_back(r);
    }
    write_timing_report(plot_dir, rows);
    std::printf("timing report written to %s/timing.csv and timing.png\n", plot_dir.c_str());
    return 0;
}

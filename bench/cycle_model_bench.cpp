// cycle_model_bench: bus writes per second of the cycle-accurate model (HarrisTop) driven
// through the host driver, against the host driver alone as the peer in the same run.
//   build/bench/cycle_model_bench [--benchmark_min_time=2]
// Frame: a generated 1241x376 'blocks' frame (the KITTI size), two chained frames.
#include <benchmark/benchmark.h>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"

namespace {

const std::vector<hc::Image>& frames() {
    static const std::vector<hc::Image> f = {hc::make_pattern(hc::Pattern::blocks, 1241, 376, 0),
                                             hc::make_pattern(hc::Pattern::blocks, 1241, 376, 1)};
    return f;
}

void BM_HostDriverOnly(benchmark::State& state) {
    const hc::Geometry g{1241, 376};
    long writes = 0;
    std::uint32_t sink = 0;
    for (auto _ : state) {
        hc::HostDriver drv(g, {&frames()[0], &frames()[1]});
        hc::BusEvent ev;
        while (drv.next(ev)) {
            sink ^= ev.data;
            ++writes;
        }
    }
    benchmark::DoNotOptimize(sink);
    state.counters["writes/s"] = benchmark::Counter(static_cast<double>(writes), benchmark::Counter::kIsRate);
}

void BM_CycleModel(benchmark::State& state) {
    const hc::Geometry g{1241, 376};
    long writes = 0;
    std::uint32_t sink = 0;
    for (auto _ : state) {
        hc::HostDriver drv(g, {&frames()[0], &frames()[1]});
        hc::HarrisTop top(g, hc::Formats{});
        hc::BusEvent ev;
        while (drv.next(ev)) {
            top.write(ev.data);
            if (ev.read) sink ^= top.corner();
        }
        writes += top.writes();
    }
    benchmark::DoNotOptimize(sink);
    state.counters["writes/s"] = benchmark::Counter(static_cast<double>(writes), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_HostDriverOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleModel)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

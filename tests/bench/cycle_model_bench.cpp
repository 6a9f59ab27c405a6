// cycle_model_bench: bus writes per second of the cycle-accurate model (HarrisTop) driven
// through the host driver, against the host driver alone as the peer in the same run.
//   build/tests/bench/cycle_model_bench [--benchmark_min_time=2]
// Frame: a generated 1241x376 'blocks' frame (the KITTI size), two chained frames.
//   BM_HostDriverOnly           the peer: the driver's writes, no model
//   BM_CycleModel               thesis formats, the instance compiled for them (default)
//   BM_CycleModelRunTimeFormats thesis formats, the instance that reads widths at run time
//   BM_CycleModelConfig         a sweep/configs/bit-widths.json configuration (tight-m3-b2:
//                               resp_w 38, bf_sum_w 22), compiled instance
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

void run_model(benchmark::State& state, const hc::Formats& f, hc::Specialisation s) {
    const hc::Geometry g{1241, 376};
    long writes = 0;
    std::uint32_t sink = 0;
    for (auto _ : state) {
        hc::HostDriver drv(g, {&frames()[0], &frames()[1]});
        hc::HarrisTop top(g, f, s);
        hc::BusEvent ev;
        while (drv.next(ev)) {
            top.write(ev.data);
            if (ev.read) sink ^= top.corner();
        }
        writes += top.writes();
        state.SetLabel(top.compiled() ? "compiled formats" : "run-time formats");
    }
    benchmark::DoNotOptimize(sink);
    state.counters["writes/s"] = benchmark::Counter(static_cast<double>(writes), benchmark::Counter::kIsRate);
}

void BM_CycleModel(benchmark::State& state) {
    run_model(state, hc::Formats{}, hc::Specialisation::compiled_if_any);
}

void BM_CycleModelRunTimeFormats(benchmark::State& state) {
    run_model(state, hc::Formats{}, hc::Specialisation::run_time);
}

void BM_CycleModelConfig(benchmark::State& state) {
    hc::Formats f;
    f.m_drop = 3;
    f.bf_sum_w = 22;
    f.bf_drop = 2;
    f.ktr_w = 35;
    f.resp_w = 38;
    run_model(state, f, hc::Specialisation::compiled_if_any);
}

}  // namespace

BENCHMARK(BM_HostDriverOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleModel)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleModelRunTimeFormats)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleModelConfig)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

// Speed of the RTL engine (Google Benchmark, not a test): samples/s and simulated clocks/s of the
// Verilated tex_unit through the harness, per configuration, ideal timing and random stalls.
// Run: build/texunit_rtl_speed  (the model comparison is not included: samples are checked by the tests)
#include <benchmark/benchmark.h>

#include <random>

#include "model/image.h"
#include "rtl/rtl_harness.h"

using namespace tex;

namespace {

void BM_RtlStream(benchmark::State& state) {
  const rtl::RtlShape& shape = rtl::compiled_shapes()[size_t(state.range(0))];
  const bool stalls = state.range(1) != 0;
  auto unit = rtl::Harness::create(shape);
  unit->reset();
  const Pyramid pyr = build_pyramid(make_pattern("noise", 1 << shape.max_log2_w, 1 << shape.max_log2_h));
  unit->load(pyr);
  SamplerConfig cfg;  // trilinear, repeat
  unit->configure(rtl::cfg_pins(cfg, shape.max_log2_w, shape.max_log2_h));
  std::mt19937_64 rng(1);
  std::vector<Request> reqs(100000);
  const int last = std::max(shape.max_log2_w, shape.max_log2_h);
  for (Request& r : reqs) {
    r.u = int32_t(rng() % (uint64_t(4) << 24)) - (int32_t(2) << 24);
    r.v = int32_t(rng() % (uint64_t(4) << 24)) - (int32_t(2) << 24);
    r.lod = int32_t(rng() % uint64_t((last + 1) * 256));
  }
  const rtl::Timing timing = stalls ? rtl::Timing::random_default() : rtl::Timing::ideal();
  uint64_t samples = 0, clocks = 0, sink = 0;
  for (auto _ : state) {
    const rtl::StreamStats st =
        unit->stream(reqs.data(), reqs.size(), timing, 7, [&](size_t, uint64_t rgba) { sink += rgba; });
    samples += st.samples;
    clocks += st.cycles + 64;  // + the idle clocks of the duplicate check
  }
  benchmark::DoNotOptimize(sink);
  state.SetLabel(shape.name + (stalls ? " random stalls" : " ideal"));
  state.counters["samples/s"] = benchmark::Counter(double(samples), benchmark::Counter::kIsRate);
  state.counters["clocks/s"] = benchmark::Counter(double(clocks), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_RtlStream)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();

#include "bench_timing.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include "engines/rtl/driver.h"
#include "model/error.h"
#include "model/texture_cache.h"
#include "model/timing.h"

namespace bench {

namespace {

constexpr size_t kTimingQueries = 200000;

struct TimingWorkload {
  const tex::rtl::RtlConfig* config = nullptr;
  const tex::Pyramid* pyramid = nullptr;
  std::vector<tex::Request> requests;
  tex::rtl::DriverOptions options;
  std::unique_ptr<tex::rtl::Driver> unit;
};

// The RTL: caches emptied (configure() resets the unit), then the requests; the clock of each response.
uint64_t run_rtl(TimingWorkload& w, std::vector<uint64_t>* clocks) {
  using namespace tex;
  w.unit->configure(SamplerConfig{}, *w.pyramid);
  const rtl::StreamStats st = rtl::stream(*w.unit, w.requests.data(), w.requests.size(), rtl::Timing{}, 7,
                                          [&](size_t i, uint64_t) {
                                            if (clocks) (*clocks)[i] = w.unit->counters().last_response_clock();
                                          });
  return st.cycles();
}

// The model: fresh caches, each request looked up (its probes' misses), clocked by the timing layer.
uint64_t run_model(const TimingWorkload& w, std::vector<uint64_t>* clocks) {
  using namespace tex;
  const MemoryLayout layout = layout_of(*w.pyramid, w.options.layout);
  TextureCache cache(layout, w.options.cache, SamplerConfig{});
  const MemoryChannel memory(w.config->line_bytes(), w.config->mem_bits / 8, w.options.memory);
  TimedStream timed(rtl::unit_shape(*w.config), &memory, Stimulus{}, 7);
  if (clocks) clocks->clear();
  for (size_t i = 0; i < w.requests.size(); i += 4096) {
    const size_t n = std::min<size_t>(4096, w.requests.size() - i);
    for (size_t k = 0; k < n; ++k) timed.push(cache.lookup_sample(w.requests[i + k], nullptr));
    timed.run(clocks);
  }
  timed.finish(clocks);
  return timed.counters().cycles();
}

void BM_timing_rtl(benchmark::State& state, TimingWorkload* w) {
  uint64_t clocks = 0;
  for (auto _ : state) clocks += run_rtl(*w, nullptr);
  state.SetItemsProcessed(int64_t(clocks));
}

void BM_timing_model(benchmark::State& state, TimingWorkload* w) {
  uint64_t clocks = 0;
  for (auto _ : state) clocks += run_model(*w, nullptr);
  state.SetItemsProcessed(int64_t(clocks));
}

}  // namespace

std::vector<std::string> register_timing_benchmarks(
    double min_time, const tex::Pyramid& pyramid,
    const std::vector<std::pair<std::string, const std::vector<tex::Request>*>>& sets) {
  using namespace tex;
  static std::vector<std::unique_ptr<TimingWorkload>> workloads;  // alive while the benchmarks run
  std::vector<std::string> names;
  const rtl::RtlConfig& rc = rtl::smallest_config_for(log2_exact(pyramid.extent0().w), log2_exact(pyramid.extent0().h), 8, Memory::Cached);
  for (const auto& [name, requests] : sets) {
    auto w = std::make_unique<TimingWorkload>();
    w->config = &rc;
    w->pyramid = &pyramid;
    w->requests.assign(requests->begin(), requests->begin() + std::min(requests->size(), kTimingQueries));
    w->unit = rtl::Driver::create(rc, w->options);
    w->unit->reset();
    w->unit->load(pyramid, LoadMethod::Backdoor);
    std::vector<uint64_t> a(w->requests.size()), b;
    run_rtl(*w, &a);
    run_model(*w, &b);
    if (a != b) throw Error("bench: the timing model's response clocks differ from " + rc.name + "'s on " + name);
    std::printf("  %-9s timing model == %s, clock for clock, on %zu requests (%llu clocks)\n", name.c_str(),
                rc.name.c_str(), a.size(), (unsigned long long)(a.back() + 1));
    benchmark::RegisterBenchmark(("timing_rtl/" + name).c_str(), BM_timing_rtl, w.get())->MinTime(min_time);
    benchmark::RegisterBenchmark(("timing_model/" + name).c_str(), BM_timing_model, w.get())->MinTime(min_time);
    names.push_back(name);
    workloads.push_back(std::move(w));
  }
  return names;
}

}  // namespace bench

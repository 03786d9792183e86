#include "bench_rtl.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>

#include "engines/rtl/driver.h"
#include "model/image.h"
#include "model/srgb.h"

namespace bench {

namespace {

void BM_rtl_sampling(benchmark::State& state, const tex::rtl::RtlConfig* config) {
  using namespace tex;
  RtlWorkload work = make_rtl_workload(*config);
  uint64_t samples = 0, clocks = 0, sink = 0;
  for (auto _ : state) {
    const rtl::StreamStats st = rtl::stream(*work.unit, work.requests.data(), work.requests.size(), rtl::Timing{}, 7,
                                            [&](size_t, uint64_t rgba) { sink += rgba; });
    samples += st.samples();
    clocks += st.cycles();
  }
  benchmark::DoNotOptimize(sink);
  state.SetItemsProcessed(int64_t(samples));
  state.counters["clocks/s"] = benchmark::Counter(double(clocks), benchmark::Counter::kIsRate);
}

}  // namespace

RtlWorkload make_rtl_workload(const tex::rtl::RtlConfig& config) {
  using namespace tex;
  rtl::DriverOptions options;  // cached configurations: the default caches (8 KiB, 2 ways) where they fit
  options.layout.block_w = config.block_w;
  options.layout.block_h = config.block_h;
  options.cache.size_bytes = std::min(options.cache.size_bytes, config.lines * config.line_bytes());
  if (config.cached) options.memory.bytes_per_clock = std::min(16u, uint32_t(config.mem_bits / 8));
  RtlWorkload work;
  work.unit = rtl::Driver::create(config, options);
  work.unit->reset();
  // The configuration's largest texture, at most 1024x1024 (the same texture for Vtex_unit_10x10
  // and Vtex_cached_13x13: its speed does not depend on the texture's size).
  const int lw = std::min(config.max_log2_w, 10), lh = std::min(config.max_log2_h, 10);
  // (a configuration with the formats: an sRGB texture, every texel through the decode tables)
  Pyramid pyr = config.formats ? build_srgb_pyramid(make_pattern("noise", 1 << lw, 1 << lh), PyramidMode::Exact)
                               : build_pyramid(make_pattern("noise", 1 << lw, 1 << lh));
  if (!config.formats)
    for (Image& img : pyr.levels) {  // 16-bit configurations take 16-bit texels
      img.channel_bits = config.cw;
      for (Texel& t : img.texels)
        for (uint16_t& c : t) c = uint16_t(c * ((1u << config.cw) - 1) / 255);
    }
  work.unit->load(pyr, LoadMethod::Backdoor);
  SamplerConfig cfg;  // trilinear, repeat
  work.unit->configure(cfg, pyr);
  std::mt19937_64 rng(1);
  work.requests.resize(1 << 16);  // 1 MB: the requests do not push the texture out of the cache
  const int last = std::max(lw, lh);
  for (Request& r : work.requests) {
    r.u = int32_t(rng() % (uint64_t(4) << 24)) - (int32_t(2) << 24);
    r.v = int32_t(rng() % (uint64_t(4) << 24)) - (int32_t(2) << 24);
    r.lod = int32_t(rng() % uint64_t((last + 1) * 256));
  }
  return work;
}

std::vector<std::string> register_rtl_benchmarks(double min_time) {
  std::vector<std::string> names;
  for (const tex::rtl::RtlConfig& c : tex::rtl::compiled_configs()) {
    names.push_back("rtl_sampling/" + c.name);
    benchmark::RegisterBenchmark(names.back().c_str(), BM_rtl_sampling, &c)->MinTime(min_time);
  }
  return names;
}

}  // namespace bench

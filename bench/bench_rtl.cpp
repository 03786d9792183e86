#include "bench_rtl.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>

#include "engines/rtl/driver.h"
#include "model/block_formats.h"
#include "model/error.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "stimulus.h"

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

bool parse_rtl_texture(const std::string& name, RtlTexture& out) {
  for (RtlTexture t : kRtlTextures)
    if (name == rtl_texture_name(t)) {
      out = t;
      return true;
    }
  return false;
}

const char* rtl_texture_name(RtlTexture t) {
  switch (t) {
    case RtlTexture::Rgba8: return "rgba8";
    case RtlTexture::Bc1: return "bc1";
    case RtlTexture::Bc7: return "bc7";
    case RtlTexture::Srgb: return "srgb";
    case RtlTexture::Etc2: return "etc2a";
    case RtlTexture::Eac: return "eac_rg11";
    case RtlTexture::Astc: return "astc8x8";
  }
  return "?";
}

bool config_takes(const tex::rtl::RtlConfig& config, RtlTexture t) {
  return t == RtlTexture::Rgba8 || config.formats;
}

RtlWorkload make_rtl_workload(const tex::rtl::RtlConfig& config, RtlTexture texture) {
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
  if (!config_takes(config, texture))
    throw Error(config.name + " has no block decoders or sRGB tables (texture " + rtl_texture_name(texture) + ")");
  const Image noise = make_pattern("noise", 1 << lw, 1 << lh);
  Pyramid pyr;
  switch (texture) {
    case RtlTexture::Rgba8:
      pyr = build_pyramid(noise);
      if (!config.formats)
        for (Image& img : pyr.levels) {  // 16-bit configurations take 16-bit texels
          img.channel_bits = config.cw;
          for (Texel& t : img.texels)
            for (uint16_t& c : t) c = uint16_t(c * ((1u << config.cw) - 1) / 255);
        }
      break;
    // Random blocks at every level, every mode of the format (BC7's 8, ETC2's 5, ASTC's legal ones
    // and a few illegal): the decoders' cost does not depend on what the blocks show. (Not
    // compressed from the noise: Mesa's BC7 encoder executes an instruction that valgrind cannot,
    // and make bench-ir runs under it.)
    case RtlTexture::Bc1: pyr = stimulus::random_block_texture(TexelFormat::Bc1, {1 << lw, 1 << lh}, 2); break;
    case RtlTexture::Bc7: pyr = stimulus::random_block_texture(TexelFormat::Bc7, {1 << lw, 1 << lh}, 2); break;
    case RtlTexture::Etc2: pyr = stimulus::random_block_texture(TexelFormat::Etc2Rgba, {1 << lw, 1 << lh}, 2); break;
    case RtlTexture::Eac: pyr = stimulus::random_block_texture(TexelFormat::EacRg11, {1 << lw, 1 << lh}, 2); break;
    case RtlTexture::Astc: pyr = stimulus::random_block_texture(TexelFormat::Astc8x8, {1 << lw, 1 << lh}, 2); break;
    case RtlTexture::Srgb: pyr = build_srgb_pyramid(noise, PyramidMode::Exact); break;
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

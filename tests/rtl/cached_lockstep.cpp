#include "cached_lockstep.h"

#include <algorithm>
#include <cstdio>

#include "model/image.h"
#include "model/srgb.h"

namespace tex::rtltest {

// A random texture for a configuration: RGBA (channels as memory holds them) or random blocks of a
// block format; sRGB if asked and the configuration has the tables (not BC4, BC5, EAC: no sRGB).
Pyramid random_pyramid(const rtl::RtlConfig& rc, TexelFormat format, Extent size, bool srgb, uint64_t seed) {
  srgb = srgb && rc.formats && format_info(format).srgb_allowed;
  if (is_compressed(format)) {
    Pyramid p = random_block_texture(format, size, seed);
    if (srgb) decode_srgb_levels(p);
    return p;
  }
  Image level0 = random_image(size.w, size.h, rc.memory_channel_bits(), seed);
  return srgb ? build_srgb_pyramid(level0, PyramidMode::Exact) : build_pyramid(std::move(level0), PyramidMode::Exact);
}


const rtl::RtlConfig& config_named(const std::string& name) {
  for (const rtl::RtlConfig& c : rtl::compiled_configs())
    if (c.name == name) return c;
  throw Error("no configuration " + name);
}

CaseResult run_case(rtl::Driver& unit, const TextureTable& table, const SamplerTable& smp, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache, int poke_texel, uint32_t fifo_depth,
                    const TextureTable* model_table, const std::vector<uint64_t>& error_reads,
                    const std::vector<uint64_t>* model_error_reads,
                    const SamplerTable* model_samplers) {
  CaseResult r;
  const Pyramid& pyr = *table[0].pyramid;
  unit.set_memory(layout, cache, timing, fifo_depth);
  unit.set_memory_errors(error_reads);
  unit.load_textures(table);
  unit.configure(smp);
  if (poke_texel >= 0) {  // planted bug: one byte of the image is wrong
    const MemoryLayout ml = layout_of(pyr, layout);
    unit.memory()->poke(ml.line_address(0, 0, 0) + uint32_t(poke_texel), 0x5A ^ uint8_t(pyr.levels[0].at(0, 0)[0]));
  }
  // The model's tables: the RTL's, unless a test plants others.
  const TextureTable& mt = model_table ? *model_table : table;
  const SamplerTable& ms = model_samplers ? *model_samplers : smp;
  SamplerPairs samplers(mt, ms);
  EngineOptions eo;
  eo.layout = layout;
  TextureCache model(texture_descriptors(mt, eo), model_cache ? *model_cache : cache, ms);
  model.set_error_reads(model_error_reads ? *model_error_reads : error_reads);
  std::vector<uint32_t> predicted;
  std::vector<RequestWork> work;  // each request's probes and their misses: what its timing depends on
  for (const Request& q : requests) {
    if (mt.at(q.texture).kind == TextureKind::Cube) {  // (the face's request and probes: the cache's own)
      work.push_back(model.lookup_sample(q, &predicted));
      continue;
    }
    const Pyramid& t = *mt.at(q.texture).pyramid;
    const Probes p = tex_probe(q, ms.at(q.sampler), t.extent0());
    RequestWork& w = work.emplace_back();
    w.probes = uint8_t(p.n);
    for (int i = 0; i < p.n; ++i) {
      const SampleLookup l = model.lookup(p.at[size_t(i)], &predicted);
      w.set_fills(i, uint32_t(l.slot[0].misses + l.slot[1].misses));
      w.error = w.error || l.error();
      if (coverage) coverage->sample(l);
    }
  }
  const std::vector<uint64_t> want_clocks = model_clocks(unit, fifo_depth, work, stim, seed);
  std::vector<uint64_t> clocks(requests.size());
  uint64_t mismatches = 0;
  try {
    const rtl::StreamStats st = rtl::stream(unit, requests.data(), requests.size(), stim, seed, [&](size_t i, uint64_t rgba) {
      clocks[i] = response_clock(unit);
      // A sample the model's caches flag answers 0 with rsp_error.
      const bool error = work[i].error, got_error = unit.last_response_error();
      const Texel want = error ? Texel{} : samplers.at(requests[i]).sample(requests[i]);
      const Texel got = rtl::unpack_rgba(rgba, unit.config().cw);
      r.flagged += got_error;
      if (got_error != error && mismatches++ == 0)
        r.failure = "sample " + std::to_string(i) + " " + describe(requests[i]) + ": RTL rsp_error " +
                    std::to_string(got_error) + ", model " + std::to_string(error);
      else if (got != want && mismatches++ == 0)
        r.failure = "sample " + std::to_string(i) + " " + describe(requests[i]) + ": RTL " + describe(got) +
                    ", model " + describe(want);
    });
    r.samples = st.samples();
    r.clocks = st.cycles();
    r.fifo_max = st.memory.fifo_max;
    const uint32_t depth = fifo_depth ? fifo_depth : uint32_t(unit.config().fifo_depth);
    if (st.memory.fifo_max > depth && r.failure.empty())
      r.failure = "the FIFO held " + std::to_string(st.memory.fifo_max) + " samples, limit " + std::to_string(depth);
    if (coverage) {
      if (st.memory.fifo_max == depth) coverage->hit("FIFO full");
      if (model.stats().evictions_of_previous) coverage->hit("a line evicted while the previous sample needs it");
      if (unit.memory()->repeats_in_flight()) coverage->hit("the same line read twice in flight");
    }
  } catch (const Error& e) {
    r.failure = e.what();
    return r;
  }
  const std::vector<uint32_t> actual = unit.memory()->take_reads();
  r.reads = actual.size();
  if (r.failure.empty() && actual != predicted) {
    size_t i = 0;
    while (i < actual.size() && i < predicted.size() && actual[i] == predicted[i]) ++i;
    char text[160];
    std::snprintf(text, sizeof text, "miss stream differs at read %zu of %zu (model %zu): RTL 0x%08x, model 0x%08x", i,
                  actual.size(), predicted.size(), i < actual.size() ? actual[i] : 0u,
                  i < predicted.size() ? predicted[i] : 0u);
    r.failure = text;
  }
  if (const std::string c = compare_clocks(clocks, want_clocks); !c.empty() && r.failure.empty()) r.failure = c;
  return r;
}

CaseResult run_case(rtl::Driver& unit, const Pyramid& pyr, const SamplerConfig& cfg, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache, int poke_texel, uint32_t fifo_depth) {
  return run_case(unit, TextureTable{{&pyr}}, SamplerTable{cfg}, layout, cache, timing, requests, stim, seed,
                  coverage, model_cache, poke_texel, fifo_depth);
}

LayoutParams random_layout(std::mt19937_64& rng, const rtl::RtlConfig& c) {
  LayoutParams layout;
  layout.block_w = c.block_w;
  layout.block_h = c.block_h;
  layout.order = BlockOrder(rng() % 2);
  layout.base = uint32_t(rng() % 4) * 4096u;
  return layout;
}

CacheParams random_cache(std::mt19937_64& rng, const rtl::RtlConfig& c) {
  CacheParams p;
  p.ways = 1 << (rng() % 3);
  const int min_lines = 4 * p.ways, max_lines = c.lines;
  int lines = min_lines;
  while (lines < max_lines && rng() % 2) lines *= 2;
  p.size_bytes = lines * c.line_bytes();
  return p;
}

rtl::MemoryTiming random_memory(std::mt19937_64& rng, const rtl::RtlConfig& c, std::string& name) {
  rtl::MemoryTiming t;
  const int kind = int(rng() % 4);
  t.latency = kind == 0 ? 1 + uint32_t(rng() % 8) : kind == 1 ? 20 + uint32_t(rng() % 200) : 100;
  t.jitter = rng() % 2 ? uint32_t(rng() % 300) : 0;
  t.bytes_per_clock = 1 + uint32_t(rng() % uint64_t(c.mem_bits / 8));
  t.max_outstanding = rng() % 3 ? 64 : 1 + uint32_t(rng() % 8);
  if (kind == 3) {
    t.request_stall_prob = 0.3;
    t.response_stall_prob = 0.3;
  }
  t.seed = rng();
  name = "latency " + std::to_string(t.latency) + "+" + std::to_string(t.jitter) + ", " +
         std::to_string(t.bytes_per_clock) + " B/clock, " + std::to_string(t.max_outstanding) + " outstanding" +
         (kind == 3 ? ", port backpressure" : "");
  return t;
}

std::vector<uint64_t> random_error_reads(std::mt19937_64& rng, int ci) {
  std::vector<uint64_t> reads;
  if (ci % 3 != 1) return reads;
  for (int n = 1 + int(rng() % 3); n > 0; --n) reads.push_back(1 + rng() % 300);
  std::sort(reads.begin(), reads.end());
  reads.erase(std::unique(reads.begin(), reads.end()), reads.end());
  return reads;
}

}  // namespace tex::rtltest

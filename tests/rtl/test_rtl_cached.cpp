// Lockstep of tex_unit_cached (docs/memory.md) against the golden model: every response bit for
// bit against tex::Sampler::sample(), and every line the RTL reads from memory against the misses
// tex::TextureCache predicts, in order, under random cache geometries, block orders, memory
// latency, jitter, bandwidth, outstanding-read limits, random ARREADY / RVALID gaps and random
// request/response stalls; a third of the cases with memory errors (reads answered SLVERR): every
// response's rsp_error against the model's caches (the flagged samples answer 0). Functional
// coverage of the cache cases is asserted per configuration.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "lockstep.h"
#include "model/image.h"
#include "model/srgb.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

// Cache-side coverage bins, counted from the model's lookups and the driver's counters.
struct CacheCoverage {
  std::map<std::string, uint64_t> bins;
  void hit(const std::string& name) { ++bins[name]; }
  void sample(const SampleLookup& l) {
    for (int s = 0; s < 2; ++s) {
      const SlotLookup& sl = l.slot[size_t(s)];
      if (!sl.needed) continue;
      const std::string level = s == 0 ? "level d" : "level d1";
      hit(level + ": " + std::to_string(sl.misses) + " missing lines");
      const uint8_t m = sl.block_mask;
      const int n = __builtin_popcount(m);
      hit(level + ": footprint in " +
          (n == 1 ? std::string("1 block") : n == 4 ? std::string("4 blocks")
           : (m == 0x3 || m == 0xC) ? std::string("2 blocks side by side") : std::string("2 blocks one above the other")));
    }
    if (l.slot[0].misses > 0 && l.slot[1].misses > 0) hit("both levels missing");
  }
  // Every bin the configuration can reach: level d1 (level 1 or more) straddles blocks along an
  // axis only if level 1 is more than one block long along it.
  std::vector<std::string> required(const rtl::RtlConfig& c) const {
    std::vector<std::string> r;
    for (int s = 0; s < 2; ++s) {
      const std::string level = s == 0 ? "level d" : "level d1";
      const bool across = (1 << (c.max_log2_w - s)) > c.block_w, down = (1 << (c.max_log2_h - s)) > c.block_h;
      const int most = (across ? 2 : 1) * (down ? 2 : 1);
      for (int k = 0; k <= most; ++k) r.push_back(level + ": " + std::to_string(k) + " missing lines");
      r.push_back(level + ": footprint in 1 block");
      if (across) r.push_back(level + ": footprint in 2 blocks side by side");
      if (down) r.push_back(level + ": footprint in 2 blocks one above the other");
      if (across && down) r.push_back(level + ": footprint in 4 blocks");
    }
    for (const char* b : {"both levels missing", "FIFO full", "a line evicted while the previous sample needs it",
                          "the same line read twice in flight"})
      r.push_back(b);
    return r;
  }
};

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

struct CachedSuite {
  std::string config;  // a compiled tex_unit_cached configuration
  std::vector<Extent> textures;  // case i: textures[i % size]
  int cases;
  size_t requests_per_case;
  bool check_coverage = true;  // every bin of CacheCoverage::required must be hit
  std::vector<TexelFormat> formats = {TexelFormat::Rgba8};  // case i: formats[i % size], random blocks
  bool srgb = false;  // odd cases sRGB (where the format has it)
};

const rtl::RtlConfig& config_named(const std::string& name) {
  for (const rtl::RtlConfig& c : rtl::compiled_configs())
    if (c.name == name) return c;
  throw Error("no configuration " + name);
}

// One case: its result, or a failure description.
struct CaseResult {
  uint64_t samples = 0, clocks = 0, reads = 0;
  uint64_t flagged = 0;   // responses with rsp_error
  uint32_t fifo_max = 0;  // largest FIFO occupancy
  std::string failure;
};

// One case over a descriptor table and a sampler table (requests name a texture and a sampler):
// every response against the model's sampler of that pair, every line read against the model's
// caches.
CaseResult run_case(rtl::Driver& unit, const TextureTable& table, const SamplerTable& smp, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache = nullptr, int poke_texel = -1, uint32_t fifo_depth = 0,
                    const TextureTable* model_table = nullptr, const std::vector<uint64_t>& error_reads = {},
                    const std::vector<uint64_t>* model_error_reads = nullptr,
                    const SamplerTable* model_samplers = nullptr) {
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

// One texture and one sampler.
CaseResult run_case(rtl::Driver& unit, const Pyramid& pyr, const SamplerConfig& cfg, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache = nullptr, int poke_texel = -1, uint32_t fifo_depth = 0) {
  return run_case(unit, TextureTable{{&pyr}}, SamplerTable{cfg}, layout, cache, timing, requests, stim, seed,
                  coverage, model_cache, poke_texel, fifo_depth);
}

// The configuration's block shape in a random block order, at a random base.
LayoutParams random_layout(std::mt19937_64& rng, const rtl::RtlConfig& c) {
  LayoutParams layout;
  layout.block_w = c.block_w;
  layout.block_h = c.block_h;
  layout.order = BlockOrder(rng() % 2);
  layout.base = uint32_t(rng() % 4) * 4096u;
  return layout;
}

// A random cache geometry the configuration holds.
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

// Case ci of a suite: in a third of the cases 1 to 3 line reads, among the first 300, answer SLVERR.
std::vector<uint64_t> random_error_reads(std::mt19937_64& rng, int ci) {
  std::vector<uint64_t> reads;
  if (ci % 3 != 1) return reads;
  for (int n = 1 + int(rng() % 3); n > 0; --n) reads.push_back(1 + rng() % 300);
  std::sort(reads.begin(), reads.end());
  reads.erase(std::unique(reads.begin(), reads.end()), reads.end());
  return reads;
}

void run_suite(const CachedSuite& suite) {
  const auto t0 = std::chrono::steady_clock::now();
  const rtl::RtlConfig& rc = config_named(suite.config);
  const uint64_t base = mix64(seed_base() ^ std::hash<std::string>{}(suite.config));
  const std::optional<uint64_t> only = env_u64("TEX_SEED");
  rtl::DriverOptions dopt;
  dopt.seed = base;
  dopt.layout.block_w = rc.block_w;
  dopt.layout.block_h = rc.block_h;
  dopt.cache.size_bytes = 16 * rc.line_bytes();
  auto unit = rtl::Driver::create(rc, dopt);
  unit->reset();
  CacheCoverage coverage;
  const std::vector<Filter> filters = all_filters();
  uint64_t samples = 0, clocks = 0, reads = 0, failures = 0, flagged = 0;
  for (int ci = 0; ci < suite.cases * scale(); ++ci) {
    const uint64_t seed = mix64(base + uint64_t(ci));
    if (only && *only != seed) continue;
    std::mt19937_64 rng(seed);
    const Extent size = suite.textures[size_t(ci) % suite.textures.size()];
    const TexelFormat format = suite.formats[size_t(ci) % suite.formats.size()];
    Pyramid pyr = random_pyramid(rc, format, size, suite.srgb && ci % 2 == 1, seed);
    if (ci % 4 == 3) {  // a quarter of the cases sample a view (base and max level: cfg_desc_last_level)
      const int b = int(rng() % uint64_t(pyr.levels.size()));
      pyr = view_pyramid(pyr, b, b + int(rng() % 4));
    }
    SamplerConfig cfg;
    cfg.filter = filters[rng() % filters.size()];
    if (ci % 3 != 2) cfg.filter = Filter{TexelFilter::Linear, MipMode::Linear};  // most cases trilinear
    if (ci % 5 == 4) randomize_aniso(rng, cfg);  // a fifth anisotropic (the probes go through the caches)
    randomize_mag_filter(rng, cfg);
    cfg.wrap_u = random_wrap(rng);
    cfg.wrap_v = random_wrap(rng);
    randomize_border(rng, cfg);
    randomize_lod_controls(rng, cfg);
    randomize_reduction(rng, cfg);
    const bool unnormalized = ci % 7 == 6;  // a seventh with unnormalized coordinates
    if (unnormalized) make_unnormalized(rng, cfg);
    const LayoutParams layout = random_layout(rng, rc);
    const CacheParams cache = random_cache(rng, rc);
    std::string memory_name, timing_name;
    const rtl::MemoryTiming memory = random_memory(rng, rc, memory_name);
    const rtl::Timing stim = random_stalls(rng, timing_name);
    std::vector<Request> requests = unnormalized ? random_texel_requests(rng, pyr.extent0(), suite.requests_per_case)
                                                 : random_requests(rng, size, suite.requests_per_case);
    fetches_and_gathers_among(rng, requests, 16, [&](int) { return pyr.extent0(); });  // texelFetch and textureGather, 1 in 16
    cfg.compare_op = CompareOp(rng() % kCompareOps);
    compares_among(rng, requests, 16, SamplerTable{cfg}, [&](int) { return pyr.depth_problem().empty(); });  // depth compares, 1 in 16
    // A quarter of the cases use a shallower FIFO (cfg_fifo_limit), down to 1 sample.
    const uint32_t fifo_depth = rng() % 4 == 0 ? 1 + uint32_t(rng() % uint64_t(rc.fifo_depth)) : 0;
    const std::vector<uint64_t> errors = random_error_reads(rng, ci);
    const CaseResult r = run_case(*unit, TextureTable{{&pyr}}, SamplerTable{cfg}, layout, cache, memory,
                                  requests, stim, rng(), &coverage, nullptr, -1, fifo_depth, nullptr, errors);
    samples += r.samples;
    flagged += r.flagged;
    clocks += r.clocks;
    reads += r.reads;
    if (!r.failure.empty()) {
      ++failures;
      ADD_FAILURE() << suite.config << " case " << ci << " (replay: TEX_SEED=" << seed << "): "
                    << size.w << "x" << size.h << " (view " << pyr.extent0().w << "x" << pyr.extent0().h << ", "
                    << pyr.levels.size() << " levels) " << format_info(format).name << (pyr.srgb ? " sRGB" : "")
                    << ", " << describe(cfg) << ", "
                    << block_order_name(layout.order) << ", " << cache.size_bytes << " B x " << cache.ways
                    << " ways, FIFO " << (fifo_depth ? std::to_string(fifo_depth) : "all") << ", " << memory_name
                    << ", stimulus " << timing_name << ", " << errors.size() << " reads answered SLVERR: " << r.failure;
      unit->reset();
      if (failures >= 3) break;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ cached   ] %s: %llu samples (%llu flagged by memory errors), %llu clocks, %llu lines read, "
              "compared bit for bit and read for read (%.1f s)\n",
              suite.config.c_str(), (unsigned long long)samples, (unsigned long long)flagged,
              (unsigned long long)clocks, (unsigned long long)reads, secs);
  if (only) return;
  EXPECT_GT(flagged, 0u) << "no case of the suite flagged a sample: the memory-error check is vacuous";
  EXPECT_LT(flagged, samples / 4);
  if (!suite.check_coverage) return;
  for (const std::string& bin : coverage.required(rc)) {
    EXPECT_GT(coverage.bins[bin], 0u) << suite.config << ": coverage bin never hit: " << bin;
    std::printf("[ coverage ] %-52s %llu\n", bin.c_str(), (unsigned long long)coverage.bins[bin]);
  }
}

}  // namespace

// 64x8 (non-square), 4x4 blocks of RGBA8, 64 lines per cache at most, a 32-sample FIFO; textures
// of powers of two and of other sides (odd, primes, 1 x N: the repeat seam's copies in memory).
TEST(RtlCached, NonSquareRgba8) {
  run_suite({"Vtex_cached_6x3", {{64, 8}, {37, 7}, {32, 8}, {60, 5}, {8, 1}, {1, 7}, {64, 4}, {13, 3}, {36, 6}}, 63, 10000});
}

// Every block format on the unit with the formats (64-byte lines: BC1, BC4, ETC2 RGB8 and RGB8A1,
// EAC R11 lines of 16x8 texels, the others 8x8), random blocks (every BC7 mode, every ETC2 mode,
// EAC's 16-bit channels, signed ones in offset binary), decoded by the RTL's 8 tap decoders
// after the cache: samples, miss streams and response clocks against the model. (The cache bins
// above are RGBA8's line shape; these lines are wider.)
TEST(RtlCached, BlockFormats) {
  run_suite({"Vtex_cached_13x13", {{64, 8}, {61, 7}, {32, 4}, {4, 4}, {13, 5}, {64, 4}, {16, 8}, {30, 6}}, 32, 6000, false,
             {TexelFormat::Bc1, TexelFormat::Bc2, TexelFormat::Bc3, TexelFormat::Bc4, TexelFormat::Bc5,
              TexelFormat::Bc7, TexelFormat::Etc2Rgb, TexelFormat::Etc2RgbA1, TexelFormat::Etc2Rgba, TexelFormat::EacR11,
              TexelFormat::EacRg11Snorm, TexelFormat::EacRg11, TexelFormat::EacR11Snorm}});
}

// The sRGB configuration (8-bit channels in memory, a 16-bit filter): every format, sRGB in every
// other case (RGBA8, BC1, BC2, BC3, BC7) and linear in the others (8-bit values through the 16-bit
// filter), against the model's linear unorm16 samples.
TEST(RtlCached, SrgbAndLinearEveryFormat) {
  run_suite({"Vtex_cached_13x13", {{64, 8}, {32, 4}, {50, 6}, {4, 4}, {64, 4}, {9, 11}, {32, 4}}, 28, 4000, false,
             {TexelFormat::Rgba8, TexelFormat::Bc1, TexelFormat::Bc7, TexelFormat::Bc4, TexelFormat::Bc3,
              TexelFormat::Bc2, TexelFormat::Bc5, TexelFormat::Etc2Rgb, TexelFormat::Etc2Rgba, TexelFormat::Etc2RgbA1},
             true});
}

// ASTC, all 14 footprints (lines of 2 x 2 blocks: 8x8 .. 24x24 texels; the texel's block is x / F),
// linear and sRGB in turn, random blocks of every mode (stimulus::random_astc_block), sides powers
// of two (a footprint of 5, 6, 10 or 12 does not divide them: the repeat seam's copy) and not,
// decoded by the RTL's 8 tap decoders (tex_astc) after the cache: samples, miss streams and
// response clocks against the model.
TEST(RtlCached, AstcFootprints) {
  std::vector<TexelFormat> astc;  // each footprint twice: linear (even cases), then sRGB (odd)
  for (int i = 0; i < 28; ++i) astc.push_back(TexelFormat(int(TexelFormat::Astc4x4) + i / 2));
  run_suite({"Vtex_cached_13x13", {{64, 32}, {61, 7}, {32, 32}, {30, 13}, {128, 16}, {100, 24}, {16, 64}, {13, 5}, {4, 4}},
             28, 3000, false, astc, true});
}

// 32x16 with 16-bit channels, 2x4 blocks (128-byte lines), 64-bit memory beats.
TEST(RtlCached, Channels16Blocks2x4) {
  run_suite({"Vtex_cached_5x4_cw16", {{32, 16}, {27, 13}, {16, 16}, {1, 8}, {32, 2}, {31, 11}}, 60, 10000});
}

// The checkers fire: a model with other caches than the RTL's gives another miss stream, and one
// wrong byte in the memory image gives a wrong sample.
// The largest textures (8192 per side: the widest coordinates, indices and addresses), wide,
// tall and square, on the configuration texsim uses for them. A few cases: the two suites above
// cover the bins.
TEST(RtlCached, LargestTextures) {
  run_suite({"Vtex_cached_13x13", {{8192, 4}, {2, 8192}, {8192, 8192}, {8191, 3}, {5, 8191}}, 5, 20000, false});
}

const std::vector<TexelFormat> kBlockFormats = {TexelFormat::Bc1,     TexelFormat::Bc2,       TexelFormat::Bc3,
                                                TexelFormat::Bc4,     TexelFormat::Bc5,       TexelFormat::Bc7,
                                                TexelFormat::Etc2Rgb, TexelFormat::Etc2RgbA1, TexelFormat::Etc2Rgba,
                                                TexelFormat::EacR11,  TexelFormat::EacR11Snorm, TexelFormat::EacRg11,
                                                TexelFormat::EacRg11Snorm,
                                                TexelFormat::Astc4x4, TexelFormat::Astc6x5,   TexelFormat::Astc8x8,
                                                TexelFormat::Astc10x6, TexelFormat::Astc12x12};

// The descriptor table: 2 to 16 textures of random sizes, wrap modes and formats (RGBA8 and block
// formats mixed; with the sRGB tables, half of them sRGB) in memory at once, a random texture in
// every request (consecutive requests interleave textures at 1 sample per clock, no flush), under
// random caches, memory timing and stalls; samples, miss streams and response clocks against the
// model.
void run_descriptor_tables(const std::string& config, int cases) {
  const rtl::RtlConfig& rc = config_named(config);
  const uint64_t base = mix64(seed_base() ^ 0xDE5C ^ std::hash<std::string>{}(config));
  const std::optional<uint64_t> only = env_u64("TEX_SEED");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  uint64_t samples = 0, switches = 0, sampler_switches = 0, reads = 0, flagged = 0;
  int full_tables = 0, full_samplers = 0, failures = 0, block_textures = 0, srgb_textures = 0, array_textures = 0;
  int cube_textures = 0;
  std::map<std::string, uint64_t> layer_cases, cube_cases;
  for (int ci = 0; ci < cases * scale(); ++ci) {
    const uint64_t seed = mix64(base + uint64_t(ci));
    if (only && *only != seed) continue;
    std::mt19937_64 rng(seed);
    const int n = ci % 4 == 0 ? kMaxTextures : 2 + int(rng() % (kMaxTextures - 1));
    full_tables += n == kMaxTextures;
    std::vector<std::vector<Pyramid>> arrays(static_cast<size_t>(n));  // each texture's layers
    TextureTable table;
    for (int t = 0; t < n; ++t) {
      std::vector<Pyramid>& pyramids = arrays[size_t(t)];
      // Up to the configuration's 64x8, half of them of powers of two; half of the textures in a
      // block format (sides >= 4).
      // With CUBE_MAPS, one in 4 a cube map of n x n RGBA faces (n + 2 <= the smaller side), one in
      // 3 of those a cube array of 2 or 3 cubes.
      const bool cube = rc.cube_maps && rng() % 4 == 0;
      const TexelFormat format =
          cube || !rc.formats || rng() % 2 ? TexelFormat::Rgba8 : kBlockFormats[rng() % kBlockFormats.size()];
      const bool blocks = is_compressed(format), srgb = rng() % 2;
      Extent size;
      if (rng() % 2)
        size = {1 << (blocks ? 2 + int(rng() % 5) : int(rng() % 7)), 1 << (blocks ? 2 + int(rng() % 2) : int(rng() % 4))};
      else
        size = {blocks ? 4 + int(rng() % 61) : 1 + int(rng() % 64), blocks ? 4 + int(rng() % 5) : 1 + int(rng() % 8)};
      // A third of them arrays of 2 to 8 layers, now and then of 256 (each layer its own texels).
      int layers = rng() % 3 ? 1 : rng() % 8 == 0 ? kMaxLayers : 2 + int(rng() % 7);
      if (cube) {
        const int face = 1 + int(rng() % uint64_t(std::min(rc.max_cube_face(), 40)));
        size = {face, face};
        layers = 6 * (rng() % 3 ? 1 : 2 + int(rng() % 2));
      }
      const bool view = !cube && rng() % 4 == 0;  // a view: levels b..b+0..3 (the descriptor's last level)
      const uint64_t b = rng(), span = rng() % 4;
      for (int l = 0; l < layers; ++l) {
        pyramids.push_back(random_pyramid(rc, format, size, srgb, rng()));
        if (view) {
          const int first = int(b % uint64_t(pyramids.back().levels.size()));
          pyramids.back() = view_pyramid(pyramids.back(), first, first + int(span));
        }
      }
      block_textures += blocks;
      srgb_textures += pyramids.back().srgb;
      array_textures += !cube && layers > 1;
      cube_textures += cube;
      BoundTexture bound{&pyramids[0], {}, cube ? TextureKind::Cube : TextureKind::Texture2D};
      for (int l = 1; l < layers; ++l) bound.more_layers.push_back(&pyramids[size_t(l)]);
      table.push_back(bound);
    }
    // The sampler table: 1 to 16 entries (a quarter full), every field random.
    const int ns = ci % 4 == 1 ? kMaxSamplers : 1 + int(rng() % kMaxSamplers);
    full_samplers += ns == kMaxSamplers;
    SamplerTable samplers;
    for (int k = 0; k < ns; ++k) samplers.push_back(random_sampler(rng, 6));  // 1 in 6 unnormalized
    const LayoutParams layout = random_layout(rng, rc);
    const CacheParams cache = random_cache(rng, rc);
    std::string memory_name, timing_name;
    const rtl::MemoryTiming memory = random_memory(rng, rc, memory_name);
    const rtl::Timing stim = random_stalls(rng, timing_name);
    std::vector<Request> requests = random_requests(rng, 6, 3, 4000);  // (cube maps': below)
    for (size_t i = 0; i < requests.size(); ++i) {
      requests[i].texture = uint8_t(rng() % uint64_t(n));
      requests[i].sampler = uint8_t(rng() % uint64_t(ns));
      switches += i > 0 && requests[i].texture != requests[i - 1].texture;
      sampler_switches += i > 0 && requests[i].sampler != requests[i - 1].sampler;
    }
    texel_coordinates_where_unnormalized(rng, requests, samplers, [&](int t) { return table[size_t(t)].pyramid->extent0(); });
    fetches_and_gathers_among(rng, requests, 16, [&](int t) { return table[size_t(t)].pyramid->extent0(); });
    layers_among(rng, requests, [&](int t) { return table[size_t(t)].layers(); });
    compares_among(rng, requests, 16, samplers, [&](int t) { return table[size_t(t)].pyramid->depth_problem().empty(); });
    // A cube map's requests: cube_request's, through a sampler a cube takes (normalized; a
    // compare's, one that compares): sampler 0 is made one.
    if (cube_textures) samplers[0].unnormalized = false;
    for (Request& q : requests) {
      const BoundTexture& t = table[q.texture];
      if (t.kind != TextureKind::Cube) continue;
      q = cube_request(rng, q, t.pyramid->extent0().w, t.pyramid->last_level(), t.layers());
      auto takes = [&](const SamplerConfig& c) {
        return !c.unnormalized && (q.op != Op::Compare || c.compare_problem().empty());
      };
      if (!takes(samplers[q.sampler])) q.sampler = 0;
      if (q.op == Op::Compare && (!takes(samplers[q.sampler]) || t.pyramid->srgb)) q.op = Op::Sample;
      const int layer_of = q.op == Op::Fetch ? q.layer : -1;
      ++cube_cases[q.op == Op::Fetch ? (layer_of >= 0 && layer_of < t.layers() ? "a face's texel fetch" : "a fetch outside the faces")
                   : q.op == Op::Gather ? "a gather"
                   : q.op == Op::Compare ? "a depth compare"
                   : q.has_derivatives ? "derivatives" : "a lod"];
      if (q.op != Op::Fetch) {
        const stage::CubeFace f = stage::cube_face(q.u, q.v, q.w);
        const int32_t n = t.pyramid->extent0().w, edge = (1 << kCoordFracBits) / n;
        const bool near_s = f.s < edge || f.s > (1 << kCoordFracBits) - edge, near_t = f.t < edge || f.t > (1 << kCoordFracBits) - edge;
        ++cube_cases[near_s && near_t ? "at a corner" : near_s || near_t ? "at an edge" : "inside a face"];
        ++cube_cases["face " + std::to_string(f.face)];
        if (q.has_derivatives) {  // anisotropic probes beyond the face (tex_cube_seam moves them)
          int face = 0;
          const Probes p = tex_probe(cube_face_request(q, face), samplers[q.sampler], t.pyramid->extent0());
          for (int i = 0; i < p.n; ++i) {
            Request probe = p.at[size_t(i)];
            if (cube_probe(face, probe) != face) ++cube_cases["a probe moved to another face"];
          }
        }
      }
    }
    for (const Request& q : requests) {  // the layer cases of arrays, counted
      const int nl = table[q.texture].layers();
      if (nl == 1 || table[q.texture].kind == TextureKind::Cube) continue;
      const int64_t whole = q.layer >> 16;
      if (q.op == Op::Fetch) ++layer_cases[stage::fetch_layer_inside(q.layer, nl) ? "fetch inside the layers" : "fetch outside the layers"];
      else if (q.layer < 0) ++layer_cases["below layer 0"];
      else if (whole >= nl) ++layer_cases["beyond the last layer"];
      else if ((q.layer & 0xFFFF) == 0x8000) ++layer_cases[whole % 2 ? "a tie, rounded up to even" : "a tie, rounded down to even"];
      else ++layer_cases["between two layers"];
    }
    const std::vector<uint64_t> errors = random_error_reads(rng, ci);
    const CaseResult r = run_case(*unit, table, samplers, layout, cache, memory, requests, stim, rng(), nullptr, nullptr,
                                  -1, 0, nullptr, errors);
    samples += r.samples;
    reads += r.reads;
    flagged += r.flagged;
    if (!r.failure.empty()) {
      ADD_FAILURE() << "case " << ci << " (replay: TEX_SEED=" << seed << "): " << n << " textures, " << ns
                    << " samplers (0: " << describe(samplers[0]) << "), " << cache.size_bytes << " B x " << cache.ways << " ways, " << memory_name << ", stimulus "
                    << timing_name << ": " << r.failure << "; the textures:" << [&] {
                         std::string list;
                         for (size_t t = 0; t < table.size(); ++t) {
                           const Pyramid& p = *table[t].pyramid;
                           list += " " + std::to_string(t) + " " + format_info(p.format).name + (p.srgb ? " sRGB " : " ") +
                                   std::to_string(p.extent0().w) + "x" + std::to_string(p.extent0().h);
                         }
                         for (size_t t = 0; t < samplers.size(); ++t) list += "; sampler " + std::to_string(t) + ": " + describe(samplers[t]);
                         return list;
                       }();
      unit->reset();
      if (++failures >= 3) break;
    }
  }
  std::printf("[ cached   ] descriptor and sampler tables: %llu samples (%llu flagged by memory errors), %llu "
              "texture and %llu sampler switches between consecutive requests, %llu lines read, %d full descriptor "
              "tables of %d, %d full sampler tables of %d, %d block-format textures, %d sRGB, %d arrays (%s)\n",
              (unsigned long long)samples, (unsigned long long)flagged, (unsigned long long)switches,
              (unsigned long long)sampler_switches, (unsigned long long)reads, full_tables, kMaxTextures,
              full_samplers, kMaxSamplers, block_textures, srgb_textures, array_textures, config.c_str());
  if (rc.cube_maps) {
    std::printf("[ cached   ] %d cube maps:", cube_textures);
    for (const auto& [c, k] : cube_cases) std::printf(" %s %llu;", c.c_str(), (unsigned long long)k);
    std::printf("\n");
  }
  if (only) return;
  EXPECT_GT(full_tables, 0);
  EXPECT_GT(full_samplers, 0);
  EXPECT_GT(array_textures, 0);
  EXPECT_EQ(cube_textures > 0, rc.cube_maps);
  if (rc.cube_maps) {
    for (const char* c : {"a face's texel fetch", "a fetch outside the faces", "a gather", "a depth compare", "derivatives",
                          "a lod", "at a corner", "at an edge", "inside a face", "face 0", "face 1", "face 2", "face 3",
                          "face 4", "face 5", "a probe moved to another face"})
      EXPECT_GT(cube_cases[c], 0u) << "cube requests: " << c;
  }
  for (const char* c : {"fetch inside the layers", "fetch outside the layers", "below layer 0", "beyond the last layer",
                        "a tie, rounded up to even", "a tie, rounded down to even", "between two layers"})
    EXPECT_GT(layer_cases[c], 0u) << "array requests: " << c;
  EXPECT_GT(sampler_switches, samples / 2);
  EXPECT_GT(flagged, 0u);
  EXPECT_EQ(block_textures > 0, rc.formats);
  EXPECT_EQ(srgb_textures > 0, rc.formats);
  EXPECT_GT(switches, samples / 2);
}

TEST(RtlCached, DescriptorAndSamplerTablesInterleave) { run_descriptor_tables("Vtex_cached_6x3", 40); }

// With the sRGB tables (CW 16 filter, 8-bit memory): sRGB and linear textures of every format mixed
// in one table; a model that filters an sRGB texture's codes as linear values is caught.
TEST(RtlCached, DescriptorTableMixesSrgbAndLinear) {
  run_descriptor_tables("Vtex_cached_13x13", 24);
  auto unit = rtl::Driver::create(config_named("Vtex_cached_13x13"), {});
  unit->reset();
  std::mt19937_64 rng(8);
  const Pyramid srgb = build_srgb_pyramid(random_image(64, 8, 8, 4), PyramidMode::Exact);
  Pyramid codes = srgb;  // planted: the stored codes, filtered as if linear (16-bit values a * 257)
  for (size_t k = 0; k < codes.levels.size(); ++k) {
    codes.levels[k] = srgb.codes[k];
    codes.levels[k].channel_bits = 16;
    for (Texel& t : codes.levels[k].texels)
      for (uint16_t& c : t) c = uint16_t(c * 257);
  }
  const std::vector<Request> requests = random_requests(rng, 6, 3, 2000);
  const TextureTable table = {{&srgb}}, wrong = {{&codes}};
  const CacheParams cache{2048, 2};
  EXPECT_EQ(run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, {}, requests, {}, 1, nullptr).failure, "");
  const CaseResult planted =
      run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, -1, 0, &wrong);
  EXPECT_EQ(planted.failure.rfind("sample ", 0), 0u) << planted.failure;
}

// Planted bugs: a model whose sampler table has the entries' wrap modes swapped, whose border
// colours differ, whose array has its layers in the other order, or whose descriptor table has its
// entries in the other order (each request then names the other texture), sees other samples.
TEST(RtlCached, DescriptorTableCheckersCatchPlantedBugs) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  std::mt19937_64 rng(3);
  const Pyramid a = build_pyramid(random_image(64, 8, 8, 1), PyramidMode::Exact);
  const Pyramid b = build_pyramid(random_image(32, 4, 8, 2), PyramidMode::Exact);
  std::vector<Request> requests = random_requests(rng, 6, 3, 2000);
  for (Request& q : requests) {
    q.texture = uint8_t(rng() % 2);
    q.sampler = uint8_t(rng() % 2);
  }
  const TextureTable table = {{&a}, {&b}};
  SamplerTable samplers(2);
  samplers[0].wrap_u = Wrap::Repeat;
  samplers[0].wrap_v = Wrap::Clamp;
  samplers[1].wrap_u = Wrap::Mirror;
  samplers[1].wrap_v = Wrap::Border;
  samplers[1].border = BorderColor::FloatOpaqueWhite;
  SamplerTable rewrapped = samplers;
  std::swap(rewrapped[0].wrap_u, rewrapped[1].wrap_u);
  SamplerTable recoloured = samplers;
  recoloured[1].border = BorderColor::FloatOpaqueBlack;
  const CacheParams cache{2048, 2};
  const CaseResult good = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr);
  EXPECT_EQ(good.failure, "");
  const CaseResult wrap = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                   -1, 0, nullptr, {}, nullptr, &rewrapped);
  EXPECT_EQ(wrap.failure.rfind("sample ", 0), 0u) << wrap.failure;
  unit->reset();
  const CaseResult colour = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                     -1, 0, nullptr, {}, nullptr, &recoloured);
  EXPECT_EQ(colour.failure.rfind("sample ", 0), 0u) << colour.failure;
  unit->reset();
  // An array whose model has its layers in the other order.
  const Pyramid c = build_pyramid(random_image(32, 4, 8, 3), PyramidMode::Exact);
  const TextureTable arrays = {{&a}, {&b, {&c}}}, swapped = {{&a}, {&c, {&b}}};
  std::vector<Request> layered = requests;
  for (Request& q : layered) q.layer = q.texture == 1 ? int32_t(rng() % 2) << 16 : 0;
  EXPECT_EQ(run_case(*unit, arrays, samplers, LayoutParams{}, cache, {}, layered, {}, 1, nullptr).failure, "");
  unit->reset();
  const CaseResult layers = run_case(*unit, arrays, samplers, LayoutParams{}, cache, {}, layered, {}, 1, nullptr, nullptr,
                                     -1, 0, &swapped);
  EXPECT_EQ(layers.failure.rfind("sample ", 0), 0u) << layers.failure;
  unit->reset();
  const TextureTable reordered = {table[1], table[0]};
  const CaseResult order = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                    -1, 0, &reordered);
  EXPECT_EQ(order.failure.rfind("sample ", 0), 0u) << order.failure;
}

// Cube maps, planted bugs: a skirt corner that is not the average of three (its R flipped in
// memory), a skirt texel across an edge from the wrong face (likewise), a model whose cube has two
// faces swapped, each seen as other samples; the unplanted cube agrees. Lookups at +X's corner
// (s, t near 0) and along its top edge at level 0, and anywhere on the cube.
TEST(RtlCached, CubeCheckersCatchPlantedBugs) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  std::mt19937_64 rng(35);
  const int n = 4;
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) faces.push_back(build_pyramid(random_image(n, n, 8, 60 + uint64_t(f)), PyramidMode::Exact));
  std::vector<Pyramid> swapped = faces;
  std::swap(swapped[2], swapped[3]);
  auto cube_of = [](const std::vector<Pyramid>& f) {
    const std::vector<const Pyramid*> p = pointers_to(f);
    return TextureTable{BoundTexture(p[0], {p.begin() + 1, p.end()}, TextureKind::Cube)};
  };
  const TextureTable table = cube_of(faces), wrong = cube_of(swapped);
  SamplerConfig bilinear;
  bilinear.filter = Filter{TexelFilter::Linear, MipMode::None};
  std::vector<Request> requests;
  for (int i = 0; i < 3000; ++i) {
    Request q;
    q.tag = uint16_t(i);
    if (i % 3 == 2) {
      q = cube_request(rng, q, n, faces[0].last_level(), 6);
      if (q.op == Op::Fetch) q.op = Op::Sample, q.lod = 0, q.layer = 0;
    } else {  // +X at its corner (s, t < 1 / 2n) or along its top edge (t < 1 / 2n)
      const double s = double(rng() % 1000) / 1000 / (i % 3 == 0 ? 2 * n : 1), t = double(rng() % 1000) / 1000 / (2 * n);
      const std::array<int32_t, 3> d = cube_direction(rng, 0, s, t);
      q.u = d[0], q.v = d[1], q.w = d[2];
    }
    requests.push_back(q);
  }
  const CacheParams cache{2048, 2};
  const SamplerTable samplers{bilinear};
  EXPECT_EQ(run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr).failure, "");
  // (byte 0 of +X's level 0: its skirt's corner texel (0, 0); byte 4: the skirt texel (1, 0) above
  // its texel (0, 0), a texel of +Y)
  for (const int poke : {0, 4}) {
    const CaseResult planted =
        run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, poke);
    EXPECT_EQ(planted.failure.rfind("sample ", 0), 0u) << "byte " << poke << ": " << planted.failure;
  }
  const CaseResult faces_swapped =
      run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, -1, 0, &wrong);
  EXPECT_EQ(faces_swapped.failure.rfind("sample ", 0), 0u) << faces_swapped.failure;
}

TEST(RtlCached, CheckersCatchPlantedBugs) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  const Pyramid pyr = build_pyramid(random_image(64, 8, 8, 7), PyramidMode::Exact);
  std::mt19937_64 rng(11);
  const std::vector<Request> requests = random_requests(rng, 6, 3, 5000);
  SamplerConfig cfg;
  LayoutParams layout;
  CacheParams cache{2048, 2}, other{2048, 1};
  rtl::MemoryTiming memory;
  const CaseResult good = run_case(*unit, pyr, cfg, layout, cache, memory, requests, {}, 1, nullptr);
  EXPECT_EQ(good.failure, "");
  EXPECT_GT(good.reads, 0u);
  const CaseResult lru = run_case(*unit, pyr, cfg, layout, cache, memory, requests, {}, 1, nullptr, &other);
  EXPECT_NE(lru.failure.find("miss stream differs"), std::string::npos) << lru.failure;
  unit->reset();
  const CaseResult data = run_case(*unit, pyr, cfg, layout, cache, memory, requests, {}, 1, nullptr, nullptr, 0);
  EXPECT_EQ(data.failure.rfind("sample ", 0), 0u) << data.failure;  // a sample mismatch, not a protocol error
  EXPECT_NE(data.failure.find(": RTL "), std::string::npos) << data.failure;

  // Block formats: the RTL decodes BC3 blocks, a model that reads the same bytes as BC2 (the same
  // line shape, so the same lines) sees other samples.
  unit = rtl::Driver::create(config_named("Vtex_cached_13x13"), {});
  unit->reset();
  const Pyramid bc3 = random_block_texture(TexelFormat::Bc3, {64, 8}, 5);
  const Pyramid as_bc2 = pyramid_of_blocks(TexelFormat::Bc2, {64, 8}, bc3.blocks);
  const TextureTable rtl_table = {{&bc3}}, model_table = {{&as_bc2}};
  const CaseResult same = run_case(*unit, rtl_table, SamplerTable{cfg}, layout, cache, memory, requests, {}, 1, nullptr);
  EXPECT_EQ(same.failure, "");
  const CaseResult misread = run_case(*unit, rtl_table, SamplerTable{cfg}, layout, cache, memory, requests, {}, 1, nullptr, nullptr, -1,
                                    0, &model_table);
  EXPECT_EQ(misread.failure.rfind("sample ", 0), 0u) << misread.failure;
}

// Memory errors: the 5th line read answers SLVERR. The samples that look the line up while it is
// cached come out flagged, as 0, and the unit keeps running (every later sample answered). A model
// that counts the error one read late, or a memory that flags the line and a model that does not,
// disagrees on a flag.
TEST(RtlCached, MemoryErrorsFlagTheSamplesThatReadTheLine) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  const Pyramid pyr = build_pyramid(random_image(64, 8, 8, 9), PyramidMode::Exact);
  std::mt19937_64 rng(13);
  const std::vector<Request> requests = random_requests(rng, 6, 3, 3000);
  const TextureTable table = {{&pyr}};
  const CacheParams cache{2048, 2};
  rtl::MemoryTiming memory;
  memory.jitter = 40;
  memory.request_stall_prob = memory.response_stall_prob = 0.2;
  const std::vector<uint64_t> fifth = {5}, sixth = {6}, none = {};
  const CaseResult good = run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, memory, requests, {}, 1,
                                   nullptr, nullptr, -1, 0, nullptr, fifth);
  EXPECT_EQ(good.failure, "");
  EXPECT_EQ(good.samples, requests.size());
  EXPECT_GT(good.flagged, 0u);
  EXPECT_LT(good.flagged, requests.size() / 10);
  unit->reset();
  const CaseResult late = run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, memory, requests, {}, 1,
                                   nullptr, nullptr, -1, 0, nullptr, fifth, &sixth);
  EXPECT_NE(late.failure.find("rsp_error"), std::string::npos) << late.failure;
  unit->reset();
  const CaseResult unseen = run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, memory, requests, {}, 1,
                                     nullptr, nullptr, -1, 0, nullptr, fifth, &none);
  EXPECT_NE(unseen.failure.find("RTL rsp_error 1, model 0"), std::string::npos) << unseen.failure;
}

// cfg_fifo_limit: a shallower FIFO holds at most that many samples and hides less latency;
// the answers and the lines read stay the same.
TEST(RtlCached, FifoLimitMakesAShallowerFifo) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  const Pyramid pyr = build_pyramid(random_image(64, 8, 8, 3), PyramidMode::Exact);
  std::mt19937_64 rng(5);
  const std::vector<Request> requests = random_requests(rng, 6, 3, 4000);
  SamplerConfig cfg;
  LayoutParams layout;
  const CacheParams cache{2048, 2};
  rtl::MemoryTiming memory;
  memory.latency = 60;
  const CaseResult full = run_case(*unit, pyr, cfg, layout, cache, memory, requests, {}, 1, nullptr);
  ASSERT_EQ(full.failure, "");
  EXPECT_EQ(full.fifo_max, uint32_t(rc.fifo_depth));
  const CaseResult shallow = run_case(*unit, pyr, cfg, layout, cache, memory, requests, {}, 1, nullptr, nullptr, -1, 4);
  ASSERT_EQ(shallow.failure, "");
  EXPECT_EQ(shallow.fifo_max, 4u);
  EXPECT_EQ(shallow.reads, full.reads);
  EXPECT_GT(shallow.clocks, full.clocks + full.clocks / 4) << "4 samples cannot hide a 60-clock latency";
  unit->set_memory(layout, cache, memory, uint32_t(rc.fifo_depth) + 1);
  EXPECT_THROW(unit->load(pyr, LoadMethod::Backdoor), Error);
}


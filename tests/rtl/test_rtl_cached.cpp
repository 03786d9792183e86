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

#include "cached_lockstep.h"
#include "lockstep.h"
#include "model/image.h"
#include "model/srgb.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

struct CachedSuite {
  std::string config;  // a compiled tex_unit_cached configuration
  std::vector<Extent> textures;  // case i: textures[i % size]
  int cases;
  size_t requests_per_case;
  bool check_coverage = true;  // every bin of CacheCoverage::required must be hit
  std::vector<TexelFormat> formats = {TexelFormat::Rgba8};  // case i: formats[i % size], random blocks
  bool srgb = false;  // odd cases sRGB (where the format has it)
};

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

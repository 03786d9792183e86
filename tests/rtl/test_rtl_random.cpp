// Constrained-random lockstep: every filter x every wrap mode per axis x several textures (both
// pyramid modes, square and non-square, 1-texel sides, sides that are not powers of two: odd and
// prime, whose odd levels read the repeat seam's copies) on each compiled configuration, random
// request timing, every response compared bit for bit with tex::Sampler::sample().
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <cstdio>

#include "coverage.h"
#include "lockstep.h"
#include "model/image.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

struct TextureSpec {
  std::string pattern;  // a built-in pattern (8-bit), or "noise16": every channel random over 16 bits
  int width, height;
  PyramidMode mode;
  int base_level = 0, max_level = kMaxLevels - 1;  // the view the unit samples (view_pyramid)
};

Image make_texture(const TextureSpec& ts) {
  if (ts.pattern != "noise16") return make_pattern(ts.pattern, ts.width, ts.height);
  Image img(ts.width, ts.height, 16);
  std::mt19937_64 rng(uint64_t(ts.width) * 4099 + uint64_t(ts.height));
  for (Texel& t : img.texels)
    for (uint16_t& c : t) c = uint16_t(rng());
  return img;
}

struct RandomSuite {
  std::string name;
  int max_log2_w, max_log2_h;
  std::vector<TextureSpec> textures;
  size_t requests_per_case;  // per (texture, filter, wrap u, wrap v)
  int cw = 8;                // bits per channel of the configuration and of its textures
};

// Totals of one suite (the functional coverage is in coverage.h).
struct Totals {
  uint64_t rounds = 0, samples = 0, clocks = 0, stall_clocks = 0, gap_clocks = 0, longest_latency = 0;
};

void run_suite(const RandomSuite& suite) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<uint64_t> only = env_u64("TEX_SEED");
  const uint64_t base = mix64(seed_base() ^ std::hash<std::string>{}(suite.name));
  auto unit = make_unit(suite.max_log2_w, suite.max_log2_h, base, "", suite.cw);
  const std::vector<Filter> filters = all_filters();
  Totals totals;
  Coverage coverage(suite.max_log2_w, suite.max_log2_h);
  uint64_t failures = 0;

  // One case: its seed draws the sampler configuration (after `configure`), the timing and the
  // requests; anisotropic cases take a quarter of the requests, each with a footprint of 1..16
  // probes along u, v or a diagonal. Returns false once enough failures are reported.
  auto run_case = [&](const TextureSpec& ts, std::optional<Pyramid>& pyr, bool port_load, uint64_t seed, bool aniso,
                      const std::function<void(std::mt19937_64&, SamplerConfig&)>& configure, bool unnormalized = false) {
    if (only && *only != seed) return true;
    if (!pyr) {  // loaded lazily: a replay of one seed loads only its texture
      pyr = view_pyramid(build_pyramid(make_texture(ts), ts.mode), ts.base_level, ts.max_level);
      unit->load(*pyr, port_load ? LoadMethod::Port : LoadMethod::Backdoor);
    }
    std::mt19937_64 rng(seed);
    SamplerConfig cfg;
    configure(rng, cfg);
    randomize_lod_controls(rng, cfg);
    randomize_reduction(rng, cfg);
    if (unnormalized) make_unnormalized(rng, cfg);
    std::string timing_name;
    const rtl::Timing timing = random_stalls(rng, timing_name);
    const size_t n = suite.requests_per_case * scale() / (aniso ? 4 : 1);
    auto reqs = unnormalized ? random_texel_requests(rng, pyr->extent0(), n) : random_requests(rng, pyr->extent0(), n);
    if (aniso)
      for (Request& q : reqs) {
        q.has_derivatives = true;
        q.deriv = random_footprint(rng, pyr->extent0(), int(rng() % 16) + 1, int(rng() % 4)).deriv;
      }
    fetches_and_gathers_among(rng, reqs, 16, [&](int) { return pyr->extent0(); });  // texelFetch and textureGather, 1 in 16
    cfg.compare_op = CompareOp(rng() % kCompareOps);
    compares_among(rng, reqs, 16, SamplerTable{cfg}, [](int) { return true; });  // depth compares, 1 in 16
    const LockstepResult r = lockstep(*unit, *pyr, cfg, reqs, timing, rng());

    ++totals.rounds;
    totals.samples += r.compared;
    totals.clocks += r.stats.cycles();
    totals.stall_clocks += r.stats.protocol.output_stall_cycles;
    totals.gap_clocks += r.stats.gap_cycles;
    totals.longest_latency = std::max(totals.longest_latency, r.stats.protocol.latency_max);
    coverage.timing(r.stats);
    if (r.compared == reqs.size())
      for (const Request& q : reqs) coverage.sample(*pyr, cfg, q);
    if (r.ok()) return true;
    ++failures;
    ADD_FAILURE() << suite.name << ": texture " << ts.pattern << ":" << ts.width << "x" << ts.height << " levels "
                  << ts.base_level << ".." << ts.max_level << " "
                  << (ts.mode == PyramidMode::Exact ? "exact" : "cascade") << ", " << describe(cfg)
                  << (aniso ? " max_aniso " + std::to_string(cfg.max_aniso) + (cfg.aniso_pow2 ? " pow2" : "") : "")
                  << ", timing " << timing_name << ", " << reqs.size() << " requests\n"
                  << r.report << "replay: TEX_SEED=" << seed
                  << (seed_base() != 20240601 ? " TEX_SEED_BASE=" + std::to_string(seed_base()) : "")
                  << " texunit_rtl_tests --gtest_filter=" << testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()
                  << "." << testing::UnitTest::GetInstance()->current_test_info()->name();
    return failures < 3;  // enough to debug; keep the log short
  };

  for (size_t ti = 0; ti < suite.textures.size(); ++ti) {
    const TextureSpec& ts = suite.textures[ti];
    const bool port_load = ti % 2;  // half through the write port, half by the backdoor: the same samples
    std::optional<Pyramid> pyr;
    for (int wu = 0; wu < kWrapModes; ++wu)
      for (int wv = 0; wv < kWrapModes; ++wv) {
        auto wraps = [&](std::mt19937_64& rng, SamplerConfig& cfg) {
          cfg.wrap_u = Wrap(wu);
          cfg.wrap_v = Wrap(wv);
          randomize_border(rng, cfg);
        };
        for (size_t fi = 0; fi < filters.size(); ++fi) {
          const uint64_t seed = mix64(base + ((ti * 6 + fi) * kWrapModes + wu) * kWrapModes + wv);
          if (!run_case(ts, pyr, port_load, seed, false, [&](std::mt19937_64& rng, SamplerConfig& cfg) {
                cfg.filter = filters[fi];
                if ((wu + wv + fi) % 2) cfg.filter.mag = TexelFilter(1 - int(cfg.filter.texel));  // magnifies apart
                wraps(rng, cfg);
              }))
            return;
        }
        // unnormalized coordinates (the clamping pairs), each texel filter with a random mip mode
        const bool clamping = (wu == int(Wrap::Clamp) || wu == int(Wrap::Border)) &&
                              (wv == int(Wrap::Clamp) || wv == int(Wrap::Border));
        for (int tf = 0; clamping && tf < 2; ++tf) {
          const uint64_t useed = mix64(base + 0x5A5A + ((ti * 2 + tf) * kWrapModes + wu) * kWrapModes + wv);
          if (!run_case(ts, pyr, port_load, useed, false, [&](std::mt19937_64& rng, SamplerConfig& cfg) {
                cfg.filter = filters[size_t(tf) * 3 + rng() % 3];
                wraps(rng, cfg);
              }, true))
            return;
        }
        // the anisotropic filter, once per wrap pair
        const uint64_t seed = mix64(base + 0xA5A5 + (ti * kWrapModes + wu) * kWrapModes + wv);
        if (!run_case(ts, pyr, port_load, seed, true, [&](std::mt19937_64& rng, SamplerConfig& cfg) {
              wraps(rng, cfg);
              randomize_aniso(rng, cfg);
            }))
          return;
      }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: %llu cases, %llu samples compared bit for bit in %.1f s (%llu clocks, %llu stall, %llu gap; "
              "latency up to %llu)\n",
              suite.name.c_str(), (unsigned long long)totals.rounds, (unsigned long long)totals.samples, secs,
              (unsigned long long)totals.clocks, (unsigned long long)totals.stall_clocks,
              (unsigned long long)totals.gap_clocks, (unsigned long long)totals.longest_latency);
  std::printf("%s functional coverage (bins hit / reachable):\n%s", suite.name.c_str(), coverage.table(env_u64("TEX_COVERAGE_BINS").value_or(0) != 0).c_str());
  testing::Test::RecordProperty("samples_compared", std::to_string(totals.samples));
  if (only) {
    EXPECT_EQ(totals.rounds, 1u) << "TEX_SEED=" << *only << " is not a case of " << suite.name;
    return;
  }
  // 6 filters and anisotropic per wrap pair; unnormalized: 4 clamping pairs x 2 texel filters
  EXPECT_EQ(totals.rounds, suite.textures.size() * ((6 + 1) * kWrapModes * kWrapModes + 4 * 2));
  // Every reachable bin of the functional coverage was exercised, and no bin declared unreachable was.
  for (const std::string& hole : coverage.holes()) ADD_FAILURE() << suite.name << " coverage: " << hole;
  EXPECT_GE(totals.longest_latency, 100u) << "no long stall happened";
}

}  // namespace

TEST(RtlRandom, Small4x4) {
  run_suite({"Small4x4", 4, 4,
             {{"noise", 16, 16, PyramidMode::Exact},
              {"noise", 16, 2, PyramidMode::Cascade, 0, 2},  // a chain cut at level 2 (cfg_last_level)
              {"noise", 1, 16, PyramidMode::Exact},
              {"testcard", 13, 11, PyramidMode::Cascade}},
             5000});
}

TEST(RtlRandom, NonSquare6x3) {
  run_suite({"NonSquare6x3", 6, 3,
             {{"noise", 64, 8, PyramidMode::Cascade},
              {"noise", 63, 7, PyramidMode::Exact, 1, 3},  // the view 31x3 .. 7x1
              {"noise", 32, 1, PyramidMode::Exact},
              {"noise", 2, 8, PyramidMode::Cascade}},
             5000});
}

TEST(RtlRandom, Large10x10) {
  run_suite({"Large10x10", 10, 10,
             {{"noise", 1024, 1024, PyramidMode::Exact},
              {"noise", 1000, 600, PyramidMode::Cascade},
              {"noise", 1024, 2, PyramidMode::Exact, 0, 4}},
             6000});
}

TEST(RtlRandom, Wide16Bit5x4) {
  // 16-bit channels (CW = 16): the lerps' products and the rounding at full width.
  run_suite({"Wide16Bit5x4", 5, 4,
             {{"noise16", 32, 16, PyramidMode::Exact},
              {"noise16", 29, 11, PyramidMode::Cascade, 0, 2},
              {"noise16", 32, 1, PyramidMode::Cascade}},
             3000, 16});
}

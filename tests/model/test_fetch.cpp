// texelFetch (Op::Fetch, stage::fetch_inside): the texel (i, j) of level k as the pyramid holds it,
// whatever the sampler; 0 and no memory read outside the texture (Vulkan's robust image access);
// the fast path and the reference path agree; a cached fetch reads exactly the line of its texel.
// Expected texels come from the pyramid's images, not from the sampler.
#include <gtest/gtest.h>

#include <random>

#include "model/error.h"
#include "model/image.h"
#include "model/memory_layout.h"
#include "model/sampler.h"
#include "model/texture_cache.h"

using namespace tex;

namespace {

// Sampler states a fetch must not see: filters, address modes, LOD bias and clamps, a border colour,
// a reduction.
std::vector<SamplerConfig> unrelated_samplers() {
  std::vector<SamplerConfig> out(4);
  out[1].filter = {TexelFilter::Nearest, MipMode::None};
  out[1].wrap_u = Wrap::Border;
  out[1].border = BorderColor::FloatOpaqueWhite;
  out[2].filter = {TexelFilter::Linear, MipMode::Linear, true};
  out[2].wrap_v = Wrap::Mirror;
  out[2].lod_bias = 3 * 256;
  out[2].reduction = Reduction::Max;
  out[3].min_lod = 2 * 256;
  out[3].max_lod = 2 * 256;
  out[3].wrap_u = Wrap::Clamp;
  return out;
}

}  // namespace

TEST(TexelFetch, NamesOfTheOperation) {
  Op op{};
  EXPECT_TRUE(parse_op("fetch", op));
  EXPECT_EQ(op, Op::Fetch);
  EXPECT_TRUE(parse_op("texelFetch", op));
  EXPECT_EQ(op, Op::Fetch);
  EXPECT_TRUE(parse_op("sample", op));
  EXPECT_EQ(op, Op::Sample);
  EXPECT_FALSE(parse_op("sampel", op));
  EXPECT_EQ(op_name(Op::Fetch), "fetch");
}

// Every texel of every level of an NPOT texture, and a ring of indices around each level and
// levels beyond both ends: the pyramid's texel inside, 0 outside; the same under every sampler.
TEST(TexelFetch, ReadsThePyramidsTexelAndZeroOutside) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 37, 23));
  const Texel zero{};
  int inside = 0, outside = 0;
  for (const SamplerConfig& cfg : unrelated_samplers()) {
    Sampler s(pyr, cfg);
    for (int k = -2; k <= pyr.last_level() + 2; ++k) {
      const Extent e = level_extent(pyr.extent0(), std::clamp(k, 0, pyr.last_level()));
      for (int j = -2; j < e.h + 2; ++j)
        for (int i = -2; i < e.w + 2; ++i) {
          const bool in = k >= 0 && k <= pyr.last_level() && i >= 0 && i < e.w && j >= 0 && j < e.h;
          const Texel want = in ? pyr.levels[size_t(k)].at(i, j) : zero;
          ASSERT_EQ(s.sample(fetch_request(i, j, k)), want) << "level " << k << " (" << i << ", " << j << ")";
          (in ? inside : outside)++;
        }
    }
    for (int32_t far : {INT32_MIN, -8192, 8192, INT32_MAX}) {
      EXPECT_EQ(s.sample(fetch_request(far, 0, 0)), zero);
      EXPECT_EQ(s.sample(fetch_request(0, far, 0)), zero);
      EXPECT_EQ(s.sample(fetch_request(0, 0, far)), zero);
    }
  }
  EXPECT_GT(inside, 4000);
  EXPECT_GT(outside, 1000);
}

// The fast path (8-bit textures) gives the reference path's texels for fetches mixed into samples.
TEST(TexelFetch, FastPathMatchesReference) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 20));
  std::mt19937_64 rng(7);
  std::vector<Request> reqs;
  for (int n = 0; n < 3000; ++n) {
    if (n % 3 == 0) {
      reqs.push_back(fetch_request(int32_t(rng() % 70) - 3, int32_t(rng() % 26) - 3, int32_t(rng() % 10) - 2, uint32_t(n)));
    } else {
      reqs.push_back(lambda_request(int32_t(rng() % (2u << 24)), int32_t(rng() % (2u << 24)), int32_t(rng() % 2048)));
    }
  }
  Sampler s(pyr, SamplerConfig{});
  std::vector<uint32_t> fast(reqs.size());
  s.sample_rgba8(reqs.data(), reqs.size(), fast.data());
  for (size_t n = 0; n < reqs.size(); ++n) {
    const Texel t = s.sample(reqs[n]);
    ASSERT_EQ(fast[n], uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24) << n;
  }
}

// A cached fetch looks up the one line that holds its texel (the layout's block of (i, j) in level
// k, in the level's parity cache) and nothing when it is outside the texture.
TEST(TexelFetch, CacheReadsTheTexelsLineOrNothing) {
  const MemoryLayout layout({40, 24}, 8, LayoutParams{});
  for (const SamplerConfig& cfg : unrelated_samplers()) {
    TextureCache cache(layout, {1024, 2}, cfg);  // (bytes, ways: 8 sets of 64-byte lines)
    std::vector<uint32_t> misses;
    int missed = 0;
    for (int k = 0; k < layout.levels(); ++k) {
      const Extent e = layout.level_size(k);
      for (int j = 0; j < e.h; j += 3)
        for (int i = 0; i < e.w; i += 5) {
          cache.reset_stats();
          misses.clear();
          const SampleLookup l = cache.lookup(fetch_request(i, j, k), &misses);
          ASSERT_TRUE(l.slot[0].needed);
          EXPECT_FALSE(l.slot[1].needed);
          EXPECT_EQ(l.slot[0].blocks, 1);
          const uint32_t want = layout.block_address(k, layout.stored_x(k, uint32_t(i)) / uint32_t(layout.block_w()),
                                                     layout.stored_y(k, uint32_t(j)) / uint32_t(layout.block_h()));
          EXPECT_EQ(cache.stats().total_lookups(), 1u);
          EXPECT_EQ(cache.stats().lookups[size_t(k & 1)], 1u) << "level " << k << ": the other parity's cache";
          if (!misses.empty()) {
            ++missed;
            ASSERT_EQ(misses.size(), 1u);
            EXPECT_EQ(misses[0], want) << "level " << k << " (" << i << ", " << j << ")";
          }
        }
    }
    EXPECT_GT(missed, 20);
    cache.reset_stats();
    misses.clear();
    for (const Request& r : {fetch_request(40, 0, 0), fetch_request(-1, 0, 0), fetch_request(0, 24, 0),
                             fetch_request(0, 0, -1), fetch_request(0, 0, layout.levels()), fetch_request(20, 12, 1)}) {
      const SampleLookup l = cache.lookup(r, &misses);
      EXPECT_FALSE(l.slot[0].needed || l.slot[1].needed);
    }
    EXPECT_EQ(cache.stats().total_lookups(), 0u);
    EXPECT_TRUE(misses.empty());
  }
}

TEST(TexelFetch, CarriesNoDerivatives) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 8, 8));
  Sampler s(pyr, SamplerConfig{});
  Request r = fetch_request(1, 1, 0);
  r.has_derivatives = true;
  EXPECT_THROW(s.sample(r), Error);
}

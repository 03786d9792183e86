// The one fast-path equivalence test: Sampler::sample_rgba8 against the reference path
// Sampler::sample, bit for bit, on random requests: the six GL filters x every wrap pair x random
// LOD bias and clamps, on random textures of many shapes (square, wide, tall, 1xN, 2048x2, odd), with
// coordinates far outside [0, 1).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "model/error.h"
#include "model/formats.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "model/sampler.h"

using namespace tex;

namespace {

// Random RGBA8 texels, with the extremes 0 and 255 often, where a packed-lane carry would show.
Image random_image(int w, int h, std::mt19937& rng) {
  Image img(w, h, 8);
  std::uniform_int_distribution<int> byte(0, 255), pick(0, 3);
  for (Texel& t : img.texels)
    for (int c = 0; c < 4; ++c) {
      const int k = pick(rng);
      t[c] = uint16_t(k == 0 ? 0 : k == 1 ? 255 : byte(rng));
    }
  return img;
}

// Coordinates: inside [0, 1), near the edges, a few textures away, or anywhere in Q8.24.
int32_t random_coord(std::mt19937& rng) {
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_int_distribution<int32_t> unit(0, (1 << 24) - 1), edge(-4096, 4096);
  std::uniform_int_distribution<int32_t> near(-(8 << 24), 8 << 24), any(INT32_MIN, INT32_MAX);
  switch (kind(rng)) {
    case 0: return unit(rng);
    case 1: return edge(rng) + (kind(rng) & 1) * (1 << 24);
    case 2: return near(rng);
    default: return any(rng);
  }
}

// LOD: magnification, over the pyramid, at exact level boundaries, or anywhere in Q8.8.
int32_t random_lod(std::mt19937& rng, int levels) {
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_int_distribution<int32_t> mag(-4 * 256, 0), pyr(0, levels * 256 + 255), level(0, levels + 1),
      jitter(-2, 2), any(kLodMin, kLodMax);
  switch (kind(rng)) {
    case 0: return mag(rng);
    case 1: return pyr(rng);
    case 2: return level(rng) * 256 + jitter(rng);
    default: return any(rng);
  }
}

uint32_t pack(const Texel& t) {
  return uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
}

}  // namespace

TEST(FastPathEquivalence, SixGlFiltersEveryWrapAndLodRange) {
  // The six GL minification filters: texel filter (nearest, linear) x mip mode (none, nearest, linear).
  const char* filters[] = {"nearest", "linear", "nearest_mipmap_nearest", "linear_mipmap_nearest",
                           "nearest_mipmap_linear", "linear_mipmap_linear"};
  // Every address mode the fast path takes (clamp to border takes the reference path).
  const Wrap wraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::MirrorClamp};
  // Powers of two and not (odd sides, primes: the repeat seam's copies).
  const int shapes[][2] = {{64, 64}, {128, 16}, {8, 256}, {1, 32}, {32, 1}, {1, 1}, {2, 2}, {256, 256}, {2048, 2},
                           {5, 3}, {7, 1}, {1, 9}, {100, 60}, {33, 127}};
  constexpr int kRequestsPerConfig = 4000;

  std::mt19937 rng(20240611);
  std::vector<Pyramid> pyramids;
  for (const auto& s : shapes)
    for (PyramidMode mode : {PyramidMode::Exact, PyramidMode::Cascade})
      pyramids.push_back(build_pyramid(random_image(s[0], s[1], rng), mode));

  size_t checked = 0, configs = 0;
  for (const char* name : filters)
    for (Wrap wu : wraps)
      for (Wrap wv : wraps) {
        SamplerConfig cfg;
        ASSERT_TRUE(parse_filter(name, cfg.filter)) << name;
        cfg.wrap_u = wu;
        cfg.wrap_v = wv;
        // Half the configs use the default bias and clamps; the others random ones (min <= max).
        if (configs % 2 == 1) {
          std::uniform_int_distribution<int32_t> bias(-3 * 256, 3 * 256), clampv(-2 * 256, 12 * 256);
          cfg.lod_bias = bias(rng);
          int32_t a = clampv(rng), b = clampv(rng);
          cfg.min_lod = std::min(a, b);
          cfg.max_lod = std::max(a, b);
        }
        const Pyramid& pyr = pyramids[configs % pyramids.size()];
        ++configs;

        std::vector<Request> reqs(kRequestsPerConfig);
        for (Request& r : reqs) r = lambda_request(random_coord(rng), random_coord(rng), random_lod(rng, pyr.last_level()));
        Sampler sampler(pyr, cfg);
        std::vector<uint32_t> fast(reqs.size());
        sampler.sample_rgba8(reqs.data(), reqs.size(), fast.data());
        for (size_t i = 0; i < reqs.size(); ++i) {
          const uint32_t ref = pack(sampler.sample(reqs[i]));
          ASSERT_EQ(fast[i], ref) << "filter " << name << " wrap " << wrap_name(wu) << "/" << wrap_name(wv)
                                  << " texture " << pyr.levels[0].width << "x" << pyr.levels[0].height << " u "
                                  << reqs[i].u << " v " << reqs[i].v << " lod " << reqs[i].lod << " bias "
                                  << cfg.lod_bias << " clamp [" << cfg.min_lod << ", " << cfg.max_lod << "]";
          ++checked;
        }
      }
  EXPECT_GE(checked, 380000u);
  EXPECT_EQ(configs, 96u);
}

// Batches of any length (including 0 and 1) give the same texels as one long batch.
TEST(FastPathEquivalence, BatchSplitsDoNotMatter) {
  std::mt19937 rng(7);
  const Pyramid pyr = build_pyramid(random_image(64, 32, rng));
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::Linear};
  std::vector<Request> reqs(1000);
  for (Request& r : reqs) r = lambda_request(random_coord(rng), random_coord(rng), random_lod(rng, pyr.last_level()));
  const Sampler sampler(pyr, cfg);
  std::vector<uint32_t> whole(reqs.size()), split(reqs.size(), 0xdeadbeef);
  sampler.sample_rgba8(reqs.data(), reqs.size(), whole.data());
  sampler.sample_rgba8(reqs.data(), 0, split.data());
  EXPECT_EQ(split[0], 0xdeadbeefu);  // n = 0 writes nothing
  size_t at = 0;
  for (size_t len : {size_t(1), size_t(7), size_t(100), size_t(892)}) {
    sampler.sample_rgba8(reqs.data() + at, len, split.data() + at);
    at += len;
  }
  ASSERT_EQ(at, reqs.size());
  EXPECT_EQ(split, whole);
}

// A sampler built for the fast path alone (SamplerPaths::FastOnly, what the model engine uses
// without --stats) gives the same texels, also after write_texel; its reference path and 16-bit
// textures are errors.
TEST(FastPathEquivalence, FastOnlySamplerGivesTheSameTexels) {
  std::mt19937 rng(11);
  const Pyramid pyr = build_pyramid(random_image(32, 64, rng));
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::Linear};
  cfg.wrap_u = Wrap::Mirror;
  std::vector<Request> reqs(2000);
  for (Request& r : reqs) r = lambda_request(random_coord(rng), random_coord(rng), random_lod(rng, pyr.last_level()));
  Sampler both(pyr, cfg);
  Sampler fast(pyr, cfg, SamplerPaths::FastOnly);
  EXPECT_EQ(fast.last_level(), both.last_level());
  const Texel planted{1, 2, 3, 4};
  both.write_texel(1, 3, 5, planted);
  fast.write_texel(1, 3, 5, planted);
  std::vector<uint32_t> a(reqs.size()), b(reqs.size());
  both.sample_rgba8(reqs.data(), reqs.size(), a.data());
  fast.sample_rgba8(reqs.data(), reqs.size(), b.data());
  EXPECT_EQ(a, b);
  for (size_t i = 0; i < 200; ++i) {
    const Texel t = both.sample(reqs[i]);
    EXPECT_EQ(b[i], uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24) << i;
  }
  EXPECT_THROW(fast.sample(reqs[0]), tex::Error);
  Pyramid wide = pyr;
  for (Image& img : wide.levels) img.channel_bits = 16;
  EXPECT_THROW(Sampler(wide, cfg, SamplerPaths::FastOnly), tex::Error);
}

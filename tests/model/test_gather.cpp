// textureGather (Op::Gather, stage::gather): the four texels a linear filter weighs at the base
// level, one component each, in GL's order (i0, j1), (i1, j1), (i1, j0), (i0, j0). Checked against
// the filter: a bilinear sample is the weighted sum of the gathered texels, with the weights worked
// out here in floating point; the sampler's filters, LOD controls and reduction do not matter, its
// address modes and border colour do; the fast path agrees; the cache reads all four taps' lines.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"
#include "model/image.h"
#include "model/memory_layout.h"
#include "model/sampler.h"
#include "model/texture_cache.h"

using namespace tex;

namespace {

constexpr Wrap kWraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};

// The weight of the second tap along an axis of n texels at coordinate u (Q8.24), as
// docs/numerics.md stage 3 defines it: t9 = floor(u n 512), w = round-half-up((t9 / 512 - 1/2) 256)
// mod 256. u is taken mod 1 (the address modes' reduction keeps the fraction, or clamps u where
// both taps read the same texel and the weight does not matter).
int weight(int32_t u, int n) {
  const int64_t t9 = (int64_t(u & ((1 << 24) - 1)) * n) >> 15;
  return int(((t9 - 255) >> 1) & 255);
}

}  // namespace

TEST(Gather, NamesOfTheOperation) {
  Op op{};
  EXPECT_TRUE(parse_op("gather", op));
  EXPECT_EQ(op, Op::Gather);
  EXPECT_TRUE(parse_op("textureGather", op));
  EXPECT_EQ(op_name(Op::Gather), "gather");
}

// Every address mode on both axes of an NPOT texture (its repeat seam included), coordinates
// across and beyond it: bilinear at level 0 = the gathered texels weighed, each channel.
TEST(Gather, BilinearIsTheGatheredTexelsWeighed) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 13, 6));
  std::mt19937_64 rng(37);
  int checked = 0;
  for (Wrap wu : kWraps)
    for (Wrap wv : kWraps) {
      SamplerConfig bilinear{{TexelFilter::Linear, MipMode::None}, wu, wv};
      bilinear.border = BorderColor::Custom;
      bilinear.border_custom = {40000, 1000, 65535, 30000};
      Sampler s(pyr, bilinear);
      for (int n = 0; n < 400; ++n) {
        const int32_t u = int32_t(rng() % (4u << 24)) - (3 << 23), v = int32_t(rng() % (4u << 24)) - (3 << 23);
        const int fx = weight(u, 13), fy = weight(v, 6);
        const Texel want = s.sample(lambda_request(u, v, 0));
        for (int c = 0; c < 4; ++c) {
          const Texel g = s.sample(gather_request(u, v, c));  // R: (i0, j1), G: (i1, j1), B: (i1, j0), A: (i0, j0)
          const int64_t sum = int64_t(256 - fx) * (256 - fy) * g[3] + int64_t(fx) * (256 - fy) * g[2] +
                              int64_t(256 - fx) * fy * g[0] + int64_t(fx) * fy * g[1];
          ASSERT_EQ(want[size_t(c)], (sum + 32768) >> 16)
              << wrap_name(wu) << "/" << wrap_name(wv) << " u=" << u << " v=" << v << " component " << c;
          ++checked;
        }
      }
    }
  EXPECT_EQ(checked, 25 * 400 * 4);
}

// The sampler's filters, LOD bias and clamps, anisotropy and reduction do not change a gather (the
// base level is gathered); its address modes do.
TEST(Gather, OnlyTheAddressModesOfTheSamplerCount) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 32, 16));
  SamplerConfig plain;
  std::vector<SamplerConfig> others(3);
  others[0].filter = {TexelFilter::Nearest, MipMode::Nearest};
  others[0].lod_bias = 4 * 256;
  others[1].filter = {TexelFilter::Linear, MipMode::Linear, true};
  others[1].min_lod = 3 * 256;
  others[1].reduction = Reduction::Min;
  others[2].filter.mag = TexelFilter::Nearest;
  others[2].reduction = Reduction::Max;
  SamplerConfig clamped;
  clamped.wrap_u = clamped.wrap_v = Wrap::Clamp;
  Sampler base(pyr, plain), clamp(pyr, clamped);
  std::mt19937_64 rng(3);
  int differ = 0;
  for (int n = 0; n < 2000; ++n) {
    const Request r = gather_request(int32_t(rng() % (3u << 24)) - (1 << 24), int32_t(rng() % (3u << 24)) - (1 << 24),
                                     int(rng() % 4));
    const Texel want = base.sample(r);
    for (const SamplerConfig& c : others) ASSERT_EQ(Sampler(pyr, c).sample(r), want) << n;
    differ += clamp.sample(r) != want;
  }
  EXPECT_GT(differ, 500) << "the address mode did not change the gathers beyond the edges";
}

TEST(Gather, FastPathMatchesReference) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 37, 20));
  for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::MirrorClamp}) {
    SamplerConfig cfg;
    cfg.wrap_u = w;
    cfg.wrap_v = Wrap::Repeat;
    Sampler s(pyr, cfg);
    std::mt19937_64 rng(11);
    std::vector<Request> reqs;
    for (int n = 0; n < 2000; ++n)
      reqs.push_back(n % 2 ? gather_request(int32_t(rng() % (4u << 24)) - (2 << 24), int32_t(rng()), int(rng() % 4))
                           : lambda_request(int32_t(rng() % (2u << 24)), int32_t(rng() % (2u << 24)), int32_t(rng() % 1024)));
    std::vector<uint32_t> fast(reqs.size());
    s.sample_rgba8(reqs.data(), reqs.size(), fast.data());
    for (size_t n = 0; n < reqs.size(); ++n) {
      const Texel t = s.sample(reqs[n]);
      ASSERT_EQ(fast[n], uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24)
          << wrap_name(w) << " request " << n;
    }
  }
}

// A gather reads its four taps' lines even where the linear filter's weights are 0: at the centre
// of texel (3, 3) its taps are texels 3 and 4 on each axis, in four 4x4 blocks (4 lines), where the
// bilinear filter weighs texel (3, 3) alone (1 line).
TEST(Gather, ReadsTheLinesOfAllFourTaps) {
  const MemoryLayout layout({64, 64}, 8, LayoutParams{});
  const int32_t centre = int32_t(3.5 / 64 * (1 << 24));  // exact: 3.5 * 2^18
  TextureCache cache(layout, {4096, 2}, SamplerConfig{});
  EXPECT_EQ(cache.lookup(gather_request(centre, centre, 0), nullptr).slot[0].blocks, 4);
  SamplerConfig bilinear;
  bilinear.filter = {TexelFilter::Linear, MipMode::None};
  TextureCache filtered(layout, {4096, 2}, bilinear);
  EXPECT_EQ(filtered.lookup(lambda_request(centre, centre, 0), nullptr).slot[0].blocks, 1);
}

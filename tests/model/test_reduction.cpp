// The min/max reduction (SamplerConfig::reduction, Vulkan reductionMode): its names, and what any
// right answer must satisfy: per channel, min <= the weighted average <= max for every filter,
// address mode, level pair and anisotropic sample (the average of texels lies between the least and
// the greatest of those it weighs, and its rounding cannot cross an integer bound); a one-texel
// filter gives the same texel for all three. Compared with llvmpipe in
// tests/sim/test_gl_sampler_states.cpp (MinMaxReductionAgreesWithLlvmpipe).
#include <gtest/gtest.h>

#include <random>

#include "model/error.h"
#include "model/image.h"
#include "model/sampler.h"

using namespace tex;

TEST(Reduction, NamesAndVulkanNames) {
  Reduction r{};
  EXPECT_TRUE(parse_reduction("min", r));
  EXPECT_EQ(r, Reduction::Min);
  EXPECT_TRUE(parse_reduction("VK_SAMPLER_REDUCTION_MODE_MAX", r));
  EXPECT_EQ(r, Reduction::Max);
  EXPECT_TRUE(parse_reduction("weighted_average", r));
  EXPECT_EQ(r, Reduction::WeightedAverage);
  EXPECT_FALSE(parse_reduction("median", r));
  EXPECT_EQ(reduction_name(Reduction::Max), "max");
}

TEST(Reduction, AverageLiesBetweenMinAndMax) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 37, 23));
  std::mt19937_64 rng(35);
  const Wrap wraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};
  int strict = 0, samples = 0;
  for (int state = 0; state < 60; ++state) {
    SamplerConfig cfg{{TexelFilter(rng() % 2), MipMode(rng() % 3), state % 4 == 3}, wraps[rng() % 5], wraps[rng() % 5]};
    cfg.filter.mag = TexelFilter(rng() % 2);
    cfg.border = BorderColor(rng() % (kBorderColors - 1));
    SamplerConfig lo = cfg, hi = cfg;
    lo.reduction = Reduction::Min;
    hi.reduction = Reduction::Max;
    Sampler avg(pyr, cfg), mn(pyr, lo), mx(pyr, hi);
    for (int i = 0; i < 500; ++i) {
      Request r = lambda_request(int32_t(rng() % (3u << 24)) - (1 << 24), int32_t(rng() % (3u << 24)) - (1 << 24),
                                 int32_t(rng() % (9 * 256)) - 2 * 256);
      if (cfg.filter.anisotropic) {  // derivatives: 1 to 16 probes
        r.has_derivatives = true;
        r.deriv = {int32_t(rng() % (1u << 22)), int32_t(rng() % (1u << 18)), int32_t(rng() % (1u << 18)),
                   int32_t(rng() % (1u << 19))};
      }
      const Texel a = avg.sample(r), l = mn.sample(r), h = mx.sample(r);
      for (size_t c = 0; c < 4; ++c) {
        ASSERT_LE(l[c], a[c]) << "channel " << c << ", state " << state << ", request " << i;
        ASSERT_LE(a[c], h[c]) << "channel " << c << ", state " << state << ", request " << i;
        strict += l[c] < h[c];
      }
      ++samples;
    }
  }
  EXPECT_GT(strict, samples) << "min and max hardly ever differ: the reductions are not weighing several texels";
}

TEST(Reduction, OneTexelFiltersGiveThatTexel) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 32, 16));
  std::mt19937_64 rng(36);
  for (MipMode mip : {MipMode::None, MipMode::Nearest}) {
    SamplerConfig cfg{{TexelFilter::Nearest, mip}, Wrap::Repeat, Wrap::Mirror};
    SamplerConfig lo = cfg, hi = cfg;
    lo.reduction = Reduction::Min;
    hi.reduction = Reduction::Max;
    Sampler avg(pyr, cfg), mn(pyr, lo), mx(pyr, hi);
    for (int i = 0; i < 2000; ++i) {
      const Request r = lambda_request(int32_t(rng() % (4u << 24)) - (2 << 24), int32_t(rng() % (4u << 24)) - (2 << 24),
                                       int32_t(rng() % (8 * 256)) - 256);
      const Texel a = avg.sample(r);
      EXPECT_EQ(mn.sample(r), a);
      EXPECT_EQ(mx.sample(r), a);
    }
  }
}

// The 8-bit fast path does not take a reduction (the model engine then uses the reference path).
TEST(Reduction, FastPathRefusesIt) {
  SamplerConfig cfg;
  cfg.reduction = Reduction::Max;
  EXPECT_FALSE(Sampler::fast_path_takes(cfg));
  EXPECT_THROW(Sampler(build_pyramid(make_pattern("noise", 8, 8)), cfg, SamplerPaths::FastOnly), Error);
}

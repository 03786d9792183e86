// Stage functions of docs/numerics.md against their definitions in real numbers.
// Every expected value here is computed from the real-valued (or GL 4.6) definition in this file,
// never from model/stages.h itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "model/stages.h"

using namespace tex;

namespace {

// GL 4.6 §8.14.2 "a mod b" and the wrap formulas of Table 8.20, with integer texel coordinates.
int64_t gl_mod(int64_t a, int64_t b) { return a - b * int64_t(std::floor(double(a) / double(b))); }
int64_t gl_mirror(int64_t a) { return a >= 0 ? a : -(1 + a); }
int64_t gl_wrap(int64_t coord, int64_t size, Wrap w) {
  switch (w) {
    case Wrap::Repeat: return gl_mod(coord, size);
    case Wrap::Clamp: return std::min(std::max(coord, int64_t(0)), size - 1);
    case Wrap::Mirror: return (size - 1) - gl_mirror(gl_mod(coord, 2 * size) - size);
    case Wrap::Border: {  // clamp(coord, -1, size); -1 and size are the border texel
      const int64_t c = std::min(std::max(coord, int64_t(-1)), size);
      return c < 0 || c == size ? stage::kBorderTap : c;
    }
    case Wrap::MirrorClamp: return std::min(std::max(gl_mirror(coord), int64_t(0)), size - 1);
  }
  return -2;
}

}  // namespace

// ---------------------------------------------------------------- stage 1: bias and clamp

TEST(Stages, BiasThenClampMatchesRealNumbers) {
  // Real-valued GL order: lambda' = clamp(lambda + bias, min, max), all in levels.
  const int32_t values[] = {kLodMin, -32767, -5000, -257, -256, -1, 0, 1, 127, 128, 255, 256, 3000, 32766, kLodMax};
  for (int32_t lod : values)
    for (int32_t bias : values)
      for (int32_t lo : {kLodMin, -256, 0, 100, 1000})
        for (int32_t hi : {lo, 0, 256, 1000, 2816, kLodMax}) {
          if (hi < lo) continue;
          const double real = std::clamp(lod / 256.0 + bias / 256.0, lo / 256.0, hi / 256.0);
          EXPECT_EQ(stage::lod_clamp(lod, bias, lo, hi), int32_t(real * 256.0))
              << lod << " + " << bias << " in [" << lo << ", " << hi << "]";
        }
  // The sum is 17 bits wide: the extreme values must not wrap around.
  EXPECT_EQ(stage::lod_clamp(kLodMax, kLodMax, kLodMin, kLodMax), kLodMax);
  EXPECT_EQ(stage::lod_clamp(kLodMin, kLodMin, kLodMin, kLodMax), kLodMin);
}

// ---------------------------------------------------------------- stage 1: level select

namespace {
struct RealLevels {
  int d, d1;
  double f;
  bool two;
};
// GL 4.6 §8.14.3 with c = 0: magnify for lambda <= 0; nearest level = ceil(lambda + 1/2) - 1 for
// lambda > 1/2 (else 0); linear: floor(lambda) and the next level with weight frac(lambda).
RealLevels real_levels(double lambda, MipMode mip, int q) {
  RealLevels r{0, std::min(1, q), 0.0, false};
  if (mip == MipMode::None || lambda <= 0) return r;
  if (mip == MipMode::Nearest) {
    r.d = lambda <= 0.5 ? 0 : std::min(int(std::ceil(lambda + 0.5)) - 1, q);
  } else {
    const int fl = int(std::floor(lambda));
    if (fl >= q) {
      r.d = q;
    } else {
      r.d = fl;
      r.two = true;
      r.f = lambda - fl;
    }
  }
  r.d1 = std::min(r.d + 1, q);
  return r;
}
}  // namespace

TEST(Stages, LodSelectMatchesGlDefinition) {
  for (int q = 0; q <= kMaxLog2Size; ++q)
    for (MipMode mip : {MipMode::None, MipMode::Nearest, MipMode::Linear})
      for (int32_t lod = -1024; lod <= 14 * 256; ++lod) {
        const stage::LevelSelect s = stage::lod_select(lod, mip, q);
        const RealLevels r = real_levels(lod / 256.0, mip, q);
        ASSERT_EQ(s.d, r.d) << "lod=" << lod << " q=" << q << " mip=" << int(mip);
        ASSERT_EQ(s.d1, r.d1) << "lod=" << lod << " q=" << q;
        ASSERT_EQ(s.two_levels, r.two) << "lod=" << lod << " q=" << q;
        ASSERT_EQ(s.f, int(r.f * 256.0)) << "lod=" << lod << " q=" << q;  // f is exactly lambda's fraction
      }
}

TEST(Stages, LodSelectBoundaries) {
  const int q = 10;
  // Magnify/minify boundary: lambda = 0 magnifies (level 0 only), +1/256 minifies.
  for (MipMode mip : {MipMode::Nearest, MipMode::Linear}) {
    EXPECT_EQ(stage::lod_select(0, mip, q).d, 0);
    EXPECT_FALSE(stage::lod_select(0, mip, q).two_levels);
    EXPECT_EQ(stage::lod_select(0, mip, q).f, 0);
    EXPECT_EQ(stage::lod_select(-1, mip, q).d, 0);
    EXPECT_FALSE(stage::lod_select(-1, mip, q).two_levels);
  }
  const auto plus = stage::lod_select(1, MipMode::Linear, q);
  EXPECT_TRUE(plus.two_levels);
  EXPECT_EQ(plus.d, 0);
  EXPECT_EQ(plus.d1, 1);
  EXPECT_EQ(plus.f, 1);
  // Nearest level: lambda = 0.5 is still level 0, 0.5 + 1/256 is level 1; 1.5 -> 1, 1.5 + 1/256 -> 2.
  EXPECT_EQ(stage::lod_select(128, MipMode::Nearest, q).d, 0);
  EXPECT_EQ(stage::lod_select(129, MipMode::Nearest, q).d, 1);
  EXPECT_EQ(stage::lod_select(384, MipMode::Nearest, q).d, 1);
  EXPECT_EQ(stage::lod_select(385, MipMode::Nearest, q).d, 2);
  EXPECT_EQ(stage::lod_select(383, MipMode::Nearest, q).d, 1);
  // Last-level clamp: at and beyond the last level there is one level with f = 0.
  for (int32_t lod : {q * 256, q * 256 + 1, q * 256 + 255, 40 * 256, kLodMax}) {
    for (MipMode mip : {MipMode::Nearest, MipMode::Linear}) {
      const auto s = stage::lod_select(lod, mip, q);
      EXPECT_EQ(s.d, q) << lod;
      EXPECT_EQ(s.d1, q) << lod;
      EXPECT_EQ(s.f, 0) << lod;
      EXPECT_FALSE(s.two_levels) << lod;
    }
  }
  const auto below_last = stage::lod_select(q * 256 - 1, MipMode::Linear, q);
  EXPECT_EQ(below_last.d, q - 1);
  EXPECT_EQ(below_last.d1, q);
  EXPECT_EQ(below_last.f, 255);
  // Mip none: always level 0, whatever lambda.
  for (int32_t lod : {kLodMin, -1, 0, 1, 128, 129, 2560, kLodMax}) {
    const auto s = stage::lod_select(lod, MipMode::None, q);
    EXPECT_EQ(s.d, 0);
    EXPECT_EQ(s.f, 0);
    EXPECT_FALSE(s.two_levels);
  }
  // A 1x1 texture (q = 0): always level 0.
  EXPECT_EQ(stage::lod_select(1000, MipMode::Linear, 0).d1, 0);
  EXPECT_FALSE(stage::lod_select(1000, MipMode::Linear, 0).two_levels);
}

// ---------------------------------------------------------------- stage 2: axis taps

namespace {
// scale and address against real arithmetic on the reduced coordinate, at a level n texels wide.
void check_taps(int32_t u, int n, Wrap mode) {
  const int32_t r = stage::reduce(u, mode);
  const double x = std::ldexp(double(r), -kCoordFracBits) * n;  // r * n exactly (|r * n| < 2^39)
  // Linear: texel centres at half-integers; p = round-half-up((u*w - 1/2) * 256).
  const stage::AxisTaps lin = stage::address(stage::scale(r, n), TexelFilter::Linear);
  const double p = std::floor((x - 0.5) * 256 + 0.5);
  ASSERT_EQ(lin.i0, int32_t(std::floor(p / 256))) << "u=" << u << " n=" << n;
  ASSERT_EQ(lin.w, int(p - 256 * std::floor(p / 256))) << "u=" << u << " n=" << n;
  ASSERT_EQ(lin.i1, lin.i0 + 1);
  // Nearest: floor(u * w), no weight.
  const stage::AxisTaps near = stage::address(stage::scale(r, n), TexelFilter::Nearest);
  ASSERT_EQ(near.i0, int32_t(std::floor(x))) << "u=" << u << " n=" << n;
  ASSERT_EQ(near.w, 0);
  ASSERT_EQ(near.i1, near.i0 + 1);
}

// What the unit reads for coordinate u on a side of n texels (reduce, scale, address, wrap; the
// seam index n read as texel 0) against GL's definition on the whole coordinate, in exact integer
// arithmetic: the same two texels, and the same weight unless both taps are one texel (then the
// weight changes nothing: lerp(a, a, w) = a).
void check_reduce_keeps_taps(int32_t u, int n, Wrap mode, TexelFilter f) {
  const stage::AxisTaps t = stage::address(stage::scale(stage::reduce(u, mode), n), f);
  auto seam = [&](int32_t x) { return x == n ? 0 : x; };
  const int64_t x0 = stage::wrap(t.i0, n, mode), x1 = seam(stage::wrap(t.i1, n, mode, true));
  // GL on the whole coordinate: t9 = floor(u * n * 512), then the same rounding, then gl_wrap.
  const int64_t t9 = (int64_t(u) * n) >> (kCoordFracBits - 9);
  int64_t i0, w;
  if (f == TexelFilter::Linear) {
    const int64_t q = (t9 - 255) >> 1;
    i0 = q >> 8;
    w = q & 255;
  } else {
    i0 = t9 >> 9;
    w = 0;
  }
  const int64_t g0 = gl_wrap(i0, n, mode), g1 = gl_wrap(i0 + 1, n, mode);
  ASSERT_EQ(x0, g0) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  if (f == TexelFilter::Nearest) return;
  ASSERT_EQ(x1, g1) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  if (g0 != g1) {
    ASSERT_EQ(t.w, w) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  }
}

// An unnormalized coordinate u (Q16.16 texels) on a side of n texels: the texels and weight GL
// names for the texel coordinate u itself (GL 4.6 8.14.2, rectangle textures; Vulkan's
// unnormalizedCoordinates), in real arithmetic, after the clamp or border wrap; the clamp of
// scale() to +-2n texels is invisible.
void check_unnormalized_taps(int32_t u, int n, Wrap mode, TexelFilter f) {
  const stage::AxisTaps t = stage::address(stage::scale(stage::reduce(u, mode, true), n, true), f);
  const double x = std::ldexp(double(u), -kTexelCoordFracBits);  // exact
  int64_t i0, w = 0;
  if (f == TexelFilter::Linear) {
    const double p = std::floor((std::floor(x * 512) - 255) / 2);  // 9 sub-texel bits, then round-half-up
    i0 = int64_t(std::floor(p / 256));
    w = int64_t(p) - 256 * i0;
  } else {
    i0 = int64_t(std::floor(x));
  }
  const int64_t g0 = gl_wrap(i0, n, mode), g1 = gl_wrap(i0 + 1, n, mode);
  ASSERT_EQ(stage::wrap(t.i0, n, mode), g0) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  if (f == TexelFilter::Nearest) return;
  ASSERT_EQ(stage::wrap(t.i1, n, mode, true), g1) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  if (g0 != g1) {
    ASSERT_EQ(t.w, w) << "u=" << u << " n=" << n << " wrap=" << int(mode);
  }
}
}  // namespace

TEST(Stages, UnnormalizedCoordinatesReadTheTexelsOfTheTexelCoordinate) {
  std::mt19937_64 rng(13);
  const int sizes[] = {1, 2, 3, 5, 8, 31, 600, 1000, 4095, 8191, 8192};
  for (int n : sizes)
    for (Wrap mode : {Wrap::Clamp, Wrap::Border})
      for (TexelFilter f : {TexelFilter::Linear, TexelFilter::Nearest}) {
        for (int i = 0; i < 20000; ++i) {
          // Half anywhere in Q16.16, half within a few texels of the side.
          const int32_t u = i % 2 ? int32_t(uint32_t(rng()))
                                  : int32_t(int64_t(rng() % uint64_t((n + 8) << 16)) - (int64_t(4) << 16));
          check_unnormalized_taps(u, n, mode, f);
        }
        for (int32_t u : {INT32_MIN, -1, 0, 1, 1 << 15, (n << 16) - 1, n << 16, (2 * n) << 16, INT32_MAX})
          check_unnormalized_taps(u, n, mode, f);
      }
}

// A power-of-two side up to 256 holds u / n exactly in Q8.24: the unnormalized sample at texel
// coordinate u is the normalized one at u / n, texel for texel and weight for weight.
TEST(Stages, UnnormalizedIsNormalizedTimesTheSize) {
  std::mt19937_64 rng(17);
  for (int lw = 0; lw <= 8; ++lw) {
    const int n = 1 << lw;
    for (Wrap mode : {Wrap::Clamp, Wrap::Border})
      for (int i = 0; i < 20000; ++i) {
        const int32_t u = int32_t(int64_t(rng() % uint64_t(4 * n << 16)) - (int64_t(n) << 16));  // [-n, 3n)
        const int32_t t_unnorm = stage::scale(stage::reduce(u, mode, true), n, true);
        const int32_t t_norm = stage::scale(stage::reduce(int32_t(int64_t(u) << (8 - lw)), mode), n);
        ASSERT_EQ(t_unnorm, t_norm) << "u=" << u << " n=" << n;
      }
  }
}

TEST(Stages, ScaleAndAddressMatchRealTexelCoordinate) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int32_t> any(INT32_MIN, INT32_MAX);
  std::vector<int> sizes;
  for (int lw = 0; lw <= kMaxLog2Size; ++lw) sizes.push_back(1 << lw);
  for (int n : {3, 5, 7, 600, 1000, 4095, 8191}) sizes.push_back(n);
  for (int n : sizes)
    for (Wrap mode : {Wrap::Repeat, Wrap::Mirror, Wrap::Clamp}) {
      for (int32_t u = -(1 << 25); u < (1 << 25); u += 99991) check_taps(u, n, mode);
      for (int i = 0; i < 20000; ++i) check_taps(any(rng), n, mode);  // the whole Q8.24 range
      for (int32_t u : {INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX - 1, INT32_MAX}) check_taps(u, n, mode);
      // Around every rounding boundary of the linear weight and every texel edge of the first texels.
      const int32_t step = int32_t((int64_t(1) << (kCoordFracBits - 9)) / n);  // about 1/512 texel
      for (int32_t k = -300; k <= 300; ++k)
        for (int32_t d = -2; d <= 2; ++d) check_taps(k * step + d, n, mode);
    }
}

// reduce() is invisible: every address mode reads the texels GL's definition names on the whole
// coordinate, at every size (powers of two, odd, primes, up to 8192) and over the whole Q8.24 range.
TEST(Stages, ReducedCoordinateReadsTheTexelsOfTheWholeOne) {
  std::mt19937_64 rng(11);
  const int sizes[] = {1, 2, 3, 4, 5, 7, 8, 9, 31, 64, 125, 600, 1000, 1021, 4096, 8191, 8192};
  for (int n : sizes)
    for (Wrap mode : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp})
      for (TexelFilter f : {TexelFilter::Linear, TexelFilter::Nearest}) {
        for (int i = 0; i < 20000; ++i) {
          // Half anywhere in Q8.24, half within a few periods of 0 (where the edges are).
          const int32_t u = i % 2 ? int32_t(uint32_t(rng())) : int32_t(int64_t(rng() % (1u << 28)) - (1 << 27));
          check_reduce_keeps_taps(u, n, mode, f);
        }
        for (int32_t u : {INT32_MIN, -(1 << 25) - 1, -(1 << 25), -(1 << 24), -1, 0, 1, (1 << 24) - 1, 1 << 24,
                          (1 << 25) - 1, 1 << 25, (1 << 25) + 1, INT32_MAX})
          check_reduce_keeps_taps(u, n, mode, f);
      }
}

// ---------------------------------------------------------------- stage 3: wrap

TEST(Stages, WrapEqualsGl46AtEveryLevelSize) {
  std::vector<int> sizes;
  for (int n = 1; n <= 70; ++n) sizes.push_back(n);
  for (int n : {125, 600, 1000, 1021, 4095, 4096, 8191, 8192}) sizes.push_back(n);
  for (int n : sizes) {
    for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp}) {
      for (int64_t i = -3 * n - 3; i <= 3 * n + 3; ++i) {
        ASSERT_EQ(stage::wrap(int32_t(i), n, w), gl_wrap(i, n, w)) << "i=" << i << " n=" << n << " wrap=" << int(w);
        // The second tap: the same texel, except at the repeat seam of a side that is not a power
        // of two, where texel 0 is read as its copy at index n.
        const int64_t second = w == Wrap::Repeat && !is_power_of_two(n) && gl_wrap(i, n, w) == 0 ? n : gl_wrap(i, n, w);
        ASSERT_EQ(stage::wrap(int32_t(i), n, w, true), second) << "i=" << i << " n=" << n << " wrap=" << int(w);
      }
      // Far indices (the extremes axis_taps can produce from Q8.24 coordinates).
      for (int64_t i : {int64_t(-(1 << 18)) - 1, int64_t(-(1 << 18)), int64_t(1 << 18), int64_t((1 << 18) + 1),
                        int64_t(-123457), int64_t(98765)})
        ASSERT_EQ(stage::wrap(int32_t(i), n, w), gl_wrap(i, n, w)) << "i=" << i << " n=" << n;
    }
  }
  // n = 1: every index maps to texel 0 in every mode but clamp to border (only index 0 is inside).
  for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::MirrorClamp})
    for (int32_t i = -9; i <= 9; ++i) EXPECT_EQ(stage::wrap(i, 1, w, i % 2 != 0), 0);
  for (int32_t i = -9; i <= 9; ++i) EXPECT_EQ(stage::wrap(i, 1, Wrap::Border), i == 0 ? 0 : stage::kBorderTap);
}

// The repeat seam's pair sits in two parity banks at every size: (x0, x1) of neighbouring taps
// differ in parity or are one texel.
TEST(Stages, RepeatSeamPairsTakeTwoBanks) {
  for (int n = 1; n <= 300; ++n)
    for (int32_t i0 = -1; i0 < n; ++i0) {
      const int32_t x0 = stage::wrap(i0, n, Wrap::Repeat), x1 = stage::wrap(i0 + 1, n, Wrap::Repeat, true);
      ASSERT_TRUE(x0 == x1 || ((x0 ^ x1) & 1)) << "n=" << n << " i0=" << i0 << ": " << x0 << ", " << x1;
    }
}

// The border colour in a channel width (stage::border_texel, round(c (2^CW - 1) / 65535)) against
// real arithmetic, and the division tex_border does without a divider, x = c (2^CW - 1) + 32767,
// floor(x / 65535) = (x + (x >> 16) + 1) >> 16, for every 16-bit c and every CW.
TEST(Stages, BorderColourInEveryChannelWidth) {
  for (int cw = 1; cw <= 16; ++cw)
    for (uint32_t c = 0; c < 65536; ++c) {
      const uint32_t max = (1u << cw) - 1;
      const uint16_t got = stage::border_texel({uint16_t(c), 0, 0, 65535}, cw)[0];
      ASSERT_EQ(got, uint16_t(std::floor(double(c) * max / 65535.0 + 0.5))) << "c " << c << " CW " << cw;
      const uint64_t x = uint64_t(c) * max + 32767;
      ASSERT_EQ(got, uint16_t((x + (x >> 16) + 1) >> 16)) << "c " << c << " CW " << cw;
      ASSERT_EQ(stage::border_texel({0, 0, 0, 65535}, cw)[3], max);
    }
}

TEST(Stages, BankIsParity) {
  for (int y = -4; y < 8; ++y)
    for (int x = -4; x < 8; ++x) EXPECT_EQ(stage::bank(x, y), ((y % 2 != 0) ? 2 : 0) + ((x % 2 != 0) ? 1 : 0));
}

// ---------------------------------------------------------------- stage 5: filter arithmetic

TEST(Stages, LerpIsExactRealInterpolation) {
  // lerp(a, b, w) = 256 * ((1 - w/256) a + (w/256) b), exactly, for all 8-bit a, b and weights.
  for (int a = 0; a < 256; ++a)
    for (int b = 0; b < 256; ++b)
      for (int w = 0; w < 256; ++w) {
        const double real = 256.0 * ((1.0 - w / 256.0) * a + (w / 256.0) * b);
        if (stage::lerp(a, b, w) != int64_t(real)) FAIL() << a << " " << b << " " << w;
      }
  // 16-bit channels with CW.16 inputs (the blend stage).
  std::mt19937 rng(3);
  std::uniform_int_distribution<int64_t> big(0, (int64_t(1) << 32) - 1);
  for (int i = 0; i < 200000; ++i) {
    const int64_t a = big(rng), b = big(rng);
    const int w = int(rng() & 255);
    const long double real = 256.0L * ((1.0L - w / 256.0L) * a + (w / 256.0L) * b);
    ASSERT_EQ(stage::lerp(a, b, w), int64_t(real)) << a << " " << b << " " << w;
  }
}

TEST(Stages, BilerpAndBlendMatchDouble) {
  std::mt19937 rng(11);
  for (int i = 0; i < 1000000; ++i) {
    const int a = rng() & 255, b = rng() & 255, c = rng() & 255, e = rng() & 255;
    const int wx = rng() & 255, wy = rng() & 255, f = rng() & 255;
    const double fx = wx / 256.0, fy = wy / 256.0, ff = f / 256.0;
    const double bil = (1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * c + fx * e);
    const int64_t got = stage::bilerp(a, b, c, e, wx, wy);
    ASSERT_EQ(got, int64_t(bil * 65536.0)) << a << " " << b << " " << c << " " << e << " " << wx << " " << wy;
    // Blend with a second bilinear value, then round half up: the only rounding of the pipeline.
    const int a2 = rng() & 255, b2 = rng() & 255, c2 = rng() & 255, e2 = rng() & 255;
    const double bil2 = (1 - fy) * ((1 - fx) * a2 + fx * b2) + fy * ((1 - fx) * c2 + fx * e2);
    const double tri = (1 - ff) * bil + ff * bil2;  // exact in double: 8 + 24 fraction bits
    const uint32_t out = stage::blend_and_round(got, stage::bilerp(a2, b2, c2, e2, wx, wy), f);
    ASSERT_EQ(out, uint32_t(std::floor(tri + 0.5))) << "tri=" << tri;
  }
  // Half-way cases round up; results stay within [0, 255].
  EXPECT_EQ(stage::blend_and_round(int64_t(1) << 15, int64_t(1) << 15, 0), 1u);   // 0.5 -> 1
  EXPECT_EQ(stage::blend_and_round((int64_t(1) << 15) - 1, (int64_t(1) << 15) - 1, 0), 0u);
  EXPECT_EQ(stage::blend_and_round(int64_t(255) << 16, int64_t(255) << 16, 255), 255u);
  EXPECT_EQ(stage::blend_and_round(0, int64_t(1) << 16, 128), 1u);  // 0.5 between 0 and 1 -> 1
  EXPECT_EQ(stage::blend_and_round(0, int64_t(1) << 16, 127), 0u);
}

// The paper's binary shift: where the sides are powers of two, scaling by level k's size is level
// 0's scale shifted by k; past the axis's last level (a 1-texel side) every address mode but
// border gives texel 0.
TEST(Stages, AddressAtLevelIsAShiftOfTheLevelZeroScale) {
  std::mt19937_64 rng(77);
  for (int i = 0; i < 200000; ++i) {
    const int32_t u = stage::reduce(int32_t(uint32_t(rng())), Wrap::Clamp);
    const int log2_size0 = int(rng() % 12), k = int(rng() % 12);
    const TexelFilter f = rng() % 2 ? TexelFilter::Linear : TexelFilter::Nearest;
    const int32_t level0 = stage::scale(u, 1 << log2_size0);
    const int nk = std::max((1 << log2_size0) >> k, 1);
    const stage::AxisTaps direct = stage::address(stage::scale(u, nk), f);
    if (k <= log2_size0) {
      const stage::AxisTaps shifted = stage::address(level0 >> k, f);
      ASSERT_EQ(shifted.i0, direct.i0) << u << " " << log2_size0 << " " << k;
      ASSERT_EQ(shifted.w, direct.w) << u << " " << log2_size0 << " " << k;
    } else {
      for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror}) {
        ASSERT_EQ(stage::wrap(direct.i0, 1, w), 0);
        ASSERT_EQ(stage::wrap(direct.i1, 1, w, true), 0);
      }
    }
  }
}

// The one reading of a minification filter name (--min-filter, texture lists' min=, scene files'
// min_filter): nearest / linear set the texel filter alone, GL's four MIPMAP names (any case, GL_
// prefix or not) the mipmap mode too; whole-filter names (trilinear, point) are no minification
// filter.
TEST(Stages, MinFilterNames) {
  TexelFilter t = TexelFilter::Linear;
  std::optional<MipMode> mip;
  EXPECT_TRUE(parse_min_filter("nearest", t, mip));
  EXPECT_EQ(t, TexelFilter::Nearest);
  EXPECT_FALSE(mip.has_value());
  EXPECT_TRUE(parse_min_filter("GL_LINEAR_MIPMAP_NEAREST", t, mip));
  EXPECT_EQ(t, TexelFilter::Linear);
  EXPECT_EQ(mip, MipMode::Nearest);
  EXPECT_TRUE(parse_min_filter("nearest_mipmap_linear", t, mip));
  EXPECT_EQ(t, TexelFilter::Nearest);
  EXPECT_EQ(mip, MipMode::Linear);
  for (const char* bad : {"trilinear", "point", "cubic", "", "linear_mipmap"}) {
    std::optional<MipMode> none;
    EXPECT_FALSE(parse_min_filter(bad, t, none)) << bad;
    EXPECT_FALSE(none.has_value()) << bad;
  }
}

// LOD stage 1b (docs/numerics.md): fixed_log2_q10 and lod_from_derivatives against log2 in
// long double; stage 1c, the LOD unit tex_lod. The measured maxima are printed and recorded in
// docs/accuracy.md and docs/numerics.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "model/formats.h"
#include "model/lod.h"

using namespace tex;

namespace {
// 1024 * log2(p), p exactly representable in long double (64-bit mantissa on x86-64).
long double real_log2_q10(uint64_t p) { return 1024.0L * std::log2((long double)p); }
}  // namespace

// The integer part is exact (leading one); each of the 10 squarings truncates the mantissa, so
// the result can only be low: the claim is floor(1024 log2 p) - 1 <= l10 <= floor(1024 log2 p).
TEST(Lod, FixedLog2Q10IsFloorWithinOneUlp) {
  long double max_err = 0;  // real - l10, in units of 1/1024
  int64_t below_floor = 0, count = 0;
  auto check = [&](uint64_t p) {
    const int64_t l10 = fixed_log2_q10(p);
    const long double real = real_log2_q10(p);
    const int64_t fl = int64_t(std::floor(real));
    ASSERT_LE(l10, fl) << "p=" << p;
    ASSERT_GE(l10, fl - 1) << "p=" << p;
    if (l10 < fl) ++below_floor;
    max_err = std::max(max_err, real - l10);
    ++count;
  };
  for (uint64_t p = 1; p <= (1u << 20); ++p) check(p);
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000000; ++i) {
    const int shift = int(rng() % 64);
    const uint64_t p = rng() >> shift;
    if (p) check(p);
  }
  for (int b = 0; b < 64; ++b) {
    check(uint64_t(1) << b);  // exact powers of two: l10 = 1024 b exactly
    EXPECT_EQ(fixed_log2_q10(uint64_t(1) << b), 1024 * b);
    if (b) check((uint64_t(1) << b) - 1);
  }
  check(UINT64_MAX);
  std::printf("fixed_log2_q10: %lld values, max (1024 log2 p - l10) = %.4Lf, l10 < floor in %lld cases\n",
              (long long)count, max_err, (long long)below_floor);
  EXPECT_LT(max_err, 2.0L);
}

// lambda error against 0.5 log2(max(rho_x^2, rho_y^2)) in long double, rho in level-0 texels.
// Bound, for rho >= 1/16 texel: final Q8.8 round-half-up <= 1/512; l10 is up to 2/1024 below
// 1024 log2 P, i.e. <= 1/1024 in lambda; Q16.16 derivatives move each component by <= 2^-17
// texels, so rho moves by <= sqrt(2) 2^-17 <= 2^-12.5 of rho = 1/16, i.e. <= 2.5e-4 levels.
// Sum < 0.0032 < 1/256 + 0 = 0.0039: the assertion is 1/256 levels (one LSB of Q8.8).
TEST(Lod, LodFromDerivativesErrorBelowOneLsb) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> expo(-4.0, 14.9), angle(0, 2 * M_PI), unit(0, 1);
  double max_err = 0, sum_err = 0;
  int n = 0;
  for (int lw = 0; lw <= kMaxLog2Size; lw += 3)
    for (int lh = 0; lh <= kMaxLog2Size; lh += 4)
      for (int i = 0; i < 50000; ++i) {
        // Random derivative vectors with lengths 2^-4 .. 2^14.9 texels, random direction and anisotropy.
        const double W = std::ldexp(1.0, lw), H = std::ldexp(1.0, lh);
        const double rx = std::exp2(expo(rng)), ax = angle(rng);
        const double ry = rx * std::exp2(-4.0 * unit(rng)), ay = angle(rng);
        Derivatives d;
        d.dudx = rx * std::cos(ax) / W;
        d.dvdx = rx * std::sin(ax) / H;
        d.dudy = ry * std::cos(ay) / W;
        d.dvdy = ry * std::sin(ay) / H;
        if (rng() & 1) {
          std::swap(d.dudx, d.dudy);
          std::swap(d.dvdx, d.dvdy);
        }
        int32_t lod = 0;
        ASSERT_TRUE(lod_from_derivatives(d, lw, lh, lod));
        const long double px = std::pow((long double)d.dudx * W, 2) + std::pow((long double)d.dvdx * H, 2);
        const long double py = std::pow((long double)d.dudy * W, 2) + std::pow((long double)d.dvdy * H, 2);
        const double real = double(0.5L * std::log2(std::max(px, py)));
        const double err = std::fabs(lod / 256.0 - real);
        max_err = std::max(max_err, err);
        sum_err += err;
        ++n;
        ASSERT_LE(err, 1.0 / 256) << "lambda=" << real << " model=" << lod / 256.0;
      }
  std::printf("lod_from_derivatives: %d queries, rho in [2^-4, 2^14.9] texels: max |lambda - real| = %.5f levels "
              "(%.3f LSB of Q8.8), mean %.5f levels\n",
              n, max_err, max_err * 256, sum_err / n);
}

TEST(Lod, LodFromDerivativesEdgeCases) {
  int32_t lod = 0;
  // No derivatives: the most negative lambda (magnify).
  ASSERT_TRUE(lod_from_derivatives({0, 0, 0, 0}, 8, 8, lod));
  EXPECT_EQ(lod, kLodMin);
  // One texel per pixel: lambda = 0 exactly; 2, 4 texels: 1, 2.
  ASSERT_TRUE(lod_from_derivatives({1.0 / 256, 0, 0, 1.0 / 256}, 8, 8, lod));
  EXPECT_EQ(lod, 0);
  ASSERT_TRUE(lod_from_derivatives({2.0 / 256, 0, 0, 1.0 / 256}, 8, 8, lod));
  EXPECT_EQ(lod, 256);
  ASSERT_TRUE(lod_from_derivatives({0, 4.0 / 64, 0, 0}, 8, 6, lod));  // v scales by the height
  EXPECT_EQ(lod, 512);
  // Not finite: refused. 2^15 texels or more (a pixel at a horizon): saturates at lambda >= 15,
  // past the last level of any texture (13 at most), never below the value just under it.
  EXPECT_FALSE(lod_from_derivatives({NAN, 0, 0, 0}, 8, 8, lod));
  EXPECT_FALSE(lod_from_derivatives({0, INFINITY, 0, 0}, 8, 8, lod));
  EXPECT_TRUE(lod_from_derivatives({0, 0, 32767.0 / 256, 0}, 8, 8, lod));
  EXPECT_NEAR(lod / 256.0, std::log2(32767.0), 1.0 / 256);
  for (double texels : {32768.0, 1e6, -1e30}) {
    ASSERT_TRUE(lod_from_derivatives({0, 0, texels / 256, 0}, 8, 8, lod)) << texels;
    EXPECT_GE(lod, 15 * 256) << texels;
    EXPECT_LE(lod, 16 * 256) << texels;
  }
}

// to_coord_fixed / to_lod_fixed: round half away from zero, range errors instead of clamping.
TEST(Lod, RealToFixedConversion) {
  int32_t x = 0;
  EXPECT_TRUE(to_coord_fixed(0.5, x));
  EXPECT_EQ(x, 1 << 23);
  EXPECT_TRUE(to_coord_fixed(-128.0, x));
  EXPECT_EQ(x, INT32_MIN);
  EXPECT_FALSE(to_coord_fixed(128.0, x));
  EXPECT_TRUE(to_coord_fixed(std::ldexp(2147483647.0, -24), x));
  EXPECT_EQ(x, INT32_MAX);
  EXPECT_TRUE(to_coord_fixed(std::ldexp(2.5, -24), x));  // half away from zero
  EXPECT_EQ(x, 3);
  EXPECT_TRUE(to_coord_fixed(std::ldexp(-2.5, -24), x));
  EXPECT_EQ(x, -3);
  EXPECT_FALSE(to_coord_fixed(NAN, x));
  EXPECT_FALSE(to_coord_fixed(INFINITY, x));
  EXPECT_FALSE(to_coord_fixed(-128.0 - std::ldexp(1.0, -23), x));
  EXPECT_TRUE(to_lod_fixed(1.5 / 256, x));
  EXPECT_EQ(x, 2);
  EXPECT_TRUE(to_lod_fixed(-128.0, x));
  EXPECT_EQ(x, kLodMin);
  EXPECT_FALSE(to_lod_fixed(128.0, x));
  EXPECT_FALSE(to_lod_fixed(-NAN, x));
}

// ------------------------------------------------------------------ tex_lod (the LOD unit)

// Hand-worked values: rho = 1024 texels is lambda 10 exactly; the diagonal (0.5, 0.5) of a 1024^2
// texture is rho = 512 sqrt 2, lambda 9.5; signs do not matter; the larger axis wins.
TEST(TexLod, HandWorkedValues) {
  constexpr int32_t one = 1 << 24, half = 1 << 23;
  EXPECT_EQ(tex_lod({one, 0, 0, 0}, 10, 10), 10 * 256);
  EXPECT_EQ(tex_lod({-one, 0, 0, 0}, 10, 10), 10 * 256);
  EXPECT_EQ(tex_lod({0, 0, 0, -one}, 3, 10), 10 * 256);  // dv/dy: the height counts
  EXPECT_EQ(tex_lod({half, half, 0, 0}, 10, 10), 9 * 256 + 128);
  EXPECT_EQ(tex_lod({0, 0, half, -half}, 10, 10), 9 * 256 + 128);
  EXPECT_EQ(tex_lod({one, 0, 0, half}, 10, 10), 10 * 256);  // max over the axes
  EXPECT_EQ(tex_lod({1 << 8, 0, 0, 0}, 0, 0), -16 * 256);   // 1/65536 of a 1-texel texture
  EXPECT_EQ(tex_lod({0, 0, 0, 0}, 13, 13), kLodMin);        // no footprint: magnify past any clamp
  // The largest derivative of the format at 8192 texels: 2^7 * 2^13 texels, lambda 20, past every
  // level (the filter clamps it to the last one; never an error).
  EXPECT_EQ(tex_lod({INT32_MAX, INT32_MIN + 1, 0, 0}, 13, 13), 20 * 256 + 128);
}

// 10 M random derivative sets over the range (1/65536 to 1 texture width per pixel,
// textures 1 to 8192 texels a side, any direction, anisotropy up to 1:256): |lambda - log2 rho|
// against the exact value from the same Q8.24 inputs. Bound: 1/512 rounding to Q8.8, + the
// interpolated table's error (2^-10 / (8 ln 2) in log2 p, halved), + the block normalization's
// truncation (< 2^-15 of rho^2): < 0.0022 levels; the assertion is the 1/64.
TEST(TexLod, ErrorOverTenMillionDerivativeSets) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> expo(-16.0, 0.0), angle(0, 2 * M_PI), aniso(0, 8.0);
  double max_err = 0, sum_err = 0, max_err_real = 0;
  const int n = 10'000'000;
  for (int i = 0; i < n; ++i) {
    const int lw = int(rng() % 14), lh = int(rng() % 14);
    const double rx = std::exp2(expo(rng)), ry = rx * std::exp2(-aniso(rng));
    const double ax = angle(rng), ay = angle(rng);
    double dn[4] = {rx * std::cos(ax), rx * std::sin(ax), ry * std::cos(ay), ry * std::sin(ay)};
    if (rng() & 1) {
      std::swap(dn[0], dn[2]);
      std::swap(dn[1], dn[3]);
    }
    LodDerivatives d;
    int32_t* q[4] = {&d.dudx, &d.dvdx, &d.dudy, &d.dvdy};
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(to_coord_fixed(dn[k], *q[k]));
    const long double W = std::ldexp(1.0L, lw - 24), H = std::ldexp(1.0L, lh - 24);
    auto sq = [](long double x) { return x * x; };
    const long double px = sq(d.dudx * W) + sq(d.dvdx * H), py = sq(d.dudy * W) + sq(d.dvdy * H);
    const double exact = double(0.5L * std::log2(std::max(px, py)));
    const double lambda = tex_lod(d, lw, lh) / 256.0;
    const double err = std::fabs(lambda - exact);
    max_err = std::max(max_err, err);
    sum_err += err;
    const double real = 0.5 * std::log2(std::max(sq(dn[0] * std::ldexp(1.0, lw)) + sq(dn[1] * std::ldexp(1.0, lh)),
                                                 sq(dn[2] * std::ldexp(1.0, lw)) + sq(dn[3] * std::ldexp(1.0, lh))));
    // Against the derivatives before Q8.24: the format's step is 2^-24 of the texture, 2^-11 texels
    // at 8192, so deep in magnification (lambda < -4) a rounded minor component can dominate; from
    // -4 up the format costs less than the unit.
    if (real >= -4) max_err_real = std::max(max_err_real, std::fabs(lambda - real));
    if (err > 1.0 / 64) FAIL() << "lambda " << lambda << " exact " << exact << " (set " << i << ")";
  }
  std::printf("tex_lod: %d derivative sets: max |lambda - log2 rho| = %.5f levels (1/%.0f), mean %.5f; against the "
              "derivatives before Q8.24, lambda >= -4: max %.5f\n",
              n, max_err, 1.0 / max_err, sum_err / n, max_err_real);
  EXPECT_LE(max_err, 1.0 / 64);
  EXPECT_LE(max_err_real, 1.0 / 64);
}

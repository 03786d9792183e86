// LOD stage 1b (docs/numerics.md): the LOD unit tex_lambda against log2 in long double, and
// lod_from_derivatives (real derivatives -> Q8.24 -> tex_lambda). The measured maxima are printed
// and recorded in docs/numerics.md and docs/accuracy.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "model/formats.h"
#include "model/lod.h"

using namespace tex;

TEST(Lod, LodFromDerivativesEdgeCases) {
  int32_t lod = 0;
  // No derivatives: the most negative lambda (magnify).
  ASSERT_TRUE(lod_from_derivatives({0, 0, 0, 0}, {256, 256}, lod));
  EXPECT_EQ(lod, kLodMin);
  // One texel per pixel: lambda = 0 exactly; 2, 4 texels: 1, 2.
  ASSERT_TRUE(lod_from_derivatives({1.0 / 256, 0, 0, 1.0 / 256}, {256, 256}, lod));
  EXPECT_EQ(lod, 0);
  ASSERT_TRUE(lod_from_derivatives({2.0 / 256, 0, 0, 1.0 / 256}, {256, 256}, lod));
  EXPECT_EQ(lod, 256);
  ASSERT_TRUE(lod_from_derivatives({0, 4.0 / 64, 0, 0}, {256, 64}, lod));  // v scales by the height
  EXPECT_EQ(lod, 512);
  // Not finite: refused. 128 texture widths or more (a pixel at a horizon; 2^15 texels here)
  // saturates the Q8.24 format at lambda 15, past the last level of any texture (13 at most).
  EXPECT_FALSE(lod_from_derivatives({NAN, 0, 0, 0}, {256, 256}, lod));
  EXPECT_FALSE(lod_from_derivatives({0, INFINITY, 0, 0}, {256, 256}, lod));
  EXPECT_TRUE(lod_from_derivatives({0, 0, 32767.0 / 256, 0}, {256, 256}, lod));
  EXPECT_NEAR(lod / 256.0, std::log2(32767.0), 1.0 / 256);
  for (double texels : {32768.0, 1e6, -1e30}) {
    ASSERT_TRUE(lod_from_derivatives({0, 0, texels / 256, 0}, {256, 256}, lod)) << texels;
    EXPECT_GE(lod, 15 * 256) << texels;
    EXPECT_LE(lod, 16 * 256) << texels;
  }
}

// to_coord_fixed rounds as std::llround(std::ldexp(u, 24)) does, on random values, exact halves,
// values one ulp either side of a half, and the ends of the range.
TEST(Lod, RealToFixedRoundsAsLlround) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> any(-128.0, 128.0);
  int checked = 0;
  for (int i = 0; i < 1000000; ++i) {
    double u = any(rng);
    if (i % 4 == 1) u = std::ldexp(std::floor(std::ldexp(u, 24)) + 0.5, -24);  // an exact half
    if (i % 4 == 2) u = std::nextafter(std::ldexp(std::floor(std::ldexp(u, 24)) + 0.5, -24), 0.0);
    if (i % 4 == 3) u = std::nextafter(std::ldexp(std::floor(std::ldexp(u, 24)) + 0.5, -24), 1e9);
    const double scaled = std::ldexp(u, 24);
    int32_t x = 0;
    const bool ok = to_coord_fixed(u, x);
    const bool in_range = scaled >= -2147483648.5 && scaled < 2147483647.5;
    ASSERT_EQ(ok, in_range) << u;
    if (ok) {
      ASSERT_EQ(x, std::llround(scaled)) << u;
      ++checked;
    }
  }
  EXPECT_GT(checked, 900000);
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

// ------------------------------------------------------------------ tex_lambda (the LOD unit)

// Hand-worked values: rho = 1024 texels is lambda 10 exactly; the diagonal (0.5, 0.5) of a 1024^2
// texture is rho = 512 sqrt 2, lambda 9.5; signs do not matter; the larger axis wins.
TEST(TexLambda, HandWorkedValues) {
  constexpr int32_t one = 1 << 24, half = 1 << 23;
  EXPECT_EQ(tex_lambda({one, 0, 0, 0}, {1024, 1024}), 10 * 256);
  EXPECT_EQ(tex_lambda({-one, 0, 0, 0}, {1024, 1024}), 10 * 256);
  EXPECT_EQ(tex_lambda({0, 0, 0, -one}, {8, 1024}), 10 * 256);  // dv/dy: the height counts
  EXPECT_EQ(tex_lambda({half, half, 0, 0}, {1024, 1024}), 9 * 256 + 128);
  EXPECT_EQ(tex_lambda({0, 0, half, -half}, {1024, 1024}), 9 * 256 + 128);
  EXPECT_EQ(tex_lambda({one, 0, 0, half}, {1024, 1024}), 10 * 256);  // max over the axes
  EXPECT_EQ(tex_lambda({1 << 8, 0, 0, 0}, {1, 1}), -16 * 256);   // 1/65536 of a 1-texel texture
  EXPECT_EQ(tex_lambda({0, 0, 0, 0}, {8192, 8192}), kLodMin);        // no footprint: magnify past any clamp
  // The largest derivative of the format at 8192 texels: 2^7 * 2^13 texels, lambda 20, past every
  // level (the filter clamps it to the last one; never an error).
  EXPECT_EQ(tex_lambda({INT32_MAX, INT32_MIN + 1, 0, 0}, {8192, 8192}), 20 * 256 + 128);
}

// 10 M random derivative sets over the range (1/65536 to 1 texture width per pixel,
// textures 1 to 8192 texels a side (half of them any size, half powers of two), any direction, anisotropy up to 1:256): |lambda - log2 rho|
// against the exact value from the same Q8.24 inputs. Bound: 1/512 rounding to Q8.8, + the
// interpolated table's error (2^-10 / (8 ln 2) in log2 p, halved), + the block normalization's
// truncation (< 2^-15 of rho^2): < 0.0022 levels; the assertion is the 1/64.
TEST(TexLambda, ErrorOverTenMillionDerivativeSets) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> expo(-16.0, 0.0), angle(0, 2 * M_PI), aniso(0, 8.0);
  double max_err = 0, sum_err = 0, max_err_real = 0;
  const int n = 10'000'000;
  for (int i = 0; i < n; ++i) {
    // Sides: a power of two 2^0..2^13, or any size 1..8192.
    auto side = [&] { return rng() & 1 ? 1 << int(rng() % 14) : int(rng() % 8192) + 1; };
    const int sw = side(), sh = side();
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
    const long double W = std::ldexp((long double)sw, -24), H = std::ldexp((long double)sh, -24);
    auto sq = [](long double x) { return x * x; };
    const long double px = sq(d.dudx * W) + sq(d.dvdx * H), py = sq(d.dudy * W) + sq(d.dvdy * H);
    const double exact = double(0.5L * std::log2(std::max(px, py)));
    const double lambda = tex_lambda(d, {sw, sh}) / 256.0;
    const double err = std::fabs(lambda - exact);
    max_err = std::max(max_err, err);
    sum_err += err;
    const double real = 0.5 * std::log2(std::max(sq(dn[0] * sw) + sq(dn[1] * sh), sq(dn[2] * sw) + sq(dn[3] * sh)));
    // Against the derivatives before Q8.24: the format's step is 2^-24 of the texture, 2^-11 texels
    // at 8192, so deep in magnification (lambda < -4) a rounded minor component can dominate; from
    // -4 up the format costs less than the unit.
    if (real >= -4) max_err_real = std::max(max_err_real, std::fabs(lambda - real));
    if (err > 1.0 / 64) FAIL() << "lambda " << lambda << " exact " << exact << " (set " << i << ")";
  }
  std::printf("tex_lambda: %d derivative sets: max |lambda - log2 rho| = %.5f levels (1/%.0f), mean %.5f; against the "
              "derivatives before Q8.24, lambda >= -4: max %.5f\n",
              n, max_err, 1.0 / max_err, sum_err / n, max_err_real);
  EXPECT_LE(max_err, 1.0 / 64);
  EXPECT_LE(max_err_real, 1.0 / 64);
}

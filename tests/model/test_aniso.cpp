// Anisotropic filtering (docs/numerics.md stage 1c and stage 6): tex_aniso's probe count, lambda'
// and spacing against their definitions in real arithmetic, the probes of tex_probe, the mean of N
// probes with one rounding (and the reciprocal the RTL divides by), and the sampler's behaviour:
// an isotropic footprint, or a cap of 1, is exactly trilinear; the fast path equals the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "model/formats.h"
#include "model/image.h"
#include "model/lod.h"
#include "model/pyramid.h"
#include "model/sampler.h"

using namespace tex;

namespace {

// Derivatives in level-0 texels of a 2^10 x 2^10 texture, as Q8.24 texture widths (exact: a
// multiple of 2^-14 texels).
LodDerivatives texels(double dudx, double dvdx, double dudy, double dvdy) {
  auto q = [](double t) { return int32_t(std::lround(t / 1024.0 * 16777216.0)); };
  return {q(dudx), q(dvdx), q(dudy), q(dvdy)};
}

Image random_image(int w, int h, std::mt19937& rng) {
  Image img(w, h, 8);
  for (Texel& t : img.texels)
    for (auto& c : t) c = uint16_t(rng() % 4 == 0 ? (rng() % 2) * 255 : rng() % 256);
  return img;
}

}  // namespace

TEST(TexAniso, TablesAreTheirDefinitions) {
  for (int n = 1; n <= kMaxAniso; ++n) {
    EXPECT_EQ(aniso_log2_q8(n), std::lround(256 * std::log2(double(n)))) << n;
    EXPECT_EQ(aniso_reciprocal(n), std::lround(65536.0 / n)) << n;
  }
}

// N = min(ceil(Pmax / Pmin), cap), and with pow2 the least power of two >= the ratio, capped at the
// largest power of two <= cap; exactly at a whole ratio, within its 1/128 tolerance, and past it.
TEST(TexAniso, ProbeCountIsTheCeilingOfTheAxisRatio) {
  struct Case {
    double major, minor;
    int cap;
    bool pow2;
    int n;
  };
  const Case cases[] = {
      {4, 4, 16, false, 1},     {4, 1, 16, false, 4},     {4.05, 1, 16, false, 5},  {3.5, 1, 16, false, 4},
      {16, 1, 16, false, 16},   {100, 1, 16, false, 16},  {100, 1, 6, false, 6},    {5, 0, 16, false, 16},
      {3, 1, 16, true, 4},      {5, 1, 16, true, 8},      {4, 1, 16, true, 4},      {9, 1, 6, true, 4},
      {1.5, 1, 1, false, 1},    {7, 1, 1, true, 1},       {2, 1, 16, false, 2},     {2.02, 1, 16, false, 3},  {4.03, 1, 16, false, 4},
  };
  for (const Case& c : cases) {
    for (bool along_x : {true, false}) {
      const LodDerivatives d = along_x ? texels(c.major, 0, 0, c.minor) : texels(0, c.minor, c.major, 0);
      const AnisoSetup a = tex_aniso(d, {1024, 1024}, c.cap, c.pow2);
      EXPECT_EQ(a.n, c.n) << c.major << "/" << c.minor << " cap " << c.cap << " pow2 " << c.pow2;
    }
  }
  // All derivatives 0: one probe at the most negative lambda, like tex_lambda.
  const AnisoSetup zero = tex_aniso({}, {1024, 1024}, 16, false);
  EXPECT_EQ(zero.n, 1);
  EXPECT_EQ(zero.lambda, kLodMin);
}

// Over random footprints: lambda' within 1/64 of log2(Pmax / N); N exact against the real ratio
// (away from whole ratios, where the 16-bit normalization may fall either way); steps = axis / N.
TEST(TexAniso, RandomFootprintsAgainstRealArithmetic) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> log_len(-6, 6), angle(0, 2 * M_PI), unit(0, 1);
  double worst_lambda = 0;
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const double px = std::exp2(log_len(rng)), py = std::exp2(log_len(rng));
    const double ax = angle(rng), ay = ax + M_PI / 2 + (unit(rng) - 0.5);  // roughly perpendicular
    const int log2_w = int(rng() % 11) + 3, log2_h = int(rng() % 11) + 3;
    const double w = std::ldexp(1.0, log2_w), h = std::ldexp(1.0, log2_h);
    auto q = [](double x) { return int32_t(std::lround(x * 16777216.0)); };
    const LodDerivatives d{q(px * std::cos(ax) / w), q(px * std::sin(ax) / h), q(py * std::cos(ay) / w),
                           q(py * std::sin(ay) / h)};
    // The quantized derivatives' exact lengths in texels.
    const double qx = std::hypot(d.dudx * w, d.dvdx * h) / 16777216.0;
    const double qy = std::hypot(d.dudy * w, d.dvdy * h) / 16777216.0;
    const double pmax = std::max(qx, qy), pmin = std::min(qx, qy);
    const int cap = int(rng() % 16) + 1;
    const AnisoSetup a = tex_aniso(d, {1 << log2_w, 1 << log2_h}, cap, false);
    // N: the least n with n^2 >= ratio^2 * 63/64, checked where the 16-bit normalization of the
    // minor axis (about ratio / 2^15 relative) cannot decide it.
    const double r2 = (pmax / pmin) * (pmax / pmin) * 63 / 64, root = std::sqrt(r2);
    if (pmin > 0.01 && std::abs(root - std::round(root)) > root * 1e-3) {
      const int n = std::min(int(std::ceil(root)), cap);
      ASSERT_EQ(a.n, n) << "Px " << qx << " Py " << qy << " cap " << cap;
      ++checked;
    }
    const double err = std::abs(a.lambda / 256.0 - std::log2(pmax / a.n));
    worst_lambda = std::max(worst_lambda, err);
    const bool major_x = qx >= qy;
    const double axis_u = major_x ? d.dudx : d.dudy, axis_v = major_x ? d.dvdx : d.dvdy;
    ASSERT_NEAR(a.step_u, axis_u / a.n, std::abs(axis_u) / a.n * 1e-4 + 1);
    ASSERT_NEAR(a.step_v, axis_v / a.n, std::abs(axis_v) / a.n * 1e-4 + 1);
  }
  std::printf("tex_aniso: max |lambda' - log2(Pmax/N)| = %.5f levels over 200000 footprints\n", worst_lambda);
  EXPECT_LE(worst_lambda, 1.0 / 64);
  EXPECT_GT(checked, 150000);
}

// The probes sit at (2i + 1 - N) / (2N) of the major axis around the centre, and saturate at the
// ends of the Q8.24 range instead of wrapping around.
TEST(TexAniso, ProbesSpreadEvenlyAlongTheMajorAxis) {
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::Linear, true};
  Request r;
  r.u = 3 << 22;
  r.v = 5 << 21;
  r.has_derivatives = true;
  r.deriv = texels(1, 0, 0, 8);  // major axis: y, along v, 8 texels: 8 probes
  const Probes p = tex_probe(r, cfg, {1024, 1024});
  ASSERT_EQ(p.n, 8);
  for (int i = 0; i < p.n; ++i) {
    const Request& q = p.at[size_t(i)];
    EXPECT_EQ(q.u, r.u) << i;
    EXPECT_NEAR(q.v - r.v, (2 * i + 1 - 8) / 16.0 * r.deriv.dvdy, 4) << i;
    EXPECT_FALSE(q.has_derivatives);
    EXPECT_EQ(q.lod, tex_lambda(r.deriv, {1024, 1024}) - 3 * 256) << i;  // lambda' = log2(8 / 8) = 0
  }
  EXPECT_EQ(p.at[7].lod, 0);
  // A request without derivatives: one probe, itself.
  Request plain = lambda_request(1, 2, 300, 9);
  const Probes one = tex_probe(plain, cfg, {1024, 1024});
  ASSERT_EQ(one.n, 1);
  EXPECT_EQ(one.at[0].u, 1);
  EXPECT_EQ(one.at[0].lod, 300);
  // Saturation at the top of the range.
  EXPECT_EQ(aniso_probe_coord(INT32_MAX - 10, 1 << 30, 15, 16), INT32_MAX);
  EXPECT_EQ(aniso_probe_coord(INT32_MIN + 10, 1 << 30, 0, 16), INT32_MIN);
  EXPECT_EQ(aniso_probe_coord(100, 7, 0, 2), 100 - 4);  // floor(-7 / 2)
}

// The RTL divides the sum of N probes by N with a reciprocal multiply: floor(X * ceil(2^25 / N) / 2^25)
// = floor(X / N) for every X it can see (X < 2^21: 16 probes of 16-bit channels, rounded to CW.0).
TEST(TexAniso, ReciprocalDivisionIsExact) {
  for (uint64_t n = 1; n <= 16; ++n) {
    const uint64_t r = ((uint64_t(1) << 25) + n - 1) / n;
    for (uint64_t x = 0; x < (uint64_t(1) << 21); ++x)
      ASSERT_EQ((x * r) >> 25, x / n) << "x " << x << " n " << n;
  }
  // And the mean's rounding: floor((S + N 2^23) / (N 2^24)) = floor(floor((S + N 2^23) / 2^24) / N).
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const int n = int(rng() % 16) + 1;
    const int64_t s = int64_t(rng() % (uint64_t(n) << 40));
    stage::Unrounded sum{s, 0, 0, 0};
    EXPECT_EQ(stage::average_and_round(sum, n)[0], uint16_t(((s + (int64_t(n) << 23)) >> 24) / n));
  }
}

// One probe (a cap of 1, or an isotropic footprint) is trilinear at tex_lambda, bit for bit; N
// probes of a one-colour texture give that colour exactly; the fast path equals the reference.
TEST(AnisoSampler, IsotropicIsTrilinearAndFastPathEqualsReference) {
  std::mt19937 rng(5);
  const Pyramid pyr = build_pyramid(random_image(128, 64, rng));
  SamplerConfig tri, aniso, aniso1, aniso_p2;
  tri.filter = {TexelFilter::Linear, MipMode::Linear};
  aniso.filter = aniso1.filter = aniso_p2.filter = {TexelFilter::Linear, MipMode::Linear, true};
  aniso1.max_aniso = 1;
  aniso_p2.aniso_pow2 = true;
  aniso_p2.wrap_u = Wrap::Mirror;
  aniso_p2.wrap_v = Wrap::Clamp;
  Sampler s_tri(pyr, tri), s_an(pyr, aniso), s_an1(pyr, aniso1), s_p2(pyr, aniso_p2);
  std::vector<Request> reqs(20000);
  std::uniform_int_distribution<int32_t> coord(-(1 << 26), 1 << 26), deriv(-(1 << 22), 1 << 22);
  for (size_t i = 0; i < reqs.size(); ++i) {
    Request& r = reqs[i];
    r.u = coord(rng);
    r.v = coord(rng);
    r.has_derivatives = true;
    if (i % 4 == 0) {  // isotropic: in texels the y vector is the x vector turned by 90 degrees
      r.deriv.dudx = deriv(rng) & ~1;
      r.deriv.dvdx = deriv(rng) & ~1;
      r.deriv.dudy = -r.deriv.dvdx / 2;  // (the texture is 128 x 64: a v step is 2 u steps in texels)
      r.deriv.dvdy = 2 * r.deriv.dudx;
    } else {
      r.deriv = {deriv(rng), deriv(rng), deriv(rng) >> (rng() % 8), deriv(rng) >> (rng() % 8)};
    }
    r.lod = tex_lambda(r.deriv, {128, 64});
    const Texel t = s_tri.sample(lambda_request(r.u, r.v, r.lod));
    EXPECT_EQ(s_an1.sample(r), t) << i;
    if (i % 4 == 0) {
      EXPECT_EQ(tex_probe(r, aniso, {128, 64}).n, 1) << i;
      EXPECT_EQ(s_an.sample(r), t) << i;
    }
  }
  for (Sampler* s : {&s_an, &s_p2, &s_an1}) {
    std::vector<uint32_t> fast(reqs.size());
    s->sample_rgba8(reqs.data(), reqs.size(), fast.data());
    for (size_t i = 0; i < reqs.size(); ++i) {
      const Texel t = s->sample(reqs[i]);
      ASSERT_EQ(fast[i], uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24) << i;
    }
  }
  // The probe histogram: every sample counted once, at its N; some use 16.
  const SamplerStats st = s_an.stats();
  uint64_t total = 0;
  for (uint64_t c : st.probes) total += c;
  EXPECT_EQ(total, st.samples);
  EXPECT_GT(st.probes[16], 0u);
  EXPECT_GT(st.probes[1], 0u);

  Image flat(16, 16, 8);
  for (Texel& t : flat.texels) t = {37, 200, 255, 1};
  Sampler s_flat(build_pyramid(flat), aniso);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(s_flat.sample(reqs[size_t(i)]), (Texel{37, 200, 255, 1})) << i;
}

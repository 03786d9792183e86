// The sampler end to end: wrap at every level (1-texel levels included), level selection at its
// boundaries, point sampling, and the fast path against the reference path.
// Expected values: on inputs where every weight is a multiple of 1/256 the real-valued GL filter
// (tests/reference/gl_reference.h) is exact in double, so the model must equal its rounding exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"
#include "model/image.h"
#include "model/sampler.h"
#include "model/srgb.h"
#include "reference/gl_reference.h"

using namespace tex;

namespace {

constexpr Wrap kWraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};

Request request(double u, double v, double lambda) {
  Request r;
  EXPECT_TRUE(to_coord_fixed(u, r.u)) << u;
  EXPECT_TRUE(to_coord_fixed(v, r.v)) << v;
  EXPECT_TRUE(to_lod_fixed(lambda, r.lod)) << lambda;
  return r;
}

// Round half up, the pipeline's one rounding.
Texel rounded(const ref::Rgba& x) {
  Texel t;
  for (int c = 0; c < 4; ++c) t[c] = uint16_t(std::floor(x[c] + 0.5));
  return t;
}

ref::GlSampler reference(const Pyramid& p, Filter f, Wrap ws, Wrap wt) {
  ref::GlSampler g;
  g.levels = &p.levels;
  g.texel = f.texel;
  g.mip = f.mip;
  g.wrap_s = ws;
  g.wrap_t = wt;
  return g;
}

// A normalized coordinate whose texel coordinate at a level of n = 2^k texels is (i + a/256) + 1/2:
// exactly representable in Q8.24, so the bilinear weight is exactly a/256.
double on_grid(int64_t i, int a, int n) { return (double(i) + a / 256.0 + 0.5) / double(n); }

std::string name_of(Filter f, Wrap wu, Wrap wv) { return filter_name(f) + "/" + wrap_name(wu) + "/" + wrap_name(wv); }

}  // namespace

TEST(Sampler, WrapAtEveryLevelIncludingOneTexelLevels) {
  // 32x4: levels 32x4, 16x2, 8x1, 4x1, 2x1, 1x1; levels with a 1-texel side from level 2 on.
  const Pyramid pyr = build_pyramid(make_pattern("noise", 32, 4));
  std::mt19937 rng(8);
  for (Wrap wu : kWraps)
    for (Wrap wv : kWraps)
      for (TexelFilter tf : {TexelFilter::Nearest, TexelFilter::Linear}) {
        const Filter f{tf, MipMode::Nearest};
        Sampler s(pyr, {f, wu, wv});
        const ref::GlSampler g = reference(pyr, f, wu, wv);
        for (int k = 0; k <= pyr.last_level(); ++k) {
          const Extent sh = level_extent({32, 4}, k);
          for (int n = 0; n < 3000; ++n) {
            // Texel coordinates from -3 to +3 level widths: every wrap period and both edges.
            const int64_t i = int64_t(rng() % (6 * sh.width() + 2)) - 3 * sh.width() - 1;
            const int64_t j = int64_t(rng() % (6 * sh.height() + 2)) - 3 * sh.height() - 1;
            const double u = on_grid(i, int(rng() & 255), sh.w), v = on_grid(j, int(rng() & 255), sh.h);
            const double lambda = k;  // nearest level: exactly level k
            const Texel got = s.sample(request(u, v, lambda));
            ASSERT_EQ(got, rounded(g.sample(u, v, lambda)))
                << name_of(f, wu, wv) << " level " << k << " (" << sh.width() << "x" << sh.height() << ") u=" << u
                << " v=" << v;
          }
        }
      }
}

// Sides that are not powers of two (docs/numerics.md stages 2 and 3): every address mode, both texel
// filters and every mip mode, at every level, against the real-valued GL reference. Coordinates
// u = K / 256 make u * n * 256 an integer at every level, so every weight is exact and the model
// must equal the reference's rounding; K spans three periods on either side (the repeat seam of
// odd levels, mirrored periods, the border).
TEST(Sampler, NonPowerOfTwoSidesMatchTheGlReference) {
  const std::pair<int, int> sizes[] = {{5, 3}, {7, 1}, {1, 9}, {13, 6}, {31, 17}, {100, 60}};
  std::mt19937 rng(39);
  size_t checked = 0;
  for (auto [w, h] : sizes) {
    const Pyramid pyr = build_pyramid(make_pattern("noise", w, h));
    for (Wrap wu : kWraps)
      for (Wrap wv : kWraps)
        for (TexelFilter tf : {TexelFilter::Nearest, TexelFilter::Linear})
          for (MipMode mm : {MipMode::None, MipMode::Nearest, MipMode::Linear}) {
            const Filter f{tf, mm};
            Sampler s(pyr, {f, wu, wv});
            const ref::GlSampler g = reference(pyr, f, wu, wv);
            for (int n = 0; n < 300; ++n) {
              const double u = double(int(rng() % (7 * 256)) - 3 * 256) / 256;
              const double v = double(int(rng() % (7 * 256)) - 3 * 256) / 256;
              const double lambda = double(int(rng() % (256 * (pyr.last_level() + 2))) - 256) / 256;
              ASSERT_EQ(s.sample(request(u, v, lambda)), rounded(g.sample(u, v, lambda)))
                  << w << "x" << h << " " << name_of(f, wu, wv) << " u=" << u << " v=" << v << " lambda=" << lambda;
              ++checked;
            }
          }
  }
  EXPECT_EQ(checked, 6u * 25 * 2 * 3 * 300);
}

// Unnormalized coordinates (GL rectangle textures, Vulkan unnormalizedCoordinates): texel
// coordinates of the base level, on NPOT sides, both clamping modes, each texel filter; texel
// coordinates on a 1/256 grid (exact weights) against GL's definition in double.
TEST(Sampler, UnnormalizedCoordinatesMatchTheGlReference) {
  const std::pair<int, int> sizes[] = {{5, 3}, {7, 1}, {1, 9}, {100, 60}, {33, 64}};
  std::mt19937 rng(41);
  size_t checked = 0;
  for (auto [w, h] : sizes) {
    const Pyramid pyr = build_pyramid(make_pattern("noise", w, h));
    for (Wrap wu : {Wrap::Clamp, Wrap::Border})
      for (Wrap wv : {Wrap::Clamp, Wrap::Border})
        for (TexelFilter tf : {TexelFilter::Nearest, TexelFilter::Linear}) {
          SamplerConfig c{{tf, MipMode::None}, wu, wv};
          c.unnormalized = true;
          c.border = BorderColor::FloatOpaqueWhite;
          Sampler s(pyr, c);
          ref::GlSampler g = reference(pyr, c.filter, wu, wv);
          g.unnormalized = true;
          g.border = {255, 255, 255, 255};
          for (int n = 0; n < 400; ++n) {
            const double x = double(int(rng() % uint32_t((w + 6) * 256)) - 3 * 256) / 256;
            const double y = double(int(rng() % uint32_t((h + 6) * 256)) - 3 * 256) / 256;
            Request r;
            ASSERT_TRUE(to_texel_coord_fixed(x, r.u) && to_texel_coord_fixed(y, r.v));
            r.lod = int32_t(rng() % 1024) - 256;  // magnified or minified: the one texel filter, level 0
            ASSERT_EQ(s.sample(r), rounded(g.sample(x, y, 0)))
                << w << "x" << h << " " << name_of(c.filter, wu, wv) << " x=" << x << " y=" << y;
            ++checked;
          }
        }
  }
  EXPECT_EQ(checked, 5u * 4 * 2 * 400);
}

// What an unnormalized sampler may be: Vulkan's rules, one line naming the field and its value.
TEST(Sampler, UnnormalizedSamplerTakesVulkansRulesOnly) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 8, 8));
  SamplerConfig ok{{TexelFilter::Linear, MipMode::None}, Wrap::Clamp, Wrap::Border};
  ok.unnormalized = true;
  EXPECT_EQ(ok.unnormalized_problem(), "");
  EXPECT_NO_THROW(Sampler(pyr, ok));
  SamplerConfig lod0 = ok;  // Vulkan's own form: nearest mipmaps, LOD clamped to 0
  lod0.filter.mip = MipMode::Nearest;
  lod0.min_lod = lod0.max_lod = 0;
  EXPECT_EQ(lod0.unnormalized_problem(), "");
  struct Bad { SamplerConfig c; std::string names; };
  std::vector<Bad> bad;
  bad.reserve(6);  // (else GCC 12's -Warray-bounds sees a string copy out of bounds)
  for (Wrap w : {Wrap::Repeat, Wrap::Mirror, Wrap::MirrorClamp}) {
    SamplerConfig c = ok;
    c.wrap_v = w;
    bad.push_back({c, "not " + wrap_name(w)});
  }
  SamplerConfig aniso = ok;
  aniso.filter.anisotropic = true;
  bad.push_back({aniso, "anisotropic"});
  SamplerConfig mag = ok;
  mag.filter.mag = TexelFilter::Nearest;
  bad.push_back({mag, "magnification filter nearest"});
  SamplerConfig mips = ok;
  mips.filter.mip = MipMode::Linear;  // max LOD left at its default
  bad.push_back({mips, "mipmap mode linear"});
  for (const Bad& b : bad) {
    const std::string p = b.c.unnormalized_problem();
    EXPECT_NE(p.find(b.names), std::string::npos) << p;
    try {
      Sampler s(pyr, b.c);
      ADD_FAILURE() << "no error for " << b.names;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(b.names), std::string::npos) << e.what();
    }
  }
}

TEST(Sampler, PointSamplingIsTexelAtFloorUW) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 16));
  std::mt19937 rng(9);
  std::uniform_int_distribution<int32_t> coord(INT32_MIN, INT32_MAX);
  for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::MirrorClamp}) {  // (border: below)
    Sampler s(pyr, {{TexelFilter::Nearest, MipMode::None}, w, w});
    for (int n = 0; n < 50000; ++n) {
      Request r;
      r.u = (n & 1) ? coord(rng) : coord(rng) >> 6;  // whole range, and near the texture
      r.v = (n & 1) ? coord(rng) : coord(rng) >> 6;
      r.lod = int32_t(rng() % 4000) - 1000;
      // floor(u * W) from the exact rational u = U / 2^24, wrapped by GL's formula.
      const int64_t x = int64_t(std::floor(std::ldexp(double(r.u), 6 - 24)));
      const int64_t y = int64_t(std::floor(std::ldexp(double(r.v), 4 - 24)));
      ASSERT_EQ(s.sample(r), pyr.levels[0].at(int(ref::gl_wrap(x, 64, w)), int(ref::gl_wrap(y, 16, w))))
          << "U=" << r.u << " V=" << r.v;
    }
  }
}

TEST(Sampler, MagnifyMinifyBoundaryAndLastLevelClamp) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 16, 16));
  const int q = pyr.last_level();
  Sampler tri(pyr, {{TexelFilter::Linear, MipMode::Linear}});
  Sampler bil(pyr, {{TexelFilter::Linear, MipMode::None}});
  const ref::GlSampler g = reference(pyr, {TexelFilter::Linear, MipMode::Linear}, Wrap::Repeat, Wrap::Repeat);
  std::mt19937 rng(10);
  for (int n = 0; n < 5000; ++n) {
    // On the 1/256-texel grid of every level at once (1/2048 = 1/128 texel of level 0).
    const double u = (int(rng() % 40000) - 20000) / 2048.0, v = (int(rng() % 40000) - 20000) / 2048.0;
    // lambda <= 0 magnifies: level 0 alone, identical to bilinear.
    for (double lambda : {0.0, -1.0 / 256, -5.0}) ASSERT_EQ(tri.sample(request(u, v, lambda)), bil.sample(request(u, v, 0)));
    // lambda = +1/256 blends level 1 with weight 1/256: exact in double, the model rounds it.
    ASSERT_EQ(tri.sample(request(u, v, 1.0 / 256)), rounded(g.sample(u, v, 1.0 / 256))) << "u=" << u << " v=" << v;
    ASSERT_EQ(tri.sample(request(u, v, 0.5)), rounded(g.sample(u, v, 0.5)));
    // At and beyond the last level: the 1x1 level, whatever u, v.
    for (double lambda : {double(q), q + 1.0 / 256, q + 0.5, 100.0})
      ASSERT_EQ(tri.sample(request(u, v, lambda)), pyr.levels[q].at(0, 0)) << "lambda=" << lambda;
    // Just below the last level: blend of level q-1 and q with weight 255/256.
    ASSERT_EQ(tri.sample(request(u, v, q - 1.0 / 256)), rounded(g.sample(u, v, q - 1.0 / 256)));
  }
}

TEST(Sampler, NearestLevelSelection) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 64));
  Sampler s(pyr, {{TexelFilter::Nearest, MipMode::Nearest}});
  std::mt19937 rng(11);
  // GL: level ceil(lambda + 1/2) - 1: 0.5 -> 0, 0.5 + 1/256 -> 1, 1.5 -> 1, 1.5 + 1/256 -> 2.
  const std::pair<double, int> cases[] = {{-3, 0}, {0, 0},         {0.5, 0}, {0.5 + 1.0 / 256, 1}, {1.0, 1},
                                          {1.5, 1}, {1.5 + 1.0 / 256, 2}, {5.5, 5}, {5.5 + 1.0 / 256, 6}, {9.0, 6}};
  for (auto [lambda, level] : cases)
    for (int n = 0; n < 200; ++n) {
      const double u = (rng() % 100000) / 100000.0, v = (rng() % 100000) / 100000.0;
      const Request r = request(u, v, lambda);
      const Image& lvl = pyr.levels[level];
      const int x = int(std::floor(std::ldexp(double(r.u), -24) * lvl.width));
      const int y = int(std::floor(std::ldexp(double(r.v), -24) * lvl.height));
      ASSERT_EQ(s.sample(r), lvl.at(x, y)) << "lambda=" << lambda << " level " << level;
    }
}

// Clamp to border (GL 4.6 §8.14.2, Vulkan "Texel Replacement"): a tap outside the level takes the
// border colour before filtering, so the edge blends into it; the reference substitutes it in its
// own texel lookup. Colours k * 257 in unorm16 are exactly k in 8 bits. Every level, both texel
// filters, one axis or both, each of Vulkan's named colours and a custom one.
TEST(Sampler, BorderColourIsATapBeforeFiltering) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 16, 8));
  std::mt19937 rng(12);
  struct Colour {
    BorderColor kind;
    Texel custom;
    ref::Rgba want;  // in 8-bit steps
  };
  const Colour colours[] = {
      {BorderColor::FloatTransparentBlack, {}, {0, 0, 0, 0}},
      {BorderColor::IntOpaqueBlack, {}, {0, 0, 0, 255}},
      {BorderColor::FloatOpaqueWhite, {}, {255, 255, 255, 255}},
      {BorderColor::Custom, {64 * 257, 128 * 257, 255 * 257, 191 * 257}, {64, 128, 255, 191}},
  };
  int outside = 0;
  for (const Colour& colour : colours)
    for (TexelFilter tf : {TexelFilter::Nearest, TexelFilter::Linear})
      for (Wrap wv : {Wrap::Border, Wrap::Repeat}) {
        SamplerConfig cfg{{tf, MipMode::Nearest}, Wrap::Border, wv};
        cfg.border = colour.kind;
        cfg.border_custom = colour.custom;
        Sampler s(pyr, cfg);
        ref::GlSampler g = reference(pyr, cfg.filter, Wrap::Border, wv);
        g.border = colour.want;
        for (int k = 0; k <= pyr.last_level(); ++k) {
          const Extent sh = level_extent({16, 8}, k);
          for (int n = 0; n < 2000; ++n) {
            const int64_t i = int64_t(rng() % (3 * sh.width() + 4)) - sh.width() - 2;
            const int64_t j = int64_t(rng() % (3 * sh.height() + 4)) - sh.height() - 2;
            const double u = on_grid(i, int(rng() & 255), sh.w), v = on_grid(j, int(rng() & 255), sh.h);
            outside += i < 0 || i >= sh.width();
            ASSERT_EQ(s.sample(request(u, v, k)), rounded(g.sample(u, v, k)))
                << border_color_name(colour.kind) << " " << texel_filter_name(tf) << " v " << wrap_name(wv)
                << " level " << k << " u=" << u << " v=" << v;
          }
        }
      }
  EXPECT_GT(outside, 20000);
}

// The border colour of an sRGB texture is linear: the filter takes it as it is, never decoded
// (GL 4.6 §8.24: only texels fetched from the texture are decoded).
TEST(Sampler, SrgbBorderColourIsLinear) {
  const Pyramid pyr = build_srgb_pyramid(make_pattern("noise", 8, 8), PyramidMode::Exact);
  SamplerConfig cfg{{TexelFilter::Nearest, MipMode::None}, Wrap::Border, Wrap::Border};
  cfg.border = BorderColor::Custom;
  cfg.border_custom = {1000, 30000, 65535, 12345};
  Sampler s(pyr, cfg);
  EXPECT_EQ(s.sample(request(-0.5, 0.5, 0)), (Texel{1000, 30000, 65535, 12345}));
  EXPECT_EQ(s.sample(request(0.5, 1.5, 0)), (Texel{1000, 30000, 65535, 12345}));
  EXPECT_EQ(s.sample(request(0.5, 0.5, 0)), pyr.levels[0].at(4, 4));
}

// The magnification filter applies where lambda' <= 0 and only there (Vulkan, GL 4.5+, GLES 3.2:
// c = 0), the minification filter above; bias and clamp decide lambda' first.
TEST(Sampler, MagnificationFilterAppliesAtLambdaZeroAndBelow) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 32, 16));
  std::mt19937 rng(13);
  int magnified = 0, minified = 0;
  for (TexelFilter mag : {TexelFilter::Nearest, TexelFilter::Linear})
    for (const char* min : {"linear", "nearest", "linear_mipmap_linear", "nearest_mipmap_nearest"}) {
      SamplerConfig cfg;
      ASSERT_TRUE(parse_filter(min, cfg.filter));
      cfg.filter.mag = mag;
      cfg.lod_bias = int32_t(rng() % 512) - 256;
      Sampler s(pyr, cfg);
      ref::GlSampler g = reference(pyr, cfg.filter, Wrap::Repeat, Wrap::Repeat);
      g.mag = mag;
      g.lod_bias = cfg.lod_bias / 256.0;
      for (int n = 0; n < 4000; ++n) {
        // Levels 0..3 at most (lambda' < 3): u on the 1/1024 grid and v on the 1/512 grid are on
        // the 1/256-texel grid of each, so the double filter is exact.
        const double u = (int(rng() % 4096) - 2048) / 1024.0, v = (int(rng() % 2048) - 1024) / 512.0;
        const double lambda = (int(rng() % 1024) - 512) / 256.0;
        const double l = lambda + g.lod_bias;
        (l <= 0 ? magnified : minified) += 1;
        ref::Choice c, nudged;  // (nearest level: a level boundary at the input is either side)
        const ref::Rgba want = g.sample(u, v, lambda, &c);
        g.sample(u + 1e-9, v + 1e-9, lambda + 1e-9, &nudged);
        if (!(c == nudged)) continue;
        ASSERT_EQ(s.sample(request(u, v, lambda)), rounded(want))
            << "mag " << texel_filter_name(mag) << " min " << min << " lambda'=" << l << " u=" << u << " v=" << v;
      }
    }
  EXPECT_GT(magnified, 10000);
  EXPECT_GT(minified, 10000);
}

// A request's own LOD bias (GLSL texture(s, uv, bias)) adds to the sampler's before the clamp: a
// request with bias b samples as the same request through a sampler whose bias is b larger, on
// both paths, for explicit lambda and for derivatives (anisotropic too); a bias that moves lambda
// past the clamp is clamped like the sampler's.
TEST(Sampler, RequestBiasAddsToTheSamplersBias) {
  Image img(64, 32, 8);
  std::mt19937_64 rng(7);
  for (Texel& t : img.texels)
    for (uint16_t& c : t) c = uint16_t(rng() & 255);
  const Pyramid p = build_pyramid(img, PyramidMode::Exact);
  for (bool aniso : {false, true}) {
    SamplerConfig base;
    base.lod_bias = 70;
    base.min_lod = -100;
    base.max_lod = 900;
    if (aniso) base.filter = Filter(TexelFilter::Linear, MipMode::Linear, true);
    Sampler s(p, base);
    int differ = 0;
    for (int i = 0; i < 2000; ++i) {
      Request r = request(double(rng() % 4096) / 2048.0 - 1.0, double(rng() % 4096) / 2048.0 - 1.0,
                          double(int(rng() % 3000) - 1000) / 256.0);
      if (i % 2) {
        r.has_derivatives = true;
        r.deriv = {int32_t(rng() % 800000), int32_t(rng() % 300000) - 150000, int32_t(rng() % 200000),
                   int32_t(rng() % 900000) - 100000};
      }
      r.bias = int32_t(rng() % 1200) - 600;
      SamplerConfig shifted = base;
      shifted.lod_bias += r.bias;
      Sampler t(p, shifted);
      Request plain = r;
      plain.bias = 0;
      const Texel got = s.sample(r), want = t.sample(plain);
      ASSERT_EQ(got, want) << "request " << i << " bias " << r.bias;
      uint32_t fast = 0, fast_want = 0;
      s.sample_rgba8(&r, 1, &fast);
      t.sample_rgba8(&plain, 1, &fast_want);
      ASSERT_EQ(fast, fast_want) << "fast path, request " << i;
      differ += got != Sampler(p, base).sample(plain);
    }
    EXPECT_GT(differ, 500) << "the bias changed too few samples to tell";
  }
}

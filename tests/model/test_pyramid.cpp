// Pyramid (docs/numerics.md "Pyramid"): exact mode against a brute-force footprint mean, cascade
// mode against its parent (the maketx comparison is in tests/sim/test_pyramid_maketx.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>
#include <tuple>

#include "model/error.h"
#include "model/image.h"
#include "model/pyramid.h"

using namespace tex;

namespace {

const std::pair<int, int> kSizes[] = {{1, 1}, {1, 16}, {16, 1}, {2, 1}, {1, 2}, {8, 8},
                                       {64, 64}, {128, 32}, {32, 128}, {4, 256}, {256, 2}};

// Round half up of sum / count, count a power of two, in integers.
int rounded_mean(uint64_t sum, uint64_t count) { return int((2 * sum + count) / (2 * count)); }

// Random 8-bit texels in all four channels, including alpha.
Image random_image(int w, int h, uint32_t seed) {
  Image img(w, h);
  uint32_t s = seed * 2654435761u + 1;
  for (auto& t : img.texels)
    for (auto& c : t) {
      s = s * 1664525u + 1013904223u;
      c = uint16_t(s >> 24);
    }
  return img;
}

void expect_exact_pyramid(const Image& l0, const std::string& what) {
  const Pyramid p = build_pyramid(l0, PyramidMode::Exact);
  int lw0 = 0, lh0 = 0;
  while ((1 << lw0) < l0.width) ++lw0;
  while ((1 << lh0) < l0.height) ++lh0;
  ASSERT_EQ(int(p.levels.size()), std::max(lw0, lh0) + 1) << what;
  for (size_t k = 0; k < p.levels.size(); ++k) {
    const int w = std::max(1, l0.width >> k), h = std::max(1, l0.height >> k);
    const Image& lvl = p.levels[k];
    ASSERT_EQ(lvl.width, w) << what << " level " << k;
    ASSERT_EQ(lvl.height, h) << what << " level " << k;
    const int fw = l0.width / w, fh = l0.height / h;  // footprint in level-0 texels
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) {
          uint64_t sum = 0;
          for (int yy = y * fh; yy < (y + 1) * fh; ++yy)
            for (int xx = x * fw; xx < (x + 1) * fw; ++xx) sum += l0.at(xx, yy)[c];
          ASSERT_EQ(lvl.at(x, y)[c], rounded_mean(sum, uint64_t(fw) * fh))
              << what << " level " << k << " texel " << x << "," << y << " channel " << c;
        }
  }
}

}  // namespace

TEST(Pyramid, ExactModeIsRoundedMeanOfLevel0Footprint) {
  for (auto [w, h] : kSizes) {
    expect_exact_pyramid(random_image(w, h, uint32_t(w * 4099 + h)), "random " + std::to_string(w) + "x" + std::to_string(h));
    expect_exact_pyramid(make_pattern("testcard", w, h), "testcard " + std::to_string(w) + "x" + std::to_string(h));
  }
  // Half-way sums round up: a 2x1 texture of 0 and 1 gives 1 (0.5 -> 1), of 0 and 0 gives 0.
  Image half(2, 1);
  half.at(0, 0) = {0, 1, 254, 255};
  half.at(1, 0) = {1, 1, 255, 255};
  const Pyramid p = build_pyramid(half, PyramidMode::Exact);
  EXPECT_EQ(p.levels[1].at(0, 0), (Texel{1, 1, 255, 255}));
}

TEST(Pyramid, CascadeModeIsRoundedMeanOfParent) {
  for (auto [w, h] : kSizes) {
    const Image l0 = random_image(w, h, uint32_t(w * 31 + h));
    const Pyramid p = build_pyramid(l0, PyramidMode::Cascade);
    ASSERT_EQ(p.levels[0].texels, l0.texels);
    for (size_t k = 1; k < p.levels.size(); ++k) {
      const Image& parent = p.levels[k - 1];
      const Image& lvl = p.levels[k];
      ASSERT_EQ(lvl.width, std::max(1, parent.width / 2));
      ASSERT_EQ(lvl.height, std::max(1, parent.height / 2));
      const int fw = parent.width / lvl.width, fh = parent.height / lvl.height;
      for (int y = 0; y < lvl.height; ++y)
        for (int x = 0; x < lvl.width; ++x)
          for (int c = 0; c < 4; ++c) {
            uint64_t sum = 0;
            for (int dy = 0; dy < fh; ++dy)
              for (int dx = 0; dx < fw; ++dx) sum += parent.at(x * fw + dx, y * fh + dy)[c];
            ASSERT_EQ(lvl.at(x, y)[c], rounded_mean(sum, uint64_t(fw) * fh)) << w << "x" << h << " level " << k;
          }
    }
  }
  // Cascade differs from exact: 4x1 of {0,1,0,1} -> exact 1x1 = round(0.5) = 1; cascade: (1,1) -> 1.
  // {0,1,1,1}: exact round(0.75) = 1; cascade (1, 1) -> 1. {0,0,0,1}: exact round(.25)=0; cascade (0,1)->1.
  Image img(4, 1);
  const uint16_t vals[4] = {0, 0, 0, 1};
  for (int x = 0; x < 4; ++x) img.at(x, 0) = {vals[x], vals[x], vals[x], vals[x]};
  EXPECT_EQ(build_pyramid(img, PyramidMode::Exact).levels[2].at(0, 0)[0], 0);
  EXPECT_EQ(build_pyramid(img, PyramidMode::Cascade).levels[2].at(0, 0)[0], 1);
}

namespace {
// Level k of a side-0 of n texels: max(1, n >> k) (GL).
int side(int n, int k) { return std::max(1, n >> k); }

// The area mean, brute force from the source texels' side: each source texel spreads over the
// output texels its area overlaps (source texel j spans [j * out, (j + 1) * out), output texel i
// spans [i * src, (i + 1) * src) in units of 1 / (src * out) of the side), then the exact rounding
// half up of S / (src_w * src_h) in integers.
Image brute_area_mean(const Image& src, int w, int h) {
  std::vector<std::array<uint64_t, 4>> sum(size_t(w) * h);
  auto overlap = [](int64_t a0, int64_t a1, int64_t b0, int64_t b1) { return std::max<int64_t>(0, std::min(a1, b1) - std::max(a0, b0)); };
  for (int yy = 0; yy < src.height; ++yy)
    for (int xx = 0; xx < src.width; ++xx)
      for (int y = 0; y < h; ++y) {
        const int64_t oy = overlap(int64_t(yy) * h, int64_t(yy + 1) * h, int64_t(y) * src.height, int64_t(y + 1) * src.height);
        if (!oy) continue;
        for (int x = 0; x < w; ++x) {
          const int64_t ox = overlap(int64_t(xx) * w, int64_t(xx + 1) * w, int64_t(x) * src.width, int64_t(x + 1) * src.width);
          for (int c = 0; c < 4; ++c) sum[size_t(y) * w + x][size_t(c)] += uint64_t(ox * oy) * src.at(xx, yy)[size_t(c)];
        }
      }
  Image out(w, h, src.channel_bits);
  const uint64_t d = uint64_t(src.width) * uint64_t(src.height);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) out.at(x, y)[size_t(c)] = uint16_t((2 * sum[size_t(y) * w + x][size_t(c)] + d) / (2 * d));
  return out;
}
}  // namespace

// Sides that are not powers of two (docs/numerics.md "Pyramid"): GL's level sizes max(1, n >> k)
// and level count floor(log2 max) + 1; exact mode the area mean of level 0, cascade the area mean of
// the parent, both against the brute-force mean.
TEST(Pyramid, NonPowerOfTwoLevelsAreAreaMeans) {
  const std::pair<int, int> sizes[] = {{3, 1}, {1, 5}, {3, 3}, {5, 3}, {7, 2}, {6, 10}, {13, 7}, {31, 17}, {100, 60}, {1, 127}};
  for (auto [w0, h0] : sizes)
    for (PyramidMode mode : {PyramidMode::Exact, PyramidMode::Cascade}) {
      const Image l0 = random_image(w0, h0, uint32_t(w0 * 977 + h0));
      const Pyramid p = build_pyramid(l0, mode);
      int levels = 1;
      while ((std::max(w0, h0) >> levels) > 0) ++levels;
      ASSERT_EQ(int(p.levels.size()), levels) << w0 << "x" << h0;
      for (size_t k = 1; k < p.levels.size(); ++k) {
        const Image& lvl = p.levels[k];
        ASSERT_EQ(lvl.width, side(w0, int(k)));
        ASSERT_EQ(lvl.height, side(h0, int(k)));
        const Image expected = brute_area_mean(mode == PyramidMode::Exact ? l0 : p.levels[k - 1], lvl.width, lvl.height);
        ASSERT_EQ(lvl.texels, expected.texels) << w0 << "x" << h0 << " level " << k << (mode == PyramidMode::Exact ? " exact" : " cascade");
      }
    }
}

// The area mean is the box of the power-of-two pyramid: area_reduce of level 0 gives every level
// build_pyramid carries from 2x2 sums; and an odd side's weights are the 3-tap polyphase box.
TEST(Pyramid, AreaMeanIsTheBoxOfPowersOfTwoAndThePolyphaseBoxOfOddSides) {
  for (auto [w, h] : kSizes) {
    const Image l0 = random_image(w, h, uint32_t(w * 7 + h));
    const Pyramid p = build_pyramid(l0, PyramidMode::Exact);
    for (size_t k = 1; k < p.levels.size(); ++k)
      ASSERT_EQ(area_reduce(l0, p.levels[k].width, p.levels[k].height).texels, p.levels[k].texels) << w << "x" << h << " " << k;
  }
  for (int m = 1; m < 40; ++m) {
    const AxisWeights a = axis_weights(2 * m + 1, m);
    for (int i = 0; i < m; ++i) {
      ASSERT_EQ(a.first[size_t(i)], 2 * i);
      ASSERT_EQ(a.weight[size_t(i)], (std::vector<uint32_t>{uint32_t(m - i), uint32_t(m), uint32_t(i + 1)})) << m << " " << i;
    }
  }
}


// view_pyramid: levels b..min(m, last) as a pyramid of their own (blocks and sRGB codes too); a
// base level beyond the last and a max level below the base are errors naming the values.
TEST(Pyramid, ViewIsTheChainFromItsBaseLevel) {
  const Pyramid p = build_pyramid(random_image(100, 60, 5), PyramidMode::Exact);  // 7 levels
  const Pyramid v = view_pyramid(p, 2, 4);
  ASSERT_EQ(v.levels.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(v.levels[size_t(k)].texels, p.levels[size_t(2 + k)].texels);
  EXPECT_EQ(v.extent0(), (Extent{25, 15}));
  EXPECT_EQ(v.extent0().w, side(100, 2));
  EXPECT_EQ(view_pyramid(p, 6, 99).levels.size(), 1u);  // the 1x1 level, a max beyond the last
  EXPECT_EQ(view_pyramid(p, 0, 99).levels.size(), p.levels.size());
  for (auto [b, m, text] : {std::tuple{7, 9, "base level 7: this texture has levels 0 to 6"},
                            std::tuple{3, 2, "max level 2 is below the base level 3"},
                            std::tuple{-1, 2, "base level -1"}}) {
    try {
      view_pyramid(p, b, m);
      ADD_FAILURE() << "no error for base " << b << " max " << m;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  }
}

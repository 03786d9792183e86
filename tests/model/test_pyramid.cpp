// Pyramid (docs/numerics.md "Pyramid"): exact mode against a brute-force footprint mean, cascade
// mode against its parent (the maketx comparison is in tests/sim/test_pyramid_maketx.cpp).
#include <gtest/gtest.h>

#include <string>

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

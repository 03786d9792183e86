// Pyramid (docs/numerics.md "Pyramid"): exact mode against a brute-force footprint mean,
// cascade mode against its parent, and exact mode against OpenImageIO's `maketx --filter box`.
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "model/image.h"
#include "model/pyramid.h"

using namespace tex;
namespace fs = std::filesystem;

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

// ---------------------------------------------------------------- against maketx

namespace {

void write_tiff(const Image& img, const std::string& path) {
  std::vector<uint8_t> px(img.texels.size() * 4);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) px[i * 4 + c] = uint8_t(img.texels[i][c]);
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << "no TIFF writer";
  OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
  // Alpha is data here: TIFF marks it associated, so neither maketx nor OIIO premultiply.
  ASSERT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close())
      << out->geterror();
}

void compare_with_maketx(const Image& l0, const std::string& name, const fs::path& dir) {
  const std::string in = (dir / (name + ".tif")).string(), tx = (dir / (name + ".tx")).string(),
                    log = (dir / (name + ".log")).string();
  write_tiff(l0, in);
  // Box filter, 8-bit output, no resize, no constant/opaque/monochrome detection (off by default).
  const std::string cmd = "maketx --filter box -d uint8 --threads 1 " + in + " -o " + tx + " > " + log + " 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_EQ(rc, 0) << "maketx failed or is missing (Debian package openimageio-tools; scripts/install-deps.sh): `"
                   << cmd << "`";
  auto input = OIIO::ImageInput::open(tx);
  ASSERT_TRUE(input) << "cannot open " << tx << ": " << OIIO::geterror();
  const Pyramid p = build_pyramid(l0, PyramidMode::Exact);
  int max_diff = 0, level_count = 0;
  for (int k = 0; input->seek_subimage(0, k); ++k) {
    ++level_count;
    ASSERT_LT(k, int(p.levels.size())) << name << ": maketx has more levels than the model";
    const OIIO::ImageSpec& s = input->spec();
    const Image& ours = p.levels[k];
    ASSERT_EQ(s.width, ours.width) << name << " level " << k;
    ASSERT_EQ(s.height, ours.height) << name << " level " << k;
    ASSERT_EQ(s.nchannels, 4) << name << " level " << k;
    std::vector<uint8_t> px(size_t(s.width) * s.height * 4);
    ASSERT_TRUE(input->read_image(0, k, 0, 4, OIIO::TypeDesc::UINT8, px.data())) << input->geterror();
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x)
        for (int c = 0; c < 4; ++c) {
          const int theirs = px[(size_t(y) * s.width + x) * 4 + c];
          const int diff = std::abs(int(ours.at(x, y)[c]) - theirs);
          max_diff = std::max(max_diff, diff);
          ASSERT_LE(diff, 1) << name << " level " << k << " texel " << x << "," << y << " channel " << c
                             << ": model " << ours.at(x, y)[c] << ", maketx " << theirs;
        }
  }
  EXPECT_EQ(level_count, int(p.levels.size())) << name;
  std::printf("maketx --filter box vs exact pyramid, %s: %d levels, max |diff| = %d\n", name.c_str(), level_count,
              max_diff);
}

}  // namespace

TEST(Pyramid, ExactModeMatchesMaketxBoxWithinOne) {
  const fs::path dir = fs::temp_directory_path() / ("texunit_maketx_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (auto [w, h] : {std::pair{64, 64}, std::pair{128, 32}, std::pair{1, 16}, std::pair{16, 1}, std::pair{1, 1}})
    for (const char* pattern : {"noise", "testcard"}) {
      const std::string name = std::string(pattern) + "_" + std::to_string(w) + "x" + std::to_string(h);
      compare_with_maketx(make_pattern(pattern, w, h), name, dir);
      if (HasFatalFailure()) break;
    }
  fs::remove_all(dir);
}

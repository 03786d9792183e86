// The exact pyramid against OpenImageIO's `maketx --filter box` (an independent implementation).
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
          ASSERT_EQ(diff, 0) << name << " level " << k << " texel " << x << "," << y << " channel " << c
                             << ": model " << ours.at(x, y)[c] << ", maketx " << theirs;
        }
  }
  EXPECT_EQ(level_count, int(p.levels.size())) << name;
  std::printf("maketx --filter box vs exact pyramid, %s: %d levels, max |diff| = %d\n", name.c_str(), level_count,
              max_diff);
}

}  // namespace

TEST(Pyramid, ExactModeEqualsMaketxBox) {
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

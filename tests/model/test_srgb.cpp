// sRGB (model/srgb.h): the decode table against the values the sRGB definition gives (spot values
// worked out by hand), the encoder as its inverse on every code, and the pyramid of an sRGB
// texture averaged in linear space (a black and white checker's mean is code 188, not 128).
// Mesa checks the same table and pyramid in tests/sim/test_block_formats_reference.cpp.
#include <gtest/gtest.h>

#include "model/error.h"
#include "model/srgb.h"

using namespace tex;

TEST(Srgb, DecodeTableSpotValues) {
  const auto& t = srgb_decode_table();
  EXPECT_EQ(t[0], 0);
  EXPECT_EQ(t[255], 65535);
  EXPECT_EQ(t[10], 199);     // 10/255 = 0.0392 is on the linear segment: / 12.92 = 0.003035
  EXPECT_EQ(t[128], 14146);  // ((128/255 + 0.055) / 1.055)^2.4 = 0.215861
  EXPECT_EQ(t[188], 32957);  // 0.502886: code 188 is the encoding of one half
  for (int c = 1; c < 256; ++c) EXPECT_GT(t[size_t(c)], t[size_t(c - 1)]) << c;  // 16 bits keep every code apart
}

TEST(Srgb, EncodeInvertsDecodeOnEveryCode) {
  for (int c = 0; c < 256; ++c) EXPECT_EQ(encode_srgb8(srgb_to_linear(c / 255.0)), c) << c;
  EXPECT_EQ(encode_srgb8(0.5), 188);
  EXPECT_EQ(encode_srgb8(0.0), 0);
  EXPECT_EQ(encode_srgb8(1.0), 255);
}

TEST(Srgb, PyramidAveragesInLinearSpace) {
  Image img(4, 4, 8);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const uint16_t v = (x + y) % 2 ? 255 : 0;
      img.at(x, y) = {v, v, uint16_t(x * 60), uint16_t(x < 2 ? 255 : 0)};
    }
  for (PyramidMode mode : {PyramidMode::Exact, PyramidMode::Cascade}) {
    const std::vector<Image> levels = srgb_box_levels(img, mode);
    ASSERT_EQ(levels.size(), 3u);
    EXPECT_EQ(levels[0].texels, img.texels);  // level 0 as given
    // Black and white in equal parts: linear 0.5, code 188 (averaging the codes would give 128).
    EXPECT_EQ(levels[1].at(0, 0)[0], 188);
    EXPECT_EQ(levels[2].at(0, 0)[1], 188);
    // Blue 0 and 60 (linear 0 and 0.0452): mean 0.0226, code 41 (not 30).
    EXPECT_EQ(levels[1].at(0, 0)[2], encode_srgb8((srgb_to_linear(0.0) + srgb_to_linear(60 / 255.0)) / 2));
    EXPECT_EQ(levels[1].at(0, 0)[2], 41);
    // Alpha is linear: the mean of the codes, rounded half up.
    EXPECT_EQ(levels[1].at(0, 0)[3], 255);
    EXPECT_EQ(levels[2].at(0, 0)[3], 128);
  }
  const Image linear = decode_srgb_level(img);
  EXPECT_EQ(linear.channel_bits, 16);
  EXPECT_EQ(linear.at(1, 0)[0], 65535);
  EXPECT_EQ(linear.at(0, 0)[3], 65535);  // 255 * 257
  EXPECT_EQ(linear.at(1, 0)[2], srgb_decode_table()[60]);
  EXPECT_THROW(srgb_box_levels(Image(2, 2, 16), PyramidMode::Exact), Error);
}

// The block decoders' rules (model/block_formats.h, docs/numerics.md): palettes worked out by hand
// from the format definitions, every interpolated value within half an LSB of the exact one, BC7
// blocks built from the specification's fields, and the BPTC tables' own invariants. Independent
// decoders check the same decoders in tests/sim/test_block_formats_reference.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "model/astc.h"
#include "model/block_formats.h"

using namespace tex;

namespace {

// A BC1/BC2/BC3 colour block: endpoints as 5:6:5 and 16 two-bit indices.
void colour_block(uint8_t* b, uint16_t c0, uint16_t c1, const int (&idx)[16]) {
  b[0] = uint8_t(c0);
  b[1] = uint8_t(c0 >> 8);
  b[2] = uint8_t(c1);
  b[3] = uint8_t(c1 >> 8);
  uint32_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= uint32_t(idx[i]) << (2 * i);
  for (int k = 0; k < 4; ++k) b[4 + k] = uint8_t(bits >> (8 * k));
}

// A BC3-alpha/BC4 channel block: two endpoints and 16 three-bit indices.
void channel_block(uint8_t* b, int a0, int a1, const int (&idx)[16]) {
  b[0] = uint8_t(a0);
  b[1] = uint8_t(a1);
  uint64_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= uint64_t(idx[i]) << (3 * i);
  for (int k = 0; k < 6; ++k) b[2 + k] = uint8_t(bits >> (8 * k));
}

constexpr int kRamp4[16] = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};
constexpr int kRamp8[16] = {0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7};

// Writes fields into a 128-bit block from bit 0 up (the BPTC field order is the test's job).
struct BitWriter {
  uint8_t* block;
  int pos = 0;
  void put(uint32_t v, int n) {
    for (int k = 0; k < n; ++k, ++pos) block[pos / 8] = uint8_t(block[pos / 8] | ((v >> k & 1) << (pos % 8)));
  }
};

}  // namespace

TEST(BlockFormats, Bc1FourAndThreeColourPalettes) {
  uint8_t b[8];
  // Red (0xF800) and blue (0x001F): c0 > c1, four colours; thirds rounded to nearest.
  colour_block(b, 0xF800, 0x001F, kRamp4);
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 0), (Rgba8{255, 0, 0, 255}));
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 1), (Rgba8{0, 0, 255, 255}));
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 2), (Rgba8{170, 0, 85, 255}));  // 510/3, 255/3
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 3), (Rgba8{85, 0, 170, 255}));
  // A grey 0x0841 (r 1 -> 8, g 2 -> 8, b 1 -> 8) above green 0x07E0 (6-bit 63 -> 255): four colours,
  // g = (2*8 + 255 + 1) / 3 = 90 (90.33), (8 + 2*255 + 1) / 3 = 173 (172.67); r = 17/3 -> 5, 9/3 -> 3.
  colour_block(b, 0x0841, 0x07E0, kRamp4);
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 0), (Rgba8{8, 8, 8, 255}));
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 2), (Rgba8{5, 90, 5, 255}));
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 3), (Rgba8{3, 173, 3, 255}));
  // c0 <= c1: three colours, the half rounded up, index 3 transparent black.
  colour_block(b, 0x07E0, 0x0841, kRamp4);
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 2), (Rgba8{4, 132, 4, 255}));  // (255 + 8 + 1) / 2
  EXPECT_EQ(decode_texel(TexelFormat::Bc1, b, 3), (Rgba8{0, 0, 0, 0}));
  // BC2 and BC3 colour blocks always take four colours: (255 + 2*8 + 1) / 3 = 90.
  uint8_t b16[16] = {};
  colour_block(b16 + 8, 0x07E0, 0x0841, kRamp4);
  EXPECT_EQ(decode_texel(TexelFormat::Bc2, b16, 3), (Rgba8{5, 90, 5, 0}));
  EXPECT_EQ(decode_texel(TexelFormat::Bc3, b16, 3)[1], 90);
}

TEST(BlockFormats, Bc2AlphaIsFourBitsReplicated) {
  uint8_t b[16] = {};
  for (int i = 0; i < 16; ++i) b[i / 2] = uint8_t(b[i / 2] | (i << (4 * (i % 2))));  // alpha of texel i = i
  for (int i = 0; i < 16; ++i) EXPECT_EQ(decode_texel(TexelFormat::Bc2, b, i)[3], i * 17) << i;
}

TEST(BlockFormats, ChannelPalettesRoundToNearest) {
  uint8_t b[16] = {};
  // a0 > a1: six interpolated sevenths. a0 = 200, a1 = 10: (6*200+10)/7 = 172.86 -> 173, ...
  channel_block(b, 200, 10, kRamp8);
  const int want8[8] = {200, 10, 173, 146, 119, 91, 64, 37};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(decode_texel(TexelFormat::Bc4, b, i), (Rgba8{uint8_t(want8[i]), 0, 0, 255})) << i;
  // a0 <= a1: four fifths, then 0 and 255. a0 = 10, a1 = 200: (4*10+200)/5 = 48, 86, 124, 162.
  channel_block(b, 10, 200, kRamp8);
  const int want6[8] = {10, 200, 48, 86, 124, 162, 0, 255};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(decode_texel(TexelFormat::Bc4, b, i)[0], want6[i]) << i;
  // BC5: the second block is green; BC3: the first block is alpha.
  channel_block(b + 8, 200, 10, kRamp8);
  EXPECT_EQ(decode_texel(TexelFormat::Bc5, b, 2), (Rgba8{48, 173, 0, 255}));
  // Every entry of every palette is within half an LSB of the exact interpolation.
  for (int a0 = 0; a0 < 256; a0 += 3)
    for (int a1 = 0; a1 < 256; a1 += 5) {
      channel_block(b, a0, a1, kRamp8);
      for (int i = 2; i < 8; ++i) {
        const double exact = a0 > a1 ? ((8 - i) * a0 + (i - 1) * a1) / 7.0
                             : i < 6 ? ((6 - i) * a0 + (i - 1) * a1) / 5.0
                                     : (i == 6 ? 0.0 : 255.0);
        ASSERT_LE(std::fabs(decode_texel(TexelFormat::Bc4, b, i)[0] - exact), 0.5) << a0 << " " << a1 << " " << i;
      }
    }
}

TEST(BlockFormats, BptcTablesKeepAnchorsInTheirSubsets) {
  for (int p = 0; p < 64; ++p) {
    std::set<int> seen2, seen3;
    for (int i = 0; i < 16; ++i) {
      seen2.insert(bc7_subset(2, p, i));
      seen3.insert(bc7_subset(3, p, i));
    }
    EXPECT_EQ(seen2.size(), 2u) << p;  // every partition uses all its subsets
    EXPECT_EQ(seen3.size(), 3u) << p;
    EXPECT_EQ(bc7_subset(2, p, 0), 0);  // texel 0 is subset 0's anchor
    EXPECT_EQ(bc7_subset(3, p, 0), 0);
    EXPECT_EQ(bc7_subset(2, p, bc7_anchor(2, p, 1)), 1) << p;
    EXPECT_EQ(bc7_subset(3, p, bc7_anchor(3, p, 1)), 1) << p;
    EXPECT_EQ(bc7_subset(3, p, bc7_anchor(3, p, 2)), 2) << p;
  }
}

// Mode 6 (one subset, RGBA 7.7.7.7 + a P-bit per endpoint, 4-bit indices) from its fields.
TEST(BlockFormats, Bc7Mode6FromFields) {
  uint8_t b[16] = {};
  BitWriter w{b};
  w.put(1 << 6, 7);  // mode 6: six zeros, then a one
  const uint32_t e0[4] = {10, 100, 127, 0}, e1[4] = {120, 5, 64, 127};
  for (int ch = 0; ch < 4; ++ch) {
    w.put(e0[ch], 7);
    w.put(e1[ch], 7);
  }
  w.put(1, 1);  // P-bit of endpoint 0
  w.put(0, 1);  // P-bit of endpoint 1
  for (int i = 0; i < 16; ++i) w.put(uint32_t(i), i == 0 ? 3 : 4);  // texel 0 is the anchor: 3 bits
  ASSERT_EQ(w.pos, 128);
  EXPECT_EQ(bc7_mode_of(b).mode, 6);
  // Endpoint channel = (7 bits << 1 | P) as 8 bits; weights 0, 4, 9, ... 64 in 64ths.
  const int weights[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
  for (int i = 0; i < 16; ++i) {
    const Rgba8 t = decode_texel(TexelFormat::Bc7, b, i);
    for (int ch = 0; ch < 4; ++ch) {
      const int a = int(e0[ch] << 1 | 1), c = int(e1[ch] << 1);
      EXPECT_EQ(t[size_t(ch)], ((64 - weights[i]) * a + weights[i] * c + 32) >> 6) << i << " " << ch;
    }
  }
  b[0] = 0;  // the reserved mode: zeros
  EXPECT_EQ(decode_texel(TexelFormat::Bc7, b, 5), (Rgba8{0, 0, 0, 0}));
}

// Mode 4 (rotation, index selection, 5-bit colour and 6-bit alpha without P-bits): the rotation
// swaps alpha with a colour channel; the selection bit swaps which indices colour and alpha take.
TEST(BlockFormats, Bc7Mode4RotationAndIndexSelection) {
  for (int rotation = 0; rotation < 4; ++rotation)
    for (int select = 0; select < 2; ++select) {
      uint8_t b[16] = {};
      BitWriter w{b};
      w.put(1 << 4, 5);
      w.put(uint32_t(rotation), 2);
      w.put(uint32_t(select), 1);
      for (int ch = 0; ch < 3; ++ch) {
        w.put(0, 5);   // colour endpoints 0 .. 31 -> 0 .. 255
        w.put(31, 5);
      }
      w.put(63, 6);  // alpha endpoints 255 .. 0
      w.put(0, 6);
      for (int i = 0; i < 16; ++i) w.put(3, i == 0 ? 1 : 2);  // 2-bit indices: texel 0 = 1, others 3
      for (int i = 0; i < 16; ++i) w.put(0, i == 0 ? 2 : 3);  // 3-bit indices: all 0
      ASSERT_EQ(w.pos, 128);
      const Bc7Mode m = bc7_mode_of(b);
      EXPECT_EQ(m.mode, 4);
      EXPECT_EQ(m.rotation, rotation);
      EXPECT_EQ(m.index_select, select);
      // Texel 5: 2-bit index 3 (weight 64), 3-bit index 0 (weight 0).
      Rgba8 want = select == 0 ? Rgba8{255, 255, 255, 255} : Rgba8{0, 0, 0, 0};
      if (rotation) std::swap(want[3], want[size_t(rotation - 1)]);
      EXPECT_EQ(decode_texel(TexelFormat::Bc7, b, 5), want) << rotation << " " << select;
    }
}

// Random blocks: decode_block and decode_texel agree; every BC7 mode and every partition of the
// partitioned modes occurs.
TEST(BlockFormats, BlockAndTexelDecodersAgree) {
  std::mt19937_64 rng(5);
  std::set<int> partitions[8];
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc2, TexelFormat::Bc3, TexelFormat::Bc4, TexelFormat::Bc5,
                        TexelFormat::Bc7})
    for (int k = 0; k < 4000; ++k) {
      uint8_t b[16];
      for (uint8_t& x : b) x = uint8_t(rng());
      if (f == TexelFormat::Bc7) b[0] = uint8_t((b[0] << (k % 8 + 1)) | (1 << (k % 8)));
      Rgba8 all[16];
      decode_block(f, b, all);
      for (int i = 0; i < 16; ++i) ASSERT_EQ(all[i], decode_texel(f, b, i)) << format_info(f).name;
      if (f == TexelFormat::Bc7) {
        const Bc7Mode m = bc7_mode_of(b);
        ASSERT_EQ(m.mode, k % 8);
        partitions[m.mode].insert(m.partition);
      }
    }
  for (int mode : {1, 2, 3, 7}) EXPECT_EQ(partitions[mode].size(), 64u) << mode;
  EXPECT_EQ(partitions[0].size(), 16u);
}

TEST(BlockFormats, LevelsSmallerThanABlockUseItsTopLeft) {
  uint8_t b[8];
  colour_block(b, 0xF800, 0x001F, kRamp4);
  const Image img = decode_level(TexelFormat::Bc1, b, 2, 1);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.at(1, 0)[2], 255);  // texel 1: blue
  EXPECT_EQ(level_bytes(TexelFormat::Bc1, 2, 1), 8u);
  EXPECT_EQ(level_bytes(TexelFormat::Bc7, 16, 8), 128u);
  EXPECT_EQ(level_bytes(TexelFormat::Rgba8, 16, 8), 512u);
}

// ASTC by hand (model/astc.h; astcenc checks every mode in tests/sim/test_astc_reference.cpp).
TEST(BlockFormats, AstcVoidExtentAndErrorColour) {
  // A void-extent LDR block without an extent: bits 8..0 = 1 1111 1100, bits 10..11 set, the
  // coordinates all ones, then R, G, B, A as 16-bit values.
  uint8_t b[16] = {0xFC, 0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x34, 0x12, 0xFF, 0x80, 0x00, 0x00, 0xFF, 0xFF};
  for (TexelFormat f : {TexelFormat::Astc4x4, TexelFormat::Astc12x12})
    for (bool srgb : {false, true}) EXPECT_EQ(decode_texel(f, b, 5, srgb), (Rgba8{0x12, 0x80, 0x00, 0xFF}));
  EXPECT_TRUE(astc_mode_of(b, 4, 4).void_extent);
  b[1] = 0xFF;  // bit 9: an HDR void extent, the error colour in the LDR profile
  EXPECT_EQ(decode_texel(TexelFormat::Astc6x6, b, 0), (Rgba8{255, 0, 255, 255}));
  b[1] = 0xF9;  // bit 10 clear: reserved
  EXPECT_EQ(decode_texel(TexelFormat::Astc6x6, b, 0), (Rgba8{255, 0, 255, 255}));
  const uint8_t reserved[16] = {};  // block mode bits 3..0 all 0: reserved
  EXPECT_TRUE(astc_mode_of(reserved, 8, 8).error);
  EXPECT_EQ(decode_texel(TexelFormat::Astc8x8, reserved, 63), (Rgba8{255, 0, 255, 255}));
}

TEST(BlockFormats, AstcSrgbExpandsEndpointsBelowTheCode) {
  // One partition, CEM 0 (luminance direct), a 2x2 grid of 1-bit weights... built from the fields:
  // block mode 0x042: bits 1..0 = 10 (rho 1..2), bits 3..2 = 00: grid (bits 8..7 + 4) x (bits 6..5
  // + 2) = 4 x 4 with rho = bit 4 | bits 1..0 << 1 = 4 (0..3, 2 bits): 32 weight bits.
  // Endpoints: 8-bit values from bit 17 (range 0..255: 2 values x 8 bits fit the 79 bits left).
  uint8_t b[16] = {};
  b[0] = 0x42;                 // block mode 0x042, partitions 1 (bits 12..11 = 0)
  const int v0 = 10, v1 = 200;  // bits 17..24 and 25..32
  b[2] = uint8_t(v0 << 1);
  b[3] = uint8_t(v0 >> 7 | v1 << 1);
  b[4] = uint8_t(v1 >> 7);
  // Weights from bit 127 down: the first weight (texel 0) = 1 of 0..3, which unquantizes to 21.
  b[15] = 0x80;                // bit 127 set: weight 0's stream bits are bits 127, 126: value 01 reversed
  const AstcMode m = astc_mode_of(b, 4, 4);
  ASSERT_FALSE(m.error);
  ASSERT_EQ(m.grid_w, 4);
  ASSERT_EQ(m.weight_levels, 4);
  ASSERT_EQ(m.colour_levels, 256);
  // Texel 0: i = 21; linear C = (0x0A0A * 43 + 0xC8C8 * 21 + 32) >> 6, sRGB C = (0x0A80 * 43 + 0xC880 * 21 + 32) >> 6.
  const int lin = (0x0A0A * 43 + 0xC8C8 * 21 + 32) >> 6, srgb = (0x0A80 * 43 + 0xC880 * 21 + 32) >> 6;
  EXPECT_EQ(astc_texel16(b, 4, 4, false, 0, 0)[0], lin);
  EXPECT_EQ(astc_texel16(b, 4, 4, true, 0, 0)[0], srgb);
  EXPECT_EQ(decode_texel(TexelFormat::Astc4x4, b, 0)[0], lin >> 8);
  EXPECT_EQ(decode_texel(TexelFormat::Astc4x4, b, 1)[0], 10);  // weight 0: the first endpoint
}

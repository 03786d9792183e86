// The model's ASTC decoder (model/astc.h) against the Khronos reference encoder's decoder, astcenc
// (Arm; Debian's libastcenc 4.2), on random blocks of every footprint (stimulus::random_astc_block:
// every block mode, partition count, endpoint mode and range, void-extent and illegal blocks) and on
// images astcenc encoded.
//
// What is compared, and why there (docs/numerics.md, "ASTC"):
//  - sRGB operation mode: astcenc returns 8-bit values, the top 8 bits of C (R, G, B and A, as the
//    specification now says for A too): equal to the model's texel, bit for bit.
//  - linear LDR mode: astcenc 4.2 implements decode_float16 only (decode_unorm8 came in 4.5), so
//    it returns FP16 values: C / 65536 rounded toward zero, 65535 as 1.0. The model keeps C
//    (astc_texel16) and returns its top 8 bits (decode_unorm8); the test converts the model's C by
//    the specification's FP16 rule and compares every bit of every channel. The 8-bit texel is a
//    function of C, so equal C is equal output under either decode mode. An illegal block's error
//    colour in decode_float16 may be NaNs (astcenc: 0xFFFF in every channel), magenta in decode_unorm8;
//    astcenc 4.2 makes an HDR endpoint mode's error colour of endpoints 0xFF00 (later versions: 0xFFFF,
//    as the specification's magenta), the same 255 in 8 bits.
//  - the block's fields (astcenc_get_block_info): error, constant, partitions, dual plane and its
//    channel, endpoint modes, ranges and weight grid.
#include <astcenc.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "model/astc.h"
#include "model/block_formats.h"
#include "stimulus.h"

using namespace tex;

namespace {

// The FP16 bits of C / 65536 rounded toward zero, 65535 as 1.0 (the specification's
// decode_float16 of an LDR texel).
uint16_t fp16_of_unorm16(uint16_t c) {
  if (c == 0xFFFF) return 0x3C00;
  if (c < 4) return uint16_t(c << 8);  // subnormal: c * 2^-16 = (c << 8) * 2^-24
  int e = 15;
  while (!(c >> e)) --e;              // c = 1.m * 2^e, value 2^(e - 16): exponent field e - 1
  const uint32_t mantissa = (uint32_t(c) << 10 >> e) & 0x3FF;
  return uint16_t((e - 1) << 10 | mantissa);
}

struct Astcenc {
  astcenc_context* ctx = nullptr;
  Astcenc(astcenc_profile profile, int fw, int fh, unsigned flags, float quality = ASTCENC_PRE_FASTEST) {
    astcenc_config cfg;
    EXPECT_EQ(astcenc_config_init(profile, unsigned(fw), unsigned(fh), 1, quality, flags, &cfg), ASTCENC_SUCCESS);
    EXPECT_EQ(astcenc_context_alloc(&cfg, 1, &ctx), ASTCENC_SUCCESS);
  }
  ~Astcenc() { astcenc_context_free(ctx); }
  // Decodes blocks of an image of w x h texels into `out` (4 values of T per texel).
  template <class T>
  void decode(const std::vector<uint8_t>& blocks, int w, int h, astcenc_type type, std::vector<T>& out) {
    out.assign(size_t(w) * size_t(h) * 4, 0);
    void* planes[1] = {out.data()};
    astcenc_image img{unsigned(w), unsigned(h), 1, type, planes};
    const astcenc_swizzle swz{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    ASSERT_EQ(astcenc_decompress_image(ctx, blocks.data(), blocks.size(), &img, &swz, 0), ASTCENC_SUCCESS);
    astcenc_decompress_reset(ctx);
  }
};

// Every texel of a level of blocks compared: the model's C (sRGB and linear) against astcenc's
// 8-bit sRGB and FP16 linear decodes. Returns the texels compared.
int compare_with_astcenc(const AstcFootprint& f, const std::vector<uint8_t>& blocks, int w, int h) {
  Astcenc linear(ASTCENC_PRF_LDR, f.w, f.h, ASTCENC_FLG_DECOMPRESS_ONLY);
  Astcenc srgb(ASTCENC_PRF_LDR_SRGB, f.w, f.h, ASTCENC_FLG_DECOMPRESS_ONLY);
  std::vector<uint16_t> half;
  std::vector<uint8_t> codes;
  linear.decode(blocks, w, h, ASTCENC_TYPE_F16, half);
  srgb.decode(blocks, w, h, ASTCENC_TYPE_U8, codes);
  const int bw = (w + f.w - 1) / f.w, bh = (h + f.h - 1) / f.h;
  AstcTexel16 lin[kMaxBlockTexels], srg[kMaxBlockTexels];
  int compared = 0;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      const uint8_t* block = &blocks[(size_t(by) * size_t(bw) + size_t(bx)) * 16];
      astc_block16(block, f.w, f.h, false, lin);
      astc_block16(block, f.w, f.h, true, srg);
      for (int i = 0; i < f.w * f.h; ++i) {
        const int x = bx * f.w + i % f.w, y = by * f.h + i / f.w;
        if (x >= w || y >= h) continue;
        const size_t at = (size_t(y) * size_t(w) + size_t(x)) * 4;
        // decode_float16's error colour may be NaNs (astcenc's: 0xFFFF in every channel), and astcenc
        // 4.2 expands an HDR partition's error colour from endpoints of 0xFF00, not 0xFFFF: both where
        // the model has the error colour, whose top 8 bits are those of 0xFF00.
        static constexpr AstcTexel16 kError = {0xFFFF, 0, 0xFFFF, 0xFFFF}, kError42 = {0xFF00, 0, 0xFF00, 0xFF00};
        AstcTexel16 want = lin[i];
        const bool nan = half[at] == 0xFFFF && half[at + 1] == 0xFFFF && half[at + 2] == 0xFFFF && half[at + 3] == 0xFFFF;
        if (lin[i] == kError && half[at] == fp16_of_unorm16(0xFF00)) want = kError42;
        if (nan) {
          EXPECT_EQ(lin[i], kError) << "NaNs where the model has no error colour";
        }
        for (int c = 0; c < 4; ++c) {
          if (!nan) {
            EXPECT_EQ(half[at + size_t(c)], fp16_of_unorm16(want[size_t(c)]))
                << f.w << "x" << f.h << " block (" << bx << ", " << by << ") texel " << i << " channel " << c
                << ": linear C " << lin[i][size_t(c)];
          }
          EXPECT_EQ(codes[at + size_t(c)], srg[i][size_t(c)] >> 8)
              << f.w << "x" << f.h << " block (" << bx << ", " << by << ") texel " << i << " channel " << c << ": sRGB";
        }
        EXPECT_EQ(astc_unorm8(want), astc_unorm8(lin[i]));  // (the unit's texel: equal either way)
        if (::testing::Test::HasFailure()) return compared;
        ++compared;
      }
    }
  return compared;
}

}  // namespace

TEST(AstcReference, Fp16RuleAsSpecified) {
  EXPECT_EQ(fp16_of_unorm16(0), 0);
  EXPECT_EQ(fp16_of_unorm16(1), 0x0100);       // 2^-16: subnormal
  EXPECT_EQ(fp16_of_unorm16(4), 0x0400);       // 2^-14: the smallest normal
  EXPECT_EQ(fp16_of_unorm16(0x8000), 0x3800);  // 0.5
  EXPECT_EQ(fp16_of_unorm16(0xFFFE), 0x3BFF);  // just below 1, toward zero
  EXPECT_EQ(fp16_of_unorm16(0xFFFF), 0x3C00);  // 1.0
}

TEST(AstcReference, AstcencDecodesRandomBlocksTheSame) {
  constexpr int kAcross = 32, kDown = 48;  // 1536 blocks per footprint
  std::mt19937_64 rng(37);
  std::set<int> partitions, weight_levels, colour_levels, cems, ccs;
  std::map<std::string, int> kinds;
  for (const AstcFootprint& f : kAstcFootprints) {
    std::vector<uint8_t> blocks(size_t(kAcross) * kDown * 16);
    for (size_t i = 0; i < blocks.size(); i += 16) stimulus::random_astc_block(rng, f.w, f.h, &blocks[i]);
    // The block's fields, as astcenc reads them.
    Astcenc info(ASTCENC_PRF_LDR, f.w, f.h, ASTCENC_FLG_DECOMPRESS_ONLY);
    for (size_t i = 0; i < blocks.size(); i += 16) {
      const AstcMode m = astc_mode_of(&blocks[i], f.w, f.h);
      astcenc_block_info bi;
      ASSERT_EQ(astcenc_get_block_info(info.ctx, &blocks[i], &bi), ASTCENC_SUCCESS);
      const std::string at = std::to_string(f.w) + "x" + std::to_string(f.h) + " block " + std::to_string(i / 16);
      ++kinds[m.void_extent ? (m.error ? "void extent, illegal" : "void extent") : m.error ? "illegal" : "weights"];
      if (m.void_extent) {  // (astcenc calls an HDR one a constant block: its texels tell, below)
        ASSERT_TRUE(bi.is_error_block || bi.is_constant_block) << at;
        continue;
      }
      ASSERT_EQ(bool(bi.is_error_block), m.error) << at;
      if (m.error) continue;
      ASSERT_EQ(int(bi.partition_count), m.partitions) << at;
      ASSERT_EQ(bool(bi.is_dual_plane_block), m.dual_plane) << at;
      ASSERT_EQ(int(bi.weight_x), m.grid_w) << at;
      ASSERT_EQ(int(bi.weight_y), m.grid_h) << at;
      ASSERT_EQ(int(bi.weight_level_count), m.weight_levels) << at;
      ASSERT_EQ(int(bi.color_level_count), m.colour_levels) << at;
      if (m.partitions > 1) {
        ASSERT_EQ(int(bi.partition_index), m.partition_seed) << at;
      }
      if (m.dual_plane) {
        ASSERT_EQ(int(bi.dual_plane_component), m.ccs) << at;
      }
      for (int p = 0; p < m.partitions; ++p) ASSERT_EQ(int(bi.color_endpoint_modes[p]), m.cem[size_t(p)]) << at;
      partitions.insert(m.partitions);
      weight_levels.insert(m.weight_levels);
      colour_levels.insert(m.colour_levels);
      if (m.dual_plane) ccs.insert(m.ccs);
      for (int p = 0; p < m.partitions; ++p) cems.insert(m.cem[size_t(p)]);
    }
    const int texels = compare_with_astcenc(f, blocks, kAcross * f.w, kDown * f.h);
    ASSERT_FALSE(HasFailure());
    std::printf("  %2dx%-2d: %d texels equal (sRGB 8-bit, linear C)\n", f.w, f.h, texels);
  }
  for (const auto& [kind, n] : kinds) std::printf("  %s: %d blocks\n", kind.c_str(), n);
  // Every feature of the LDR profile was decoded (and the HDR endpoint modes, to the error colour).
  EXPECT_EQ(partitions.size(), 4u);
  EXPECT_EQ(weight_levels.size(), 12u);
  EXPECT_EQ(cems.size(), 16u);
  EXPECT_EQ(ccs.size(), 4u);
  EXPECT_EQ(colour_levels.size(), 17u) << "colour ranges decoded: " << colour_levels.size();
  EXPECT_GT(kinds["void extent"], 0);
  EXPECT_GT(kinds["void extent, illegal"], 0);
  EXPECT_GT(kinds["illegal"], 0);
}

TEST(AstcReference, AstcencDecodesEncodedImagesTheSame) {
  // A 100 x 76 image (no footprint divides it: the last blocks are cut), encoded by astcenc itself.
  const int w = 100, h = 76;
  const Image img = stimulus::random_image(w, h, 8, 3, 2);
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) rgba[i * 4 + size_t(c)] = uint8_t(img.texels[i][size_t(c)]);
  for (const AstcFootprint& f : kAstcFootprints) {
    Astcenc enc(ASTCENC_PRF_LDR, f.w, f.h, 0, ASTCENC_PRE_FASTEST);
    std::vector<uint8_t> blocks(size_t((w + f.w - 1) / f.w) * size_t((h + f.h - 1) / f.h) * 16);
    void* planes[1] = {rgba.data()};
    astcenc_image in{unsigned(w), unsigned(h), 1, ASTCENC_TYPE_U8, planes};
    const astcenc_swizzle swz{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    ASSERT_EQ(astcenc_compress_image(enc.ctx, &in, &swz, blocks.data(), blocks.size(), 0), ASTCENC_SUCCESS);
    const int texels = compare_with_astcenc(f, blocks, w, h);
    ASSERT_FALSE(HasFailure());
    ASSERT_EQ(texels, w * h);
  }
}

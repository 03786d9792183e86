// The cached memory hierarchy of the model (docs/memory.md): layout addresses, the memory image and
// its file header, and the caches' lookups, LRU and miss order, against values worked out by hand
// from the specification.
#include <gtest/gtest.h>

#include <cstring>

#include "model/error.h"
#include "model/memory_layout.h"
#include "model/texture_cache.h"
#include "model/stages.h"

using namespace tex;

namespace {

Image numbered(int w, int h, int bits = 8) {
  Image img(w, h, bits);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {uint16_t(x), uint16_t(y), uint16_t(x + y), uint16_t(bits > 8 ? 0x1234 : 200)};
  return img;
}

uint32_t u32_at(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, &b[at], 4);
  return v;
}

// A request at texel centre (x + 1/2, y + 1/2) of level 0 of a 2^lw x 2^lh texture.
Request at_texel(double x, double y, int lw, int lh, double lod = 0) {
  Request r;
  to_coord_fixed(x / (1 << lw), r.u);
  to_coord_fixed(y / (1 << lh), r.v);
  to_lod_fixed(lod, r.lod);
  return r;
}

}  // namespace

TEST(MemoryLayout, RowMajorAddressesOfA8x4Texture) {
  const MemoryLayout l(3, 2, 8, LayoutParams{});  // 8x4, 4x4 blocks of RGBA8: 64-byte lines
  EXPECT_EQ(l.line_bytes(), 64);
  ASSERT_EQ(l.levels(), 4);
  // level 0: 2x1 blocks; level 1 (4x2): 1 block; level 2 (2x1): 1; level 3 (1x1): 1.
  EXPECT_EQ(l.level_base(0), 0u);
  EXPECT_EQ(l.level_base(1), 128u);
  EXPECT_EQ(l.level_base(2), 192u);
  EXPECT_EQ(l.level_base(3), 256u);
  EXPECT_EQ(l.image_bytes(), 320u);
  EXPECT_EQ(l.line_address(0, 1, 0), 64u);

  const Pyramid pyr = build_pyramid(numbered(8, 4));
  const std::vector<uint8_t> img = build_memory_image(pyr, l);
  ASSERT_EQ(img.size(), 320u);
  // Texel (5, 2) of level 0: block (1, 0) at 64, texel (1, 2) of the block: byte 64 + (2*4 + 1)*4.
  EXPECT_EQ(img[100], 5);  // R
  EXPECT_EQ(img[101], 2);  // G
  EXPECT_EQ(img[102], 7);  // B
  EXPECT_EQ(img[103], 200);
  // Level 1 is 4x2: the block's rows 2 and 3 are padding (0).
  for (size_t i = 128 + 2 * 16; i < 192; ++i) EXPECT_EQ(img[i], 0) << i;
  EXPECT_EQ(img[128 + 4 * (1 * 4 + 3) + 3], pyr.levels[1].at(3, 1)[3]);
}

TEST(MemoryLayout, MortonOrderAndBase) {
  LayoutParams p;
  p.block_w = p.block_h = 2;
  p.order = BlockOrder::Morton;
  p.base = 4096;
  const MemoryLayout sq(3, 3, 8, p);  // 8x8: 4x4 blocks of 2x2 texels, 16-byte lines
  EXPECT_EQ(sq.block_index(0, 1, 2), 1u + 8u);   // bx bit 0 -> bit 0, by bit 1 -> bit 3
  EXPECT_EQ(sq.line_address(0, 1, 2), 4096u + 9u * 16u);
  const MemoryLayout wide(4, 2, 8, p);  // 16x4: 8x2 blocks, m = 1
  EXPECT_EQ(wide.block_index(0, 5, 1), 3u + (2u << 2));  // low bits 1,1; then bx >> 1 = 2 above
  EXPECT_THROW(MemoryLayout(3, 3, 8, LayoutParams{4, 4, BlockOrder::RowMajor, 100}), Error);  // misaligned
  EXPECT_THROW(MemoryLayout(3, 3, 8, LayoutParams{3, 4, BlockOrder::RowMajor, 0}), Error);
}

TEST(MemoryLayout, SixteenBitTexelsAndFileHeader) {
  const MemoryLayout l(2, 2, 16, LayoutParams{});
  EXPECT_EQ(l.texel_bytes(), 8);
  EXPECT_EQ(l.line_bytes(), 128);
  const Pyramid pyr = build_pyramid(numbered(4, 4, 16));
  const std::vector<uint8_t> f = memory_image_file(pyr, l);
  ASSERT_EQ(std::string(f.begin(), f.begin() + 8), "TEXMEM01");
  const uint32_t header = u32_at(f, 8);
  EXPECT_EQ(header, 64u + 8u * 3u);
  EXPECT_EQ(u32_at(f, 20), 3u);    // levels
  EXPECT_EQ(u32_at(f, 24), 16u);   // channel bits
  EXPECT_EQ(u32_at(f, 28), 8u);    // texel bytes
  EXPECT_EQ(u32_at(f, 44), 128u);  // line bytes
  EXPECT_EQ(f.size(), size_t(header) + 3u * 128u);
  // Texel (3, 1) of level 0: byte (1*4 + 3)*8 of the first line; A = 0x1234 little-endian.
  const size_t at = header + 7 * 8;
  EXPECT_EQ(f[at], 3);
  EXPECT_EQ(f[at + 2], 1);
  EXPECT_EQ(f[at + 6], 0x34);
  EXPECT_EQ(f[at + 7], 0x12);
}

TEST(TextureCache, LruEvictsTheLeastRecentlyUsedWay) {
  // 64x64 RGBA8, 4x4 blocks (row-major, 16 per row), 16 lines in 4 sets of 4 ways: every block
  // with even bx and by is in set 0. Point sampling of level 0.
  const MemoryLayout l(6, 6, 8, LayoutParams{});
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Nearest, MipMode::None};
  TextureCache cache(l, CacheParams{1024, 4}, cfg, 6, 6);
  EXPECT_EQ(cache.sets(), 4);
  std::vector<uint32_t> misses;
  auto block = [&](int bx) { cache.lookup(at_texel(bx * 4 + 0.5, 0.5, 6, 6), &misses); };
  for (int bx : {0, 2, 4, 6, 0, 8, 2, 0, 4}) block(bx);
  // A B C D fill the set; A hits; E evicts B (least recent); B evicts C; A hits; C evicts D.
  const std::vector<uint32_t> want = {0, 128, 256, 384, 512, 128, 256};
  EXPECT_EQ(misses, want);
  EXPECT_EQ(cache.stats().total_hits(), 2u);
}

TEST(TextureCache, FootprintStraddlingABlockCornerMissesFourLinesInParityOrder) {
  const MemoryLayout l(6, 6, 8, LayoutParams{});
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::None};
  TextureCache cache(l, CacheParams{8192, 1}, cfg, 6, 6);
  std::vector<uint32_t> misses;
  // (4, 4) of level 0: taps 3 and 4 on both axes, weight 1/2: blocks (0,0) (1,0) (0,1) (1,1).
  const SampleLookup r = cache.lookup(at_texel(4, 4, 6, 6), &misses);
  EXPECT_EQ(r.slot[0].blocks, 4);
  EXPECT_FALSE(r.slot[1].needed);
  EXPECT_EQ(misses, (std::vector<uint32_t>{0, 64, 1024, 1088}));
  // At a texel centre both weights are 0: one tap, one line (already there).
  const SampleLookup c = cache.lookup(at_texel(2.5, 2.5, 6, 6), &misses);
  EXPECT_EQ(c.slot[0].blocks, 1);
  EXPECT_EQ(c.slot[0].misses, 0);
}

TEST(TextureCache, TrilinearReadsLevelD1OnlyWhenItsWeightIsNotZero) {
  const MemoryLayout l(6, 6, 8, LayoutParams{});
  SamplerConfig cfg;  // trilinear
  TextureCache cache(l, CacheParams{8192, 2}, cfg, 6, 6);
  std::vector<uint32_t> misses;
  const SampleLookup whole = cache.lookup(at_texel(9, 9, 6, 6, 1.0), &misses);  // f = 0
  EXPECT_EQ(whole.slot[0].level, 1);
  EXPECT_FALSE(whole.slot[1].needed);
  for (uint32_t a : misses) EXPECT_GE(a, l.level_base(1)) << a;
  for (uint32_t a : misses) EXPECT_LT(a, l.level_base(2)) << a;
  misses.clear();
  const SampleLookup half = cache.lookup(at_texel(9, 9, 6, 6, 1.5), &misses);
  EXPECT_TRUE(half.slot[1].needed);
  EXPECT_EQ(half.slot[1].level, 2);
  ASSERT_FALSE(misses.empty());
  EXPECT_GE(misses.back(), l.level_base(2));  // level d's misses first, then d1's
}

TEST(TextureCache, RepeatWrapAtTheRightEdgeStraddlesTheLastAndFirstBlockColumns) {
  const MemoryLayout l(4, 4, 8, LayoutParams{});  // 16x16: 4 block columns
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::None};
  TextureCache cache(l, CacheParams{4096, 1}, cfg, 4, 4);
  std::vector<uint32_t> misses;
  cache.lookup(at_texel(16, 2.5, 4, 4), &misses);  // taps x 15 and 0 (repeat), y centred
  EXPECT_EQ(misses, (std::vector<uint32_t>{0, 3 * 64}));  // parity 0: column 0; parity 1: column 3
}

TEST(TextureCache, ACacheLargerThanTheTextureMissesOnlyOnce) {
  const MemoryLayout l(5, 5, 8, LayoutParams{});
  SamplerConfig cfg;
  TextureCache cache(l, CacheParams{32768, 4}, cfg, 5, 5);
  std::vector<Request> rs;
  for (int i = 0; i < 2000; ++i) rs.push_back(at_texel(i * 0.37, i * 0.71, 5, 5, (i % 60) / 10.0 - 1));
  std::vector<uint32_t> misses;
  for (const Request& r : rs) cache.lookup(r, &misses);
  EXPECT_LE(misses.size(), l.image_bytes() / 64);
  const size_t first = misses.size();
  for (const Request& r : rs) cache.lookup(r, &misses);
  EXPECT_EQ(misses.size(), first);
}

TEST(TextureCache, GeometryTheHardwareCannotHaveIsAnError) {
  const MemoryLayout l(5, 5, 8, LayoutParams{});
  EXPECT_THROW(TextureCache(l, CacheParams{8192, 3}, SamplerConfig{}, 5, 5), Error);
  EXPECT_THROW(TextureCache(l, CacheParams{100, 1}, SamplerConfig{}, 5, 5), Error);
  EXPECT_THROW(TextureCache(l, CacheParams{3 * 64 * 4, 1}, SamplerConfig{}, 5, 5), Error);  // 12 sets
  EXPECT_THROW(TextureCache(l, CacheParams{128, 1}, SamplerConfig{}, 5, 5), Error);  // 2 sets
}

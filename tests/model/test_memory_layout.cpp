// The pyramid in memory (docs/memory.md §1): block grids, level bases, row-major and Morton block
// order, texel bytes, padding, the memory image and its file header. Addresses are worked out by
// hand from the specification; the whole-image check places every texel with its own small
// implementation of the specification's formulas.
#include <gtest/gtest.h>

#include <random>

#include <algorithm>
#include <string>
#include <vector>

#include "model/error.h"
#include "model/memory_layout.h"
#include "stimulus.h"

using namespace tex;

namespace {

// Texel (x, y) of level 0: R = x, G = y, B = x + y, A = 200 (8-bit); 16-bit channels put x and y in
// the high byte too, so that both bytes of a word are checked.
Image numbered(int w, int h, int bits = 8) {
  Image img(w, h, bits);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = bits > 8 ? Texel{uint16_t(0x100 * x + 0x11), uint16_t(0x1000 * y + 0x22), uint16_t(x + y), 0x1234}
                              : Texel{uint16_t(x), uint16_t(y), uint16_t(x + y), 200};
  return img;
}

LayoutParams params(int bw, int bh, BlockOrder order = BlockOrder::RowMajor, uint32_t base = 0) {
  LayoutParams p;
  p.block_w = bw;
  p.block_h = bh;
  p.order = order;
  p.base = base;
  return p;
}

uint32_t u32_at(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | b[at + size_t(i)];
  return v;
}
uint64_t u64_at(const std::vector<uint8_t>& b, size_t at) { return uint64_t(u32_at(b, at + 4)) << 32 | u32_at(b, at); }

// The 4 bytes of an 8-bit texel at `at` of the image.
void expect_rgba8_at(const std::vector<uint8_t>& img, size_t at, const Texel& t) {
  for (size_t c = 0; c < 4; ++c) EXPECT_EQ(img[at + c], t[c]) << "byte " << at + c;
}

void expect_zero(const std::vector<uint8_t>& img, size_t from, size_t to) {
  for (size_t i = from; i < to; ++i) EXPECT_EQ(img[i], 0) << "padding byte " << i;
}

std::string error_of(int w, int h, int bits, const LayoutParams& p) {
  try {
    MemoryLayout({w, h}, bits, p);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(MemoryLayout, BlockOrderNames) {
  BlockOrder o = BlockOrder::Morton;
  EXPECT_TRUE(parse_block_order("row-major", o));
  EXPECT_EQ(o, BlockOrder::RowMajor);
  EXPECT_TRUE(parse_block_order("morton", o));
  EXPECT_EQ(o, BlockOrder::Morton);
  for (const char* bad : {"rowmajor", "Morton", "z-order", ""}) EXPECT_FALSE(parse_block_order(bad, o)) << bad;
  EXPECT_EQ(block_order_name(BlockOrder::RowMajor), "row-major");
  EXPECT_EQ(block_order_name(BlockOrder::Morton), "morton");
}

TEST(MemoryLayout, EightByFourIn4x4Blocks) {
  // 64-byte lines. Level 0 (8x4): 2x1 blocks; level 1 (4x2), 2 (2x1), 3 (1x1): one padded block each.
  const MemoryLayout l({8, 4}, 8, LayoutParams{});
  EXPECT_EQ(l.texel_bytes(), 4);
  EXPECT_EQ(l.line_bytes(), 64);
  ASSERT_EQ(l.levels(), 4);
  const uint32_t nbx[] = {2, 1, 1, 1}, base[] = {0, 128, 192, 256};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(l.blocks_x(k), nbx[k]) << k;
    EXPECT_EQ(l.blocks_y(k), 1u) << k;
    EXPECT_EQ(l.level_base(k), base[k]) << k;
  }
  EXPECT_EQ(l.image_bytes(), 320u);
  EXPECT_EQ(l.line_address(0, 3, 3), 0u);
  EXPECT_EQ(l.line_address(0, 5, 2), 64u);
  EXPECT_EQ(l.line_address(1, 3, 1), 128u);
  EXPECT_EQ(l.line_address(3, 0, 0), 256u);
  EXPECT_EQ(l.texel_offset(5, 2), (2u * 4 + 1) * 4);
  // A one-row grid: Morton order is row-major order.
  const MemoryLayout m({8, 4}, 8, params(4, 4, BlockOrder::Morton));
  EXPECT_EQ(m.block_index(0, 1, 0), 1u);
  EXPECT_EQ(m.image_bytes(), 320u);

  const Pyramid pyr = build_pyramid(numbered(8, 4));
  const std::vector<uint8_t> img = build_memory_image(pyr, l);
  ASSERT_EQ(img.size(), 320u);
  expect_rgba8_at(img, 64 + (2 * 4 + 1) * 4, Texel{5, 2, 7, 200});  // texel (5, 2) of level 0
  expect_rgba8_at(img, 0, Texel{0, 0, 0, 200});
  expect_rgba8_at(img, 128 + (1 * 4 + 3) * 4, pyr.levels[1].at(3, 1));
  expect_rgba8_at(img, 192 + 4, pyr.levels[2].at(1, 0));
  expect_rgba8_at(img, 256, pyr.levels[3].at(0, 0));
  // Padding: level 1's block rows 2 and 3, level 2's past its first two texels, level 3's past one.
  expect_zero(img, 128 + 2 * 16, 192);
  expect_zero(img, 192 + 8, 256);
  expect_zero(img, 256 + 4, 320);
  EXPECT_EQ(build_memory_image(pyr, m), img);
}

TEST(MemoryLayout, EightByFourIn2x2BlocksBothOrders) {
  // 16-byte lines. Level 0: 4x2 blocks (128 B); level 1 (4x2): 2x1 (32 B); level 2 (2x1): one block,
  // its second row padding; level 3: one block.
  const MemoryLayout rm({8, 4}, 8, params(2, 2));
  const MemoryLayout mo({8, 4}, 8, params(2, 2, BlockOrder::Morton));
  for (const MemoryLayout* l : {&rm, &mo}) {
    EXPECT_EQ(l->line_bytes(), 16);
    const uint32_t nbx[] = {4, 2, 1, 1}, nby[] = {2, 1, 1, 1}, base[] = {0, 128, 160, 176};
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(l->blocks_x(k), nbx[k]) << k;
      EXPECT_EQ(l->blocks_y(k), nby[k]) << k;
      EXPECT_EQ(l->level_base(k), base[k]) << k;
    }
    EXPECT_EQ(l->image_bytes(), 192u);
  }
  // Level 0 in Morton order (m = 1): (0,0) (1,0) (0,1) (1,1), then (2,0) (3,0) (2,1) (3,1).
  EXPECT_EQ(rm.line_address(0, 4, 1), 2u * 16);  // block (2, 0)
  EXPECT_EQ(mo.line_address(0, 4, 1), 4u * 16);
  EXPECT_EQ(rm.line_address(0, 2, 2), 5u * 16);  // block (1, 1)
  EXPECT_EQ(mo.line_address(0, 2, 2), 3u * 16);
  EXPECT_EQ(rm.line_address(0, 6, 0), 3u * 16);  // block (3, 0)
  EXPECT_EQ(mo.line_address(0, 6, 0), 5u * 16);
  EXPECT_EQ(rm.line_address(0, 7, 3), 7u * 16);  // block (3, 1): last in both
  EXPECT_EQ(mo.line_address(0, 7, 3), 7u * 16);
  EXPECT_EQ(mo.line_address(1, 3, 1), 128u + 16);  // level 1, block (1, 0)

  const Pyramid pyr = build_pyramid(numbered(8, 4));
  const std::vector<uint8_t> a = build_memory_image(pyr, rm), b = build_memory_image(pyr, mo);
  // Texel (4, 1) is texel (0, 1) of block (2, 0): byte 8 of the line.
  expect_rgba8_at(a, 32 + 8, Texel{4, 1, 5, 200});
  expect_rgba8_at(b, 64 + 8, Texel{4, 1, 5, 200});
  expect_rgba8_at(a, 112 + 12, Texel{7, 3, 10, 200});
  expect_rgba8_at(b, 112 + 12, Texel{7, 3, 10, 200});
  expect_rgba8_at(b, 144 + 12, pyr.levels[1].at(3, 1));
  expect_rgba8_at(b, 160 + 4, pyr.levels[2].at(1, 0));
  expect_zero(b, 160 + 8, 176);  // level 2's second row
  expect_zero(b, 176 + 4, 192);
}

TEST(MemoryLayout, MortonIndexOfSquareWideAndTallGrids) {
  const LayoutParams p = params(2, 2, BlockOrder::Morton);
  const MemoryLayout sq({8, 8}, 8, p);  // 4x4 blocks
  EXPECT_EQ(sq.block_index(0, 1, 2), 0b1001u);  // bx bit 0 -> bit 0, by bit 1 -> bit 3
  EXPECT_EQ(sq.block_index(0, 3, 3), 15u);
  EXPECT_EQ(sq.block_index(0, 2, 1), 0b0110u);
  const MemoryLayout wide({16, 4}, 8, p);  // 8x2 blocks, m = 1: (bx >> 1) above the low pair
  EXPECT_EQ(wide.block_index(0, 5, 1), 3u + (2u << 2));
  EXPECT_EQ(wide.block_index(0, 6, 0), 0u + (3u << 2));
  const MemoryLayout tall({4, 16}, 8, p);  // 2x8 blocks
  EXPECT_EQ(tall.block_index(0, 1, 5), 3u + (2u << 2));
  EXPECT_EQ(tall.block_index(0, 0, 6), 0u + (3u << 2));
  EXPECT_EQ(tall.block_index(1, 0, 3), 3u);  // level 1 is 1x4 blocks: m = 0
}

TEST(MemoryLayout, SixteenBitTexels) {
  EXPECT_EQ(MemoryLayout({4, 4}, 1, LayoutParams{}).texel_bytes(), 4);
  EXPECT_EQ(MemoryLayout({4, 4}, 8, LayoutParams{}).texel_bytes(), 4);
  EXPECT_EQ(MemoryLayout({4, 4}, 9, LayoutParams{}).texel_bytes(), 8);
  const MemoryLayout l({8, 4}, 16, LayoutParams{});  // 8x4: 128-byte lines
  EXPECT_EQ(l.texel_bytes(), 8);
  EXPECT_EQ(l.line_bytes(), 128);
  EXPECT_EQ(l.level_base(1), 256u);
  EXPECT_EQ(l.level_base(3), 512u);
  EXPECT_EQ(l.image_bytes(), 640u);
  const Pyramid pyr = build_pyramid(numbered(8, 4, 16));
  const std::vector<uint8_t> img = build_memory_image(pyr, l);
  ASSERT_EQ(img.size(), 640u);
  // Texel (5, 2): block (1, 0), texel (1, 2) of it: 128 + (2*4 + 1)*8. R 0x0511, G 0x2022, B 7, A 0x1234.
  const std::vector<uint8_t> want = {0x11, 0x05, 0x22, 0x20, 7, 0, 0x34, 0x12};
  EXPECT_EQ(std::vector<uint8_t>(img.begin() + 200, img.begin() + 208), want);
  const Texel t = pyr.levels[2].at(1, 0);
  for (size_t c = 0; c < 4; ++c) EXPECT_EQ(img[384 + 8 + 2 * c] | img[384 + 8 + 2 * c + 1] << 8, t[c]) << c;
  expect_zero(img, 384 + 16, 512);
  // A 12-bit texture is stored in the low 12 bits of each word.
  Image twelve(2, 2, 12);
  for (Texel& x : twelve.texels) x = {0xABC, 0xFFF, 0x001, 0x800};
  const std::vector<uint8_t> t12 = build_memory_image(build_pyramid(twelve), MemoryLayout({2, 2}, 12, params(2, 2)));
  EXPECT_EQ(std::vector<uint8_t>(t12.begin(), t12.begin() + 8),
            (std::vector<uint8_t>{0xBC, 0x0A, 0xFF, 0x0F, 0x01, 0x00, 0x00, 0x08}));
}

TEST(MemoryLayout, EveryTexelWhereTheSpecificationPutsIt) {
  struct Case {
    int lw, lh, bits, bw, bh;
    BlockOrder order;
    uint32_t base;
  };
  const Case cases[] = {{5, 2, 8, 4, 4, BlockOrder::Morton, 0},   {2, 5, 8, 2, 8, BlockOrder::Morton, 4096},
                        {4, 4, 16, 8, 2, BlockOrder::RowMajor, 128}, {5, 3, 16, 2, 2, BlockOrder::Morton, 0},
                        {3, 3, 8, 8, 8, BlockOrder::RowMajor, 256}, {0, 0, 8, 2, 4, BlockOrder::Morton, 32}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::to_string(c.lw) + "x" + std::to_string(c.lh) + " cw" + std::to_string(c.bits) + " block " +
                 std::to_string(c.bw) + "x" + std::to_string(c.bh) + " " + block_order_name(c.order));
    const MemoryLayout l({1 << c.lw, 1 << c.lh}, c.bits, params(c.bw, c.bh, c.order, c.base));
    const Pyramid pyr = build_pyramid(numbered(1 << c.lw, 1 << c.lh, c.bits));
    const std::vector<uint8_t> img = build_memory_image(pyr, l);
    const size_t tb = c.bits > 8 ? 8 : 4, lb = size_t(c.bw * c.bh) * tb;
    std::vector<bool> written(img.size(), false);
    size_t level_base = 0;  // from the base
    for (size_t k = 0; k < pyr.levels.size(); ++k) {
      const Image& lv = pyr.levels[k];
      const int nbx = std::max(lv.width / c.bw, 1), nby = std::max(lv.height / c.bh, 1);
      EXPECT_EQ(l.level_base(int(k)), c.base + level_base);
      for (int y = 0; y < lv.height; ++y)
        for (int x = 0; x < lv.width; ++x) {
          const int bx = x / c.bw, by = y / c.bh;
          size_t index = size_t(by * nbx + bx);
          if (c.order == BlockOrder::Morton) {
            int m = 0;
            while ((2 << m) <= nbx && (2 << m) <= nby) ++m;
            index = 0;
            for (int i = 0; i < m; ++i) index |= size_t((bx >> i) & 1) << (2 * i) | size_t((by >> i) & 1) << (2 * i + 1);
            index += size_t((bx >> m) + (by >> m)) << (2 * m);
          }
          const size_t at = level_base + index * lb + size_t((y % c.bh) * c.bw + x % c.bw) * tb;
          ASSERT_LT(at + tb, img.size() + 1);
          for (size_t c4 = 0; c4 < 4; ++c4) {
            const uint16_t v = lv.at(x, y)[c4];
            const uint16_t got = tb == 4 ? img[at + c4] : uint16_t(img[at + 2 * c4] | img[at + 2 * c4 + 1] << 8);
            ASSERT_EQ(got, v) << "level " << k << " texel " << x << "," << y << " channel " << c4;
          }
          for (size_t i = 0; i < tb; ++i) {
            ASSERT_FALSE(written[at + i]) << "two texels at byte " << at + i;
            written[at + i] = true;
          }
        }
      level_base += size_t(nbx * nby) * lb;
    }
    EXPECT_EQ(l.image_bytes(), level_base);
    for (size_t i = 0; i < img.size(); ++i)
      if (!written[i]) {
        ASSERT_EQ(img[i], 0) << "padding byte " << i;
      }
  }
}

TEST(MemoryLayout, FileHeader) {
  const MemoryLayout l({8, 4}, 8, params(2, 2, BlockOrder::Morton, 4096));
  const Pyramid pyr = build_pyramid(numbered(8, 4));
  const std::vector<uint8_t> f = memory_image_file(pyr, l);
  ASSERT_EQ(f.size(), 104u + 192u);
  EXPECT_EQ(std::string(f.begin(), f.begin() + 8), "TEXMEM03");
  const uint32_t want32[] = {104, 8, 4, 4, 8, 4, 2, 2, 1, 16};  // offsets 8 .. 44
  for (size_t i = 0; i < 10; ++i) EXPECT_EQ(u32_at(f, 8 + 4 * i), want32[i]) << "offset " << 8 + 4 * i;
  EXPECT_EQ(u64_at(f, 48), 4096u);
  EXPECT_EQ(u64_at(f, 56), 192u);
  const uint64_t bases[] = {4096, 4096 + 128, 4096 + 160, 4096 + 176};
  EXPECT_EQ(u32_at(f, 64), 0u);  // RGBA
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(u64_at(f, 72 + 8 * k), bases[k]) << k;
  // Texel (2, 2) of level 0: Morton block 3 of 16 bytes, first texel.
  expect_rgba8_at(f, 104 + 48, Texel{2, 2, 4, 200});
  EXPECT_EQ(std::vector<uint8_t>(f.begin() + 104, f.end()), build_memory_image(pyr, l));

  const std::vector<uint8_t> g = memory_image_file(build_pyramid(numbered(4, 4, 16)), MemoryLayout({4, 4}, 16, {}));
  EXPECT_EQ(u32_at(g, 8), 72u + 8 * 3);
  EXPECT_EQ(u32_at(g, 24), 16u);   // channel bits
  EXPECT_EQ(u32_at(g, 28), 8u);    // texel bytes
  EXPECT_EQ(u32_at(g, 40), 0u);    // row-major
  EXPECT_EQ(u32_at(g, 44), 128u);  // line bytes
  EXPECT_EQ(g.size(), 96u + 3 * 128);
}

TEST(MemoryLayout, BadGeometryIsAnErrorNamingTheValue) {
  EXPECT_NE(error_of(8, 8, 8, params(3, 4)).find("block width 3"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 8, params(4, 16)).find("block height 16"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 8, params(1, 2)).find("block width 1"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 8, params(4, 4, BlockOrder::RowMajor, 100)).find("100"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 16, params(4, 4, BlockOrder::RowMajor, 64)).find("128-byte"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 0, LayoutParams{}).find("0 bits"), std::string::npos);
  EXPECT_NE(error_of(8, 8, 17, LayoutParams{}).find("17 bits"), std::string::npos);
  EXPECT_NE(error_of(8193, 8, 8, LayoutParams{}).find("side 8193"), std::string::npos);
  EXPECT_NE(error_of(8, 0, 8, LayoutParams{}).find("side 0"), std::string::npos);
  EXPECT_EQ(error_of(8192, 5, 8, LayoutParams{}), "(no error)");
  // 8x8 in 4x4 blocks is 256 + 64 + 64 + 64 = 448 bytes: it may end at 2^32 exactly, not past it.
  EXPECT_EQ(error_of(8, 8, 8, params(4, 4, BlockOrder::RowMajor, 0xFFFFFE40u)), "(no error)");
  EXPECT_NE(error_of(8, 8, 8, params(4, 4, BlockOrder::RowMajor, 0xFFFFFE80u)).find("4294967360"), std::string::npos);
  // An image for another texture.
  const MemoryLayout l({8, 4}, 8, LayoutParams{});
  EXPECT_THROW(build_memory_image(build_pyramid(numbered(4, 8)), l), Error);
  EXPECT_THROW(build_memory_image(build_pyramid(numbered(8, 4, 16)), l), Error);
}

// decode_line is the inverse of the image: every line of every level, decoded, gives back each
// texel of the pyramid exactly once, in both block orders, for wide, tall and 16-bit textures; an
// address that is not a line start is refused.
TEST(MemoryLayout, DecodingEveryLineGivesBackThePyramid) {
  struct Case {
    int w, h, bits, bw, bh;
    BlockOrder order;
    uint32_t base;
  };
  for (const Case& c : {Case{32, 8, 8, 4, 4, BlockOrder::Morton, 0}, Case{8, 32, 8, 2, 4, BlockOrder::Morton, 128},
                        Case{16, 16, 16, 4, 2, BlockOrder::RowMajor, 4096}, Case{64, 4, 8, 8, 8, BlockOrder::RowMajor, 0},
                        Case{5, 3, 8, 4, 4, BlockOrder::RowMajor, 0}, Case{100, 60, 8, 4, 4, BlockOrder::Morton, 64},
                        Case{31, 17, 16, 2, 4, BlockOrder::RowMajor, 0}, Case{1, 7, 8, 8, 8, BlockOrder::Morton, 0}}) {
    const Pyramid pyr = build_pyramid(numbered(c.w, c.h, c.bits), PyramidMode::Exact);
    const MemoryLayout layout(pyr.extent0(), c.bits, params(c.bw, c.bh, c.order, c.base));
    const std::vector<uint8_t> image = build_memory_image(pyr, layout);
    std::vector<std::vector<int>> seen(pyr.levels.size());
    for (size_t k = 0; k < pyr.levels.size(); ++k) seen[k].assign(pyr.levels[k].texels.size(), 0);
    // Every line decodes, but in Morton order a grid that is not a power of two has holes.
    const bool holes = c.order == BlockOrder::Morton && (!is_power_of_two(c.w) || !is_power_of_two(c.h));
    for (uint64_t off = 0; off < image.size(); off += uint64_t(layout.line_bytes())) {
      const bool line = decode_line(layout, c.base + uint32_t(off), &image[off], [&](int, int level, int x, int y, const Texel& t) {
        EXPECT_EQ(t, pyr.levels[size_t(level)].at(x, y)) << "level " << level << " (" << x << ", " << y << ")";
        ++seen[size_t(level)][size_t(y * pyr.levels[size_t(level)].width + x)];
      });
      ASSERT_TRUE(line || holes) << off;
    }
    for (size_t k = 0; k < seen.size(); ++k)
      EXPECT_TRUE(std::all_of(seen[k].begin(), seen[k].end(), [](int n) { return n == 1; })) << "level " << k;
    // With seam_copies, each repeat seam's copy comes as the texel it copies: column 0 once more on a
    // side that is not a power of two, row 0 likewise, texel (0, 0) a fourth time with both.
    for (std::vector<int>& s : seen) std::fill(s.begin(), s.end(), 0);
    for (uint64_t off = 0; off < image.size(); off += uint64_t(layout.line_bytes()))
      decode_line(layout, c.base + uint32_t(off), &image[off], [&](int, int level, int x, int y, const Texel& t) {
        EXPECT_EQ(t, pyr.levels[size_t(level)].at(x, y)) << "level " << level << " (" << x << ", " << y << ")";
        ++seen[size_t(level)][size_t(y * pyr.levels[size_t(level)].width + x)];
      }, true);
    for (size_t k = 0; k < seen.size(); ++k) {
      const Image& l = pyr.levels[k];
      const bool sx = !is_power_of_two(l.width), sy = !is_power_of_two(l.height);
      for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x)
          ASSERT_EQ(seen[k][size_t(y * l.width + x)], 1 + (sx && x == 0) + (sy && y == 0) + (sx && sy && x == 0 && y == 0))
              << "level " << k << " (" << x << ", " << y << ") of " << c.w << "x" << c.h;
    }
    const auto ignore = [](int, int, int, int, const Texel&) {};
    EXPECT_FALSE(decode_line(layout, c.base + 4, image.data(), ignore));  // not a line start
    EXPECT_FALSE(decode_line(layout, c.base + uint32_t(image.size()), image.data(), ignore));  // past the image
    if (c.base) {
      EXPECT_FALSE(decode_line(layout, 0, image.data(), ignore));  // below the base
    }
  }
}

namespace {

// A pyramid of random blocks of format f (its levels decoded from them), as a texture file gives.
Pyramid random_block_pyramid(TexelFormat f, Extent size0, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<uint8_t>> blocks;
  for (int k = 0; k < level_count(size0); ++k) {
    const Extent s = level_extent(size0, k);
    std::vector<uint8_t>& b = blocks.emplace_back(level_bytes(f, s.width(), s.height()));
    for (uint8_t& x : b) x = uint8_t(rng());
    if (f == TexelFormat::Bc7)
      for (size_t i = 0; i < b.size(); i += 16) b[i] |= 1;  // mode 0: no reserved blocks
  }
  return pyramid_of_blocks(f, size0, std::move(blocks));
}

}  // namespace

// A block format keeps the line's bytes and packs whole 4x4 blocks in it, wider than tall.
TEST(MemoryLayout, BlockFormatsPackWholeBlocksPerLine) {
  const MemoryLayout bc1({64, 32}, 8, LayoutParams{}, TexelFormat::Bc1);
  EXPECT_EQ(bc1.line_bytes(), 64);
  EXPECT_EQ(bc1.block_w(), 16);  // 8 blocks of 8 bytes: 4 x 2 blocks
  EXPECT_EQ(bc1.block_h(), 8);
  EXPECT_EQ(bc1.texel_offset(5, 6), (1u * 4 + 1) * 8);  // block (1, 1) of the line
  EXPECT_EQ(bc1.texel_offset(21, 9), (0u * 4 + 1) * 8); // (x 21 -> 5 in its line, y 9 -> 1)
  const MemoryLayout bc7({64, 32}, 8, LayoutParams{}, TexelFormat::Bc7);
  EXPECT_EQ(bc7.block_w(), 8);  // 4 blocks of 16 bytes: 2 x 2
  EXPECT_EQ(bc7.block_h(), 8);
  EXPECT_EQ(bc7.texel_offset(5, 6), 3u * 16);
  // Lines of 8x8 texels: 8x4 + 4x2 + 2x1 lines, then one (padded) line for each of the 4 levels
  // from 8x4 down to 1x1.
  EXPECT_EQ(bc7.image_bytes(), (32u + 8 + 2 + 4) * 64);
  const MemoryLayout small({64, 32}, 8, params(2, 2, BlockOrder::RowMajor, 0), TexelFormat::Bc1);
  EXPECT_EQ(small.line_bytes(), 16);
  EXPECT_EQ(small.block_w(), 8);
  EXPECT_EQ(small.block_h(), 4);
  try {
    MemoryLayout({64, 32}, 16, LayoutParams{}, TexelFormat::Bc1);
    ADD_FAILURE() << "16-bit BC1";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bc1 holds 8-bit channels, not 16"), std::string::npos) << e.what();
  }
}

// The memory image of a compressed pyramid holds its blocks; decoding every line of it gives back
// every texel of every level exactly once, in both block orders.
TEST(MemoryLayout, CompressedImageDecodesToTheLevels) {
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc3, TexelFormat::Bc7, TexelFormat::Astc5x4, TexelFormat::Astc6x6,
                        TexelFormat::Astc8x8, TexelFormat::Astc12x10})
    for (BlockOrder order : {BlockOrder::RowMajor, BlockOrder::Morton})
      for (Extent size : {Extent{64, 16}, Extent{12, 20}, Extent{100, 60}}) {
      // (ASTC: the stimulus's blocks, of every mode; random bytes would be the error colour)
      const Pyramid pyr = is_astc(f) ? stimulus::random_block_texture(f, size, 7 + uint64_t(f))
                                     : random_block_pyramid(f, size, 7 + uint64_t(f));
      const MemoryLayout l(size, 8, params(4, 4, order, 512), f);
      const std::vector<uint8_t> img = build_memory_image(pyr, l);
      ASSERT_EQ(img.size(), l.image_bytes());
      std::vector<std::vector<int>> seen;
      for (const Image& level : pyr.levels) seen.emplace_back(size_t(level.width) * level.height, 0);
      bool holes = false;  // a Morton grid that is not a power of two (also ASTC's seam copies)
      for (int k = 0; k < l.levels(); ++k)
        holes |= order == BlockOrder::Morton && (!is_power_of_two(int(l.blocks_x(k))) || !is_power_of_two(int(l.blocks_y(k))));
      for (uint32_t a = 512; a < 512 + l.image_bytes(); a += uint32_t(l.line_bytes())) {
        const bool line = decode_line(l, a, &img[a - 512], [&](int, int k, int x, int y, const Texel& t) {
          ++seen[size_t(k)][size_t(y) * pyr.levels[size_t(k)].width + size_t(x)];
          EXPECT_EQ(t, pyr.levels[size_t(k)].at(x, y)) << format_info(f).name << " level " << k << " (" << x << ", " << y << ")";
        });
        ASSERT_TRUE(line || holes) << a;
      }
      for (const auto& level : seen)
        for (int n : level) ASSERT_EQ(n, 1) << format_info(f).name;
    }
  Pyramid wrong = random_block_pyramid(TexelFormat::Bc1, {64, 16}, 1);
  EXPECT_THROW(build_memory_image(wrong, MemoryLayout({64, 16}, 8, LayoutParams{}, TexelFormat::Bc7)), Error);
}

// The repeat seam's copies (docs/memory.md §1): a level side that is not a power of two keeps texel
// column (row) 0 again after its last one, at seam_x (seam_y): the texels' own index for RGBA, the
// side rounded up to a 4x4 block for a block format, whose whole block column 0 is copied (no
// block is re-encoded). Powers of two have none, and their layout is what it always was.
TEST(MemoryLayout, NonPowerOfTwoLevelsKeepTheSeamCopies) {
  const Pyramid pyr = build_pyramid(numbered(5, 3), PyramidMode::Exact);
  const MemoryLayout l({5, 3}, 8, LayoutParams{});
  ASSERT_EQ(l.levels(), 3);  // 5x3, 2x1, 1x1
  EXPECT_EQ(l.seam_x(0), 5u);
  EXPECT_EQ(l.seam_y(0), 3u);
  EXPECT_EQ(l.blocks_x(0), 2u);  // texels 0..5 in 4-wide blocks
  EXPECT_EQ(l.blocks_y(0), 1u);  // rows 0..3
  EXPECT_EQ(l.stored_x(0, 5), 5u);
  const std::vector<uint8_t> img = build_memory_image(pyr, l);
  auto at = [&](int k, uint32_t x, uint32_t y) { return l.line_address(k, x, y) - l.params().base + l.texel_offset(x, y); };
  for (uint32_t y = 0; y < 3; ++y) expect_rgba8_at(img, at(0, 5, y), pyr.levels[0].at(0, int(y)));
  for (uint32_t x = 0; x < 5; ++x) expect_rgba8_at(img, at(0, x, 3), pyr.levels[0].at(int(x), 0));
  expect_rgba8_at(img, at(0, 5, 3), pyr.levels[0].at(0, 0));
  // Row-major with the pitch of the grid: 1000x600 in 4x4 blocks is 251 x 151 blocks (the seam
  // copies need the 1001st column and 601st row).
  const MemoryLayout big({1000, 600}, 8, LayoutParams{});
  EXPECT_EQ(big.blocks_x(0), 251u);
  EXPECT_EQ(big.blocks_y(0), 151u);
  EXPECT_EQ(big.block_index(0, 3, 2), 2u * 251 + 3);
  EXPECT_EQ(big.level_base(1), 251u * 151 * 64);
  // BC1, 12 x 8 (three 4x4 blocks a row, one 16x8 line): block column 0 copied to column 3.
  const Pyramid bc = random_block_pyramid(TexelFormat::Bc1, {12, 8}, 3);
  const MemoryLayout lb({12, 8}, 8, LayoutParams{}, TexelFormat::Bc1);
  EXPECT_EQ(lb.seam_x(0), 12u);
  EXPECT_EQ(lb.seam_y(0), 0u);  // 8: a power of two
  const std::vector<uint8_t> bimg = build_memory_image(bc, lb);
  auto bat = [&](int k, uint32_t x, uint32_t y) { return lb.line_address(k, x, y) - lb.params().base + lb.texel_offset(x, y); };
  for (uint32_t y = 0; y < 8; y += 4)
    for (int i = 0; i < 8; ++i) EXPECT_EQ(bimg[bat(0, 12, y) + size_t(i)], bimg[bat(0, 0, y) + size_t(i)]) << y << " " << i;
  // Level 1 (6 x 4: two blocks, seam at 8) and level 2 (3 x 2: one block, seam at 4).
  EXPECT_EQ(lb.seam_x(1), 8u);
  EXPECT_EQ(lb.seam_x(2), 4u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(bimg[bat(2, 4, 0) + size_t(i)], bimg[bat(2, 0, 0) + size_t(i)]) << i;
}


// ASTC (docs/memory.md §1): a 64-byte line holds 2 x 2 blocks of the footprint, so a line's texels
// need not be a power of two; the block of texel x is x / fw (a reciprocal multiply, exact for every
// x below 2^16). The repeat seam's copy: a side that is not a power of two, and a power-of-two side
// longer than a block that the footprint does not divide, keep block column (row) 0 again after the
// last, at the side rounded up to the footprint.
TEST(MemoryLayout, AstcLinesHoldTwoByTwoBlocksOfAnyFootprint) {
  const MemoryLayout l({64, 64}, 8, LayoutParams{}, TexelFormat::Astc6x5);
  EXPECT_EQ(l.block_w(), 12);
  EXPECT_EQ(l.block_h(), 10);
  EXPECT_EQ(l.line_x(11), 0u);
  EXPECT_EQ(l.line_x(12), 1u);
  EXPECT_EQ(l.line_y(29), 2u);
  EXPECT_EQ(l.texel_offset(7, 3), 1u * 16);        // block (1, 0) of its line
  EXPECT_EQ(l.texel_offset(13, 17), 2u * 16);      // block (2, 3): (0, 1) of line (1, 1)
  EXPECT_EQ(l.texel_in_block(13, 17), 1 + 6 * 2);  // (13 - 12, 17 - 15)
  for (uint32_t x = 0; x < 70000; ++x) ASSERT_EQ(l.block_column(x), x / 6) << x;
  for (uint32_t y = 0; y < 70000; ++y) ASSERT_EQ(l.block_row(y), y / 5) << y;
  // 64 = 10 blocks of 6 + 4: a seam copy at 66 (block column 11), the row spans 72 texels: 6 lines.
  EXPECT_EQ(l.seam_x(0), 66u);
  EXPECT_EQ(l.seam_y(0), 65u);  // 13 blocks of 5: the copy at 65
  EXPECT_EQ(l.blocks_x(0), 6u);
  EXPECT_EQ(l.blocks_y(0), 7u);  // rows 0..69
  // Level 4 (4 x 4): inside one block, no copy needed. Level 3 (8 x 8): past one block across.
  EXPECT_EQ(l.seam_x(4), 0u);
  EXPECT_EQ(l.seam_x(3), 12u);
  EXPECT_EQ(l.seam_y(3), 10u);
  // 4x4 and 8x8 divide every power-of-two side past a block: no copies, as BC's.
  const MemoryLayout a8({64, 64}, 8, LayoutParams{}, TexelFormat::Astc8x8);
  for (int k = 0; k < a8.levels(); ++k) EXPECT_EQ(a8.seam_x(k), 0u) << k;
  EXPECT_EQ(a8.block_w(), 16);
  // The copy holds block column 0's blocks, byte for byte.
  const Pyramid p = stimulus::random_block_texture(TexelFormat::Astc6x5, {64, 64}, 5);
  const std::vector<uint8_t> img = build_memory_image(p, l);
  auto at = [&](uint32_t x, uint32_t y) { return l.line_address(0, x, y) + l.texel_offset(x, y); };
  for (uint32_t y = 0; y < 64; y += 5)
    for (int i = 0; i < 16; ++i) ASSERT_EQ(img[at(66, y) + size_t(i)], img[at(0, y) + size_t(i)]) << y;
  for (int i = 0; i < 16; ++i) ASSERT_EQ(img[at(66, 65) + size_t(i)], img[at(0, 0) + size_t(i)]);
}

// A view (GL's base and max level) is a pyramid of its own: levels b..min(m, last) of the
// texture, with GL's sizes of level b's chain. Its layout placed where level b of the whole
// texture's layout starts gives every one of its levels at the address the whole layout gives
// level b + k (so a driver points a descriptor at level b), in both block orders, RGBA and BC1, of
// sizes powers of two and not. And the errors name the value.
TEST(MemoryLayout, AViewIsTheLayoutFromItsBaseLevel) {
  const Extent sizes[] = {{64, 8}, {100, 60}, {37, 5}, {1000, 600}, {7, 129}, {1, 33}};
  for (const Extent size : sizes)
    for (const BlockOrder order : {BlockOrder::RowMajor, BlockOrder::Morton})
      for (const TexelFormat format : {TexelFormat::Rgba8, TexelFormat::Bc1}) {
        LayoutParams params;
        params.order = order;
        params.base = 4096;
        const MemoryLayout whole(size, 8, params, format);
        for (int b = 0; b < whole.levels(); ++b)
          for (int m = b; m < whole.levels(); m += 2) {
            LayoutParams at = params;
            at.base = whole.level_base(b);
            const MemoryLayout view(whole.level_size(b), 8, at, format, m - b + 1);
            ASSERT_EQ(view.levels(), m - b + 1);
            for (int k = 0; k < view.levels(); ++k) {
              ASSERT_EQ(view.level_size(k), whole.level_size(b + k)) << size.w << "x" << size.h << " b" << b << " k" << k;
              ASSERT_EQ(view.level_base(k), whole.level_base(b + k)) << size.w << "x" << size.h << " b" << b << " k" << k;
              ASSERT_EQ(view.blocks_x(k), whole.blocks_x(b + k));
              ASSERT_EQ(view.seam_x(k), whole.seam_x(b + k));
            }
          }
      }
  EXPECT_THROW(MemoryLayout({100, 60}, 8, LayoutParams{}, TexelFormat::Rgba8, 8), Error);  // 7 levels
  try {
    MemoryLayout({100, 60}, 8, LayoutParams{}, TexelFormat::Rgba8, 9);
    ADD_FAILURE() << "9 levels of a 100x60 texture taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("9 levels"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 to 7"), std::string::npos) << e.what();
  }
}

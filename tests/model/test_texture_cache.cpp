// The two texture caches (docs/memory.md §2): reset state, true LRU, set index, which lines a
// sample needs, the lookup and miss order, statistics. Hand-worked cases first, then a brute-force
// reference written here from the specification (a list per set, most recent first) that must
// produce the same lookups and the same miss stream over random requests and configurations.
#include <gtest/gtest.h>

#include <algorithm>
#include <list>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "model/error.h"
#include "model/memory_layout.h"
#include "model/stages.h"
#include "model/texture_cache.h"

using namespace tex;

namespace {

using Misses = std::vector<uint32_t>;

// A request at (x, y) in level-0 texels (texel centres at i + 1/2) of a 2^lw x 2^lh texture.
Request at_texel(double x, double y, int lw, int lh, double lod = 0) {
  Request r;
  EXPECT_TRUE(to_coord_fixed(x / (1 << lw), r.u));
  EXPECT_TRUE(to_coord_fixed(y / (1 << lh), r.v));
  EXPECT_TRUE(to_lod_fixed(lod, r.lod));
  return r;
}
// The same on a texture of any size.
Request at_size(double x, double y, Extent e) {
  Request r;
  EXPECT_TRUE(to_coord_fixed(x / e.w, r.u));
  EXPECT_TRUE(to_coord_fixed(y / e.h, r.v));
  return r;
}

SamplerConfig filter(TexelFilter t, MipMode m, Wrap wu = Wrap::Repeat, Wrap wv = Wrap::Repeat) {
  SamplerConfig c;
  c.filter = {t, m};
  c.wrap_u = wu;
  c.wrap_v = wv;
  return c;
}
const SamplerConfig kPoint = filter(TexelFilter::Nearest, MipMode::None);
const SamplerConfig kBilinear = filter(TexelFilter::Linear, MipMode::None);
const SamplerConfig kTrilinear = filter(TexelFilter::Linear, MipMode::Linear);

// 64x64 RGBA8 in 4x4 row-major blocks: 16 blocks per row of level 0, 64-byte lines; level 1 at 16384.
const MemoryLayout k64 = MemoryLayout({64, 64}, 8, LayoutParams{});
uint32_t block0(int bx, int by) { return uint32_t(by * 16 + bx) * 64; }
uint32_t block1(int bx, int by) { return 16384 + uint32_t(by * 8 + bx) * 64; }

TextureCache cache64(int size, int ways, const SamplerConfig& cfg) { return TextureCache(k64, {size, ways}, cfg); }

void expect_way(const TextureCache& c, int cache, int set, int way, bool valid, uint32_t tag, int age) {
  const TextureCache::Way w = c.way(cache, set, way);
  EXPECT_EQ(w.valid, valid) << "cache " << cache << " set " << set << " way " << way;
  if (valid) {
    EXPECT_EQ(w.tag, tag) << "cache " << cache << " set " << set << " way " << way;
  }
  EXPECT_EQ(w.age, age) << "cache " << cache << " set " << set << " way " << way;
}

std::string cache_error(const MemoryLayout& l, CacheParams p) {
  try {
    TextureCache(l, p, SamplerConfig{});
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(TextureCache, ResetMakesEveryWayInvalidWithAgeEqualToItsNumber) {
  const TextureCache c = cache64(2048, 4, kPoint);  // 32 lines: 8 sets of 4
  EXPECT_EQ(c.sets(), 8);
  EXPECT_EQ(c.ways(), 4);
  for (int cache = 0; cache < 2; ++cache)
    for (int s = 0; s < 8; ++s)
      for (int w = 0; w < 4; ++w) expect_way(c, cache, s, w, false, 0, w);
}

TEST(TextureCache, SetIndexIsTheParitiesUnderAHashOfTheRest) {
  // 16 sets: k = 2, set = {(xh ^ reverse2(yh mod 4) ^ (yh >> 2)) mod 4, by & 1, bx & 1}.
  const TextureCache c = cache64(64 * 16, 1, kPoint);
  EXPECT_EQ(c.set_index(0, 0), 0);
  EXPECT_EQ(c.set_index(1, 0), 1);
  EXPECT_EQ(c.set_index(0, 1), 2);
  EXPECT_EQ(c.set_index(4, 0), 0b1000);  // xh 2
  EXPECT_EQ(c.set_index(0, 2), 0b1000);  // yh 01 reversed: 10
  EXPECT_EQ(c.set_index(3, 2), 0b1101);  // xh 01 ^ 10
  EXPECT_EQ(c.set_index(5, 7), 0b0111);  // xh 10 ^ yh 11 reversed 11 = 01; parities 11
  EXPECT_EQ(c.set_index(0, 8), 0b0100);  // yh 100: its bit 2 folds onto bit 0 of the hash
  EXPECT_EQ(c.set_index(8, 0), 0);       // xh 100: beyond 4 hash values
  const TextureCache four = cache64(64 * 4, 1, kPoint);  // 4 sets: k = 0, the parities alone
  EXPECT_EQ(four.set_index(6, 5), 0b10);
}

TEST(TextureCache, LruOnAFourWaySetWorkedByHand) {
  // 16 lines: 4 sets of 4 ways. Point sampling of level 0, row 0: blocks with even bx
  // are all in set 0 (4 sets: the set is the parities alone).
  TextureCache c = cache64(1024, 4, kPoint);
  ASSERT_EQ(c.sets(), 4);
  Misses misses;
  auto block = [&](int bx) { c.lookup(at_texel(bx * 4 + 0.5, 0.5, 6, 6), &misses); };
  // A B C D fill the set, ways 3, 2, 1, 0 (the oldest first).
  for (int bx : {0, 2, 4, 6}) block(bx);
  expect_way(c, 0, 0, 0, true, block0(6, 0), 0);
  expect_way(c, 0, 0, 1, true, block0(4, 0), 1);
  expect_way(c, 0, 0, 2, true, block0(2, 0), 2);
  expect_way(c, 0, 0, 3, true, block0(0, 0), 3);
  // A hits; E evicts B (the least recently used); B evicts C; A hits; C evicts D.
  block(0);
  expect_way(c, 0, 0, 3, true, block0(0, 0), 0);
  expect_way(c, 0, 0, 2, true, block0(2, 0), 3);
  for (int bx : {8, 2, 0, 4}) block(bx);
  EXPECT_EQ(misses, (Misses{0, 128, 256, 384, 512, 128, 256}));
  expect_way(c, 0, 0, 0, true, block0(4, 0), 0);
  expect_way(c, 0, 0, 1, true, block0(2, 0), 2);
  expect_way(c, 0, 0, 2, true, block0(8, 0), 3);
  expect_way(c, 0, 0, 3, true, block0(0, 0), 1);
  for (int s = 1; s < 4; ++s)
    for (int w = 0; w < 4; ++w) {
      expect_way(c, 0, s, w, false, 0, w);
      expect_way(c, 1, s, w, false, 0, w);
    }
  EXPECT_EQ(c.stats().lookups[0], 9u);
  EXPECT_EQ(c.stats().hits[0], 2u);
  EXPECT_EQ(c.stats().misses[0], 7u);
  EXPECT_EQ(c.stats().lookups[1], 0u);
  EXPECT_EQ(c.memory_read_bytes(), 7u * 64);
}

TEST(TextureCache, DirectMappedConflictsAndTheSquareWindowOfSets) {
  {
    TextureCache c = cache64(256, 1, kPoint);  // 4 sets of 1
    Misses misses;
    for (int i = 0; i < 6; ++i) c.lookup(at_texel((i % 2) * 8 + 1, 1, 6, 6), &misses);  // blocks 0 and 2: set 0
    EXPECT_EQ(misses, (Misses{0, 128, 0, 128, 0, 128}));
    for (int i = 0; i < 6; ++i) c.lookup(at_texel(1, (i % 2) * 8 + 1, 6, 6), &misses);  // (0, 0), (0, 2): set 0
    EXPECT_EQ(misses.size(), 12u);
    EXPECT_EQ(c.stats().total_hits(), 0u);
  }
  {
    TextureCache c = cache64(512, 2, kPoint);  // the same with 2 ways: two misses, then hits
    Misses misses;
    for (int i = 0; i < 6; ++i) c.lookup(at_texel((i % 2) * 8 + 1, 1, 6, 6), &misses);
    EXPECT_EQ(misses, (Misses{0, 128}));
  }
  {
    // 16 sets of 1: a 4x4 window of blocks fits, and so does a row of 8 blocks or a column of 8
    // aligned to 8 (a Morton index would give either only 4 sets); a row of 16 blocks does not.
    auto misses_of_two_passes = [](const std::vector<std::pair<int, int>>& blocks) {
      TextureCache c = cache64(1024, 1, kPoint);
      Misses misses;
      for (int pass = 0; pass < 2; ++pass)
        for (const auto& [bx, by] : blocks) c.lookup(at_texel(bx * 4 + 1, by * 4 + 1, 6, 6), &misses);
      return misses.size();
    };
    std::vector<std::pair<int, int>> window, row8, column8, row16;
    for (int by = 4; by < 8; ++by)
      for (int bx = 8; bx < 12; ++bx) window.emplace_back(bx, by);
    for (int i = 0; i < 8; ++i) row8.emplace_back(i, 5), column8.emplace_back(3, i + 8);
    for (int i = 0; i < 16; ++i) row16.emplace_back(i, 2);
    EXPECT_EQ(misses_of_two_passes(window), 16u);
    EXPECT_EQ(misses_of_two_passes(row8), 8u);
    EXPECT_EQ(misses_of_two_passes(column8), 8u);
    EXPECT_EQ(misses_of_two_passes(row16), 32u);
  }
}

TEST(TextureCache, FootprintStraddlingABlockCornerUsesFourSetsInParityOrder) {
  TextureCache c = cache64(256, 1, kBilinear);  // 4 sets of 1
  Misses misses;
  // (8, 4): taps x 7, 8 and y 3, 4, weights 1/2: blocks (1,0) (2,0) (1,1) (2,1). Parities
  // (2,0) 0, (1,0) 1, (2,1) 2, (1,1) 3; sets (4 sets: the parities) 0, 1, 2, 3.
  const SampleLookup l = c.lookup(at_texel(8, 4, 6, 6), &misses);
  EXPECT_EQ(l.slot[0].level, 0);
  EXPECT_TRUE(l.slot[0].needed);
  EXPECT_EQ(l.slot[0].blocks, 4);
  EXPECT_EQ(l.slot[0].misses, 4);
  EXPECT_EQ(l.slot[0].block_mask, 0xF);
  EXPECT_FALSE(l.slot[1].needed);
  EXPECT_EQ(l.slot[1].blocks, 0);
  EXPECT_EQ(misses, (Misses{block0(2, 0), block0(1, 0), block0(2, 1), block0(1, 1)}));
  expect_way(c, 0, 0, 0, true, block0(2, 0), 0);
  expect_way(c, 0, 1, 0, true, block0(1, 0), 0);
  expect_way(c, 0, 2, 0, true, block0(2, 1), 0);
  expect_way(c, 0, 3, 0, true, block0(1, 1), 0);
  // All four stay: the same sample again hits four times.
  const SampleLookup again = c.lookup(at_texel(8, 4, 6, 6), &misses);
  EXPECT_EQ(again.slot[0].blocks, 4);
  EXPECT_EQ(again.slot[0].misses, 0);
  EXPECT_EQ(misses.size(), 4u);
}

TEST(TextureCache, TapsOfWeightZeroAreNotLookedUp) {
  Misses misses;
  {
    TextureCache c = cache64(8192, 2, kPoint);
    // Point sampling next to a block corner: one texel, (3, 3), in block (0, 0).
    const SampleLookup a = c.lookup(at_texel(3.96875, 3.96875, 6, 6), &misses);
    EXPECT_EQ(a.slot[0].blocks, 1);
    EXPECT_EQ(a.slot[0].block_mask, 0x1);
    // Just past it: texel (4, 4), block (1, 1), parity 3.
    const SampleLookup b = c.lookup(at_texel(4, 4, 6, 6), &misses);
    EXPECT_EQ(b.slot[0].blocks, 1);
    EXPECT_EQ(b.slot[0].block_mask, 0x8);
    EXPECT_EQ(misses, (Misses{block0(0, 0), block0(1, 1)}));
  }
  misses.clear();
  {
    TextureCache c = cache64(8192, 2, kBilinear);
    // At a texel centre wx = wy = 0: only (x0, y0), texel (6, 5) of block (1, 1).
    const SampleLookup centre = c.lookup(at_texel(6.5, 5.5, 6, 6), &misses);
    EXPECT_EQ(centre.slot[0].blocks, 1);
    EXPECT_EQ(centre.slot[0].block_mask, 0x8);
    // wy = 0: taps x 3 and 4 in row 5: blocks (0, 1) and (1, 1).
    const SampleLookup row = c.lookup(at_texel(4, 5.5, 6, 6), &misses);
    EXPECT_EQ(row.slot[0].blocks, 2);
    EXPECT_EQ(row.slot[0].block_mask, 0xC);
    // wx = 0: taps y 3 and 4 in column 6: blocks (1, 0) and (1, 1).
    const SampleLookup col = c.lookup(at_texel(6.5, 4, 6, 6), &misses);
    EXPECT_EQ(col.slot[0].blocks, 2);
    EXPECT_EQ(col.slot[0].block_mask, 0xA);
    EXPECT_EQ(misses, (Misses{block0(1, 1), block0(0, 1), block0(1, 0)}));
  }
}

TEST(TextureCache, TrilinearWithFZeroDoesNotTouchTheNextLevel) {
  TextureCache c = cache64(8192, 2, kTrilinear);
  Misses misses;
  // lod 1: d = 1, f = 0. (9, 9) is texel centre (4.5, 4.5) of level 1: texel (4, 4), block (1, 1).
  const SampleLookup whole = c.lookup(at_texel(9, 9, 6, 6, 1.0), &misses);
  EXPECT_EQ(whole.slot[0].level, 1);
  EXPECT_EQ(whole.slot[0].blocks, 1);
  EXPECT_FALSE(whole.slot[1].needed);
  EXPECT_EQ(whole.slot[1].blocks, 0);
  EXPECT_EQ(misses, (Misses{block1(1, 1)}));
  EXPECT_EQ(c.stats().lookups[0], 0u);
  EXPECT_EQ(c.stats().lookups[1], 1u);
  // lod 1.5: f = 128, d1 = 2 (16x16 at 20480): (2.25, 2.25) there, taps 1 and 2: block (0, 0).
  const SampleLookup half = c.lookup(at_texel(9, 9, 6, 6, 1.5), &misses);
  EXPECT_TRUE(half.slot[1].needed);
  EXPECT_EQ(half.slot[1].level, 2);
  EXPECT_EQ(half.slot[0].misses, 0);
  EXPECT_EQ(half.slot[1].blocks, 1);
  EXPECT_EQ(half.slot[1].misses, 1);
  EXPECT_EQ(misses, (Misses{block1(1, 1), 20480}));
  EXPECT_EQ(c.stats().lookups[0], 1u);
  // Mip nearest and no mip never read a second level.
  TextureCache n = cache64(8192, 2, filter(TexelFilter::Linear, MipMode::Nearest));
  EXPECT_FALSE(n.lookup(at_texel(9, 9, 6, 6, 1.25), &misses).slot[1].needed);
}

TEST(TextureCache, MissOrderIsLevelDThenD1EachInParityOrder) {
  TextureCache c = cache64(8192, 2, kTrilinear);
  Misses misses;
  // lod 0.5 at (8, 8): level 0 taps 7, 8 (blocks 1, 2 on both axes); level 1 at (4, 4): taps 3, 4
  // (blocks 0, 1).
  const SampleLookup l = c.lookup(at_texel(8, 8, 6, 6, 0.5), &misses);
  EXPECT_EQ(l.slot[0].misses, 4);
  EXPECT_EQ(l.slot[1].misses, 4);
  EXPECT_EQ(misses, (Misses{block0(2, 2), block0(1, 2), block0(2, 1), block0(1, 1),  //
                            block1(0, 0), block1(1, 0), block1(0, 1), block1(1, 1)}));
  EXPECT_EQ(c.stats().misses[0], 4u);
  EXPECT_EQ(c.stats().misses[1], 4u);
}

TEST(TextureCache, WrapAtTheEdgesStraddlesTheLastAndFirstBlockColumns) {
  const MemoryLayout l({16, 16}, 8, LayoutParams{});  // 16x16: 4 block columns
  auto run = [&](Wrap wu, Wrap wv, double x, double y) {
    TextureCache c(l, {4096, 1}, filter(TexelFilter::Linear, MipMode::None, wu, wv));
    Misses misses;
    c.lookup(at_texel(x, y, 4, 4), &misses);
    return misses;
  };
  // u = 1: taps x 15 and 16. Repeat: 16 -> 0, block column 0 (parity 0) before column 3.
  EXPECT_EQ(run(Wrap::Repeat, Wrap::Repeat, 16, 2.5), (Misses{0, 3 * 64}));
  EXPECT_EQ(run(Wrap::Clamp, Wrap::Repeat, 16, 2.5), (Misses{3 * 64}));   // 16 -> 15
  EXPECT_EQ(run(Wrap::Mirror, Wrap::Repeat, 16, 2.5), (Misses{3 * 64}));  // 16 -> 15
  // u = 0: taps -1 and 0.
  EXPECT_EQ(run(Wrap::Repeat, Wrap::Repeat, 0, 2.5), (Misses{0, 3 * 64}));
  EXPECT_EQ(run(Wrap::Mirror, Wrap::Repeat, 0, 2.5), (Misses{0}));  // -1 -> 0
  // The same down the side: rows 15 and 0.
  EXPECT_EQ(run(Wrap::Repeat, Wrap::Repeat, 2.5, 16), (Misses{0, 3 * 4 * 64}));
  EXPECT_EQ(run(Wrap::Repeat, Wrap::Clamp, 2.5, 16), (Misses{3 * 4 * 64}));
  // Clamp to border: a tap outside the level reads no line; mirror clamp to edge: -1 -> 0, 16 -> 15.
  EXPECT_EQ(run(Wrap::Border, Wrap::Repeat, 16, 2.5), (Misses{3 * 64}));
  EXPECT_EQ(run(Wrap::Border, Wrap::Repeat, 0, 2.5), (Misses{0}));
  EXPECT_EQ(run(Wrap::Border, Wrap::Border, 0, 0), (Misses{0}));  // three of the four taps outside
  EXPECT_EQ(run(Wrap::Border, Wrap::Repeat, -8, 2.5), (Misses{}));  // the whole footprint outside
  EXPECT_EQ(run(Wrap::MirrorClamp, Wrap::Repeat, 16, 2.5), (Misses{3 * 64}));
  EXPECT_EQ(run(Wrap::MirrorClamp, Wrap::Repeat, 0, 2.5), (Misses{0}));
  EXPECT_EQ(run(Wrap::MirrorClamp, Wrap::Repeat, -20, 2.5), (Misses{3 * 64}));  // mirrored once, then clamped
}

// The repeat seam of a side that is not a power of two: 12 texels in 4-wide blocks is 3 block
// columns (0, 1, 2), and taps 11 and 0 would be block columns 2 and 0, both even: one set group
// asked for two lines. The second tap reads texel 0's copy at column 12, block column 3 (odd).
TEST(TextureCache, NonPowerOfTwoRepeatSeamReadsTheCopyColumn) {
  const MemoryLayout l({12, 16}, 8, LayoutParams{});
  ASSERT_EQ(l.blocks_x(0), 4u);  // 13 texel columns
  TextureCache c(l, {4096, 1}, filter(TexelFilter::Linear, MipMode::None));
  Misses misses;
  c.lookup(at_size(12, 2.5, {12, 16}), &misses);  // u = 1: taps 11 and 12 (the copy)
  EXPECT_EQ(misses, (Misses{2 * 64, 3 * 64}));     // block columns 2 (parity 0) and 3 (parity 1)
  misses.clear();
  c.lookup(at_size(0, 2.5, {12, 16}), &misses);  // u = 0: taps -1 -> 11 and 0 -> the copy at 12
  EXPECT_EQ(misses, (Misses{}));                 // the same two lines
}

// Random footprints on sides that are not powers of two (odd, primes, 1xN), every address mode,
// RGBA and block formats, both orders and every block shape: no two distinct blocks of one level's
// footprint share a parity (TextureCache::lookup throws std::logic_error if they do).
TEST(TextureCache, NonPowerOfTwoFootprintsNeverShareAParity) {
  std::mt19937_64 rng(39);
  const Extent sizes[] = {{5, 3}, {7, 1}, {1, 9}, {12, 20}, {100, 60}, {1000, 600}, {127, 31}};
  const int shapes[][2] = {{4, 4}, {2, 2}, {8, 4}, {2, 8}};
  size_t probes = 0;
  for (const Extent& e : sizes)
    for (TexelFormat f : {TexelFormat::Rgba8, TexelFormat::Bc1, TexelFormat::Bc7})
      for (const auto& sh : shapes) {
        if (f != TexelFormat::Rgba8 && (e.w % 4 || e.h % 4 || sh[0] * sh[1] < 16)) continue;
        LayoutParams lp;
        lp.block_w = sh[0];
        lp.block_h = sh[1];
        lp.order = rng() & 1 ? BlockOrder::Morton : BlockOrder::RowMajor;
        const MemoryLayout l(e, 8, lp, f);
        for (Wrap wu : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp})
          for (Wrap wv : {Wrap::Repeat, Wrap::Mirror, Wrap::MirrorClamp}) {
            TextureCache c(l, {4096, 2}, filter(TexelFilter::Linear, MipMode::Linear, wu, wv));
            for (int i = 0; i < 200; ++i) {
              Request r;
              r.u = int32_t(int64_t(rng() % (6u << 24)) - (3 << 24));
              r.v = int32_t(int64_t(rng() % (6u << 24)) - (3 << 24));
              r.lod = int32_t(rng() % uint64_t(256 * (l.levels() + 1)));
              ASSERT_NO_THROW(c.lookup(r, nullptr)) << e.w << "x" << e.h << " " << format_info(f).name << " " << sh[0]
                                                    << "x" << sh[1] << " u " << r.u << " v " << r.v << " lod " << r.lod;
              ++probes;
            }
          }
      }
  EXPECT_GT(probes, 100000u);
}

// ASTC footprints (docs/memory.md §1): the taps of a level's 2x2 footprint, after the address mode
// (the repeat seam's second tap at the copy where the layout keeps one), read at most 4 blocks of
// 4 different block parities (the cached unit's data banks) in at most 4 lines of 4 different line
// parities (its set groups), for every footprint, sides powers of two and not, every address
// mode. Checked from the stages and the layout, not through the cache (which checks the line rule).
TEST(TextureCache, AstcFootprintsReadFourBanksAndFourSetGroups) {
  std::mt19937_64 rng(41);
  const Extent sizes[] = {{32, 32}, {64, 16}, {128, 2}, {1, 64}, {100, 60}, {13, 7}, {256, 256}};
  size_t checked = 0;
  for (int fi = 0; fi < 14; ++fi) {
    const TexelFormat f = TexelFormat(int(TexelFormat::Astc4x4) + fi);
    for (const Extent& e : sizes) {
      LayoutParams lp;
      lp.order = rng() & 1 ? BlockOrder::Morton : BlockOrder::RowMajor;
      const MemoryLayout l(e, 8, lp, f);
      for (Wrap w : {Wrap::Repeat, Wrap::Mirror, Wrap::Clamp, Wrap::MirrorClamp})
        for (int k = 0; k < l.levels(); ++k) {
          const Extent s = level_extent(e, k);
          for (int i = 0; i < 64; ++i) {
            const int32_t ru = int32_t(rng() % (4u << 24)) - (2 << 24), rv = int32_t(rng() % (4u << 24)) - (2 << 24);
            const stage::WrappedTaps tu = stage::axis_taps(ru, s.w, w, TexelFilter::Linear, false, l.seam_x(k) != 0);
            const stage::WrappedTaps tv = stage::axis_taps(rv, s.h, w, TexelFilter::Linear, false, l.seam_y(k) != 0);
            const uint32_t xs[2] = {l.stored_x(k, uint32_t(tu.i0)), l.stored_x(k, uint32_t(tu.i1))};
            const uint32_t ys[2] = {l.stored_y(k, uint32_t(tv.i0)), l.stored_y(k, uint32_t(tv.i1))};
            uint32_t block_at[4][2], line_at[4][2];
            bool block_used[4] = {}, line_used[4] = {};
            for (uint32_t x : xs)
              for (uint32_t y : ys) {
                const uint32_t bx = l.block_column(x), by = l.block_row(y), lx = l.line_x(x), ly = l.line_y(y);
                const int bp = int((by & 1) << 1 | (bx & 1)), lp2 = int((ly & 1) << 1 | (lx & 1));
                ASSERT_TRUE(!block_used[bp] || (block_at[bp][0] == bx && block_at[bp][1] == by))
                    << format_info(f).name << " " << e.w << "x" << e.h << " level " << k << " " << wrap_name(w)
                    << ": two blocks of bank " << bp << " (taps " << tu.i0 << ", " << tu.i1 << " / " << tv.i0 << ", " << tv.i1 << ")";
                ASSERT_TRUE(!line_used[lp2] || (line_at[lp2][0] == lx && line_at[lp2][1] == ly))
                    << format_info(f).name << " " << e.w << "x" << e.h << " level " << k << " " << wrap_name(w)
                    << ": two lines of parity " << lp2;
                block_used[bp] = line_used[lp2] = true;
                block_at[bp][0] = bx;
                block_at[bp][1] = by;
                line_at[lp2][0] = lx;
                line_at[lp2][1] = ly;
                ++checked;
              }
          }
        }
      // And the cache itself takes them.
      TextureCache c(l, {4096, 2}, filter(TexelFilter::Linear, MipMode::Linear, Wrap::Repeat, Wrap::Mirror));
      for (int i = 0; i < 500; ++i) {
        Request r;
        r.u = int32_t(int64_t(rng() % (6u << 24)) - (3 << 24));
        r.v = int32_t(int64_t(rng() % (6u << 24)) - (3 << 24));
        r.lod = int32_t(rng() % uint64_t(256 * (l.levels() + 1)));
        ASSERT_NO_THROW(c.lookup(r, nullptr)) << format_info(f).name << " " << e.w << "x" << e.h;
      }
    }
  }
  EXPECT_GT(checked, 500000u);
}

// The sampler table: each request's sampler (Request::sampler) gives its address modes, so one
// texture read through two samplers reads other lines at the same coordinates; a request naming a
// sampler beyond the table is an error.
TEST(TextureCache, EachRequestUsesTheSamplerItNames) {
  const MemoryLayout l({16, 16}, 8, LayoutParams{});  // 16x16: 4 block columns
  TextureCache c({TextureDescriptor{l}}, {4096, 1},
                 SamplerTable{filter(TexelFilter::Linear, MipMode::None, Wrap::Repeat, Wrap::Repeat),
                              filter(TexelFilter::Linear, MipMode::None, Wrap::Border, Wrap::Repeat)});
  Request r = at_texel(16, 2.5, 4, 4);  // u = 1: taps x 15 and 16
  Misses misses;
  c.lookup(r, &misses);
  EXPECT_EQ(misses, (Misses{0, 3 * 64}));  // sampler 0, repeat: 16 -> 0
  r.u = at_texel(0, 2.5, 4, 4).u;          // u = 0: taps -1 and 0, block columns 3 and 0 cached now
  r.sampler = 1;                           // border: -1 reads nothing, 0 hits
  misses.clear();
  EXPECT_EQ(c.lookup(r, &misses).slot[0].blocks, 1);
  EXPECT_EQ(misses, Misses{});
  r.sampler = 2;
  EXPECT_THROW(c.lookup(r, &misses), Error);
  EXPECT_THROW(TextureCache({TextureDescriptor{l}}, {4096, 1}, SamplerTable{}), Error);
  EXPECT_THROW(TextureCache({TextureDescriptor{l}}, {4096, 1}, SamplerTable(kMaxSamplers + 1)), Error);
}

TEST(TextureCache, ASecondPassOverASmallTextureNeverMisses) {
  // 32x32 in 4x4 blocks: levels of 8x8, 4x4, 2x2, 1, 1, 1 blocks = 87 lines, none evicted (the
  // even levels' 64 + 4 + 1 lines fall at most 3 to a set of 4 ways).
  const MemoryLayout l({32, 32}, 8, LayoutParams{});
  TextureCache c(l, {32768, 4}, kTrilinear);
  std::vector<Request> rs;
  for (int lod = 0; lod <= 5; ++lod)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) rs.push_back(at_texel(x + 0.25, y + 0.25, 5, 5, lod));
  Misses misses;
  for (const Request& r : rs) c.lookup(r, &misses);
  EXPECT_EQ(misses.size(), 87u);
  EXPECT_EQ(std::set<uint32_t>(misses.begin(), misses.end()).size(), 87u);
  EXPECT_EQ(c.memory_read_bytes(), 87u * 64);
  c.reset_stats();
  EXPECT_EQ(c.stats().total_lookups(), 0u);
  EXPECT_EQ(c.memory_read_bytes(), 0u);
  for (const Request& r : rs) c.lookup(r, &misses);
  EXPECT_EQ(misses.size(), 87u);
  EXPECT_EQ(c.stats().total_misses(), 0u);
  EXPECT_EQ(c.stats().total_hits(), c.stats().total_lookups());
  EXPECT_GE(c.stats().total_lookups(), rs.size());
}

TEST(TextureCache, CountsEvictionsOfTheLinesThePreviousSampleUsed) {
  TextureCache c = cache64(256, 1, kPoint);  // 4 sets of 1
  c.lookup(at_texel(1, 1, 6, 6), nullptr);   // block (0, 0), set 0
  c.lookup(at_texel(9, 1, 6, 6), nullptr);   // block (2, 0), set 0: evicts the previous sample's line
  EXPECT_EQ(c.stats().evictions_of_previous, 1u);
  c.lookup(at_texel(5, 1, 6, 6), nullptr);   // block (1, 0), set 1 (empty)
  c.lookup(at_texel(1, 1, 6, 6), nullptr);   // set 0 again: evicts (2, 0), used two samples ago
  EXPECT_EQ(c.stats().evictions_of_previous, 1u);
  EXPECT_EQ(c.stats().total_misses(), 4u);
}

TEST(TextureCache, GeometryTheHardwareCannotHaveIsAnError) {
  const MemoryLayout l({32, 32}, 8, LayoutParams{});  // 64-byte lines
  EXPECT_NE(cache_error(l, {8192, 3}).find("ways 3"), std::string::npos);
  EXPECT_NE(cache_error(l, {8192, 8}).find("ways 8"), std::string::npos);
  EXPECT_NE(cache_error(l, {100, 1}).find("100"), std::string::npos);
  EXPECT_NE(cache_error(l, {3 * 64 * 4, 1}).find("12 sets"), std::string::npos);
  EXPECT_NE(cache_error(l, {128, 1}).find("2 sets"), std::string::npos);
  EXPECT_NE(cache_error(l, {512, 4}).find("2 sets"), std::string::npos);  // 8 lines in 4 ways: too few
  EXPECT_EQ(cache_error(l, {1024, 4}), "(no error)");
  EXPECT_EQ(cache_error(l, {1024, 2}), "(no error)");
  const MemoryLayout wide({32, 32}, 16, LayoutParams{});  // 128-byte lines: 8 KiB is fine, 8 KiB + 64 is not
  EXPECT_EQ(cache_error(wide, {8192, 4}), "(no error)");
  EXPECT_NE(cache_error(wide, {8192 + 64, 4}).find("8256"), std::string::npos);
}

// ---------------------------------------------------------------- brute-force reference

namespace {

// docs/memory.md §1 and §2 written out the plain way.
class Reference {
 public:
  struct Slot {
    int level = 0;
    bool needed = false;
    int blocks = 0, misses = 0;
    int mask = 0;
  };

  Reference(int lw, int lh, int bits, const LayoutParams& p, const CacheParams& c, const SamplerConfig& cfg)
      : lw_(lw), lh_(lh), p_(p), cfg_(cfg), ways_(c.ways) {
    line_ = size_t(p.block_w * p.block_h * (bits > 8 ? 8 : 4));
    sets_ = int(size_t(c.size_bytes) / line_ / size_t(c.ways));
    uint64_t at = p.base;
    for (int k = 0; k <= std::max(lw, lh); ++k) {
      const int w = std::max(1, (1 << lw) >> k), h = std::max(1, (1 << lh) >> k);
      nbx_.push_back(std::max(w / p.block_w, 1));
      nby_.push_back(std::max(h / p.block_h, 1));
      base_.push_back(at);
      at += uint64_t(nbx_.back() * nby_.back()) * line_;
    }
  }

  uint32_t address(int k, int bx, int by) const {
    uint64_t index = uint64_t(by) * uint64_t(nbx_[size_t(k)]) + uint64_t(bx);
    if (p_.order == BlockOrder::Morton) {
      int m = 0;
      while ((2 << m) <= nbx_[size_t(k)] && (2 << m) <= nby_[size_t(k)]) ++m;
      index = morton(bx & ((1 << m) - 1), by & ((1 << m) - 1)) + (uint64_t((bx >> m) + (by >> m)) << (2 * m));
    }
    return uint32_t(base_[size_t(k)] + index * line_);
  }
  static uint64_t morton(int bx, int by) {
    uint64_t code = 0;
    for (int i = 0; i < 16; ++i) code |= uint64_t((bx >> i) & 1) << (2 * i) | uint64_t((by >> i) & 1) << (2 * i + 1);
    return code;
  }

  // docs/memory.md §2: parities in bits 1..0, above them k = log2(sets / 4) bits of
  // x/2 XOR (y/2 with its low k bits in reverse order) XOR (y/2 shifted down by k).
  int set_of(int bx, int by) const {
    int k = 0;
    while ((4 << k) < sets_) ++k;
    const int xh = bx / 2, yh = by / 2;
    int reversed = 0;
    for (int i = 0; i < k; ++i) reversed = reversed * 2 + ((yh >> i) & 1);
    const int hash = (xh ^ reversed ^ (yh >> k)) % (1 << k);
    return hash * 4 + (by % 2) * 2 + bx % 2;
  }

  // Returns false (with a message) if two distinct blocks of a footprint share a parity.
  bool lookup(const Request& r, Slot out[2], Misses& misses, std::string& why) {
    const int last = std::max(lw_, lh_);
    const stage::LevelSelect sel = stage::lod(r.lod, cfg_.lod_bias, cfg_.min_lod, cfg_.max_lod, cfg_.filter.mip, last);
    const int32_t ru = stage::reduce(r.u, cfg_.wrap_u), rv = stage::reduce(r.v, cfg_.wrap_v);
    const TexelFilter tf = sel.magnify ? cfg_.filter.mag : cfg_.filter.texel;
    const bool linear = tf == TexelFilter::Linear;
    for (int s = 0; s < 2; ++s) {
      Slot& o = out[s];
      o = Slot{};
      o.level = s == 0 ? sel.d : sel.d1;
      o.needed = s == 0 || sel.f != 0;
      if (!o.needed) continue;
      const int k = o.level;
      const int nw = 1 << std::max(lw_ - k, 0), nh = 1 << std::max(lh_ - k, 0);
      const stage::AxisTaps tu = stage::address(stage::scale(ru, nw), tf);
      const stage::AxisTaps tv = stage::address(stage::scale(rv, nh), tf);
      const int x0 = stage::wrap(tu.i0, nw, cfg_.wrap_u), x1 = stage::wrap(tu.i1, nw, cfg_.wrap_u, true);
      const int y0 = stage::wrap(tv.i0, nh, cfg_.wrap_v), y1 = stage::wrap(tv.i1, nh, cfg_.wrap_v, true);
      std::vector<std::pair<int, int>> taps = {{x0, y0}};
      if (linear && tu.w != 0) taps.push_back({x1, y0});
      if (linear && tv.w != 0) taps.push_back({x0, y1});
      if (linear && tu.w != 0 && tv.w != 0) taps.push_back({x1, y1});
      std::set<std::pair<int, int>> distinct;
      for (const auto& [x, y] : taps)
        if (x >= 0 && y >= 0) distinct.insert({x / p_.block_w, y / p_.block_h});  // (a border tap reads nothing)
      std::vector<std::pair<int, int>> blocks(distinct.begin(), distinct.end());
      auto parity = [](const std::pair<int, int>& b) { return (b.second & 1) * 2 + (b.first & 1); };
      std::sort(blocks.begin(), blocks.end(), [&](const auto& a, const auto& b) { return parity(a) < parity(b); });
      for (size_t i = 1; i < blocks.size(); ++i)
        if (parity(blocks[i]) == parity(blocks[i - 1])) {
          why = "two blocks of one footprint with the same parity";
          return false;
        }
      for (const auto& b : blocks) {
        ++o.blocks;
        o.mask |= 1 << parity(b);
        const uint32_t a = address(k, b.first, b.second);
        std::list<uint32_t>& set = sets_lru_[{k % 2, set_of(b.first, b.second)}];
        const auto it = std::find(set.begin(), set.end(), a);
        if (it != set.end()) {
          set.splice(set.begin(), set, it);
        } else {
          ++o.misses;
          misses.push_back(a);
          set.push_front(a);
          if (int(set.size()) > ways_) set.pop_back();
        }
      }
    }
    return true;
  }

 private:
  int lw_, lh_;
  LayoutParams p_;
  SamplerConfig cfg_;
  int ways_, sets_;
  size_t line_;
  std::vector<int> nbx_, nby_;
  std::vector<uint64_t> base_;
  std::map<std::pair<int, int>, std::list<uint32_t>> sets_lru_;  // (cache, set): lines, most recent first
};

// Requests that wander (hits), jump (misses), and land on texel centres, block edges and whole
// lods (taps and levels of weight 0).
class RequestMaker {
 public:
  RequestMaker(int lw, int lh, uint64_t seed) : lw_(lw), lh_(lh), rng_(seed) {}
  Request next() {
    const int last = std::max(lw_, lh_);
    Request r = prev_;
    switch (pick(0, 3)) {
      case 0:
      case 1:  // a step of up to 2 texels of level 0 and a little lod
        r.u = std::clamp(r.u + pick(-(2 << (24 - lw_)), 2 << (24 - lw_)), -(3 << 24), 3 << 24);
        r.v = std::clamp(r.v + pick(-(2 << (24 - lh_)), 2 << (24 - lh_)), -(3 << 24), 3 << 24);
        r.lod = std::clamp(r.lod + pick(-48, 48), -512, (last + 1) * 256);
        break;
      case 2:  // anywhere
        r.u = pick(-(2 << 24), 3 << 24);
        r.v = pick(-(2 << 24), 3 << 24);
        r.lod = pick(-512, (last + 1) * 256);
        break;
      default: {  // a texel centre or edge of a level, at that level's whole lod or not
        const int k = pick(0, last);
        r.u = on_grid(lw_, k);
        r.v = on_grid(lh_, k);
        r.lod = pick(0, 2) ? k * 256 : pick(-256, (last + 1) * 256);
      }
    }
    prev_ = r;
    return r;
  }
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

 private:
  // u at texel i's centre or left edge of level k (i from 2 before the level to 2 past it).
  int32_t on_grid(int log2_size, int k) {
    const int n = 1 << std::max(log2_size - k, 0);
    const int i = pick(-2, n + 1);
    const int shift = 23 - log2_size + k;  // half a texel of level k in Q8.24
    return pick(0, 1) ? (2 * i + 1) * (1 << shift) : 2 * i * (1 << shift);
  }
  int lw_, lh_;
  std::mt19937_64 rng_;
  Request prev_;
};

}  // namespace

TEST(TextureCache, AgreesWithABruteForceReferenceOnRandomRequests) {
  struct Config {
    int lw, lh, ways, bw, bh;
    BlockOrder order;
    int bits;
  };
  const Config configs[] = {
      {6, 6, 1, 4, 4, BlockOrder::RowMajor, 8},  {7, 4, 2, 8, 2, BlockOrder::RowMajor, 8},
      {4, 7, 4, 4, 4, BlockOrder::Morton, 8},    {5, 5, 1, 8, 2, BlockOrder::Morton, 8},
      {8, 3, 2, 4, 4, BlockOrder::RowMajor, 16}, {3, 6, 4, 8, 2, BlockOrder::RowMajor, 16},
      {6, 2, 1, 4, 4, BlockOrder::Morton, 16},   {2, 2, 2, 8, 2, BlockOrder::Morton, 16},
  };
  const TexelFilter texels[] = {TexelFilter::Nearest, TexelFilter::Linear};
  const MipMode mips[] = {MipMode::None, MipMode::Nearest, MipMode::Linear};
  const Wrap wraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};
  constexpr int kRequestsPerConfig = 100000;
  uint64_t total_misses = 0, total_lookups = 0;
  int run = 0;
  for (const Config& cf : configs) {
    for (int fi = 0; fi < 6; ++fi, ++run) {
      RequestMaker maker(cf.lw, cf.lh, 1000 + uint64_t(run));
      SamplerConfig cfg = filter(texels[fi % 2], mips[fi / 2], wraps[run % 5], wraps[(run / 5) % 5]);
      if (maker.pick(0, 2) == 0) cfg.filter.mag = texels[1 - fi % 2];  // a magnification filter of its own
      if (maker.pick(0, 3) == 0) {  // bias and lod clamps now and then
        cfg.lod_bias = maker.pick(-256, 256);
        cfg.min_lod = maker.pick(-256, 256);
        cfg.max_lod = cfg.min_lod + maker.pick(0, 1024);
      }
      const int line = cf.bw * cf.bh * (cf.bits > 8 ? 8 : 4);
      LayoutParams lp;
      lp.block_w = cf.bw;
      lp.block_h = cf.bh;
      lp.order = cf.order;
      lp.base = uint32_t(line * maker.pick(0, 4096));
      const CacheParams cp{line * cf.ways * (4 << maker.pick(0, 2)), cf.ways};
      const std::string name = std::to_string(1 << cf.lw) + "x" + std::to_string(1 << cf.lh) + " cw" +
                               std::to_string(cf.bits) + " block " + std::to_string(cf.bw) + "x" +
                               std::to_string(cf.bh) + " " + block_order_name(cf.order) + ", " +
                               std::to_string(cp.size_bytes) + " B x " + std::to_string(cf.ways) + " ways, " +
                               filter_name(cfg.filter) + " " + wrap_name(cfg.wrap_u) + "/" + wrap_name(cfg.wrap_v);
      SCOPED_TRACE(name);
      TextureCache cache(MemoryLayout({1 << cf.lw, 1 << cf.lh}, cf.bits, lp), cp, cfg);
      Reference ref(cf.lw, cf.lh, cf.bits, lp, cp, cfg);
      Misses got, want;
      uint64_t misses = 0;
      const int n = kRequestsPerConfig / 6 + (fi < kRequestsPerConfig % 6 ? 1 : 0);
      for (int i = 0; i < n; ++i) {
        const Request r = maker.next();
        got.clear();
        want.clear();
        const SampleLookup l = cache.lookup(r, &got);
        Reference::Slot s[2];
        std::string why;
        ASSERT_TRUE(ref.lookup(r, s, want, why)) << why << " at request " << i;
        for (size_t j = 0; j < 2; ++j) {
          const SlotLookup& g = l.slot[j];
          ASSERT_EQ(g.level, s[j].level) << "request " << i << " slot " << j;
          ASSERT_EQ(g.needed, s[j].needed) << "request " << i << " slot " << j;
          ASSERT_EQ(g.blocks, s[j].blocks) << "request " << i << " slot " << j;
          ASSERT_EQ(g.misses, s[j].misses) << "request " << i << " slot " << j;
          ASSERT_EQ(int(g.block_mask), s[j].mask) << "request " << i << " slot " << j;
        }
        ASSERT_EQ(got, want) << "miss stream, request " << i;
        misses += want.size();
      }
      const CacheStats& st = cache.stats();
      EXPECT_EQ(st.total_misses(), misses);
      EXPECT_EQ(st.total_hits() + st.total_misses(), st.total_lookups());
      EXPECT_EQ(cache.memory_read_bytes(), misses * uint64_t(line));
      // Neither all hits nor all misses: the run exercised the replacement.
      EXPECT_GT(st.total_hits(), 0u);
      EXPECT_GT(st.total_misses(), 0u);
      total_misses += st.total_misses();
      total_lookups += st.total_lookups();
    }
  }
  EXPECT_GT(total_lookups, 2 * total_misses);
}

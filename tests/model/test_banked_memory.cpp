// Banked memory (docs/numerics.md stage 4) and the paper's cost per sample: reads, banks, multiplies.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <stdexcept>

#include "model/banked_memory.h"
#include "model/image.h"
#include "model/sampler.h"

using namespace tex;

namespace {

Request request(double u, double v, double lambda) {
  Request r;
  EXPECT_TRUE(to_coord_fixed(u, r.u) && to_coord_fixed(v, r.v) && to_lod_fixed(lambda, r.lod));
  return r;
}

struct Cost {
  uint64_t reads = 0, multiplies = 0;
  std::set<std::pair<int, int>> level_banks;  // (level, bank) pairs read
};

Cost cost_of_one_sample(Sampler& s, const Request& r) {
  s.reset_stats();
  s.sample(r);
  const SamplerStats st = s.stats();
  Cost c;
  c.reads = st.memory.reads;
  c.multiplies = st.multiplies_per_channel;
  for (size_t k = 0; k < st.memory.bank_reads.size(); ++k)
    for (int b = 0; b < 4; ++b) {
      EXPECT_LE(st.memory.bank_reads[k][b], 1u) << "a bank read twice in one sample";
      if (st.memory.bank_reads[k][b]) c.level_banks.insert({int(k), b});
    }
  return c;
}

}  // namespace

TEST(BankedMemory, TrilinearInteriorIs8ReadsIn8BanksAnd7Multiplies) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 1024, 1024));
  for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror}) {
    Sampler s(pyr, {{TexelFilter::Linear, MipMode::Linear}, w, w});
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> uv(0.05, 0.95), lod(0.01, 5.99);  // levels 1024..16: footprints inside the texture
    for (int i = 0; i < 5000; ++i) {
      const Cost c = cost_of_one_sample(s, request(uv(rng), uv(rng), lod(rng)));
      ASSERT_EQ(c.reads, 8u);
      ASSERT_EQ(c.level_banks.size(), 8u);
      ASSERT_EQ(c.multiplies, 7u);
    }
  }
}

TEST(BankedMemory, BilinearIs4ReadsAnd3MultipliesPointIs1Read) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 1024, 1024));
  Sampler bil(pyr, {{TexelFilter::Linear, MipMode::None}});
  Sampler mipn(pyr, {{TexelFilter::Linear, MipMode::Nearest}});
  Sampler point(pyr, {{TexelFilter::Nearest, MipMode::None}});
  Sampler point_mip(pyr, {{TexelFilter::Nearest, MipMode::Linear}});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> uv(0.05, 0.95), lod(-3, 8.9);
  for (int i = 0; i < 5000; ++i) {
    const Request r = request(uv(rng), uv(rng), lod(rng));
    for (Sampler* s : {&bil, &mipn}) {
      const Cost c = cost_of_one_sample(*s, r);
      ASSERT_EQ(c.reads, 4u);
      ASSERT_EQ(c.level_banks.size(), 4u);
      ASSERT_EQ(c.multiplies, 3u);
    }
    const Cost p = cost_of_one_sample(point, r);
    ASSERT_EQ(p.reads, 1u);
    ASSERT_EQ(p.multiplies, 0u);
    // Nearest texel in two levels (nearest_mipmap_linear): 1 read per level, one blend.
    const Cost pm = cost_of_one_sample(point_mip, r);
    ASSERT_EQ(pm.reads, r.lod > 0 ? 2u : 1u);
    ASSERT_EQ(pm.multiplies, r.lod > 0 ? 1u : 0u);
  }
}

TEST(BankedMemory, EveryLevelHasFourBanksHoldingItsTexels) {
  for (auto [w, h] : {std::pair{16, 8}, std::pair{1, 8}, std::pair{8, 1}, std::pair{1, 1}, std::pair{64, 64}}) {
    const Pyramid pyr = build_pyramid(make_pattern("noise", w, h));
    BankedMipMemory mem(pyr);
    ASSERT_EQ(mem.levels(), int(pyr.levels.size()));
    for (int k = 0; k < mem.levels(); ++k) {
      const Image& lvl = pyr.levels[k];
      ASSERT_EQ(mem.shape(k).width(), lvl.width);
      ASSERT_EQ(mem.shape(k).height(), lvl.height);
      for (int y = 0; y < lvl.height; ++y)
        for (int x = 0; x < lvl.width; ++x) {
          mem.reset_stats();
          const auto t = mem.fetch(k, x, x, y, y, true);
          ASSERT_EQ(t[0], lvl.at(x, y)) << w << "x" << h << " level " << k << " texel " << x << "," << y;
          ASSERT_EQ(mem.stats().bank_reads[k][((y & 1) << 1) | (x & 1)], 1u);  // parity bank
          // A 2x2 footprint returns the four texels in order a, b, c, e.
          const int x1 = (x + 1) % lvl.width, y1 = (y + 1) % lvl.height;
          const auto f = mem.fetch(k, x, x1, y, y1, false);
          ASSERT_EQ(f[0], lvl.at(x, y));
          ASSERT_EQ(f[1], lvl.at(x1, y));
          ASSERT_EQ(f[2], lvl.at(x, y1));
          ASSERT_EQ(f[3], lvl.at(x1, y1));
        }
    }
  }
  // Over random trilinear samples of a 64x64 texture every level of 2x2 or more uses all 4 banks.
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 64));
  Sampler s(pyr, {{TexelFilter::Linear, MipMode::Linear}});
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uv(-2, 2), lod(0, 7);
  for (int i = 0; i < 20000; ++i) s.sample(request(uv(rng), uv(rng), lod(rng)));
  const auto& banks = s.stats().memory.bank_reads;
  ASSERT_EQ(banks.size(), 7u);
  for (int k = 0; k < 6; ++k)
    for (int b = 0; b < 4; ++b) EXPECT_GT(banks[k][b], 0u) << "level " << k << " bank " << b;
}

TEST(BankedMemory, ConflictIsDetected) {
  // The check can fire: texels 0 and 2 of a row share bank 0 but not the word.
  BankedMipMemory mem(build_pyramid(make_pattern("noise", 8, 8)));
  EXPECT_THROW(mem.fetch(0, 0, 2, 0, 0, false), std::logic_error);
  EXPECT_THROW(mem.fetch(0, 0, 0, 1, 3, false), std::logic_error);
}

// The planted bug of the repeat seam: an odd level whose seam pair reads texel 0 itself (n - 1 and 0,
// both even) rather than its copy at n asks one bank for two words; the check fires. The copy is
// what the layout stores, and it holds texel 0.
TEST(BankedMemory, SeamTapFromTheWrongBankIsAConflict) {
  const Pyramid pyr = build_pyramid(make_pattern("noise", 7, 5));
  BankedMipMemory mem(pyr);
  EXPECT_THROW(mem.fetch(0, 6, 0, 1, 2, false), std::logic_error);  // x: 6 and 0
  EXPECT_THROW(mem.fetch(0, 1, 2, 4, 0, false), std::logic_error);  // y: 4 and 0
  const auto f = mem.fetch(0, 6, 7, 4, 5, false);                    // the copies
  EXPECT_EQ(f[0], pyr.levels[0].at(6, 4));
  EXPECT_EQ(f[1], pyr.levels[0].at(0, 4));
  EXPECT_EQ(f[2], pyr.levels[0].at(6, 0));
  EXPECT_EQ(f[3], pyr.levels[0].at(0, 0));
  EXPECT_EQ(stage::wrap(-1 + 1, 7, Wrap::Repeat, true), 7);  // what wrap gives the second tap
}

TEST(BankedMemory, NoConflictInAnyWrapOrFilterOrSize) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uv(-130.0 / 1.0, 127.9), near_uv(-3, 3), lod(-2, 13);
  for (auto [w, h] : {std::pair{1024, 1024}, std::pair{256, 4}, std::pair{1, 64}, std::pair{32, 1}, std::pair{1, 1},
                      std::pair{2, 2}, std::pair{2048, 1}, std::pair{1000, 600}, std::pair{7, 5}, std::pair{3, 1},
                      std::pair{1, 13}}) {
    const Pyramid pyr = build_pyramid(make_pattern("noise", w, h));
    for (Wrap wu : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp})
      for (Wrap wv : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp})
        for (TexelFilter tf : {TexelFilter::Nearest, TexelFilter::Linear})
          for (MipMode mm : {MipMode::None, MipMode::Nearest, MipMode::Linear}) {
            Sampler s(pyr, {{tf, mm}, wu, wv});
            for (int i = 0; i < 300; ++i) {
              const bool wide = i & 1;
              const double u = wide ? std::clamp(uv(rng), -128.0, 127.9) : near_uv(rng);
              const double v = wide ? std::clamp(uv(rng), -128.0, 127.9) : near_uv(rng);
              ASSERT_NO_THROW(s.sample(request(u, v, lod(rng)))) << w << "x" << h << " u=" << u << " v=" << v;
            }
            // At most 8 reads per sample, whatever happens at the edges.
            ASSERT_LE(s.stats().memory.reads, 8u * s.stats().samples);
          }
  }
}

// Depth compare (Op::Compare, percentage-closer filtering): the reference in the depth's codes as
// exact rational arithmetic rounds it; the eight operators as Vulkan's VkCompareOp words them; and
// a compare sample is the same filter of the texture whose texels are the tests' results (1 or 0,
// the border colour's R tested too), under every filter, address mode pair and anisotropy, on both
// paths and through the cache.
#include <gtest/gtest.h>

#include <random>

#include "model/error.h"
#include "model/memory_layout.h"
#include "model/sampler.h"
#include "model/stages.h"
#include "model/texture_cache.h"
#include "stimulus.h"

using namespace tex;

namespace {

// The pyramid whose texels are the tests' results: R = max where `reference OP R` holds, else 0;
// G = B = 0; A = max.
Pyramid tested(const Pyramid& p, CompareOp op, uint32_t reference) {
  Pyramid out = p;
  const uint16_t one = uint16_t((1u << p.levels[0].channel_bits) - 1);
  for (Image& img : out.levels)
    for (Texel& t : img.texels) t = {stage::compare_passes(op, reference, t[0]) ? one : uint16_t(0), 0, 0, one};
  return out;
}

}  // namespace

TEST(DepthCompare, NamesOfTheOperators) {
  CompareOp op{};
  EXPECT_TRUE(parse_compare_op("lequal", op));
  EXPECT_EQ(op, CompareOp::LessOrEqual);
  EXPECT_TRUE(parse_compare_op("GL_GEQUAL", op));
  EXPECT_EQ(op, CompareOp::GreaterOrEqual);
  EXPECT_TRUE(parse_compare_op("VK_COMPARE_OP_NOT_EQUAL", op));
  EXPECT_EQ(op, CompareOp::NotEqual);
  EXPECT_TRUE(parse_compare_op("less-or-equal", op));
  EXPECT_EQ(op, CompareOp::LessOrEqual);
  EXPECT_FALSE(parse_compare_op("lesser", op));
  EXPECT_EQ(compare_op_name(CompareOp::GreaterOrEqual), "greater-or-equal");
  Op o{};
  EXPECT_TRUE(parse_op("compare", o));
  EXPECT_EQ(o, Op::Compare);
}

// Each operator on a reference below, equal to and above the depth (VkCompareOp: "reference < test").
TEST(DepthCompare, OperatorsAsVulkanWordsThem) {
  const bool want[kCompareOps][3] = {
      // reference < depth, ==, >
      {false, false, false},  // never
      {true, false, false},   // less
      {false, true, false},   // equal
      {true, true, false},    // less or equal
      {false, false, true},   // greater
      {true, false, true},    // not equal
      {false, true, true},    // greater or equal
      {true, true, true},     // always
  };
  for (int op = 0; op < kCompareOps; ++op)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(stage::compare_passes(CompareOp(op), 100 + uint32_t(k) - 1, 100), want[op][k]) << compare_op_name(CompareOp(op)) << " " << k;
}

// round(clamp(ref, 0, 1) * (2^cw - 1)), half up, by exact integers of the rational ref / 2^24.
TEST(DepthCompare, ReferenceInTheDepthsCodes) {
  std::mt19937_64 rng(3);
  for (int cw : {8, 16}) {
    const int64_t max = (int64_t(1) << cw) - 1;
    EXPECT_EQ(stage::compare_reference(-5, cw), 0u);
    EXPECT_EQ(stage::compare_reference(1 << 24, cw), uint32_t(max));
    EXPECT_EQ(stage::compare_reference(INT32_MAX, cw), uint32_t(max));
    for (int i = 0; i < 200000; ++i) {
      const int32_t ref = int32_t(rng() % ((1u << 24) + 1));
      // The nearest code: the one whose distance 2 * |ref * max - code * 2^24| is least, ties up.
      int64_t best = 0;
      for (int64_t code = std::max<int64_t>(0, (ref * max >> 24) - 1); code <= std::min(max, (ref * max >> 24) + 2); ++code) {
        const int64_t d = std::abs(2 * (int64_t(ref) * max - code * (int64_t(1) << 24)));
        const int64_t db = std::abs(2 * (int64_t(ref) * max - best * (int64_t(1) << 24)));
        if (d < db || (d == db && code > best)) best = code;
      }
      ASSERT_EQ(stage::compare_reference(ref, cw), uint32_t(best)) << "ref " << ref << " cw " << cw;
    }
  }
}

// PCF: a compare sample is the sampler's filter of the tested texture (the border colour's R tested
// too), on both paths; min/max and unnormalized samplers refuse it.
TEST(DepthCompare, FilteringTheTestsIsFilteringTheTestedTexture) {
  std::mt19937_64 rng(9);
  int samples = 0, partial = 0;
  for (int cw : {8, 16}) {
    const Extent size{19, 12};
    const Pyramid depth = build_pyramid(stimulus::random_image(size.w, size.h, cw, 4, 0));
    for (int trial = 0; trial < 48; ++trial) {
      SamplerConfig cfg = stimulus::random_sampler(rng);
      cfg.reduction = Reduction::WeightedAverage;
      cfg.compare_op = CompareOp(rng() % kCompareOps);
      const int32_t ref = int32_t(rng() % ((1u << 24) + 1));
      const uint32_t code = stage::compare_reference(ref, cw);
      SamplerConfig tested_cfg = cfg;  // the border colour, tested
      tested_cfg.border = BorderColor::Custom;
      const uint16_t border_r = stage::border_texel(cfg.border_unorm16(), cw)[0];
      tested_cfg.border_custom = {stage::compare_passes(cfg.compare_op, code, border_r) ? uint16_t(65535) : uint16_t(0), 0, 0, 65535};
      const Pyramid t = tested(depth, cfg.compare_op, code);
      Sampler compare(depth, cfg), plain(t, tested_cfg);
      std::vector<Request> reqs = stimulus::random_requests(rng, size, 300);
      for (Request& r : reqs) {
        r.op = Op::Compare;
        r.ref = ref;
      }
      std::vector<uint32_t> fast(reqs.size());
      const bool fast_path = cw == 8 && Sampler::fast_path_takes(cfg);
      if (fast_path) Sampler(depth, cfg, SamplerPaths::FastOnly).sample_rgba8(reqs.data(), reqs.size(), fast.data());
      for (size_t i = 0; i < reqs.size(); ++i) {
        Request flat = reqs[i];
        flat.op = Op::Sample;
        const Texel want = plain.sample(flat), got = compare.sample(reqs[i]);
        ASSERT_EQ(got, want) << "request " << i << " " << compare_op_name(cfg.compare_op) << " ref " << ref;
        partial += got[0] != 0 && got[0] != (1u << cw) - 1;
        if (fast_path) {
          ASSERT_EQ(fast[i], uint32_t(want[0]) | uint32_t(want[3]) << 24) << "fast path, request " << i;
        }
        ++samples;
      }
    }
  }
  EXPECT_GT(partial, samples / 20) << "footprints that straddle the reference";
  SamplerConfig minmax;
  minmax.reduction = Reduction::Max;
  Request r;
  r.op = Op::Compare;
  EXPECT_THROW(Sampler(build_pyramid(stimulus::random_image(4, 4, 8, 1, 0)), minmax).sample(r), Error);
  EXPECT_NE(minmax.compare_problem(), "");
}

// A compare reads the lines a sample of the same coordinates reads.
TEST(DepthCompare, CacheReadsTheSamplesLines) {
  std::mt19937_64 rng(2);
  const Extent size{40, 24};
  const MemoryLayout layout(size, 8, LayoutParams{});
  const SamplerConfig cfg = stimulus::random_sampler(rng);
  TextureCache a(layout, CacheParams{}, cfg), b(layout, CacheParams{}, cfg);
  for (Request r : stimulus::random_requests(rng, size, 2000)) {
    std::vector<uint32_t> sample_lines, compare_lines;
    a.lookup_sample(r, &sample_lines);
    r.op = Op::Compare;
    r.ref = int32_t(rng() % (1u << 24));
    b.lookup_sample(r, &compare_lines);
    ASSERT_EQ(compare_lines, sample_lines);
  }
}

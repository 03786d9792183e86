// Array textures (stage::array_layer, the Sampler's layers, MemoryLayout's layer stride, the
// cache's lookups): the layer is clamp(RNE(a), 0, layers - 1) as the C library's round-to-nearest-
// even gives it; sampling layer l of an array gives what a texture of that layer alone gives, on
// both paths; a fetch outside the layers reads nothing; layer l's lines are layer 0's layout moved
// by l layer strides.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <random>

#include "stimulus.h"
#include "model/error.h"
#include "model/memory_layout.h"
#include "model/sampler.h"
#include "model/stages.h"
#include "model/texture_cache.h"

using namespace tex;

TEST(ArrayLayer, RoundsHalfToEvenAndClampsAsTheCLibrary) {
  ASSERT_EQ(std::fegetround(), FE_TONEAREST);
  auto reference = [](int32_t a, int layers) {
    const double r = std::nearbyint(double(a) / 65536.0);  // round half to even, independently
    return int(std::clamp(r, 0.0, double(layers - 1)));
  };
  // The ties, on both sides of each.
  EXPECT_EQ(stage::array_layer(32768, 8), 0);       // 0.5 -> 0
  EXPECT_EQ(stage::array_layer(32769, 8), 1);
  EXPECT_EQ(stage::array_layer(3 * 32768, 8), 2);   // 1.5 -> 2
  EXPECT_EQ(stage::array_layer(5 * 32768, 8), 2);   // 2.5 -> 2
  EXPECT_EQ(stage::array_layer(5 * 32768 + 1, 8), 3);
  EXPECT_EQ(stage::array_layer(-32768, 8), 0);      // -0.5 -> 0 (clamped)
  EXPECT_EQ(stage::array_layer(INT32_MAX, 8), 7);
  EXPECT_EQ(stage::array_layer(INT32_MIN, 8), 0);
  std::mt19937_64 rng(11);
  for (int i = 0; i < 1'000'000; ++i) {
    const int layers = 1 + int(rng() % 256);
    const int32_t a = stimulus::random_layer(rng, layers);
    ASSERT_EQ(stage::array_layer(a, layers), reference(a, layers)) << a << " of " << layers << " layers";
  }
  EXPECT_EQ(stage::request_layer(Op::Fetch, 3, 4), 3);
  EXPECT_EQ(stage::request_layer(Op::Fetch, 4, 4), -1);
  EXPECT_EQ(stage::request_layer(Op::Fetch, -1, 4), -1);
  EXPECT_EQ(stage::request_layer(Op::Gather, 4 << 16, 4), 3);
}

// Every operation and both paths: layer l of an array as layer l's pyramid alone gives it.
TEST(ArrayLayer, SamplingALayerIsSamplingThatTexture) {
  std::mt19937_64 rng(5);
  const Extent size{21, 12};
  const std::vector<Pyramid> layers = stimulus::random_layers(size, 5, 3);
  int outside = 0;
  for (int trial = 0; trial < 24; ++trial) {
    SamplerConfig cfg = stimulus::random_sampler(rng);
    Sampler array(stimulus::pointers_to(layers), cfg);
    std::vector<Sampler> alone;
    for (const Pyramid& p : layers) alone.emplace_back(p, cfg);
    std::vector<Request> reqs = stimulus::random_requests(rng, size, 400);
    stimulus::fetches_and_gathers_among(rng, reqs, 4, [&](int) { return size; });
    stimulus::layers_among(rng, reqs, [](int) { return 5; });
    std::vector<uint32_t> fast(reqs.size());
    const bool fast_path = Sampler::fast_path_takes(cfg);
    if (fast_path) {
      Sampler only_fast(stimulus::pointers_to(layers), cfg, SamplerPaths::FastOnly);
      only_fast.sample_rgba8(reqs.data(), reqs.size(), fast.data());
    }
    for (size_t i = 0; i < reqs.size(); ++i) {
      const Request& r = reqs[i];
      const int l = stage::request_layer(r.op, r.layer, 5);
      Texel want{};
      if (l >= 0) {
        Request flat = r;
        flat.layer = 0;
        want = alone[size_t(l)].sample(flat);
      } else {
        ++outside;
      }
      ASSERT_EQ(array.sample(r), want) << "request " << i << " layer " << r.layer << " op " << op_name(r.op);
      if (fast_path) {
        ASSERT_EQ(fast[i], uint32_t(want[0]) | uint32_t(want[1]) << 8 | uint32_t(want[2]) << 16 | uint32_t(want[3]) << 24)
            << "fast path, request " << i;
      }
    }
  }
  EXPECT_GT(outside, 10);  // fetches outside the layers were drawn
}

TEST(ArrayLayer, LayersOfOneShapeOnly) {
  const std::vector<Pyramid> a = stimulus::random_layers({8, 8}, 2, 1);
  const Pyramid other = stimulus::random_pyramid({8, 4}, 2);
  EXPECT_THROW(Sampler({&a[0], &other}, SamplerConfig{}), Error);
  EXPECT_THROW(Sampler(std::vector<const Pyramid*>{}, SamplerConfig{}), Error);
  EXPECT_THROW(MemoryLayout({8, 8}, 8, LayoutParams{}, TexelFormat::Rgba8, 0, 0), Error);
  EXPECT_THROW(MemoryLayout({8, 8}, 8, LayoutParams{}, TexelFormat::Rgba8, 0, kMaxLayers + 1), Error);
  // 256 layers of 8192 x 8192 RGBA8 do not fit 32-bit addresses.
  EXPECT_THROW(MemoryLayout({8192, 8192}, 8, LayoutParams{}, TexelFormat::Rgba8, 0, 256), Error);
}

// The image of an array is each layer's image at base + l * layer_bytes, the layer bytes those of
// one pyramid; decode_line names the layer of each line.
TEST(ArrayLayer, MemoryImageIsLayerAfterLayer) {
  for (const BlockOrder order : {BlockOrder::RowMajor, BlockOrder::Morton}) {
    LayoutParams p;
    p.order = order;
    p.base = 4096;
    const std::vector<Pyramid> layers = stimulus::random_layers({13, 6}, 3, 9);
    const MemoryLayout one = layout_of(layers[0], p);
    const MemoryLayout array = layout_of(layers[0], p, 3);
    EXPECT_EQ(array.layer_bytes(), one.image_bytes());
    EXPECT_EQ(array.image_bytes(), 3 * one.image_bytes());
    const std::vector<uint8_t> image = build_memory_image(stimulus::pointers_to(layers), array);
    for (int l = 0; l < 3; ++l) {
      LayoutParams moved = p;
      moved.base = p.base + uint32_t(l) * array.layer_bytes();
      const std::vector<uint8_t> alone = build_memory_image(layers[size_t(l)], layout_of(layers[0], moved));
      EXPECT_TRUE(std::equal(alone.begin(), alone.end(), image.begin() + std::ptrdiff_t(l) * array.layer_bytes()))
          << "layer " << l;
      EXPECT_EQ(array.line_address(2, 1, 1, l), layout_of(layers[0], moved).line_address(2, 1, 1));
    }
    int texels = 0;
    for (uint64_t off = 0; off < image.size(); off += uint64_t(array.line_bytes()))
      decode_line(array, p.base + uint32_t(off), &image[off], [&](int layer, int level, int x, int y, const Texel& t) {
        ASSERT_EQ(t, layers[size_t(layer)].levels[size_t(level)].at(x, y));
        ++texels;
      });
    int want = 0;
    for (const Pyramid& pyr : layers)
      for (const Image& img : pyr.levels) want += img.width * img.height;
    EXPECT_EQ(texels, want);
    EXPECT_THROW(build_memory_image(stimulus::pointers_to(layers), one), Error);  // 3 layers, a layout of 1
  }
}

// The lines a request of layer l misses in a cold cache: those a cache of layer l's texture alone,
// at its place in memory, misses.
TEST(ArrayLayer, CacheReadsTheLayersLines) {
  std::mt19937_64 rng(8);
  const Extent size{40, 24};
  const int n = 4;
  const std::vector<Pyramid> layers = stimulus::random_layers(size, n, 4);
  LayoutParams p;
  p.base = 1 << 20;
  const MemoryLayout array = layout_of(layers[0], p, n);
  for (int trial = 0; trial < 8; ++trial) {
    const SamplerConfig cfg = stimulus::random_sampler(rng);
    std::vector<Request> reqs = stimulus::random_requests(rng, size, 300);
    stimulus::fetches_and_gathers_among(rng, reqs, 4, [&](int) { return size; });
    stimulus::layers_among(rng, reqs, [&](int) { return n; });
    for (const Request& r : reqs) {
      std::vector<uint32_t> got, want;
      TextureCache cache(array, CacheParams{}, cfg);  // cold, as `alone` below
      cache.lookup_sample(r, &got);
      const int l = stage::request_layer(r.op, r.layer, n);
      if (l < 0) {
        EXPECT_TRUE(got.empty()) << "a fetch outside the layers reads nothing";
        continue;
      }
      // Layer l alone at its place in memory.
      LayoutParams moved = p;
      moved.base = p.base + uint32_t(l) * array.layer_bytes();
      TextureCache alone(layout_of(layers[0], moved), CacheParams{}, cfg);
      Request flat = r;
      flat.layer = 0;
      alone.lookup_sample(flat, &want);
      ASSERT_EQ(got, want) << "layer " << l;
    }
  }
}

// The sampler's pipeline stages as pure, bit-exact functions (docs/numerics.md, stages 1-5).
// Both the reference sampler and the fast path call these, and the RTL implements them.
#pragma once
#include <algorithm>
#include <cstdint>

#include "formats.h"

namespace tex::stage {

// Stage 1: GL order: add the bias, then clamp to [min_lod, max_lod]. All Q8.8.
inline int32_t bias_and_clamp(int32_t lod, int32_t bias, int32_t min_lod, int32_t max_lod) {
  return std::clamp(lod + bias, min_lod, max_lod);
}

struct LevelSelect {
  int d = 0;       // first level
  int d1 = 0;      // second level: min(d + 1, last)
  int f = 0;       // weight of level d1, 0..255
  bool two_levels = false;  // the filter blends two levels (trilinear minification, d < last)
};

inline LevelSelect select_levels(int32_t lod, MipMode mip, int last_level) {
  LevelSelect s;
  if (mip != MipMode::None && lod > 0) {
    if (mip == MipMode::Nearest) {
      s.d = std::min((lod + 127) >> kLodFracBits, last_level);
    } else {
      s.d = std::min(lod >> kLodFracBits, last_level);
      s.two_levels = s.d < last_level;
      s.f = s.two_levels ? (lod & 255) : 0;
    }
  }
  s.d1 = std::min(s.d + 1, last_level);
  return s;
}

// Stage 2: the two integer texel indices along one axis and the weight of the second.
struct AxisTaps {
  int32_t i0 = 0, i1 = 0;
  int w = 0;
};

inline AxisTaps axis_taps(int32_t coord, int log2_size, TexelFilter filter) {
  const int32_t t9 = coord >> (15 - log2_size);  // floor(u * size * 512): a fixed shift per level
  AxisTaps t;
  if (filter == TexelFilter::Linear) {
    const int32_t p = (t9 - 255) >> 1;  // round-half-up((u * size - 1/2) * 256)
    t.i0 = p >> 8;
    t.w = p & 255;
  } else {
    t.i0 = t9 >> 9;  // floor(u * size)
  }
  t.i1 = t.i0 + 1;
  return t;
}

// Stage 3: OpenGL wrap of an integer texel index into [0, 2^log2_size).
inline int32_t wrap_index(int32_t i, int log2_size, Wrap wrap) {
  const int32_t n = 1 << log2_size;
  switch (wrap) {
    case Wrap::Repeat: return i & (n - 1);
    case Wrap::Clamp: return std::clamp(i, 0, n - 1);
    case Wrap::Mirror: {
      const int32_t m = i & (2 * n - 1);
      return m < n ? m : 2 * n - 1 - m;
    }
  }
  return 0;
}

// Stage 4: the bank of a texel: its parity in x and y.
inline int bank_of(int32_t x, int32_t y) { return int((y & 1) << 1 | (x & 1)); }

// Stage 5: one lerp is one multiply; the result gains 8 fraction bits and is exact.
inline int64_t lerp(int64_t a, int64_t b, int w) { return (a << kWeightBits) + (b - a) * w; }

// Bilinear of one channel: CW.16, exact.
inline int64_t bilerp(int64_t a, int64_t b, int64_t c, int64_t e, int wx, int wy) {
  return lerp(lerp(a, b, wx), lerp(c, e, wx), wy);
}

// Blend of two bilinear results (CW.16) by f, then the one rounding (half up) to CW bits.
inline uint32_t blend_and_round(int64_t bil_d, int64_t bil_d1, int f) {
  return uint32_t((lerp(bil_d, bil_d1, f) + (int64_t(1) << 23)) >> 24);
}

}  // namespace tex::stage

// The sampler's pipeline stages as pure, bit-exact functions (docs/numerics.md). Each carries the
// name of the RTL module that implements it (docs/architecture.md has the table):
//   lod -> tex_lod, scale -> tex_scale, address -> tex_address, wrap -> tex_wrap,
//   bank -> tex_bank (with BankedMipMemory::fetch -> tex_fetch), lerp -> tex_lerp, filter -> tex_filter.
// Sampler::sample() (the reference path) calls them in pipeline order; the 8-bit fast path
// (Sampler::sample_rgba8) re-implements the same arithmetic for speed and is tested equal to it.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "formats.h"

namespace tex::stage {

// ---------------------------------------------------------------- lod (tex_lod)

// GL order: add the bias, then clamp to [min_lod, max_lod]. All Q8.8. (tex_lod clock 1)
inline int32_t lod_clamp(int32_t lod, int32_t bias, int32_t min_lod, int32_t max_lod) {
  return std::clamp(lod + bias, min_lod, max_lod);
}

struct LevelSelect {
  int d = 0;       // first level
  int d1 = 0;      // second level: min(d + 1, last)
  int f = 0;       // weight of level d1, 0..255
  bool two_levels = false;  // the filter blends two levels (trilinear minification, d < last)
  bool magnify = false;     // lambda' <= 0: the magnification filter (Vulkan, GL 4.5+, GLES 3.2: c = 0)
};

// Levels d, d1 and the blend weight from a clamped lambda. (tex_lod clock 2)
inline LevelSelect lod_select(int32_t lod, MipMode mip, int last_level) {
  LevelSelect s;
  s.magnify = lod <= 0;
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

inline LevelSelect lod(int32_t lambda, int32_t bias, int32_t min_lod, int32_t max_lod, MipMode mip, int last_level) {
  return lod_select(lod_clamp(lambda, bias, min_lod, max_lod), mip, last_level);
}

// The texel filter of a sample: the magnification filter where lambda' <= 0, else the
// minification filter's. (tex_lod's minify, clock 3; tex_front picks the filter by it)
inline TexelFilter texel_filter(const LevelSelect& s, const Filter& f) { return s.magnify ? f.mag : f.texel; }

// ---------------------------------------------------------------- scale (tex_scale)

// The coordinate brought into one period of its address mode before it is scaled: repeat keeps
// u mod 1, mirrored repeat u mod 2 (masks of Q8.24's integer bits), the clamping modes (clamp to
// edge, to border, mirror clamp) clamp(u, -2, 2). Every tap then reads the texel it would read
// without this step (repeat and mirror are periodic in u; beyond +-2 the clamping modes give only
// edge or border taps), the texel indices stay within [-2n - 1, 2n], and u * n is a 27 x 14-bit
// product. (docs/numerics.md stage 2)
// An unnormalized coordinate (Q16.16 texels; its sampler clamps, SamplerConfig::check) passes
// unchanged: scale() takes it as it is.
inline int32_t reduce(int32_t coord, Wrap mode, bool unnormalized = false) {
  constexpr int32_t kOne = int32_t(1) << kCoordFracBits;
  if (unnormalized) return coord;
  switch (mode) {
    case Wrap::Repeat: return coord & (kOne - 1);
    case Wrap::Mirror: return coord & (2 * kOne - 1);
    default: return std::clamp(coord, -2 * kOne, 2 * kOne);
  }
}

// floor(u * n * 512) for a level n texels wide along this axis: the level's texels with 9 fraction
// bits. `reduced` is reduce(u); where n is a power of two 2^a this is the paper's binary shift
// u >> (15 - a), and level k's value the shift of level 0's by k (floors of shifts compose).
// An unnormalized coordinate is in texels already: floor(u * 512), clamped to [-2n, 2n] texels as
// the normalized clamping modes are (the RTL clamps to +-2^(ML+1), the largest side's 2n: both
// read the same taps, every index beyond n - 1 or below 0 being an edge or border tap).
inline int32_t scale(int32_t reduced, int n, bool unnormalized = false) {
  if (unnormalized)
    return std::clamp(reduced >> (kTexelCoordFracBits - 9), -2 * n * 512, 2 * n * 512);
  return int32_t((int64_t(reduced) * n) >> (kCoordFracBits - 9));
}

// ---------------------------------------------------------------- address (tex_address)

// The two integer texel indices along one axis at one level and the weight of the second.
struct AxisTaps {
  int32_t i0 = 0, i1 = 0;
  int w = 0;
};

// `t9`: scale() at this level. A side that reached 1 texel scales by 1 there: repeat, clamp and
// mirror map every index of a 1-texel side to 0, so only clamp to border can tell the two apart.
inline AxisTaps address(int32_t t9, TexelFilter filter) {
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

// ---------------------------------------------------------------- wrap (tex_wrap)

// What wrap gives for a clamp-to-border tap outside the level: the tap reads no texel and takes the
// border colour.
constexpr int32_t kBorderTap = -1;

// The address mode of an integer texel index on a side of n texels, into [0, n) or kBorderTap
// (GL 4.6 Table 8.20, Vulkan "Wrapping Operation"; docs/numerics.md stage 3). `second`: the index
// is the second tap of a pair (i1 = i0 + 1). The repeat seam of a side that is not a power of two:
// the pair (n-1, 0) gives (n-1, n), index n naming texel 0's copy stored after the last texel
// (stored_side), so the two taps sit in different parity banks (n - 1 and 0 are both even when n
// is odd) and, in the cached unit, in neighbouring blocks. `seam`: the side has that copy (every
// side that is not a power of two; in the cached unit's memory also a power-of-two side that an
// ASTC footprint does not divide: MemoryLayout::seam_x).
inline int32_t wrap(int32_t i, int32_t n, Wrap mode, bool second = false, bool seam = false) {
  switch (mode) {
    case Wrap::Repeat: {
      const int32_t m = (i % n + n) % n;
      return second && m == 0 && (seam || !is_power_of_two(n)) ? n : m;
    }
    case Wrap::Clamp: return std::clamp(i, 0, n - 1);
    case Wrap::Mirror: {
      const int32_t m = (i % (2 * n) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case Wrap::Border: return i >= 0 && i < n ? i : kBorderTap;
    case Wrap::MirrorClamp: return std::min(i < 0 ? -1 - i : i, n - 1);  // mirror(i) = -(1 + i) below 0
  }
  return 0;
}

// One axis of a footprint at a level of n texels, from the reduced coordinate: both taps' indices
// after the address mode (i1 as the second tap: the repeat seam's copy) and the weight of i1.
// (tex_scale, tex_address, tex_wrap)
struct WrappedTaps {
  int32_t i0 = 0, i1 = 0;
  int w = 0;
};
inline WrappedTaps axis_taps(int32_t reduced, int n, Wrap mode, TexelFilter filter, bool unnormalized,
                             bool seam = false) {
  const AxisTaps t = address(scale(reduced, n, unnormalized), filter);
  return {wrap(t.i0, n, mode), wrap(t.i1, n, mode, true, seam), t.w};
}

// The border colour in a level's channel width: the sampler's unorm16 value c as
// round(c * (2^CW - 1) / 65535), exact (CW = 16: c itself). An sRGB texture's filter takes linear
// unorm16 texels, so its border colour is linear, never decoded. (tex_border)
inline Texel border_texel(const Texel& unorm16, int channel_bits) {
  Texel t;
  const uint32_t max = (1u << channel_bits) - 1;
  for (size_t c = 0; c < 4; ++c) t[c] = uint16_t((uint32_t(unorm16[c]) * max + 32767) / 65535);
  return t;
}

// ---------------------------------------------------------------- texel fetch (tex_front)

// texelFetch (Op::Fetch; GLSL texelFetch, SPIR-V OpImageFetch): the request's u, v and lod are the
// integers i, j and the level k, relative to the view's base. It reads texel (i, j) of level k,
// with no LOD bias or clamp, no address mode and no filter; where k is not a level of the texture
// (0..last_level) or (i, j) is outside that level it reads nothing and the result is 0 (Vulkan's
// robust image access: (0, 0, 0, 0)). (tex_front: level k, the nearest texel of (i + 1/2,
// j + 1/2) texels in clamp-to-border mode; a fetch that reads nothing leaves as 0.)
inline bool fetch_inside(int32_t i, int32_t j, int32_t level, int last_level, Extent size0) {
  if (level < 0 || level > last_level) return false;
  const Extent e = level_extent(size0, level);
  return i >= 0 && i < e.w && j >= 0 && j < e.h;
}

// ---------------------------------------------------------------- cube face (tex_cube)

// The face a direction (rx, ry, rz) selects and its coordinates (Vulkan "Cube Map Face Selection"):
// the major axis, a tie going to rz over ry and rx and to ry over rx; faces +X, -X, +Y, -Y, +Z, -Z
// are 0..5 (the layers of a cube), and (sc, tc, rc) by the specification's table. s = (sc / |rc| +
// 1) / 2 and t likewise, each the exact quotient rounded to the nearest Q8.24 (half up), so in
// [0, 1]. A direction of (0, 0, 0) selects +Z at the face's centre.
struct CubeFace {
  int face = 4;
  int32_t s = 1 << 23, t = 1 << 23;  // Q8.24, 0..1
  int64_t sc = 0, tc = 0, rc = 0;    // the table's components (Q8.24; -INT32_MIN fits), for the derivatives
};
// floor(num / den + 1/2) for den > 0: the nearest integer, a half up.
inline __int128 round_quotient(__int128 num, __int128 den) {
  const __int128 n2 = 2 * num + den, d2 = 2 * den;
  return n2 >= 0 ? n2 / d2 : -((-n2 + d2 - 1) / d2);
}
inline int32_t cube_coordinate(int64_t sc, int64_t arc) {  // round((sc / arc + 1) / 2 * 2^24), arc > 0
  return int32_t(round_quotient((__int128(sc) + arc) << (kCoordFracBits - 1), arc));  // (sc + |rc|) 2^23 / |rc|
}
inline CubeFace cube_face(int32_t rx, int32_t ry, int32_t rz) {
  const int64_t x = rx, y = ry, z = rz;  // (-INT32_MIN must not wrap)
  const int64_t ax = std::abs(x), ay = std::abs(y), az = std::abs(z);
  CubeFace f;
  if (az >= ax && az >= ay) {
    f.face = z >= 0 ? 4 : 5;
    f.sc = z >= 0 ? x : -x;
    f.tc = -y;
    f.rc = z;
  } else if (ay >= ax) {
    f.face = y >= 0 ? 2 : 3;
    f.sc = x;
    f.tc = y >= 0 ? z : -z;
    f.rc = y;
  } else {
    f.face = x >= 0 ? 0 : 1;
    f.sc = x >= 0 ? -z : z;
    f.tc = -y;
    f.rc = x;
  }
  const int64_t arc = std::abs(f.rc);
  if (arc == 0) return f;  // (0, 0, 0): +Z, its centre
  f.s = cube_coordinate(f.sc, arc);
  f.t = cube_coordinate(f.tc, arc);
  return f;
}
// 1/D for D in [2^31, 2^32) as R <= 2^62 / D, within 2^-25 of it (tex_cube_face): a 256-entry
// table of 10 bits, t = floor(2^18 / (257 + i)) for D's 8 bits below its leading one (R0 = t 2^21),
// then two Newton steps R' = R + R (2^62 - D R) / 2^62 with their products truncated, the second
// from R1's top 18 bits (h = R1 >> 14): each step's products fit 18-bit multipliers (D x t, t x
// delta1, D x h, h x delta2: 7 DSP tiles of 18 x 18) and the steps approach 1/D from below.
inline uint32_t cube_reciprocal(uint32_t d) {
  const uint64_t t = 262144u / (257u + ((d >> 23) & 255u));            // 2^18 / (257 + i): 10 bits
  const uint64_t delta1 = ((uint64_t(1) << 41) - uint64_t(d) * t) >> 9;  // (2^62 - D R0) >> 30
  const uint64_t r1 = (t << 21) + ((t * delta1) >> 11);                 // R0 + (R0 delta1 >> 32)
  const uint64_t h = r1 >> 14;                                           // <= 2^17
  const uint64_t delta2 = ((uint64_t(1) << 48) - uint64_t(d) * h) >> 16;  // (2^62 - D h 2^14) >> 30
  return uint32_t((h << 14) + ((h * delta2) >> 18));
}
// The position of the leading one of v > 0.
inline int leading_one(uint64_t v) { return 63 - __builtin_clzll(v); }
// The face's derivatives of s and t along one screen axis from the direction's (drx, dry, drz)
// (Vulkan "Cube Map Derivative Transformation", the quotient rule): ds = (dsc - sc' drc') / (2 |rc|)
// with sc' = 2s - 1 (the exact s), dsc and drc' = sign(rc) drc picked and signed by the face's
// table; dt likewise. In face widths per pixel, Q8.24, what tex_lambda takes with the
// face's size. The arithmetic is tex_cube's, in block floating point (it feeds a LOD of 8 fraction
// bits, which tex_lambda takes from 16-bit magnitudes): the axis' three derivatives share a shift
// e that leaves them 18 bits (a, b), sc' keeps 17 bits (c = (2s - 2^24) >> 8), g = a 2^16 - c b,
// g keeps 18 bits (shift f), times the reciprocal's 17 bits (R >> 15 of cube_reciprocal of |rc|
// normalized by k to [2^31, 2^32)), then shifted by e + k + f - 40, rounded half up and saturated
// to 32 bits. Within 2^-13 of the largest of the axis' terms (tex_lambda resolves 2^-8 of a level);
// 0 for rc = 0.
inline std::array<int32_t, 2> cube_derivatives(const CubeFace& f, int32_t drx, int32_t dry, int32_t drz) {
  if (f.rc == 0) return {0, 0};
  int64_t dsc = 0, dtc = 0, drc = 0;
  switch (f.face) {  // (int64: -INT32_MIN)
    case 0: dsc = -int64_t(drz), dtc = -int64_t(dry), drc = drx; break;
    case 1: dsc = drz, dtc = -int64_t(dry), drc = drx; break;
    case 2: dsc = drx, dtc = drz, drc = dry; break;
    case 3: dsc = drx, dtc = -int64_t(drz), drc = dry; break;
    case 4: dsc = drx, dtc = -int64_t(dry), drc = drz; break;
    default: dsc = -int64_t(drx), dtc = -int64_t(dry), drc = drz; break;
  }
  const int64_t darc = f.rc < 0 ? -drc : drc;
  const uint64_t arc = uint64_t(std::abs(f.rc));
  const int k = 31 - leading_one(arc);
  const int64_t r17 = int64_t(cube_reciprocal(uint32_t(arc << k)) >> 15);
  const uint64_t m = std::max({uint64_t(std::abs(dsc)), uint64_t(std::abs(dtc)), uint64_t(std::abs(darc))});
  const int e = m >= (1u << 17) ? leading_one(m) - 16 : 0;
  std::array<int32_t, 2> out{};
  for (int axis = 0; axis < 2; ++axis) {
    const int64_t a = (axis == 0 ? dsc : dtc) >> e, b = darc >> e;
    const int64_t c = ((2 * int64_t(axis == 0 ? f.s : f.t)) - (int64_t(1) << kCoordFracBits)) >> 8;
    const int64_t g = a * 65536 - c * b;
    const uint64_t ag = uint64_t(std::abs(g));
    const int fs = ag >= (1u << 17) ? leading_one(ag) - 16 : 0;
    const int64_t p = (g >> fs) * r17;
    const int sh = e + k + fs - 40;
    // (sh in [-40, 24] and |p| <= 2^33: the shifted product fits 64 bits)
    const int64_t q = sh >= 0 ? p * (int64_t(1) << sh) : (p + (int64_t(1) << (-sh - 1))) >> -sh;
    out[size_t(axis)] = int32_t(std::clamp<int64_t>(q, INT32_MIN, INT32_MAX));
  }
  return out;
}
// The face coordinates (s, t) of `face`, Q8.24, as a direction on the unit cube (the table
// inverted: sc = 2s - 1, tc = 2t - 1, |rc| = 1), then the face and coordinates that direction
// selects: a point beyond a face's edge (an anisotropic probe) on the face it lies over.
inline CubeFace cube_reproject(int face, int32_t s, int32_t t) {
  constexpr int64_t one = int64_t(1) << kCoordFracBits;
  const int64_t sc = 2 * int64_t(s) - one, tc = 2 * int64_t(t) - one;
  auto c = [](int64_t v) { return int32_t(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX)); };
  switch (face) {
    case 0: return cube_face(c(one), c(-tc), c(-sc));
    case 1: return cube_face(c(-one), c(-tc), c(sc));
    case 2: return cube_face(c(sc), c(one), c(tc));
    case 3: return cube_face(c(sc), c(-one), c(-tc));
    case 4: return cube_face(c(sc), c(-tc), c(one));
    default: return cube_face(c(-sc), c(-tc), c(-one));
  }
}
// A cube face's taps along one axis (s or t, Q8.24 in [0, 1]) at a level of n texels, in the
// skirted face's stored indices (MemoryLayout, cube_skirts: the face at 1..n, its neighbours' edge
// texels at 0 and n + 1): a linear filter's i0 in -1..n-1 and i1 = i0 + 1 moved by one; a nearest
// texel clamped to the face (Vulkan: a nearest filter clamps within the face), then moved by one.
inline WrappedTaps cube_taps(int32_t s, int n, TexelFilter filter) {
  const AxisTaps a = address(scale(s, n), filter);
  if (filter == TexelFilter::Nearest) {
    const int32_t i = std::clamp(a.i0, 0, n - 1) + 1;
    return {i, i, 0};
  }
  return {std::clamp(a.i0, -1, n) + 1, std::clamp(a.i1, -1, n) + 1, a.w};
}

// ---------------------------------------------------------------- array layer (tex_layer)

// The layer an array request reads (Vulkan "Image Operations", the layer of an array image):
// clamp(RNE(a), 0, layers - 1) of the Q16.16 layer coordinate a, rounding a tie to the even layer
// (no filtering across layers; a 2D texture is an array of one layer). A texel fetch's layer is an
// integer: a layer outside 0..layers - 1 reads nothing (fetch_layer_inside).
inline int array_layer(int32_t a, int layers) {
  const int64_t whole = int64_t(a) >> kTexelCoordFracBits;
  const int64_t rounded = (int64_t(a) + (int64_t(1) << (kTexelCoordFracBits - 1)) - 1 + (whole & 1)) >> kTexelCoordFracBits;
  return int(std::clamp<int64_t>(rounded, 0, layers - 1));
}
inline bool fetch_layer_inside(int32_t layer, int layers) { return layer >= 0 && layer < layers; }
// A cube array's first layer of the cube its layer coordinate picks (6 layers, +X .. -Z, a cube).
inline int cube_base_layer(int32_t a, int layers) { return 6 * array_layer(a, layers / 6); }
// The layer a request reads: array_layer, or a fetch's integer layer (-1 when it reads nothing).
inline int request_layer(Op op, int32_t a, int layers) {
  if (op == Op::Fetch) return fetch_layer_inside(a, layers) ? int(a) : -1;
  return array_layer(a, layers);
}

// ---------------------------------------------------------------- fetch (tex_fetch, tex_bank)

// The bank of a texel: its parity in x and y.
inline int bank(int32_t x, int32_t y) { return int((y & 1) << 1 | (x & 1)); }

// ---------------------------------------------------------------- filter (tex_filter, tex_lerp)

// One lerp is one multiply; the result gains 8 fraction bits and is exact.
inline int64_t lerp(int64_t a, int64_t b, int w) { return (a << kWeightBits) + (b - a) * w; }

// Bilinear of one channel: CW.16, exact.
inline int64_t bilerp(int64_t a, int64_t b, int64_t c, int64_t e, int wx, int wy) {
  return lerp(lerp(a, b, wx), lerp(c, e, wx), wy);
}

// Blend of two bilinear results (CW.16) by f, then the one rounding (half up) to CW bits.
inline uint32_t blend_and_round(int64_t bil_d, int64_t bil_d1, int f) {
  return uint32_t((lerp(bil_d, bil_d1, f) + (int64_t(1) << 23)) >> 24);
}

// The whole filter, all four channels, before the rounding: taps {a, b, c, e} = T(x0,y0), T(x1,y0),
// T(x0,y1), T(x1,y1) of levels d (slot 0) and d1 (slot 1), their weights, and the level blend f.
// Each channel is CW.24, exact.
struct Footprint {
  std::array<Texel, 4> taps;
  int fx = 0, fy = 0;
};
using Unrounded = std::array<int64_t, 4>;
inline Unrounded filter_unrounded(const Footprint& d, const Footprint& d1, int f) {
  Unrounded out;
  for (size_t c = 0; c < 4; ++c) {
    const int64_t b0 = bilerp(d.taps[0][c], d.taps[1][c], d.taps[2][c], d.taps[3][c], d.fx, d.fy);
    const int64_t b1 = bilerp(d1.taps[0][c], d1.taps[1][c], d1.taps[2][c], d1.taps[3][c], d1.fx, d1.fy);
    out[c] = lerp(b0, b1, f);
  }
  return out;
}

// The min/max reduction (Reduction::Min, Max) of one probe: per channel, the least or greatest of
// the texels the filter weighs with a weight above 0 (Vulkan "Texel Filtering", reductionMode):
// tap a always (its weights are 256 - fx and 256 - fy, never 0), b where fx > 0, c where fy > 0,
// e where both; level d1's taps where f > 0 (a two-level sample). A nearest filter has fx = fy = 0:
// its one texel per level. As CW.24 (the texel * 2^24), so that a probe's value and the rounding
// after it are those of the weighted average's path.
inline Unrounded reduce_taps(const Footprint& d, const Footprint& d1, int f, bool max) {
  Unrounded out;
  for (size_t c = 0; c < 4; ++c) {
    uint32_t v = d.taps[0][c];
    auto take = [&](const Footprint& s) {
      const uint32_t t[4] = {s.taps[0][c], s.taps[1][c], s.taps[2][c], s.taps[3][c]};
      const bool weighed[4] = {true, s.fx > 0, s.fy > 0, s.fx > 0 && s.fy > 0};
      for (int k = 0; k < 4; ++k)
        if (weighed[k]) v = max ? std::max(v, t[k]) : std::min(v, t[k]);
    };
    take(d);
    if (f > 0) take(d1);
    out[c] = int64_t(v) << 24;
  }
  return out;
}

// textureGather (Op::Gather; GL 4.6 §8.14.2, Vulkan "Texel Gathering"): one component of the four
// texels a linear filter weighs at the base level — the sampler's address modes and border colour
// apply, its filters, LOD controls and reduction do not — in the order (i0, j1), (i1, j1), (i1, j0),
// (i0, j0) as R, G, B, A: taps c, e, b, a. (tex_front: level 0, the linear filter's taps, all four
// read; tex_filter passes them through its registers as a min/max does.)
inline Texel gather(const Footprint& d, int component) {
  const size_t c = size_t(component & 3);
  return {d.taps[2][c], d.taps[3][c], d.taps[1][c], d.taps[0][c]};
}

// ---------------------------------------------------------------- depth compare (tex_filter)

// A depth compare's reference (Op::Compare: Request::ref, Dref, signed Q8.24) in a cw-bit depth's
// codes: clamped to [0, 1] (Vulkan clamps a unorm depth's Dref), then round(Dref * (2^cw - 1)),
// half up, so that a reference and a texel compare as codes of one precision and EQUAL means the
// same code. (tex_unit_cached: at the request port; a cw-bit code rides with the request.)
inline uint32_t compare_reference(int32_t ref, int cw) {
  const int64_t r = std::clamp<int64_t>(ref, 0, int64_t(1) << kCoordFracBits);
  return uint32_t((r * ((int64_t(1) << cw) - 1) + (int64_t(1) << (kCoordFracBits - 1))) >> kCoordFracBits);
}
// `reference OP depth` (VkCompareOp's text: "reference < test" for LESS, ...).
inline bool compare_passes(CompareOp op, uint32_t reference, uint32_t depth) {
  switch (op) {
    case CompareOp::Never: return false;
    case CompareOp::Less: return reference < depth;
    case CompareOp::Equal: return reference == depth;
    case CompareOp::LessOrEqual: return reference <= depth;
    case CompareOp::Greater: return reference > depth;
    case CompareOp::NotEqual: return reference != depth;
    case CompareOp::GreaterOrEqual: return reference >= depth;
    case CompareOp::Always: return true;
  }
  return false;
}
// Percentage-closer filtering: each tap's depth (its R channel, a cw-bit unorm code: D16 in a unit
// of 16-bit channels) compared before the filter, the tap becoming (1, 0, 0, 1) where the test
// passes and (0, 0, 0, 1) where it fails — a border tap's depth is the border colour's R. The
// filter then weighs the passes: R is the filtered fraction, G = B = 0, A = 1, Vulkan's [D, 0, 0, 1].
// (tex_filter's clock 1, before its lerps.)
inline void compare_taps(Footprint& f, CompareOp op, uint32_t reference, int cw) {
  const uint16_t one = uint16_t((1u << cw) - 1);
  for (Texel& t : f.taps) t = {compare_passes(op, reference, t[0]) ? one : uint16_t(0), 0, 0, one};
}

// The mean of n probes (the sum of their CW.24 values) and the one rounding, half up, to CW bits:
// round(sum / (n * 2^24)). With n = 1 this is blend_and_round. (tex_accum; the RTL divides by n
// with a reciprocal multiply, docs/numerics.md stage 6, equal for every sum it can see.)
inline Texel average_and_round(const Unrounded& sum, int n) {
  Texel out;
  for (size_t c = 0; c < 4; ++c)
    out[c] = uint16_t((sum[c] + (int64_t(n) << 23)) / (int64_t(n) << 24));
  return out;
}

inline Texel filter(const Footprint& d, const Footprint& d1, int f) { return average_and_round(filter_unrounded(d, d1, f), 1); }

}  // namespace tex::stage

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
// is odd) and, in the cached unit, in neighbouring blocks.
inline int32_t wrap(int32_t i, int32_t n, Wrap mode, bool second = false) {
  switch (mode) {
    case Wrap::Repeat: {
      const int32_t m = (i % n + n) % n;
      return second && m == 0 && !is_power_of_two(n) ? n : m;
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
inline WrappedTaps axis_taps(int32_t reduced, int n, Wrap mode, TexelFilter filter, bool unnormalized) {
  const AxisTaps t = address(scale(reduced, n, unnormalized), filter);
  return {wrap(t.i0, n, mode), wrap(t.i1, n, mode, true), t.w};
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
  int32_t sc = 0, tc = 0, rc = 0;    // the table's components (Q8.24), for the derivatives
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
  const int64_t ax = std::abs(int64_t(rx)), ay = std::abs(int64_t(ry)), az = std::abs(int64_t(rz));
  CubeFace f;
  if (az >= ax && az >= ay) {
    f.face = rz >= 0 ? 4 : 5;
    f.sc = rz >= 0 ? rx : -rx;
    f.tc = -ry;
    f.rc = rz;
  } else if (ay >= ax) {
    f.face = ry >= 0 ? 2 : 3;
    f.sc = rx;
    f.tc = ry >= 0 ? rz : -rz;
    f.rc = ry;
  } else {
    f.face = rx >= 0 ? 0 : 1;
    f.sc = rx >= 0 ? -rz : rz;
    f.tc = -ry;
    f.rc = rx;
  }
  const int64_t arc = std::abs(int64_t(f.rc));
  if (arc == 0) return f;  // (0, 0, 0): +Z, its centre
  f.s = cube_coordinate(f.sc, arc);
  f.t = cube_coordinate(f.tc, arc);
  return f;
}
// The face's derivatives of s and t from those of the direction (Vulkan "Cube Map Derivative
// Transformation", the quotient rule): ds/dx = (dsc/dx |rc| - sc d|rc|/dx) / (2 rc^2), with dsc and
// drc the direction's derivatives picked and signed by the face's table; each the exact rational
// rounded to the nearest Q8.24 (half up) and saturated to 32 bits. In face widths per pixel, what
// tex_lambda takes with the face's size.
inline int32_t cube_derivative(int64_t dsc, int64_t sc, int64_t drc, int64_t rc) {
  if (rc == 0) return 0;
  const int64_t arc = std::abs(rc), darc = rc < 0 ? -drc : drc;
  const __int128 num = (__int128(dsc) * arc - __int128(sc) * darc) << (kCoordFracBits - 1);
  __int128 q = round_quotient(num, __int128(rc) * rc);
  if (q > INT32_MAX) q = INT32_MAX;
  if (q < INT32_MIN) q = INT32_MIN;
  return int32_t(q);
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

// The direction's derivative along one screen axis, (drx, dry, drz), as the face's (dsc, dtc, drc).
inline std::array<int32_t, 3> cube_axes(int face, int32_t drx, int32_t dry, int32_t drz) {
  switch (face) {
    case 0: return {-drz, -dry, drx};
    case 1: return {drz, -dry, drx};
    case 2: return {drx, drz, dry};
    case 3: return {drx, -drz, dry};
    case 4: return {drx, -dry, drz};
    default: return {-drx, -dry, drz};
  }
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

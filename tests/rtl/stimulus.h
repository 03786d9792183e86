// Stimulus shared by the RTL test binaries that do not link lockstep.cpp (header-only, model types
// only): unnormalized samplers and their texel coordinates.
#pragma once
#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "model/sampler.h"

namespace tex::rtltest {

// A coordinate of an unnormalized sampler, Q16.16 texels, for a side of n texels: near a texel
// edge or centre within 3 texels of the side (a few raw units off), anywhere in [-2n, 3n), any
// 32-bit value, or an edge case (0, n, beyond 2n, +-2^14 texels: past the RTL's clamp).
inline int32_t texel_coordinate(std::mt19937_64& rng, int n) {
  const int kind = int(rng() % 100);
  const int64_t one = int64_t(1) << kTexelCoordFracBits;
  if (kind < 50) {
    int64_t u = (int64_t(rng() % uint64_t(n + 6)) - 3) * one + ((rng() & 1) ? one / 2 : 0);
    if (rng() % 3) u += int64_t(rng() % 257) - 128;
    return int32_t(u);
  }
  if (kind < 80) return int32_t(int64_t(rng() % uint64_t(5 * n * one)) - 2 * n * one);
  if (kind < 92) return int32_t(uint32_t(rng()));
  const int64_t edges[] = {0, 1, -1, n * one, n * one - 1, 2 * n * one + 1, -2 * n * one - 1,
                           int64_t(1) << 30, -(int64_t(1) << 30), INT32_MIN, INT32_MAX};
  return int32_t(edges[rng() % (sizeof edges / sizeof edges[0])]);
}

// Makes a sampler unnormalized the way Vulkan allows: its wrap modes clamp (clamp to edge or to
// border, drawn again if not), one texel filter, no anisotropy, the base level only (mipmap mode
// none, or its mode with max LOD clamped to <= 0).
inline void make_unnormalized(std::mt19937_64& rng, SamplerConfig& c) {
  c.unnormalized = true;
  for (Wrap* w : {&c.wrap_u, &c.wrap_v})
    if (*w != Wrap::Clamp && *w != Wrap::Border) *w = rng() % 2 ? Wrap::Clamp : Wrap::Border;
  c.filter.anisotropic = false;
  c.filter.mag = c.filter.texel;
  if (c.filter.mip != MipMode::None && rng() % 2) c.filter.mip = MipMode::None;
  if (c.filter.mip != MipMode::None) {  // Vulkan's form: mipmaps clamped to level 0
    c.max_lod = std::min(c.max_lod, rng() % 2 ? 0 : -int32_t(rng() % 512));
    c.min_lod = std::min(c.min_lod, c.max_lod);
  }
}

// Gives the requests of the table's unnormalized samplers texel coordinates of their texture.
template <class SizeOf>
void texel_coordinates_where_unnormalized(std::mt19937_64& rng, std::vector<Request>& requests,
                                          const SamplerTable& samplers, SizeOf size_of_texture) {
  for (Request& r : requests)
    if (samplers[r.sampler].unnormalized) {
      const Extent e = size_of_texture(r.texture);
      r.u = texel_coordinate(rng, e.w);
      r.v = texel_coordinate(rng, e.h);
    }
}

}  // namespace tex::rtltest

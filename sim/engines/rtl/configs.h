// The compiled RTL configurations (declared once, in sim/engines/rtl/CMakeLists.txt) and what each
// takes: the smallest that holds a texture or a frame, the checks of its inputs, its cache pins and
// the shape the timing model clocks like it. No Verilated code and no pins: the model engine learns
// the configurations here, not from the pin driver (driver.h).
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "engines/engine.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"
#include "model/timing.h"

namespace tex::rtl {

// One Verilated parameter configuration of tex_unit or tex_unit_cached (TAG_W = kTagBits).
struct RtlConfig {
  std::string name;  // Verilator --prefix, e.g. "Vtex_unit_10x10"
  int max_log2_w = 0, max_log2_h = 0;
  int cw = 8;  // bits per channel
  // tex_unit_cached only (cached = false: tex_unit, the on-chip level memories).
  bool cached = false;
  int block_w = 0, block_h = 0;  // BLOCK_W, BLOCK_H
  int lines = 0;                 // LINES: lines per cache at most
  int fifo_depth = 0;            // FIFO_DEPTH
  int mem_bits = 0;              // MEM_W: bits of a memory beat
  int miss_depth = 0;            // MISS_DEPTH: lines requested and not yet received, at most
  int textures = 1;              // TEXTURES: descriptor-table entries (tex_unit: 1)
  int fill_depth = 4;            // FILL_DEPTH: lines received and not yet written (the RTL's default)
  // BLOCK_FORMATS = SRGB = 1: BC1-BC5 and BC7 blocks and sRGB codes decoded after the cache, 8-bit
  // channels in memory, a CW = 16 filter (a linear 8-bit texture's values enter it as they are).
  bool formats = false;
  int samplers = 1;              // SAMPLERS: sampler-table entries (tex_unit: its one sampler)
  // CUBE_MAPS = 1: cube maps and cube arrays (tex_cube ahead of tex_probe, tex_cube_seam after it:
  // 10 clocks more latency), faces of n x n texels with n + 2 at most the smaller side.
  bool cube_maps = false;
  int max_cube_face() const { return (1 << std::min(max_log2_w, max_log2_h)) - 2; }
  int memory_channel_bits() const { return formats ? 8 : cw; }
  int line_bytes() const { return block_w * block_h * (memory_channel_bits() > 8 ? 8 : 4); }
  Memory memory() const { return cached ? Memory::Cached : Memory::OnChip; }
  bool fits(int log2_w, int log2_h) const { return log2_w <= max_log2_w && log2_h <= max_log2_h; }
  std::string max_texture() const;  // "1024x1024"
};

// Every compiled configuration (declared once, in sim/engines/rtl/CMakeLists.txt), in that order.
const std::vector<RtlConfig>& compiled_configs();
// The smallest configuration of that memory organisation with cw-bit channels that holds the
// pyramid (cached: with the block shape asked for, and the formats if `formats`); throws tex::Error
// naming the largest one when none does (and the texture: `size` if given, else 2^log2_w x 2^log2_h).
const RtlConfig& smallest_config_for(int log2_w, int log2_h, int cw = 8, Memory memory = Memory::OnChip,
                                     int block_w = 4, int block_h = 4, bool formats = false, Extent size = {},
                                     bool cubes = false);
// The same for a descriptor table: the largest sides, the widest channels the filter takes, and,
// cached, a configuration with the formats if any texture is block-compressed or sRGB, and the
// smallest whose caches and FIFO hold `cache` and `fifo_depth` when one does (if none does, the
// smallest that holds the textures: cache_pins() then says what does not fit).
const RtlConfig& smallest_config_for(const TextureTable& textures, Memory memory, int block_w, int block_h,
                                     const CacheParams* cache = nullptr, uint32_t fifo_depth = 0);
// Everything the RTL cannot take, as one tex::Error, before any clock: a texture too large or with
// other channel widths than the configuration's, a lambda outside the 16-bit Q8.8 port.
void check_inputs(const RtlConfig& config, const Pyramid& pyramid, const std::vector<Request>& requests = {});
void check_request(const Request& request, size_t index);  // lod and bias fit the 16-bit Q8.8 ports
// A cube map the configuration cannot take (no CUBE_MAPS, a face larger than max_cube_face(), not
// RGBA), as one tex::Error.
void check_cube(const RtlConfig& config, const BoundTexture& texture);

// The cache pins of tex_unit_cached for a cache geometry (throws tex::Error when the
// configuration cannot hold it).
struct CachePins {
  bool block_morton = false;
  uint8_t log2_sets = 2, log2_ways = 0;
  uint32_t fifo_limit = 0;  // samples the FIFO holds at most
};
// Throws tex::Error naming what does not fit the configuration. fifo_depth 0 = its FIFO_DEPTH.
CachePins cache_pins(const RtlConfig& config, const LayoutParams& layout, const CacheParams& cache,
                     uint32_t fifo_depth);

// The parameters the timing model needs to clock this configuration like the RTL (fifo_depth: the
// cfg_fifo_limit in use, 0 = FIFO_DEPTH).
UnitShape unit_shape(const RtlConfig& config, uint32_t fifo_depth = 0);

}  // namespace tex::rtl

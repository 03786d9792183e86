// The compiled configurations and what each takes (configs.h).
#include "engines/rtl/configs.h"

#include <algorithm>
#include <cstdio>

#include "model/block_formats.h"
#include "model/error.h"
#include "model/formats.h"
#include "rtl_config_list.h"  // generated: TEX_RTL_CONFIGS(X), the list of sim/engines/rtl/CMakeLists.txt

namespace tex::rtl {

const std::vector<RtlConfig>& compiled_configs() {
#define TEX_RTL_CONFIG_ENTRY(prefix, log2_w, log2_h, cw, cached, bw, bh, lines, fifo, mem_w, miss, formats, cubes) \
  RtlConfig{#prefix, log2_w, log2_h, cw, cached, bw, bh, lines, fifo, mem_w, miss, cached ? kMaxTextures : 1, 4, \
            formats != 0, cached ? kMaxSamplers : 1, cubes != 0},
  static const std::vector<RtlConfig> configs = {TEX_RTL_CONFIGS(TEX_RTL_CONFIG_ENTRY)};
#undef TEX_RTL_CONFIG_ENTRY
  return configs;
}

namespace {

std::string size_text(int log2_w, int log2_h) { return std::to_string(1 << log2_w) + "x" + std::to_string(1 << log2_h); }

}  // namespace

// ---------------------------------------------------------------- configurations and inputs

std::string RtlConfig::max_texture() const { return size_text(max_log2_w, max_log2_h); }

const RtlConfig& smallest_config_for(int log2_w, int log2_h, int cw, Memory memory, int block_w, int block_h,
                                     bool formats, Extent size, bool cubes) {
  const RtlConfig* best = nullptr;
  const RtlConfig* largest = nullptr;
  const bool cached = memory == Memory::Cached;
  // A unit with the formats also takes 8-bit linear textures (its filter's 16-bit channels hold
  // their 8-bit values: the same results); among units that fit, the smallest, then one without.
  auto takes = [&](const RtlConfig& c) {
    return c.cached == cached && (formats ? c.formats : c.cw == cw || (c.formats && cw == 8)) && (!cubes || c.cube_maps);
  };
  auto area = [](const RtlConfig* c) { return c->max_log2_w + c->max_log2_h; };
  for (const RtlConfig& c : compiled_configs()) {
    if (!takes(c)) continue;
    if (cached && (c.block_w != block_w || c.block_h != block_h)) continue;
    if (c.fits(log2_w, log2_h) &&
        (!best || area(&c) < area(best) || (area(&c) == area(best) && best->formats && !c.formats)))
      best = &c;
    if (!largest || area(&c) > area(largest)) largest = &c;
  }
  if (best) return *best;
  if (!largest) {
    std::string built;
    for (const RtlConfig& c : compiled_configs())
      if (const std::string shape = std::to_string(c.block_w) + "x" + std::to_string(c.block_h);
          takes(c) && built.find(shape) == std::string::npos)
        built += (built.empty() ? "" : ", ") + shape;
    if (cached && !built.empty())
      throw Error("no cached RTL configuration is built for " + std::to_string(block_w) + "x" +
                  std::to_string(block_h) + " blocks of " + std::to_string(cw) + "-bit texels (built: " + built + ")");
    throw Error("no " + memory_name(memory) + " RTL configuration is built for " + std::to_string(cw) +
                "-bit channels" + (formats ? " with the block decoders and sRGB tables" : "") +
                (cubes ? " and cube maps (CUBE_MAPS: tex_unit_cached only)" : ""));
  }
  const std::string named = size.w > 1 || size.h > 1 ? std::to_string(size.w) + "x" + std::to_string(size.h)
                                                      : size_text(log2_w, log2_h);
  // On chip: say whether the cached unit would take it (the sRGB and block-format units are cached).
  std::string hint = "use --engine model for larger textures";
  if (!cached)
    for (const RtlConfig& c : compiled_configs())
      if (c.cached && c.fits(log2_w, log2_h) && (c.cw == cw || c.formats)) {
        hint = "use --memory cached (" + c.name + " takes " + c.max_texture() + ") or --engine model";
        break;
      }
  throw Error("texture " + named + " does not fit the RTL: the largest compiled " +
              (cached ? std::string("tex_unit_cached") : "on-chip tex_unit") + (cw != 8 ? " of " + std::to_string(cw) + "-bit channels" : std::string()) +
              " takes " + largest->max_texture() + " (" + hint + ")");
}

const RtlConfig& smallest_config_for(const TextureTable& textures, Memory memory, int block_w, int block_h,
                                     const CacheParams* cache, uint32_t fifo_depth) {
  int log2_w = 0, log2_h = 0, cw = 8;
  Extent largest_size;  // the largest sides, as the error names them
  bool formats = false;  // cached: blocks or sRGB codes to decode after the cache (a CW = 16 unit)
  bool cubes = false;    // a cube map: CUBE_MAPS, and its skirted faces (n + 2) fit both sides
  for (const BoundTexture& t : textures) {
    const bool cube = t.kind == TextureKind::Cube;
    cubes = cubes || cube;
    const int skirt = cube ? log2_ceil(t.pyramid->extent0().w + 2) : 0;
    log2_w = std::max({log2_w, log2_ceil(t.pyramid->extent0().w), skirt});
    log2_h = std::max({log2_h, log2_ceil(t.pyramid->extent0().h), skirt});
    largest_size = {std::max(largest_size.w, t.pyramid->extent0().w), std::max(largest_size.h, t.pyramid->extent0().h)};
    cw = std::max(cw, t.pyramid->levels[0].channel_bits);
    formats = formats || t.pyramid->srgb || is_compressed(t.pyramid->format);
  }
  formats = formats && memory == Memory::Cached;
  const RtlConfig& fits =
      smallest_config_for(log2_w, log2_h, formats ? 16 : cw, memory, block_w, block_h, formats, largest_size, cubes);
  auto holds = [&](const RtlConfig& c) {
    return cache->size_bytes / c.line_bytes() <= c.lines && fifo_depth <= uint32_t(c.fifo_depth);
  };
  if (memory != Memory::Cached || !cache || holds(fits)) return fits;
  // A larger configuration of the same kind whose caches hold the geometry asked for.
  const RtlConfig* best = nullptr;
  for (const RtlConfig& c : compiled_configs())
    if (c.cached && (fits.formats ? c.formats : c.cw == fits.cw || (c.formats && fits.cw == 8)) && (!cubes || c.cube_maps) &&
        c.block_w == block_w && c.block_h == block_h &&
        c.fits(log2_w, log2_h) && holds(c) &&
        (!best || c.max_log2_w + c.max_log2_h < best->max_log2_w + best->max_log2_h))
      best = &c;
  return best ? *best : fits;
}

void check_inputs(const RtlConfig& config, const Pyramid& pyramid, const std::vector<Request>& requests) {
  const Extent e = pyramid.extent0();
  if (!config.fits(log2_ceil(e.w), log2_ceil(e.h)))
    throw Error("texture " + std::to_string(e.w) + "x" + std::to_string(e.h) + " does not fit " + config.name +
                " (at most " + config.max_texture() + ")");
  // A unit with the formats filters 16-bit channels: an sRGB texture's decoded ones, or a linear
  // 8-bit texture's as they are; memory holds 8-bit channels (or blocks) for both.
  const int bits = pyramid.levels[0].channel_bits;
  if (config.formats ? pyramid.memory_channel_bits() != 8 : bits != config.cw)
    throw Error(config.name + " is built for " +
                (config.formats ? std::string("8-bit channels in memory (RGBA8, blocks or sRGB)")
                                : std::to_string(config.cw) + "-bit channels") +
                "; this texture has " + std::to_string(config.formats ? pyramid.memory_channel_bits() : bits) +
                "-bit channels");
  // (on chip a block-format or sRGB texture is held decoded, as the paper's memories hold texels)
  if ((pyramid.srgb || is_compressed(pyramid.format)) && config.cached && !config.formats)
    throw Error(std::string("a ") + format_info(pyramid.format).name + (pyramid.srgb ? " sRGB" : "") + " texture: " +
                config.name + " has no block decoders or sRGB tables (built without FORMATS)");
  for (size_t i = 0; i < requests.size(); ++i) check_request(requests[i], i);
}

void check_cube(const RtlConfig& config, const BoundTexture& texture) {
  const int n = texture.pyramid->extent0().w;
  if (!config.cube_maps)
    throw Error(config.name + ": a cube map; this configuration is built without cube maps (CUBE_MAPS = 0)");
  if (n > config.max_cube_face())
    throw Error(config.name + ": a cube map of " + std::to_string(n) + "x" + std::to_string(n) +
                " faces; its faces take at most " + std::to_string(config.max_cube_face()) + "x" +
                std::to_string(config.max_cube_face()) + " (stored with a one-texel skirt, n + 2 <= " +
                std::to_string(config.max_cube_face() + 2) + ")");
}

void check_request(const Request& request, size_t index) {
  if (request.op != Op::Sample && request.op != Op::Compare && request.has_derivatives)
    throw Error("request " + std::to_string(index) + ": a " + op_name(request.op) + " carries no derivatives");
  if (request.component > 3)
    throw Error("request " + std::to_string(index) + ": component " + std::to_string(request.component) + " is not 0..3");
  if (!request.has_derivatives && (request.lod < kLodMin || request.lod > kLodMax))
    throw Error("request " + std::to_string(index) + ": lod " + std::to_string(request.lod) +
                "/256 is outside the 16-bit Q8.8 port of the RTL");
  if (request.bias < kLodMin || request.bias > kLodMax)
    throw Error("request " + std::to_string(index) + ": bias " + std::to_string(request.bias) +
                "/256 is outside the 16-bit Q8.8 port of the RTL");
}

CachePins cache_pins(const RtlConfig& config, const LayoutParams& layout, const CacheParams& cache,
                     uint32_t fifo_depth) {
  if (layout.block_w != config.block_w || layout.block_h != config.block_h)
    throw Error(config.name + " is built for " + std::to_string(config.block_w) + "x" + std::to_string(config.block_h) +
                " blocks, not " + std::to_string(layout.block_w) + "x" + std::to_string(layout.block_h));
  const int line = config.line_bytes();
  const int lines = cache.size_bytes / line;
  const int sets = lines / std::max(cache.ways, 1);
  if (lines > config.lines)
    throw Error("a cache of " + std::to_string(cache.size_bytes / 1024.0).substr(0, 5) + " KiB (" +
                std::to_string(lines) + " lines of " + std::to_string(line) + " bytes) does not fit " + config.name +
                ": at most " + std::to_string(config.lines) + " lines (" +
                std::to_string(config.lines * line / 1024) + " KiB) per cache");
  if (fifo_depth > uint32_t(config.fifo_depth))
    throw Error("a FIFO of " + std::to_string(fifo_depth) + " samples does not fit " + config.name + ": FIFO_DEPTH is " +
                std::to_string(config.fifo_depth));
  CachePins p;
  p.fifo_limit = fifo_depth ? fifo_depth : uint32_t(config.fifo_depth);
  p.block_morton = layout.order == BlockOrder::Morton;
  while ((1 << p.log2_sets) < sets) ++p.log2_sets;
  while ((1 << p.log2_ways) < cache.ways) ++p.log2_ways;
  if ((1 << p.log2_sets) != sets || (1 << p.log2_ways) != cache.ways || sets < 4)
    throw Error("cache geometry " + std::to_string(lines) + " lines / " + std::to_string(cache.ways) +
                " ways: the sets must be a power of two, at least 4");
  return p;
}

UnitShape unit_shape(const RtlConfig& config, uint32_t fifo_depth) {
  UnitShape s;
  s.cached = config.cached;
  if (!config.cached) return s;
  s.fifo_depth = uint32_t(config.fifo_depth);
  s.fifo_limit = fifo_depth;
  s.miss_depth = uint32_t(config.miss_depth);
  s.fill_depth = uint32_t(config.fill_depth);
  s.line_beats = uint32_t(config.line_bytes() * 8 / config.mem_bits);
  s.cube_clocks = config.cube_maps ? kCubeClocks : 0;
  return s;
}

}  // namespace tex::rtl

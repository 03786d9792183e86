#include "texture_cache.h"

#include <stdexcept>

#include "error.h"
#include "sampler.h"
#include "stages.h"

namespace tex {

std::vector<MemoryLayout> pack_layouts(const std::vector<Extent>& sizes, int channel_bits,
                                       const LayoutParams& params, const std::vector<TexelFormat>& formats,
                                       const std::vector<int>& levels, const std::vector<int>& layers,
                                       const std::vector<TextureKind>& kinds) {
  std::vector<MemoryLayout> out;
  LayoutParams p = params;
  uint64_t next = params.base;
  for (const Extent& size : sizes) {
    if (next > 0xFFFFFFFFull)
      throw Error("textures: " + std::to_string(sizes.size()) + " pyramids do not fit the 32-bit address space");
    p.base = uint32_t(next);
    const TexelFormat f = out.size() < formats.size() ? formats[out.size()] : TexelFormat::Rgba8;
    const int n = out.size() < levels.size() ? levels[out.size()] : 0;
    const int l = out.size() < layers.size() ? layers[out.size()] : 1;
    const TextureKind k = out.size() < kinds.size() ? kinds[out.size()] : TextureKind::Texture2D;
    out.emplace_back(size, channel_bits, p, f, n, l, k);  // throws when it ends beyond 2^32
    next += out.back().image_bytes();                   // a whole number of lines
  }
  return out;
}

TextureCache::TextureCache(const MemoryLayout& layout, const CacheParams& params, const SamplerConfig& config)
    : TextureCache({TextureDescriptor{layout}}, params, SamplerTable{config}) {}

TextureCache::TextureCache(std::vector<TextureDescriptor> textures, const CacheParams& params,
                           SamplerTable samplers)
    : textures_(std::move(textures)), samplers_(std::move(samplers)), ways_(params.ways) {
  if (textures_.empty() || textures_.size() > size_t(kMaxTextures))
    throw Error("texture cache: " + std::to_string(textures_.size()) + " textures; the descriptor table holds 1 to " +
                std::to_string(kMaxTextures));
  if (samplers_.empty() || samplers_.size() > size_t(kMaxSamplers))
    throw Error("texture cache: " + std::to_string(samplers_.size()) + " samplers; the sampler table holds 1 to " +
                std::to_string(kMaxSamplers));
  for (size_t i = 0; i < samplers_.size(); ++i) check_sampler(samplers_[i], "texture cache: sampler " + std::to_string(i) + ": ");
  const MemoryLayout& layout0 = textures_[0].layout;
  line_bytes_ = layout0.line_bytes();
  for (const TextureDescriptor& t : textures_)
    if (t.layout.line_bytes() != line_bytes_ || t.layout.params().block_w != layout0.params().block_w ||
        t.layout.params().block_h != layout0.params().block_h)
      throw Error("texture cache: every texture must have the same block shape and texel size");
  if (ways_ != 1 && ways_ != 2 && ways_ != 4)
    throw Error("cache ways " + std::to_string(ways_) + ": must be 1, 2 or 4");
  const int line = line_bytes_;
  if (params.size_bytes <= 0 || params.size_bytes % line != 0)
    throw Error("cache size " + std::to_string(params.size_bytes) + " bytes is not a whole number of " +
                std::to_string(line) + "-byte lines");
  sets_ = params.size_bytes / line / ways_;
  if (sets_ < 4 || (sets_ & (sets_ - 1)) != 0)
    throw Error("a cache of " + std::to_string(params.size_bytes) + " bytes with " + std::to_string(ways_) +
                " ways has " + std::to_string(sets_) + " sets: must be a power of two, at least 4");
  while ((4 << log2_sets_hi_) < sets_) ++log2_sets_hi_;
  reversed_.assign(size_t(sets_ / 4), 0);
  for (uint32_t i = 0; i < reversed_.size(); ++i)
    for (int b = 0; b < log2_sets_hi_; ++b)
      if (i >> b & 1) reversed_[i] |= 1u << (log2_sets_hi_ - 1 - b);
  for (auto& c : caches_) {
    c.assign(size_t(sets_ * ways_), Way{});
    for (int s = 0; s < sets_; ++s)
      for (int w = 0; w < ways_; ++w) c[size_t(s * ways_ + w)].age = w;  // reset: age = way number
  }
}

bool TextureCache::access(int cache, int set, uint32_t address, Way*& used_way) {
  Way* ways = &caches_[size_t(cache)][size_t(set * ways_)];
  const int n = ways_;
  // The hit, else the victim: the way of age n - 1 (the ages of a set are always 0..n-1).
  int used = -1;
  for (int w = 0; w < n; ++w)
    if (ways[w].valid && ways[w].tag == address) used = w;
  const bool hit = used >= 0;
  if (!hit)
    for (int w = 0; w < n; ++w)
      if (ways[w].age == n - 1) used = w;
  const int age = ways[used].age;
  for (int w = 0; w < n; ++w) ways[w].age += ways[w].age < age;
  ways[used].age = 0;
  ++stats_.lookups[size_t(cache)];
  const uint64_t previous_use = ways[used].last_use;
  ways[used].last_use = sample_ + 1;
  used_way = &ways[used];
  if (hit) {
    ++stats_.hits[size_t(cache)];
    return true;
  }
  if (ways[used].valid && previous_use == sample_) ++stats_.evictions_of_previous;
  ways[used].valid = true;
  ways[used].tag = address;
  ++reads_;
  ways[used].error = next_error_ < error_reads_.size() && error_reads_[next_error_] == reads_;
  next_error_ += ways[used].error;
  ++stats_.misses[size_t(cache)];
  return false;
}

void TextureCache::bad_texture(const Request& r) const {
  throw Error("texture cache: request names texture " + std::to_string(r.texture) + "; the table holds " +
              std::to_string(textures_.size()));
}

void TextureCache::bad_sampler(const Request& r) const {
  throw Error("texture cache: request names sampler " + std::to_string(r.sampler) + "; the table holds " +
              std::to_string(samplers_.size()));
}


RequestWork TextureCache::lookup_sample(const Request& r, std::vector<uint32_t>* misses) {
  const MemoryLayout& layout = texture(r).layout;
  RequestWork w;
  if (layout.kind() == TextureKind::Cube && r.op != Op::Fetch && r.has_derivatives) {
    // The face's request and its probes, each on the face it lies over (as Sampler::sample).
    int face = 0;
    const Request q = cube_face_request(r, face);
    const int base = stage::cube_base_layer(r.layer, layout.layers());
    const Probes p = tex_probe(q, sampler(r), layout.size0());
    w.probes = uint8_t(p.n);
    for (int i = 0; i < p.n; ++i) {
      Request probe = p.at[size_t(i)];
      const int f = cube_probe(face, probe);
      const SampleLookup l = lookup_at(probe, base + f, true, misses);
      w.set_fills(i, uint32_t(l.slot[0].misses + l.slot[1].misses));
      w.error = w.error || l.error();
    }
    return w;
  }
  if (!r.has_derivatives) {  // (one probe: the request itself)
    const SampleLookup l = lookup(r, misses);
    w.set_fills(0, uint32_t(l.slot[0].misses + l.slot[1].misses));
    w.error = l.error();
    return w;
  }
  const Probes p = tex_probe(r, sampler(r), layout.size0());
  w.probes = uint8_t(p.n);
  for (int i = 0; i < p.n; ++i) {
    const SampleLookup l = lookup(p.at[size_t(i)], misses);
    w.set_fills(i, uint32_t(l.slot[0].misses + l.slot[1].misses));
    w.error = w.error || l.error();
  }
  return w;
}

SampleLookup TextureCache::lookup(const Request& r, std::vector<uint32_t>* misses) {
  if (r.has_derivatives) throw Error("texture cache: lookup() takes a probe; use lookup_sample() for a request");
  const MemoryLayout& layout = texture(r).layout;
  if (layout.kind() == TextureKind::Cube && r.op != Op::Fetch) {  // the direction's face
    int face = 0;
    const Request q = cube_face_request(r, face);
    return lookup_at(q, stage::cube_base_layer(r.layer, layout.layers()) + face, true, misses);
  }
  return lookup_at(r, stage::request_layer(r.op, r.layer, layout.layers()), layout.kind() == TextureKind::Cube, misses);
}

SampleLookup TextureCache::lookup_at(const Request& r, int layer, bool cube, std::vector<uint32_t>* misses) {
  const MemoryLayout& layout = texture(r).layout;
  const SamplerConfig& smp = sampler(r);
  SampleLookup out;
  // Each slot's level and taps: (x0, y0) always, x1 / y1 when their weight is not 0; a
  // clamp-to-border tap outside the level (stage::kBorderTap) reads no line. A texel fetch reads
  // its one texel in slot 0, or nothing (stage::fetch_inside).
  struct Taps {
    int32_t x[2], y[2];
    int nx = 1, ny = 1;
  } taps[2];
  // (layer -1: a fetch outside the layers. A cube face's texel (i, j) is stored at (i + 1, j + 1):
  // a cube's (u, v) here are its face's (s, t), its taps stage::cube_taps.)
  if (r.op == Op::Fetch) {
    out.slot[0].level = r.lod;
    out.slot[0].needed = layer >= 0 && stage::fetch_inside(r.u, r.v, r.lod, layout.levels() - 1, layout.size0());
    taps[0] = {{r.u + cube, r.u + cube}, {r.v + cube, r.v + cube}};
  } else {
    const int32_t ru = cube ? r.u : stage::reduce(r.u, smp.wrap_u, smp.unnormalized);
    const int32_t rv = cube ? r.v : stage::reduce(r.v, smp.wrap_v, smp.unnormalized);
    // The footprint of level k: a tap whose weight is 0 reads nothing, unless `all` (a gather).
    auto footprint = [&](int k, TexelFilter filter, bool all) -> Taps {
      const Extent e = layout.level_size(k);
      // (the repeat seam's second tap reads the copy wherever the layout keeps one)
      const stage::WrappedTaps tu = cube ? stage::cube_taps(ru, e.w, filter)
                                         : stage::axis_taps(ru, e.w, smp.wrap_u, filter, smp.unnormalized, layout.seam_x(k) != 0);
      const stage::WrappedTaps tv = cube ? stage::cube_taps(rv, e.h, filter)
                                         : stage::axis_taps(rv, e.h, smp.wrap_v, filter, smp.unnormalized, layout.seam_y(k) != 0);
      return {{tu.i0, tu.i1}, {tv.i0, tv.i1}, all || tu.w != 0 ? 2 : 1, all || tv.w != 0 ? 2 : 1};
    };
    if (r.op == Op::Gather) {  // the linear filter's four taps at the base level, all read
      out.slot[0].needed = true;
      taps[0] = footprint(0, TexelFilter::Linear, true);
    } else {
      const stage::LevelSelect sel =
          stage::lod(r.lod, smp.lod_bias + r.bias, smp.min_lod, smp.max_lod, smp.filter.mip, layout.levels() - 1);
      const TexelFilter texel_filter = stage::texel_filter(sel, smp.filter);
      for (int s = 0; s < 2; ++s) {
        SlotLookup& sl = out.slot[size_t(s)];
        sl.level = s == 0 ? sel.d : sel.d1;
        sl.needed = s == 0 || sel.f != 0;
        if (sl.needed) taps[s] = footprint(sl.level, texel_filter, false);
      }
    }
  }
  for (int s = 0; s < 2; ++s) {
    SlotLookup& sl = out.slot[size_t(s)];
    if (!sl.needed) continue;
    const int k = sl.level;
    const int32_t* x = taps[s].x;
    const int32_t* y = taps[s].y;
    const int nx = taps[s].nx, ny = taps[s].ny;
    // Distinct blocks by parity (two distinct blocks of a footprint differ in a parity).
    uint32_t bx_of[4] = {}, by_of[4] = {};
    for (int j = 0; j < nx; ++j)
      for (int i = 0; i < ny; ++i) {
        if (x[j] == stage::kBorderTap || y[i] == stage::kBorderTap) continue;
        const uint32_t sx = cube ? uint32_t(x[j]) : layout.stored_x(k, uint32_t(x[j]));  // (a cube: no seam copy)
        const uint32_t sy = cube ? uint32_t(y[i]) : layout.stored_y(k, uint32_t(y[i]));
        const uint32_t bx = layout.line_x(sx), by = layout.line_y(sy);
        const int p = int((by & 1) << 1 | (bx & 1));
        // Two blocks of one parity would need two lookups in one set group: the layout (the
        // seam copies included) rules it out.
        if ((sl.block_mask >> p & 1) && (bx_of[p] != bx || by_of[p] != by))
          throw std::logic_error("texture cache: two blocks of one parity in a footprint");
        sl.block_mask |= uint8_t(1 << p);
        bx_of[p] = bx;
        by_of[p] = by;
      }
    const int cache = k & 1;
    std::array<uint32_t, 4> address{};
    bool same = last_[size_t(cache)].mask == sl.block_mask;
    for (int p = 0; p < 4; ++p)
      if (sl.block_mask >> p & 1) {
        address[size_t(p)] = layout.block_address(k, bx_of[p], by_of[p], layer);
        same = same && address[size_t(p)] == last_[size_t(cache)].address[size_t(p)];
      }
    LastLookup& last = last_[size_t(cache)];
    if (same) {  // the lines the last lookup of this cache left most recent: all hit, no age moves
      for (int p = 0; p < 4; ++p)
        if (sl.block_mask >> p & 1) {
          ++sl.blocks;
          last.way[size_t(p)]->last_use = sample_ + 1;
          sl.error = sl.error || last.way[size_t(p)]->error;
        }
      stats_.lookups[size_t(cache)] += uint64_t(sl.blocks);
      stats_.hits[size_t(cache)] += uint64_t(sl.blocks);
      continue;
    }
    last.mask = sl.block_mask;
    last.address = address;
    for (int p = 0; p < 4; ++p) {
      if (!(sl.block_mask >> p & 1)) continue;
      ++sl.blocks;
      if (!access(cache, set_index(bx_of[p], by_of[p]), address[size_t(p)], last.way[size_t(p)])) {
        ++sl.misses;
        if (misses) misses->push_back(address[size_t(p)]);
      }
      sl.error = sl.error || last.way[size_t(p)]->error;
    }
  }
  ++sample_;
  return out;
}

}  // namespace tex

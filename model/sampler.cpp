#include "sampler.h"

#include <string>
#include <type_traits>

#include "cube_map.h"
#include "error.h"
#include "stages.h"

namespace tex {

std::string SamplerConfig::unnormalized_problem() const {
  if (!unnormalized) return "";
  const std::string head = "unnormalized coordinates ";
  for (const Wrap w : {wrap_u, wrap_v})
    if (w != Wrap::Clamp && w != Wrap::Border)
      return head + "take the clamp or border address mode, not " + wrap_name(w);
  if (filter.anisotropic) return head + "take no anisotropic filter";
  if (filter.mag != filter.texel)
    return head + "take one texel filter: the magnification filter " + texel_filter_name(filter.mag) +
           " differs from the minification filter " + texel_filter_name(filter.texel);
  if (filter.mip != MipMode::None && max_lod > 0)
    return head + "read the base level only: mipmap mode " + mip_mode_name(filter.mip) + " with max LOD " +
           std::to_string(max_lod / 256.0) + " (use mipmap mode none, or a max LOD of 0)";
  return "";
}

std::string SamplerConfig::compare_problem() const {
  if (reduction != Reduction::WeightedAverage)
    return "a depth compare filters the weighted average of the tests, not their " + reduction_name(reduction) +
           " (Vulkan: compareEnable with reductionMode WEIGHTED_AVERAGE only)";
  if (unnormalized) return "a depth compare takes normalized coordinates (Vulkan: not with unnormalizedCoordinates)";
  return "";
}

void check_sampler(const SamplerConfig& config, const std::string& where) {
  if (const std::string p = config.unnormalized_problem(); !p.empty()) throw Error(where + p);
}

Request cube_face_request(const Request& r, int& face) {
  const stage::CubeFace f = stage::cube_face(r.u, r.v, r.w);
  face = f.face;
  Request q = r;
  q.u = f.s;
  q.v = f.t;
  q.w = 0;
  if (r.has_derivatives) {
    const std::array<int32_t, 2> dx = stage::cube_derivatives(f, r.deriv.dudx, r.deriv.dvdx, r.dwdx);
    const std::array<int32_t, 2> dy = stage::cube_derivatives(f, r.deriv.dudy, r.deriv.dvdy, r.dwdy);
    q.deriv = {dx[0], dx[1], dy[0], dy[1]};
    q.dwdx = q.dwdy = 0;
  }
  return q;
}

int cube_probe(int face, Request& probe) {
  constexpr int32_t one = 1 << kCoordFracBits;
  if (probe.u >= 0 && probe.u <= one && probe.v >= 0 && probe.v <= one) return face;
  const stage::CubeFace f = stage::cube_reproject(face, probe.u, probe.v);
  probe.u = f.s;
  probe.v = f.t;
  return f.face;
}

Sampler::Sampler(const std::vector<const Pyramid*>& layers, const SamplerConfig& config, SamplerPaths paths,
                 TextureKind kind)
    : config_(config),
      channel_bits_(layers.empty() ? 8 : layers[0]->levels[0].channel_bits),
      border_(stage::border_texel(config.border_unorm16(), channel_bits_)),
      size0_(layers.empty() ? Extent{} : layers[0]->extent0()),
      last_level_(layers.empty() ? 0 : layers[0]->last_level()),
      layers_(int(layers.size())),
      depth_problem_(layers.empty() ? "" : layers[0]->depth_problem()),
      kind_(kind) {
  if (layers_ < 1 || layers_ > kMaxLayers)
    throw Error("sampler: " + std::to_string(layers_) + " layers; an array texture has 1 to " + std::to_string(kMaxLayers));
  for (int l = 1; l < layers_; ++l)
    if (layers[size_t(l)]->extent0() != size0_ || layers[size_t(l)]->last_level() != last_level_ ||
        layers[size_t(l)]->levels[0].channel_bits != channel_bits_ || layers[size_t(l)]->format != layers[0]->format)
      throw Error("sampler: layer " + std::to_string(l) + " differs from layer 0 in size, level count, format or channel width");
  check_sampler(config, "sampler: ");
  if (paths == SamplerPaths::FastOnly && channel_bits_ != 8)
    throw Error("sampler: the fast path takes 8-bit channels; this texture has " + std::to_string(channel_bits_));
  if (paths == SamplerPaths::FastOnly && !fast_path_takes(config))
    throw Error("sampler: the fast path takes neither clamp to border nor a magnification filter of its own");
  if (kind == TextureKind::Cube) {  // skirted faces, the reference path
    if (paths == SamplerPaths::FastOnly) throw Error("sampler: a cube map is sampled by the reference path");
    if (config.unnormalized) throw Error("sampler: a cube map takes normalized coordinates (Vulkan: not unnormalizedCoordinates)");
    for (const Pyramid& p : cube_skirts(layers)) memory_.emplace_back(p);
    return;
  }
  if (paths == SamplerPaths::Both)
    for (const Pyramid* p : layers) memory_.emplace_back(*p);
  if (channel_bits_ == 8)
    for (int l = 0; l < layers_; ++l)
      for (const Image& img : layers[size_t(l)]->levels) {
        packed_.emplace_back(size_t(stored_side(img.width)) * size_t(stored_side(img.height)));
        const int k = int(packed_.size()) - 1 - l * (last_level_ + 1);
        for (int y = 0; y < img.height; ++y)
          for (int x = 0; x < img.width; ++x) write_packed(l, k, x, y, img.at(x, y));
      }
}

void Sampler::write_packed(int layer, int level, int32_t x, int32_t y, const Texel& t) {
  const Extent e = level_extent(size0_, level);
  const size_t stride = size_t(stored_side(e.w));
  const uint32_t v = uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
  BigVector<uint32_t>& p = packed_[size_t(layer * (last_level_ + 1) + level)];
  with_seam_copies(x, y, seam_copy(e.w), seam_copy(e.h),
                   [&](int32_t sx, int32_t sy) { p[size_t(sy) * stride + size_t(sx)] = v; });
}

bool Sampler::fast_path_takes(const SamplerConfig& config) {
  return !config.uses_border() && config.filter.mag == config.filter.texel && !config.unnormalized &&
         config.reduction == Reduction::WeightedAverage;
}

void Sampler::write_texel(int level, int32_t x, int32_t y, const Texel& t, int layer) {
  if (kind_ == TextureKind::Cube) throw Error("sampler: a cube map's texels are written with their skirts (cube_skirts)");
  if (!memory_.empty()) memory_[size_t(layer)].write(level, x, y, t);
  if (channel_bits_ == 8) write_packed(layer, level, x, y, t);
}

BankedMipMemory& Sampler::memory_of(const Request& r) {
  if (memory_.empty()) throw Error("sampler: built for the fast path only (SamplerPaths::FastOnly); sample_rgba8 samples it");
  return memory_[size_t(stage::array_layer(r.layer, layers_))];
}

Probes tex_probe(const Request& r, const SamplerConfig& config, Extent size0) {
  Probes p;
  p.at[0] = r;
  p.at[0].has_derivatives = false;
  if (!r.has_derivatives) return p;
  if (config.probe_cap() == 1) {  // one probe at tex_lambda (what tex_aniso gives with a cap of 1)
    p.at[0].lod = tex_lambda(r.deriv, size0);
    return p;
  }
  const AnisoSetup a = tex_aniso(r.deriv, size0, config.probe_cap(), config.aniso_pow2);
  p.n = a.n;
  for (int i = 0; i < a.n; ++i) {
    Request& q = p.at[size_t(i)];
    q = p.at[0];
    q.u = aniso_probe_coord(r.u, a.step_u, i, a.n);
    q.v = aniso_probe_coord(r.v, a.step_v, i, a.n);
    q.lod = a.lambda;
  }
  return p;
}

int tex_probe_count(const Request& r, const SamplerConfig& config, Extent size0) {
  if (!r.has_derivatives || config.probe_cap() == 1) return 1;
  return tex_aniso(r.deriv, size0, config.probe_cap(), config.aniso_pow2).n;
}

// The stages in pipeline order, as the RTL runs them (model/stages.h, docs/architecture.md).
Texel Sampler::sample(const Request& r) {
  if (r.op == Op::Fetch) return fetch(r);
  if (r.op == Op::Gather) return gather(r);
  if (r.op == Op::Compare) {
    if (const std::string p = config_.compare_problem(); !p.empty()) throw Error("sampler: " + p);
    if (!depth_problem_.empty()) throw Error("sampler: a depth compare of " + depth_problem_);
  }
  // A cube: the face's 2D request, each probe on the face it lies over (a cube array: the layer
  // picks the cube).
  int face = 0;
  const bool cube = kind_ == TextureKind::Cube;
  const Request q = cube ? cube_face_request(r, face) : r;
  const size_t cube_base = cube ? size_t(stage::cube_base_layer(r.layer, layers_)) : 0;
  auto value = [&](const Request& probe) {
    if (!cube) return sample_probe(probe);
    Request on_face = probe;  // (a cube's memories are always built: the reference path)
    const int f = cube_probe(face, on_face);
    return probe_value(memory_[cube_base + size_t(f)], on_face, true);
  };
  const Probes p = tex_probe(q, config_, size0_);
  ++samples_;
  ++probes_[size_t(p.n)];
  if (config_.reduction != Reduction::WeightedAverage) {  // the min or max over the probes too
    stage::Unrounded m = value(p.at[0]);
    for (int i = 1; i < p.n; ++i) {
      const stage::Unrounded t = value(p.at[size_t(i)]);
      for (size_t c = 0; c < 4; ++c) m[c] = config_.reduction == Reduction::Max ? std::max(m[c], t[c]) : std::min(m[c], t[c]);
    }
    return stage::average_and_round(m, 1);
  }
  stage::Unrounded sum{};
  for (int i = 0; i < p.n; ++i) {
    const stage::Unrounded t = value(p.at[size_t(i)]);
    for (size_t c = 0; c < 4; ++c) sum[c] += t[c];
  }
  return stage::average_and_round(sum, p.n);
}

// texelFetch: one probe, no filter (the filter's point sampling returns the texel exactly).
Texel Sampler::fetch(const Request& r) {
  if (memory_.empty()) throw Error("sampler: built for the fast path only (SamplerPaths::FastOnly); sample_rgba8 samples it");
  if (r.has_derivatives) throw Error("sampler: a texel fetch carries no derivatives");
  ++samples_;
  ++probes_[1];
  if (!stage::fetch_inside(r.u, r.v, r.lod, last_level(), size0_) || !stage::fetch_layer_inside(r.layer, layers_)) return {};
  const int32_t skirt = kind_ == TextureKind::Cube;  // (a cube face's texel (i, j) is stored at (i + 1, j + 1))
  return memory_[size_t(r.layer)].fetch(r.lod, r.u + skirt, r.u + skirt, r.v + skirt, r.v + skirt, true, border_)[0];
}

// textureGather: the linear filter's four taps at the base level, one component of each.
Texel Sampler::gather(const Request& r) {
  if (r.has_derivatives) throw Error("sampler: a gather carries no derivatives");
  if (kind_ == TextureKind::Cube) {
    int face = 0;
    const Request q = cube_face_request(r, face);
    ++samples_;
    ++probes_[1];
    BankedMipMemory& m = memory_[size_t(stage::cube_base_layer(r.layer, layers_) + face)];
    return stage::gather(footprint(m, 0, q.u, q.v, TexelFilter::Linear, true, true), r.component);
  }
  BankedMipMemory& memory = memory_of(r);
  ++samples_;
  ++probes_[1];
  const int32_t ru = stage::reduce(r.u, config_.wrap_u, config_.unnormalized), rv = stage::reduce(r.v, config_.wrap_v, config_.unnormalized);
  return stage::gather(footprint(memory, 0, ru, rv, TexelFilter::Linear, true), r.component);
}

// The 2x2 footprint of level k at the reduced coordinates (all four taps read, or only the first
// for a nearest filter unless `all_taps`), with the weights of the second taps.
stage::Footprint Sampler::footprint(BankedMipMemory& memory, int k, int32_t ru, int32_t rv, TexelFilter filter,
                                    bool all_taps, bool cube) {
  const Extent e = level_extent(size0_, k);  // (a skirted face's memory is 2 wider)
  const stage::WrappedTaps tu = cube ? stage::cube_taps(ru, e.w, filter)
                                     : stage::axis_taps(ru, e.w, config_.wrap_u, filter, config_.unnormalized);
  const stage::WrappedTaps tv = cube ? stage::cube_taps(rv, e.h, filter)
                                     : stage::axis_taps(rv, e.h, config_.wrap_v, filter, config_.unnormalized);
  stage::Footprint f;
  f.taps = memory.fetch(k, tu.i0, tu.i1, tv.i0, tv.i1, !all_taps && filter == TexelFilter::Nearest, border_);
  f.fx = tu.w;
  f.fy = tv.w;
  return f;
}

stage::Unrounded Sampler::sample_probe(const Request& r) {
  if (kind_ == TextureKind::Cube) throw Error("sampler: a cube map's probes are sample()'s (their faces)");
  return probe_value(memory_of(r), r, false);
}

stage::Unrounded Sampler::probe_value(BankedMipMemory& memory, const Request& r, bool cube) {
  const stage::LevelSelect sel =
      stage::lod(r.lod, config_.lod_bias + r.bias, config_.min_lod, config_.max_lod, config_.filter.mip, last_level());
  // (A cube face's s, t are in [0, 1] already: no address mode.)
  const int32_t ru = cube ? r.u : stage::reduce(r.u, config_.wrap_u, config_.unnormalized);
  const int32_t rv = cube ? r.v : stage::reduce(r.v, config_.wrap_v, config_.unnormalized);
  const TexelFilter texel_filter = stage::texel_filter(sel, config_.filter);
  const bool linear = texel_filter == TexelFilter::Linear;

  // Slot 0 is level d, slot 1 level d1 (fetched only when the filter blends two levels: with
  // f = 0 the blend returns slot 0 exactly).
  stage::Footprint slot[2];
  const int slots = sel.two_levels ? 2 : 1;
  for (int s = 0; s < slots; ++s) slot[s] = footprint(memory, s == 0 ? sel.d : sel.d1, ru, rv, texel_filter, false, cube);
  if (r.op == Op::Compare)  // each tap's test, then the filter weighs the passes
    for (int s = 0; s < slots; ++s)
      stage::compare_taps(slot[s], config_.compare_op, stage::compare_reference(r.ref, channel_bits_), channel_bits_);
  if (config_.reduction != Reduction::WeightedAverage)  // compares, no multiplies
    return stage::reduce_taps(slot[0], slot[sel.two_levels ? 1 : 0], sel.f, config_.reduction == Reduction::Max);
  multiplies_ += (linear ? 3 : 0) * slots + (sel.two_levels ? 1 : 0);
  return stage::filter_unrounded(slot[0], slot[sel.two_levels ? 1 : 0], sel.f);
}

namespace {

// ---------------------------------------------------------------- fast path (8-bit channels)
// Same results as sample() (docs/numerics.md), arranged for speed; it does not call the stage
// functions (tests/model/test_fastpath_equivalence.cpp checks every filter and wrap against sample()):
// - the filter and wrap modes are template parameters, so their branches leave the loop;
// - per-level constants (texel pointer, shifts, masks) are looked up in a small table;
// - two channels share one 64-bit word (R|B and G|A, 32 bits each): one multiply does two lerps.
//   Every value of stage 5 is a non-negative integer < 2^32 per channel (CW.24 with CW = 8), so
//   (a << 8) + (b - a) * w computed modulo 2^64 on the packed word gives both channels exactly:
//   the negative (b - a) terms borrow across the halves, but the exact sum has no negative half.

struct FastLevel {
  const uint32_t* texels;  // row-major packed RGBA8 of the stored sides
  size_t stride;           // stored width (stored_side)
  int32_t w, h;            // the level's sides
  int32_t seam_w, seam_h;  // the second repeat tap at the seam: 0 (a power of two) or the copy at w (h)
};

// R and B (bytes 0 and 2) in the low and high 32-bit halves; G and A likewise.
inline uint64_t spread_rb(uint32_t t) { return (t & 0xFFu) | uint64_t(t & 0xFF0000u) << 16; }
inline uint64_t spread_ga(uint32_t t) { return (t >> 8 & 0xFFu) | uint64_t(t >> 24) << 32; }

// stage::lerp on two packed channels, exact (see above).
inline uint64_t lerp2(uint64_t a, uint64_t b, uint32_t w) { return (a << 8) + (b - a) * w; }

// stage::wrap of an index of a reduced coordinate (stage::reduce): repeat indices are in [-1, n],
// mirror in [-1, 2n], so compares replace the modulo; same results. `seam`: FastLevel::seam_w/h.
template <Wrap W>
inline int32_t wrap_first(int32_t i, int32_t n) {
  if constexpr (W == Wrap::MirrorClamp) {
    const int32_t m = i < 0 ? -1 - i : i;
    return m > n - 1 ? n - 1 : m;
  }
  if constexpr (W == Wrap::Repeat) return i < 0 ? n - 1 : i;  // (a first tap is never n)
  if constexpr (W == Wrap::Clamp) return i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
  if constexpr (W == Wrap::Mirror) {
    const int32_t m = i < 0 ? -1 - i : i;                  // -1 -> 0
    const int32_t f = m < n ? m : 2 * n - 1 - m;           // counts back down from the far edge
    return f < 0 ? 0 : f;                                  // 2n -> -1 -> 0
  }
  return 0;
}
template <Wrap W>
inline int32_t wrap_second(int32_t i, int32_t n, int32_t seam) {
  if constexpr (W == Wrap::Repeat) return i == n || i == 0 ? seam : i;  // (a second tap is never -1)
  return wrap_first<W>(i, n);
}

// Bilinear (or nearest) of one level: CW.16 per channel, R|B in rb, G|A in ga.
struct Packed2x2 {
  uint64_t rb, ga;
};

// A depth compare's test (stage::compare_taps): a texel becomes R = A = 255 where it passes, else
// A = 255 alone.
struct DepthTest {
  CompareOp op = CompareOp::Always;
  uint32_t reference = 0;  // stage::compare_reference, 8 bits
  uint32_t operator()(uint32_t t) const { return stage::compare_passes(op, reference, t & 255) ? 0xFF0000FFu : 0xFF000000u; }
};

// `u`, `v`: stage::reduce of the probe's coordinates. CMP: each texel replaced by its depth test.
template <TexelFilter TF, Wrap WU, Wrap WV, bool CMP = false>
[[gnu::always_inline]] inline Packed2x2 filter_level(const FastLevel& lv, int32_t u, int32_t v, const DepthTest& test = {}) {
  const int32_t tu = stage::scale(u, lv.w), tv = stage::scale(v, lv.h);
  auto texel = [&](uint32_t t) {
    if constexpr (CMP) return test(t);
    return t;
  };
  if constexpr (TF == TexelFilter::Nearest) {
    // i0 = floor(u * size) = t9 >> 9; weights are 0, so the result is texel a, scaled to CW.16.
    const int32_t x = wrap_first<WU>(tu >> 9, lv.w);
    const int32_t y = wrap_first<WV>(tv >> 9, lv.h);
    const uint32_t a = texel(lv.texels[size_t(y) * lv.stride + size_t(x)]);
    return {spread_rb(a) << 16, spread_ga(a) << 16};
  } else {
    const int32_t pu = (tu - 255) >> 1, pv = (tv - 255) >> 1;
    const uint32_t wx = uint32_t(pu & 255), wy = uint32_t(pv & 255);
    const int32_t x0 = wrap_first<WU>(pu >> 8, lv.w), x1 = wrap_second<WU>((pu >> 8) + 1, lv.w, lv.seam_w);
    const int32_t y0 = wrap_first<WV>(pv >> 8, lv.h), y1 = wrap_second<WV>((pv >> 8) + 1, lv.h, lv.seam_h);
    const uint32_t* row0 = lv.texels + size_t(y0) * lv.stride;
    const uint32_t* row1 = lv.texels + size_t(y1) * lv.stride;
    const uint32_t a = texel(row0[x0]), b = texel(row0[x1]), c = texel(row1[x0]), e = texel(row1[x1]);
    const uint64_t top_rb = lerp2(spread_rb(a), spread_rb(b), wx), bot_rb = lerp2(spread_rb(c), spread_rb(e), wx);
    const uint64_t top_ga = lerp2(spread_ga(a), spread_ga(b), wx), bot_ga = lerp2(spread_ga(c), spread_ga(e), wx);
    return {lerp2(top_rb, bot_rb, wy), lerp2(top_ga, bot_ga, wy)};
  }
}

// stage::gather at the base level: byte `component` of taps c, e, b, a as R, G, B, A.
template <Wrap WU, Wrap WV>
inline uint32_t gather_level(const FastLevel& lv, int32_t u, int32_t v, int component) {
  const int32_t pu = (stage::scale(u, lv.w) - 255) >> 1, pv = (stage::scale(v, lv.h) - 255) >> 1;
  const int32_t x0 = wrap_first<WU>(pu >> 8, lv.w), x1 = wrap_second<WU>((pu >> 8) + 1, lv.w, lv.seam_w);
  const int32_t y0 = wrap_first<WV>(pv >> 8, lv.h), y1 = wrap_second<WV>((pv >> 8) + 1, lv.h, lv.seam_h);
  const uint32_t* row0 = lv.texels + size_t(y0) * lv.stride;
  const uint32_t* row1 = lv.texels + size_t(y1) * lv.stride;
  const int shift = 8 * (component & 3);
  auto byte = [&](uint32_t t) { return t >> shift & 255; };
  return byte(row1[x0]) | byte(row1[x1]) << 8 | byte(row0[x1]) << 16 | byte(row0[x0]) << 24;
}

// One probe: the trilinear (or nearest-level) value before rounding, CW.24 per channel.
template <TexelFilter TF, MipMode MM, Wrap WU, Wrap WV, bool CMP = false>
[[gnu::always_inline]] inline Packed2x2 probe_packed(const FastLevel* levels, int last, const SamplerConfig& cfg, int32_t u_in, int32_t v_in,
                              int32_t lambda, const DepthTest& test = {}) {
  const int32_t u = stage::reduce(u_in, WU), v = stage::reduce(v_in, WV);
  const int32_t lod = stage::lod_clamp(lambda, cfg.lod_bias, cfg.min_lod, cfg.max_lod);
  if constexpr (MM == MipMode::Linear) {
    // stage::lod_select without branches: lod <= 0 gives d = 0, f = 0; past the last level
    // f = 0. Both levels are always filtered (d1 = d when d is last): with f = 0 the blend
    // returns level d exactly, as in sample().
    const int32_t l = lod > 0 ? lod : 0;
    const bool past_last = (l >> kLodFracBits) >= last;
    const int d = past_last ? last : l >> kLodFracBits;
    const uint32_t f = past_last ? 0u : uint32_t(l & 255);
    const int d1 = d < last ? d + 1 : last;
    const Packed2x2 b0 = filter_level<TF, WU, WV, CMP>(levels[d], u, v, test);
    const Packed2x2 b1 = filter_level<TF, WU, WV, CMP>(levels[d1], u, v, test);
    return {lerp2(b0.rb, b1.rb, f), lerp2(b0.ga, b1.ga, f)};
  } else {
    int d = 0;
    if constexpr (MM == MipMode::Nearest) d = lod > 0 ? std::min((lod + 127) >> kLodFracBits, last) : 0;
    const Packed2x2 b0 = filter_level<TF, WU, WV, CMP>(levels[d], u, v, test);
    return {b0.rb << 8, b0.ga << 8};
  }
}

// One sample or depth compare (CMP: each texel tested first, stage::compare_taps) as packed RGBA8.
template <TexelFilter TF, MipMode MM, Wrap WU, Wrap WV, bool CMP>
[[gnu::always_inline]] inline uint32_t sample_packed(const FastLevel* levels, int last, Extent size0,
                                                     const SamplerConfig& cfg, const Request& r, const DepthTest& test) {
  if (r.has_derivatives) {
    // The probes of tex_probe, summed per channel (16 probes of CW.24 need 36 bits: unpacked).
    const Probes p = tex_probe(r, cfg, size0);
    stage::Unrounded sum{};
    for (int k = 0; k < p.n; ++k) {
      const Request& q = p.at[size_t(k)];
      const Packed2x2 t = probe_packed<TF, MM, WU, WV, CMP>(levels, last, cfg, q.u, q.v, q.lod + q.bias, test);
      sum[0] += int64_t(t.rb & 0xFFFFFFFFu);
      sum[1] += int64_t(t.ga & 0xFFFFFFFFu);
      sum[2] += int64_t(t.rb >> 32);
      sum[3] += int64_t(t.ga >> 32);
    }
    const Texel t = stage::average_and_round(sum, p.n);
    return uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
  }
  constexpr uint64_t kHalf = (uint64_t(1) << 23) | (uint64_t(1) << 55);  // rounding of both channels
  Packed2x2 tri = probe_packed<TF, MM, WU, WV, CMP>(levels, last, cfg, r.u, r.v, r.lod + r.bias, test);
  // The one rounding, half up, of all four channels; then back to packed RGBA8.
  tri.rb = (tri.rb + kHalf) >> 24;
  tri.ga = (tri.ga + kHalf) >> 24;
  return uint32_t(tri.rb & 0xFF) | uint32_t(tri.ga & 0xFF) << 8 | uint32_t(tri.rb >> 16 & 0xFF0000) |
         uint32_t(tri.ga >> 8 & 0xFF000000u);
}

template <TexelFilter TF, MipMode MM, Wrap WU, Wrap WV>
void sample_batch(const FastLevel* layer0, int last, int layers, Extent size0, const SamplerConfig& cfg,
                  const Request* requests, size_t n, uint32_t* out) {
  for (size_t i = 0; i < n; ++i) {
    const Request& r = requests[i];
    // (One layer: every sample reads it, a fetch of another layer nothing; no rounding to do.)
    const int layer = layers == 1 ? (r.op == Op::Fetch && r.layer != 0 ? -1 : 0)
                                  : stage::request_layer(r.op, r.layer, layers);
    const FastLevel* levels = layer0 + size_t(layer < 0 ? 0 : layer) * size_t(last + 1);
    if (r.op == Op::Fetch) [[unlikely]] {
      out[i] = layer >= 0 && stage::fetch_inside(r.u, r.v, r.lod, last, size0)
                   ? levels[r.lod].texels[size_t(r.v) * levels[r.lod].stride + size_t(r.u)]
                   : 0;
      continue;
    }
    if (r.op == Op::Gather) [[unlikely]] {
      out[i] = gather_level<WU, WV>(levels[0], stage::reduce(r.u, WU), stage::reduce(r.v, WV), r.component);
      continue;
    }
    if (r.op == Op::Compare) [[unlikely]] {
      out[i] = sample_packed<TF, MM, WU, WV, true>(levels, last, size0, cfg, r,
                                                   DepthTest{cfg.compare_op, stage::compare_reference(r.ref, 8)});
      continue;
    }
    out[i] = sample_packed<TF, MM, WU, WV, false>(levels, last, size0, cfg, r, DepthTest{});
  }
}

// Calls fn with the mode as a compile-time constant (std::integral_constant).
template <class Fn>
void with_wrap(Wrap w, Fn&& fn) {
  switch (w) {
    case Wrap::Repeat: return fn(std::integral_constant<Wrap, Wrap::Repeat>{});
    case Wrap::Clamp: return fn(std::integral_constant<Wrap, Wrap::Clamp>{});
    case Wrap::Mirror: return fn(std::integral_constant<Wrap, Wrap::Mirror>{});
    case Wrap::MirrorClamp: return fn(std::integral_constant<Wrap, Wrap::MirrorClamp>{});
    case Wrap::Border: break;  // (fast_path_takes: the reference path samples it)
  }
  throw Error("sample_rgba8: clamp to border is sampled by the reference path (Sampler::sample)");
}
template <class Fn>
void with_mip(MipMode m, Fn&& fn) {
  switch (m) {
    case MipMode::None: return fn(std::integral_constant<MipMode, MipMode::None>{});
    case MipMode::Nearest: return fn(std::integral_constant<MipMode, MipMode::Nearest>{});
    case MipMode::Linear: return fn(std::integral_constant<MipMode, MipMode::Linear>{});
  }
}
template <class Fn>
void with_texel_filter(TexelFilter t, Fn&& fn) {
  if (t == TexelFilter::Linear) return fn(std::integral_constant<TexelFilter, TexelFilter::Linear>{});
  return fn(std::integral_constant<TexelFilter, TexelFilter::Nearest>{});
}

}  // namespace

void Sampler::sample_rgba8(const Request* requests, size_t n, uint32_t* out) const {
  if (channel_bits_ != 8)
    throw Error("sample_rgba8: texture has " + std::to_string(channel_bits_) + "-bit channels; it takes 8-bit only");
  if (!fast_path_takes(config_))
    throw Error("sample_rgba8: clamp to border and a magnification filter of its own take the reference path");
  // Built per call rather than stored, so a copied Sampler never points into another's texels; an
  // array's layers one after another (layer l's level k at l * (last + 1) + k).
  const int last = last_level_;
  FastLevel one_layer[kMaxLevels];
  std::vector<FastLevel> array_levels(layers_ > 1 ? packed_.size() : 0);
  FastLevel* levels = layers_ > 1 ? array_levels.data() : one_layer;
  for (size_t i = 0; i < packed_.size(); ++i) {
    const Extent e = level_extent(size0_, int(i % size_t(last + 1)));
    levels[i] = {packed_[i].data(), size_t(stored_side(e.w)), e.w, e.h, is_power_of_two(e.w) ? 0 : e.w,
                 is_power_of_two(e.h) ? 0 : e.h};
  }
  const int layers = layers_;
  const SamplerConfig& cfg = config_;
  with_texel_filter(cfg.filter.texel, [&](auto tf) {
    with_mip(cfg.filter.mip, [&](auto mm) {
      with_wrap(cfg.wrap_u, [&](auto wu) {
        with_wrap(cfg.wrap_v, [&](auto wv) {
          sample_batch<decltype(tf)::value, decltype(mm)::value, decltype(wu)::value, decltype(wv)::value>(
              levels, last, layers, size0_, cfg, requests, n, out);
        });
      });
    });
  });
}

SamplerStats Sampler::stats() const {
  BankStats banks;  // every layer's reads, per level and bank
  for (const BankedMipMemory& m : memory_) {
    const BankStats& b = m.stats();
    banks.reads += b.reads;
    if (banks.bank_reads.size() < b.bank_reads.size()) banks.bank_reads.resize(b.bank_reads.size());
    for (size_t k = 0; k < b.bank_reads.size(); ++k)
      for (size_t i = 0; i < 4; ++i) banks.bank_reads[k][i] += b.bank_reads[k][i];
  }
  return {samples_, multiplies_, banks, probes_};
}

void Sampler::reset_stats() {
  samples_ = multiplies_ = 0;
  probes_ = {};
  for (BankedMipMemory& m : memory_) m.reset_stats();
}

}  // namespace tex

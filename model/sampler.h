// The texture sampler: LOD, address generation, wrap, banked fetch and filter, bit-exact.
#pragma once
#include <array>
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "banked_memory.h"
#include "formats.h"
#include "lod.h"
#include "pyramid.h"
#include "stages.h"

namespace tex {

// The sampler state (Vulkan's VkSamplerCreateInfo; docs/numerics.md): filters, address modes, LOD
// bias and clamp, anisotropy, border colour. One entry of the cached unit's sampler table, field
// for field the RTL's cfg_smp_* (docs/rtl-interface.md); the on-chip unit has one.
struct SamplerConfig {
  Filter filter;
  Wrap wrap_u = Wrap::Repeat;
  Wrap wrap_v = Wrap::Repeat;
  int32_t lod_bias = 0;        // Q8.8
  int32_t min_lod = kLodMin;   // Q8.8
  int32_t max_lod = kLodMax;   // Q8.8
  int max_aniso = kMaxAniso;   // anisotropic filter: probes per sample at most, 1..16
  bool aniso_pow2 = false;     // anisotropic filter: probe counts rounded up to powers of two
  BorderColor border = BorderColor::FloatTransparentBlack;  // clamp-to-border taps (GL's default)
  Texel border_custom{};       // BorderColor::Custom: RGBA unorm16 (65535 = 1.0), linear
  // Vulkan's unnormalizedCoordinates, GL's rectangle textures: u, v in texels of level 0 (Q16.16),
  // not in texture widths. Only with what Vulkan allows beside it (unnormalized_problem).
  bool unnormalized = false;
  // Vulkan's reductionMode (GL_TEXTURE_REDUCTION_MODE_ARB): the weighted average, or the minimum or
  // maximum of the texels weighed (stage::reduce_taps).
  Reduction reduction = Reduction::WeightedAverage;
  // Vulkan's compareOp (GL's TEXTURE_COMPARE_FUNC): how an Op::Compare request's reference is
  // tested against each texel's depth (stage::compare_taps). Other requests do not use it.
  CompareOp compare_op = CompareOp::LessOrEqual;
  // The cap tex_aniso applies: max_aniso for the anisotropic filter, else 1 (one probe).
  int probe_cap() const { return filter.anisotropic ? max_aniso : 1; }
  // The border colour as RGBA unorm16 (stage::border_texel takes it to a level's channel width).
  Texel border_unorm16() const {
    switch (border) {
      case BorderColor::FloatTransparentBlack:
      case BorderColor::IntTransparentBlack: return {0, 0, 0, 0};
      case BorderColor::FloatOpaqueBlack:
      case BorderColor::IntOpaqueBlack: return {0, 0, 0, 65535};
      case BorderColor::FloatOpaqueWhite:
      case BorderColor::IntOpaqueWhite: return {65535, 65535, 65535, 65535};
      case BorderColor::Custom: return border_custom;
    }
    return {};
  }
  bool uses_border() const { return wrap_u == Wrap::Border || wrap_v == Wrap::Border; }
  // Why an unnormalized sampler cannot be this one, or "" (also for a normalized one): Vulkan's
  // rules (VkSamplerCreateInfo): clamp to edge or border on both axes, the magnification filter
  // equal to the minification filter, no anisotropy, and the base level only (mipmap mode none,
  // or a max LOD of at most 0, as Vulkan's nearest mipmaps with minLod = maxLod = 0 give).
  std::string unnormalized_problem() const;
  // Why a depth compare cannot be sampled through this sampler, or "": Vulkan's rules (a compare
  // takes the weighted average, not a min/max reduction, and normalized coordinates).
  std::string compare_problem() const;
};
// Throws tex::Error naming the field and its value when the sampler is one the unit cannot take
// (unnormalized_problem); `where` prefixes the message (a file and line, an option).
void check_sampler(const SamplerConfig& config, const std::string& where = "");
// A frame's samplers: requests name an entry by Request::sampler (1..kMaxSamplers entries).
using SamplerTable = std::vector<SamplerConfig>;

// One request in the hardware's formats (docs/numerics.md). It carries either lambda or the four
// derivatives (then the LOD unit computes lambda, and with the anisotropic filter the probes).
struct Request {
  int32_t u = 0, v = 0;  // Q8.24
  int32_t lod = 0;       // Q8.8, before bias and clamp (requests without derivatives)
  int32_t bias = 0;      // Q8.8, the request's own LOD bias (GLSL texture(s, uv, bias)): added to the sampler's
  uint32_t tag = 0;
  uint8_t texture = 0;   // cached unit: the descriptor-table entry sampled (0..kMaxTextures-1)
  uint8_t sampler = 0;   // cached unit: the sampler-table entry it is sampled with (0..kMaxSamplers-1)
  Op op = Op::Sample;    // Op::Fetch: u, v, lod are the integers i, j and the level (stage::fetch_inside)
  uint8_t component = 0; // Op::Gather: the channel gathered, 0 (R) .. 3 (A)
  int32_t layer = 0;     // an array texture's layer coordinate, Q16.16 (stage::array_layer); Op::Fetch: the integer layer
  int32_t ref = 0;       // Op::Compare: the depth reference Dref, Q8.24 (stage::compare_reference)
  // A cube map's direction is (u, v, w), Q8.24 (any length); with derivatives, deriv's (dudx, dvdx,
  // dudy, dvdy) and these are its derivatives per pixel (texture widths: the cube's unit).
  int32_t w = 0;
  int32_t dwdx = 0, dwdy = 0;
  bool has_derivatives = false;  // (a fetch has none)
  LodDerivatives deriv;  // Q8.24 texture widths per pixel (requests with derivatives)
};
// texelFetch of texel (i, j) of `level` (Op::Fetch).
inline Request fetch_request(int32_t i, int32_t j, int32_t level, uint32_t tag = 0) {
  Request r;
  r.op = Op::Fetch;
  r.u = i;
  r.v = j;
  r.lod = level;
  r.tag = tag;
  return r;
}
// textureGather of `component` at (u, v) (Op::Gather; Q8.24).
inline Request gather_request(int32_t u, int32_t v, int component, uint32_t tag = 0) {
  Request r;
  r.op = Op::Gather;
  r.u = u;
  r.v = v;
  r.component = uint8_t(component);
  r.tag = tag;
  return r;
}
inline Request lambda_request(int32_t u, int32_t v, int32_t lod, uint32_t tag = 0) {
  Request r;
  r.u = u;
  r.v = v;
  r.lod = lod;
  r.tag = tag;
  return r;
}

// A cube request (its direction (u, v, w) and derivatives) as the 2D request of the face it
// selects (stage::cube_face, stage::cube_derivatives): u, v the face's (s, t) in [0, 1], the
// derivatives those of s and t in face widths per pixel; `face` 0..5 (+X, -X, +Y, -Y, +Z, -Z).
Request cube_face_request(const Request& r, int& face);
// A probe of a face's request (tex_probe's) that lies beyond the face (an anisotropic probe near a
// seam): moved onto the face it lies over (stage::cube_reproject). Returns the probe's face.
int cube_probe(int face, Request& probe);

// The trilinear probes of one request (tex_probe): a request without derivatives is one probe at its
// own (u, v, lod); one with derivatives takes lambda' and N from tex_aniso (with the filter's cap,
// SamplerConfig::probe_cap) and N probes along the major axis. Probes carry no derivatives.
struct Probes {
  int n = 1;
  std::array<Request, kMaxAniso> at;
};
Probes tex_probe(const Request& r, const SamplerConfig& config, Extent size0);
// Only the probe count N of tex_probe (what the on-chip unit's timing depends on).
int tex_probe_count(const Request& r, const SamplerConfig& config, Extent size0);

struct SamplerStats {
  uint64_t samples = 0;
  uint64_t multiplies_per_channel = 0;  // lerps that do work: 3 per bilinear level, +1 for the blend
  BankStats memory;                     // texel words read, per level and bank
  std::array<uint64_t, kMaxAniso + 1> probes{};  // samples by probe count (index 1..16)
};

// Which paths a Sampler can take: both, or the 8-bit fast path alone (it then skips building the
// reference path's banked memories: a texture's set-up costs half as much).
enum class SamplerPaths { Both, FastOnly };

class Sampler {
 public:
  // Whether the 8-bit fast path (sample_rgba8) takes this configuration: not with clamp to border,
  // a magnification filter apart from the minification filter, unnormalized coordinates or a
  // min/max reduction (the reference path does them).
  static bool fast_path_takes(const SamplerConfig& config);
  // Throws tex::Error for FastOnly with channels other than 8 bits or a configuration the fast path
  // does not take.
  Sampler(const Pyramid& pyramid, const SamplerConfig& config, SamplerPaths paths = SamplerPaths::Both)
      : Sampler(std::vector<const Pyramid*>{&pyramid}, config, paths) {}
  // An array texture: its layers (1..kMaxLayers pyramids of one size, format and level count; a
  // request reads the layer stage::request_layer gives). A cube map (TextureKind::Cube): 6 faces a
  // cube, square (a cube array: several cubes; the request's layer picks the cube), sampled by
  // direction across the seams (cube_skirts), on the reference path only; a fetch's layer is the
  // face's (6c + face). Throws tex::Error naming a layer that differs from layer 0, a layer count
  // outside 1..kMaxLayers (a cube's: not a multiple of 6), a cube with unnormalized coordinates or
  // for the fast path.
  Sampler(const std::vector<const Pyramid*>& layers, const SamplerConfig& config,
          SamplerPaths paths = SamplerPaths::Both, TextureKind kind = TextureKind::Texture2D);

  // Reference path: every stage in order, counting reads and multiplies (not with FastOnly: throws
  // tex::Error).
  Texel sample(const Request& r);
  // One probe's trilinear value before rounding (CW.24 per channel); counts reads and multiplies.
  stage::Unrounded sample_probe(const Request& probe);

  // Fast path for 8-bit channels: packed RGBA8 (R in the low byte), no counters.
  // Bit-identical to sample() (tests/test_sampler.cpp checks it).
  void sample_rgba8(const Request* requests, size_t n, uint32_t* out) const;

  // Replaces one texel of the pyramid (of an array, of layer `layer`) the sampler reads (both paths).
  void write_texel(int level, int32_t x, int32_t y, const Texel& t, int layer = 0);

  SamplerStats stats() const;
  void reset_stats();
  const SamplerConfig& config() const { return config_; }
  int last_level() const { return last_level_; }
  int layers() const { return layers_; }
  int channel_bits() const { return channel_bits_; }

 private:
  Texel fetch(const Request& r);   // sample() of an Op::Fetch request
  Texel gather(const Request& r);  // and of an Op::Gather one
  stage::Footprint footprint(BankedMipMemory& memory, int level, int32_t ru, int32_t rv, TexelFilter filter,
                             bool all_taps, bool cube = false);
  // One probe's trilinear value (sample_probe) in `memory`: a 2D texture's layer, or a skirted cube
  // face (cube: u, v are the face's s, t).
  stage::Unrounded probe_value(BankedMipMemory& memory, const Request& probe, bool cube);
  BankedMipMemory& memory_of(const Request& r);  // the reference path's memories of r's layer
  void write_packed(int layer, int level, int32_t x, int32_t y, const Texel& t);

  SamplerConfig config_;
  std::vector<BankedMipMemory> memory_;  // the reference path's memories, per layer (none with FastOnly)
  int channel_bits_;
  Texel border_;  // the border colour in the levels' channel width
  Extent size0_;
  int last_level_;
  int layers_;
  std::string depth_problem_;  // why no depth compare reads the texture (Pyramid::depth_problem)
  TextureKind kind_;
  uint64_t samples_ = 0, multiplies_ = 0;
  std::array<uint64_t, kMaxAniso + 1> probes_{};
  // Per layer and level (at layer * (last_level + 1) + level), row-major RGBA8 of the stored sides
  // (stored_side: with the seam copies), fast path only.
  std::vector<BigVector<uint32_t>> packed_;
};

}  // namespace tex

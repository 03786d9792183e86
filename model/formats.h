// Fixed-point formats and parameters shared by the model and the RTL.
// The RTL copy lives in rtl/tex_pkg.sv; tests/test_params.cpp checks that both agree.
// docs/numerics.md explains every format and every rounding.
#pragma once
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace tex {

constexpr int kCoordFracBits = 24;  // u, v: signed Q8.24, 1.0 = one texture width
constexpr int kTexelCoordFracBits = 16;  // u, v of an unnormalized sampler: signed Q16.16 in texels of level 0
constexpr int kLodFracBits = 8;     // lambda: signed Q8.8 in levels
constexpr int kWeightBits = 8;      // fx, fy, f: 0..255 = 0..255/256
constexpr int kMaxLog2Size = 13;    // 8192 texels per side at most (any size 1..8192)
constexpr int kMaxSize = 1 << kMaxLog2Size;
constexpr int kMaxLevels = kMaxLog2Size + 1;
constexpr int kMaxChannelBits = 16;
constexpr int kDefaultChannelBits = 8;
constexpr int kLodMin = -(1 << 15);  // Q8.8 range of lambda, bias and clamps
constexpr int kLodMax = (1 << 15) - 1;
constexpr int kMaxAniso = 16;       // anisotropic filtering: at most 16 probes per sample
constexpr int kMaxTextures = 16;    // entries of the cached unit's texture descriptor table
constexpr int kMaxSamplers = 16;    // and of its sampler table
constexpr int kMaxLayers = 256;     // layers of an array texture (the cached unit's cfg_desc_layers_m1: 8 bits)

// Address modes (Vulkan's VkSamplerAddressMode, GL's TEXTURE_WRAP_*): repeat, clamp to edge, mirrored
// repeat, clamp to border (a tap outside the level takes the sampler's border colour), mirror clamp
// to edge (mirrored once about 0, then clamped). The values are the RTL's 3-bit wrap fields.
enum class Wrap : uint8_t { Repeat = 0, Clamp = 1, Mirror = 2, Border = 3, MirrorClamp = 4 };
constexpr int kWrapModes = 5;
enum class TexelFilter : uint8_t { Nearest = 0, Linear = 1 };
enum class MipMode : uint8_t { None = 0, Nearest = 1, Linear = 2 };
enum class PyramidMode : uint8_t { Exact = 0, Cascade = 1 };

// A filter as the user names it: a texel filter within a level and a mip mode between levels
// (Vulkan's minFilter and mipmapMode), and the magnification filter (magFilter), which applies
// where lambda <= 0 (docs/numerics.md stage 1). GL's six minification filters are the six
// combinations of texel and mip; a named filter magnifies with its own texel filter, so `mag`
// starts equal to `texel` (--mag-filter sets it apart).
// `anisotropic` (EXT_texture_filter_anisotropic): up to SamplerConfig::max_aniso trilinear probes
// along the footprint's major axis for requests that carry derivatives (docs/numerics.md stage 1c).
struct Filter {
  TexelFilter texel = TexelFilter::Linear;
  MipMode mip = MipMode::Linear;
  bool anisotropic = false;
  TexelFilter mag = TexelFilter::Linear;
  constexpr Filter() = default;
  constexpr Filter(TexelFilter t, MipMode m, bool a = false) : texel(t), mip(m), anisotropic(a), mag(t) {}
  // Written out (not `= default`) so this header also compiles as C++17 (the SystemC library).
  bool operator==(const Filter& o) const {
    return texel == o.texel && mip == o.mip && anisotropic == o.anisotropic && mag == o.mag;
  }
  bool operator!=(const Filter& o) const { return !(*this == o); }
};

// Border colours (Vulkan's VkBorderColor, whose values these are, and VK_EXT_custom_border_color):
// what a clamp-to-border tap outside the level reads. The unit's formats are unsigned normalized,
// so an INT colour reads as its FLOAT twin (1 is the channel's maximum).
enum class BorderColor : uint8_t {
  FloatTransparentBlack = 0,
  IntTransparentBlack = 1,
  FloatOpaqueBlack = 2,
  IntOpaqueBlack = 3,
  FloatOpaqueWhite = 4,
  IntOpaqueWhite = 5,
  Custom = 6,  // SamplerConfig::border_custom
};
constexpr int kBorderColors = 7;

// How a filter combines the texels it weighs (Vulkan 1.2's VkSamplerReductionMode, whose values
// these are; GL_ARB_texture_filter_minmax): their weighted average (every filter's default), or
// the component-wise minimum or maximum of the texels it weighs with a weight above 0, over the
// footprint, both levels of a two-level sample and an anisotropic sample's probes.
enum class Reduction : uint8_t { WeightedAverage = 0, Min = 1, Max = 2 };
constexpr int kReductions = 3;

// What a request asks of the unit (the RTL's req_op, tex_pkg::OP_*): a filtered sample (GLSL
// texture*); textureGather: one component of the four texels a linear filter weighs at the base
// level (stage::gather); a depth compare (GLSL texture* of a shadow sampler, SPIR-V
// OpImageSampleDref*): each texel's depth compared with the request's reference by the sampler's
// compare op, then filtered (percentage-closer filtering; stage::compare_taps); or texelFetch: the
// texel (i, j) of one level, no filter, no address mode, 0 outside the level or the view's levels
// (Vulkan's robust image access).
enum class Op : uint8_t { Sample = 0, Gather = 1, Compare = 2, Fetch = 3 };

// What a texture's layers are (Vulkan's image view types): 2D images (a 2D texture: one layer; a 2D
// array: several), or cube maps, six faces a cube (+X, -X, +Y, -Y, +Z, -Z: layers 6c .. 6c + 5 of
// cube c; a cube array: several cubes), sampled by a direction across the faces' seams.
enum class TextureKind : uint8_t { Texture2D = 0, Cube = 1 };

// A depth compare's operator (Vulkan's VkCompareOp, whose values these are; GL's
// TEXTURE_COMPARE_FUNC): the test is `reference OP texel depth`, 1 where it passes, else 0.
enum class CompareOp : uint8_t {
  Never = 0, Less = 1, Equal = 2, LessOrEqual = 3, Greater = 4, NotEqual = 5, GreaterOrEqual = 6, Always = 7
};
constexpr int kCompareOps = 8;

// Names: point, bilinear, trilinear, mip_nearest (bilinear in the nearest level), anisotropic
// (trilinear probes), and the six GL names (nearest, linear, nearest_mipmap_nearest, ...).
bool parse_filter(const std::string& name, Filter& out);
std::string filter_name(Filter f);  // with "/mag-" and the mag filter when it differs from the texel filter
// nearest | linear (GL_NEAREST, VK_FILTER_LINEAR, ...: case and prefix ignored).
bool parse_texel_filter(const std::string& name, TexelFilter& out);
std::string texel_filter_name(TexelFilter f);
// A minification filter: nearest | linear (the texel filter alone; `mip` untouched), or one of GL's
// four *_MIPMAP_* names (any case, GL_ prefix or not), which give the mipmap mode too (`mip`).
// The one reading of --min-filter, texture lists' min= and scene files' min_filter.
bool parse_min_filter(const std::string& name, TexelFilter& texel, std::optional<MipMode>& mip);
// none | nearest | linear (a mipmapMode; "none": the base level only).
bool parse_mip_mode(const std::string& name, MipMode& out);
std::string mip_mode_name(MipMode m);
// repeat | clamp | mirror | border | mirror-clamp, and the GL and Vulkan names (GL_CLAMP_TO_EDGE,
// mirrored_repeat, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER, ...: case and prefix ignored).
bool parse_wrap(const std::string& name, Wrap& out);
std::string wrap_name(Wrap w);
constexpr const char* kWrapNames = "repeat | clamp | mirror | border | mirror-clamp (or GL / Vulkan names)";
// transparent-black | opaque-black | opaque-white, each also int-... and the Vulkan names
// (VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE, ...).
bool parse_border_color(const std::string& name, BorderColor& out);
std::string border_color_name(BorderColor b);
bool parse_pyramid_mode(const std::string& name, PyramidMode& out);
// weighted-average | min | max (and the Vulkan names, VK_SAMPLER_REDUCTION_MODE_MIN, ...).
bool parse_reduction(const std::string& name, Reduction& out);
std::string reduction_name(Reduction r);
// sample | gather | compare | fetch (also textureGather, texelFetch).
bool parse_op(const std::string& name, Op& out);
std::string op_name(Op op);
// never | less | equal | less-or-equal | greater | not-equal | greater-or-equal | always, GL's
// names (GL_LEQUAL, gequal, notequal, ...) and Vulkan's (VK_COMPARE_OP_LESS_OR_EQUAL, ...).
bool parse_compare_op(const std::string& name, CompareOp& out);
std::string compare_op_name(CompareOp op);
constexpr const char* kCompareOpNames = "never | less | equal | less-or-equal | greater | not-equal | greater-or-equal | always";

constexpr bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }
// ceil(log2 n) for n >= 1 (log2 n itself for a power of two).
constexpr int log2_ceil(int n) {
  int l = 0;
  while ((1 << l) < n) ++l;
  return l;
}

// A texture's or a level's size in texels (Vulkan's VkExtent2D).
struct Extent {
  int w = 1, h = 1;
  int width() const { return w; }
  int height() const { return h; }
  bool operator==(const Extent& o) const { return w == o.w && h == o.h; }
  bool operator!=(const Extent& o) const { return !(*this == o); }
};

// Level geometry of docs/numerics.md (GL's): level k is max(1, floor(w0 / 2^k)) x max(1, floor(h0 / 2^k))
// texels, floor(log2 max(w0, h0)) + 1 levels; a side that reaches 1 stays 1.
inline int level_count(Extent e0) {
  int n = 1;
  for (int m = e0.w > e0.h ? e0.w : e0.h; m > 1; m >>= 1) ++n;
  return n;
}
inline Extent level_extent(Extent e0, int k) { return {e0.w >> k > 1 ? e0.w >> k : 1, e0.h >> k > 1 ? e0.h >> k : 1}; }

// One texel: up to 4 channels of up to 16 bits (R, G, B, A).
using Texel = std::array<uint16_t, 4>;

// Real value -> fixed point, rounding half away from zero. Return false when out of range
// or not finite: callers report the error, the model never clamps silently.
// (Inline: texsim converts every value of a query trace with them.)
inline bool to_fixed(double x, int frac_bits, int64_t lo, int64_t hi, int32_t& out) {
  if (!std::isfinite(x)) return false;
  const double scaled = x * double(int64_t(1) << frac_bits);  // exact: a power of two
  if (scaled < static_cast<double>(lo) - 0.5 || scaled >= static_cast<double>(hi) + 0.5) return false;
  // Round half away from zero (llround's rule) without a libm call: truncate, then look at the
  // exact remainder (|scaled| < 2^32, so both are exact in a double).
  long long r = static_cast<long long>(scaled);
  const double rest = scaled - static_cast<double>(r);
  r += int(rest >= 0.5) - int(rest <= -0.5);  // (no branch: the remainders are random)
  if (r < lo || r > hi) return false;
  out = static_cast<int32_t>(r);
  return true;
}
inline bool to_coord_fixed(double u, int32_t& out) { return to_fixed(u, kCoordFracBits, INT32_MIN, INT32_MAX, out); }
// A coordinate of an unnormalized sampler (Vulkan unnormalizedCoordinates, GL rectangle textures): texels.
inline bool to_texel_coord_fixed(double u, int32_t& out) {
  return to_fixed(u, kTexelCoordFracBits, INT32_MIN, INT32_MAX, out);
}
inline bool to_lod_fixed(double lambda, int32_t& out) { return to_fixed(lambda, kLodFracBits, kLodMin, kLodMax, out); }

}  // namespace tex

// An independent double-precision texture filter written from the OpenGL 4.6 specification
// (§8.14 "Texture Minification", §8.14.2 wrap, §8.14.3 mipmapping, §8.15 magnification), used as
// the real-valued reference of tests/test_accuracy.cpp and tests/test_sampler.cpp.
// It deliberately uses nothing from model/stages.h or model/sampler.cpp: only the texel data of
// the 8-bit pyramid levels (tex::Image) and the enum names of model/formats.h.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "model/formats.h"
#include "model/image.h"

namespace ref {

using Rgba = std::array<double, 4>;

// GL 4.6 §8.14.2: a mod b = a - b * floor(a / b); mirror(a) = a >= 0 ? a : -(1 + a).
inline int64_t gl_mod(int64_t a, int64_t b) {
  int64_t m = a % b;
  return m < 0 ? m + b : m;
}
inline int64_t gl_mirror(int64_t a) { return a >= 0 ? a : -(1 + a); }

// Table 8.20: the integer texel coordinate after the wrap mode, for a level of `size` texels;
// CLAMP_TO_BORDER gives -1 or `size` outside the level (the border texel).
inline int64_t gl_wrap(int64_t coord, int64_t size, tex::Wrap w) {
  switch (w) {
    case tex::Wrap::Repeat: return gl_mod(coord, size);
    case tex::Wrap::Clamp: return std::clamp<int64_t>(coord, 0, size - 1);  // CLAMP_TO_EDGE
    case tex::Wrap::Mirror: return (size - 1) - gl_mirror(gl_mod(coord, 2 * size) - size);  // MIRRORED_REPEAT
    case tex::Wrap::Border: return std::clamp<int64_t>(coord, -1, size);                   // CLAMP_TO_BORDER
    case tex::Wrap::MirrorClamp: return std::clamp<int64_t>(gl_mirror(coord), 0, size - 1);  // MIRROR_CLAMP_TO_EDGE
  }
  return 0;
}

// Which texels and levels a query uses: equal for two inputs means the (piecewise continuous)
// filter is on the same piece for both. Used to recognise discontinuity crossings.
struct Choice {
  int level0 = 0, level1 = -1;
  int64_t i = 0, j = 0;  // nearest texel of level0 (texel filter nearest only)
  bool operator==(const Choice&) const = default;
};

struct GlSampler {
  const std::vector<tex::Image>* levels = nullptr;  // levels[0] is the base level, level k max(1, n >> k) per side
  tex::TexelFilter texel = tex::TexelFilter::Linear;  // TEXTURE_MIN_FILTER's texel filter
  tex::MipMode mip = tex::MipMode::Linear;
  std::optional<tex::TexelFilter> mag;  // TEXTURE_MAG_FILTER; none: the same as `texel`
  Rgba border{};  // TEXTURE_BORDER_COLOR in the filtered values' scale (after `decode`: never decoded)
  tex::Wrap wrap_s = tex::Wrap::Repeat, wrap_t = tex::Wrap::Repeat;
  double lod_bias = 0, min_lod = -1000, max_lod = 1000;
  bool unnormalized = false;  // s, t are texel coordinates (rectangle textures: u' = s, v' = t)
  // A texel's stored value to the value filtered (sRGB: decoded in double); none: as stored.
  double (*decode)(int channel, double stored) = nullptr;

  int q() const { return int(levels->size()) - 1; }

  double texel_value(int k, int64_t i, int64_t j, int c) const {
    const tex::Image& img = (*levels)[k];
    const int64_t x = gl_wrap(i, img.width, wrap_s), y = gl_wrap(j, img.height, wrap_t);
    if (x < 0 || x >= img.width || y < 0 || y >= img.height) return border[size_t(c)];  // §8.14.2: the border
    const double v = img.at(int(x), int(y))[c];
    return decode ? decode(c, v) : v;
  }

  // §8.14.2: NEAREST takes the texel containing (u', v') = (s w, t h); LINEAR weights the 2x2
  // texels around (u' - 1/2, v' - 1/2) by the fractional parts alpha and beta.
  Rgba level_filter(int k, double s, double t, Choice* choice = nullptr,
                    tex::TexelFilter filter = tex::TexelFilter::Linear) const {
    const tex::Image& img = (*levels)[k];
    const double us = unnormalized ? s : s * img.width, vt = unnormalized ? t : t * img.height;
    Rgba out{};
    if (filter == tex::TexelFilter::Nearest) {
      const int64_t i = int64_t(std::floor(us)), j = int64_t(std::floor(vt));
      if (choice) choice->i = i, choice->j = j;
      for (int c = 0; c < 4; ++c) out[c] = texel_value(k, i, j, c);
      return out;
    }
    const double x = us - 0.5, y = vt - 0.5;
    const int64_t i0 = int64_t(std::floor(x)), j0 = int64_t(std::floor(y));
    const double alpha = x - std::floor(x), beta = y - std::floor(y);
    for (int c = 0; c < 4; ++c)
      out[c] = (1 - alpha) * (1 - beta) * texel_value(k, i0, j0, c) + alpha * (1 - beta) * texel_value(k, i0 + 1, j0, c) +
               (1 - alpha) * beta * texel_value(k, i0, j0 + 1, c) + alpha * beta * texel_value(k, i0 + 1, j0 + 1, c);
    return out;
  }

  // §8.14.1 and §8.14.3 with c = 0: lambda' = clamp(lambda + bias, min, max); magnify when
  // lambda' <= 0 (§8.15: the MAG_FILTER, on the base level); NEAREST_MIPMAP: level ceil(lambda' + 1/2) - 1 for
  // lambda' > 1/2 else 0, at most q; LINEAR_MIPMAP: levels floor(lambda') and +1 blended by
  // frac(lambda'), or level q alone when lambda' >= q.
  Rgba sample(double s, double t, double lambda, Choice* choice = nullptr) const {
    const double l = std::clamp(lambda + lod_bias, min_lod, max_lod);
    if (choice) *choice = Choice{};
    if (l <= 0) {
      if (choice && mag.value_or(texel) != texel) choice->level1 = -2;  // (another piece than minification)
      return level_filter(0, s, t, choice, mag.value_or(texel));
    }
    if (mip == tex::MipMode::None) return level_filter(0, s, t, choice, texel);
    if (mip == tex::MipMode::Nearest) {
      const int d = l <= 0.5 ? 0 : std::min(int(std::ceil(l + 0.5)) - 1, q());
      if (choice) choice->level0 = d;
      return level_filter(d, s, t, choice, texel);
    }
    if (l >= q()) {
      if (choice) choice->level0 = q();
      return level_filter(q(), s, t, choice, texel);
    }
    const int d1 = int(std::floor(l));
    const double f = l - d1;
    if (choice) choice->level0 = d1, choice->level1 = d1 + 1;
    const Rgba a = level_filter(d1, s, t, choice, texel), b = level_filter(d1 + 1, s, t, nullptr, texel);
    Rgba out;
    for (int c = 0; c < 4; ++c) out[c] = (1 - f) * a[c] + f * b[c];
    return out;
  }
};

}  // namespace ref

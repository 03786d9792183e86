#include "srgb.h"

#include <cmath>

#include "error.h"
#include "pyramid.h"

namespace tex {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

const std::array<uint16_t, 256>& srgb_decode_table() {
  static const std::array<uint16_t, 256> table = [] {
    std::array<uint16_t, 256> t{};
    for (int c = 0; c < 256; ++c) t[size_t(c)] = uint16_t(std::lround(65535.0 * srgb_to_linear(c / 255.0)));
    return t;
  }();
  return table;
}

uint8_t encode_srgb8(double linear) { return uint8_t(std::floor(255.0 * linear_to_srgb(linear) + 0.5)); }

std::vector<Image> srgb_box_levels(const Image& level0, PyramidMode mode) {
  if (level0.channel_bits != 8) throw Error("an sRGB texture holds 8-bit codes, not " + std::to_string(level0.channel_bits) + "-bit channels");
  // Alpha and the level shapes as build_pyramid makes them; R, G, B replaced below.
  std::vector<Image> levels = build_pyramid(level0, mode).levels;
  // Decoded level 0 (or, in cascade mode, the previous level) in double.
  auto decode = [](const Image& img) {
    std::vector<std::array<double, 3>> d(img.texels.size());
    for (size_t i = 0; i < d.size(); ++i)
      for (int c = 0; c < 3; ++c) d[i][size_t(c)] = srgb_to_linear(img.texels[i][size_t(c)] / 255.0);
    return d;
  };
  std::vector<std::array<double, 3>> source = decode(level0);
  int src_w = level0.width, src_h = level0.height;
  for (int k = 1; k < int(levels.size()); ++k) {
    Image& out = levels[size_t(k)];
    const Extent s = level_extent({level0.width, level0.height}, k);
    // The area weights of build_pyramid (a box where the sides are powers of two).
    const AxisWeights ax = axis_weights(src_w, s.width()), ay = axis_weights(src_h, s.height());
    const double area = double(src_w) * double(src_h);
    for (int y = 0; y < s.height(); ++y)
      for (int x = 0; x < s.width(); ++x) {
        std::array<double, 3> sum{};
        for (size_t dy = 0; dy < ay.weight[size_t(y)].size(); ++dy)
          for (size_t dx = 0; dx < ax.weight[size_t(x)].size(); ++dx) {
            const double w = double(ay.weight[size_t(y)][dy]) * double(ax.weight[size_t(x)][dx]);
            const size_t at = size_t(ay.first[size_t(y)] + int(dy)) * size_t(src_w) + size_t(ax.first[size_t(x)] + int(dx));
            for (int c = 0; c < 3; ++c) sum[size_t(c)] += w * source[at][size_t(c)];
          }
        for (int c = 0; c < 3; ++c) out.at(x, y)[size_t(c)] = encode_srgb8(sum[size_t(c)] / area);
      }
    if (mode == PyramidMode::Cascade) {  // the next level from this one's codes
      source = decode(out);
      src_w = s.width();
      src_h = s.height();
    }
  }
  return levels;
}

Texel encode_srgb_texel(const Texel& linear16) {
  Texel t;
  for (int c = 0; c < 3; ++c) t[size_t(c)] = encode_srgb8(linear16[size_t(c)] / 65535.0);
  t[3] = uint16_t((uint32_t(linear16[3]) * 255 + 32767) / 65535);
  return t;
}

Pyramid build_srgb_pyramid(const Image& level0, PyramidMode mode) {
  Pyramid p;
  p.mode = mode;
  p.levels = srgb_box_levels(level0, mode);
  decode_srgb_levels(p);
  return p;
}

void decode_srgb_levels(Pyramid& pyramid) {
  pyramid.srgb = true;
  if (!is_compressed(pyramid.format)) pyramid.codes = pyramid.levels;
  if (is_astc(pyramid.format))  // ASTC's sRGB mode decodes other codes (model/astc.h)
    for (size_t k = 0; k < pyramid.levels.size(); ++k)
      pyramid.levels[k] = decode_level(pyramid.format, pyramid.blocks[k].data(), pyramid.levels[k].width,
                                       pyramid.levels[k].height, true);
  for (Image& level : pyramid.levels) level = decode_srgb_level(level);
}

Image decode_srgb_level(const Image& srgb8) {
  const std::array<uint16_t, 256>& table = srgb_decode_table();
  Image out(srgb8.width, srgb8.height, kLinearBits);
  for (size_t i = 0; i < out.texels.size(); ++i) {
    for (int c = 0; c < 3; ++c) out.texels[i][size_t(c)] = table[srgb8.texels[i][size_t(c)] & 255];
    out.texels[i][3] = uint16_t(srgb8.texels[i][3] * 257);
  }
  return out;
}

}  // namespace tex

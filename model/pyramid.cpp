#include "pyramid.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "error.h"

namespace tex {

namespace {

// Sums per channel over each texel's footprint in level 0 (exact mode) or in the parent (cascade).
struct SumImage {
  int w = 0, h = 0;
  BigVector<std::array<uint64_t, 4>> sums;
};

// Halves each side that is larger than 1, adding the 2x2 (or 2x1, 1x2) children. `at(x, y)` is a
// child's sums (level 0's texels or a SumImage's entries).
template <class At>
SumImage reduce(int in_w, int in_h, const At& at, int log2_w, int log2_h) {
  SumImage out;
  out.w = 1 << log2_w;
  out.h = 1 << log2_h;
  out.sums.resize(size_t(out.w) * out.h);
  const int sx = in_w / out.w, sy = in_h / out.h;
  for (int y = 0; y < out.h; ++y)
    for (int x = 0; x < out.w; ++x) {
      std::array<uint64_t, 4> sum{};
      for (int dy = 0; dy < sy; ++dy)
        for (int dx = 0; dx < sx; ++dx) {
          const auto& child = at(x * sx + dx, y * sy + dy);
          for (int c = 0; c < 4; ++c) sum[size_t(c)] += child[size_t(c)];
        }
      out.sums[size_t(y) * out.w + x] = sum;
    }
  return out;
}
SumImage reduce(const SumImage& in, int log2_w, int log2_h) {
  return reduce(in.w, in.h, [&](int x, int y) -> const std::array<uint64_t, 4>& { return in.sums[size_t(y) * in.w + x]; },
                log2_w, log2_h);
}
// Level 1 straight from level 0's texels (no copy of level 0 as sums: the largest level is read once).
SumImage reduce(const Image& in, int log2_w, int log2_h) {
  return reduce(in.width, in.height, [&](int x, int y) -> const Texel& { return in.at(x, y); }, log2_w, log2_h);
}

// Mean of `count` (a power of two) texels per sum, rounded half up.
Image to_image(const SumImage& s, int count, int channel_bits) {
  const int shift = log2_exact(count);
  Image img(s.w, s.h, channel_bits);
  for (size_t i = 0; i < s.sums.size(); ++i)
    for (int c = 0; c < 4; ++c) img.texels[i][c] = uint16_t((s.sums[i][c] + uint64_t(count / 2)) >> shift);
  return img;
}

}  // namespace

AxisWeights axis_weights(int src, int dst) {
  AxisWeights a;
  for (int i = 0; i < dst; ++i) {
    const int64_t lo = int64_t(i) * src, hi = int64_t(i + 1) * src;
    const int j0 = int(lo / dst), j1 = int((hi - 1) / dst);
    a.first.push_back(j0);
    std::vector<uint32_t> w;
    for (int j = j0; j <= j1; ++j) w.push_back(uint32_t(std::min(hi, int64_t(j + 1) * dst) - std::max(lo, int64_t(j) * dst)));
    a.weight.push_back(std::move(w));
  }
  return a;
}

Image area_reduce(const Image& src, int w, int h) {
  const AxisWeights ax = axis_weights(src.width, w), ay = axis_weights(src.height, h);
  // Every output texel's weights sum to src.width * src.height: the mean is S / D, rounded half up
  // as floor((2S + D) / 2D) (D may be odd). Rows pass along x first, each source row once or twice.
  const uint64_t d = uint64_t(src.width) * uint64_t(src.height);
  Image out(w, h, src.channel_bits);
  std::vector<std::array<uint64_t, 4>> row(static_cast<size_t>(w)), acc(static_cast<size_t>(w));
  int row_y = -1;
  for (int oy = 0; oy < h; ++oy) {
    for (auto& a : acc) a = {};
    for (size_t l = 0; l < ay.weight[size_t(oy)].size(); ++l) {
      const int y = ay.first[size_t(oy)] + int(l);
      if (y != row_y) {  // the x pass of source row y
        row_y = y;
        for (int ox = 0; ox < w; ++ox) {
          std::array<uint64_t, 4> sum{};
          const auto& wx = ax.weight[size_t(ox)];
          for (size_t k = 0; k < wx.size(); ++k) {
            const Texel& t = src.at(ax.first[size_t(ox)] + int(k), y);
            for (size_t c = 0; c < 4; ++c) sum[c] += uint64_t(wx[k]) * t[c];
          }
          row[size_t(ox)] = sum;
        }
      }
      const uint64_t wy = ay.weight[size_t(oy)][l];
      for (int ox = 0; ox < w; ++ox)
        for (size_t c = 0; c < 4; ++c) acc[size_t(ox)][c] += wy * row[size_t(ox)][c];
    }
    for (int ox = 0; ox < w; ++ox)
      for (size_t c = 0; c < 4; ++c) out.at(ox, oy)[c] = uint16_t((2 * acc[size_t(ox)][c] + d) / (2 * d));
  }
  return out;
}

Pyramid build_pyramid(Image level0_in, PyramidMode mode) {
  Pyramid p;
  p.mode = mode;
  const Extent e0{level0_in.width, level0_in.height};
  const int levels = level_count(e0);
  p.levels.reserve(size_t(levels));  // (`level0` stays valid as levels are added)
  p.levels.push_back(std::move(level0_in));
  const Image& level0 = p.levels[0];
  if (!is_power_of_two(e0.w) || !is_power_of_two(e0.h)) {
    // Not a power of two: each level the area mean of level 0 (exact) or of its parent (cascade).
    for (int k = 1; k < levels; ++k) {
      const Extent shape = level_extent(e0, k);
      p.levels.push_back(area_reduce(mode == PyramidMode::Exact ? level0 : p.levels.back(), shape.w, shape.h));
    }
    return p;
  }
  // Powers of two: the same means (area_reduce gives them too; tests check it), from 2x2 sums
  // carried level to level, which costs a third of the work.
  SumImage sums;
  for (int k = 1; k < levels; ++k) {
    const Extent shape = level_extent(e0, k);
    const int lw = log2_exact(shape.w), lh = log2_exact(shape.h);
    if (mode == PyramidMode::Exact) {
      // footprint sums carried exactly
      sums = k == 1 ? reduce(level0, lw, lh) : reduce(sums, lw, lh);
      const int count = (level0.width / shape.width()) * (level0.height / shape.height());
      p.levels.push_back(to_image(sums, count, level0.channel_bits));
    } else {
      const Image& parent = p.levels.back();
      SumImage s = reduce(parent, lw, lh);
      const int count = (parent.width / shape.width()) * (parent.height / shape.height());
      p.levels.push_back(to_image(s, count, level0.channel_bits));
    }
  }
  return p;
}

}  // namespace tex

namespace tex {

Pyramid pyramid_of_blocks(TexelFormat format, Extent e0, std::vector<std::vector<uint8_t>> blocks) {
  if (!is_compressed(format)) throw Error("pyramid_of_blocks: RGBA8 has no blocks");
  if (int(blocks.size()) != level_count(e0))
    throw Error("pyramid_of_blocks: " + std::to_string(blocks.size()) + " levels of blocks, a full chain has " +
                std::to_string(level_count(e0)));
  Pyramid p;
  p.format = format;
  for (int k = 0; k < int(blocks.size()); ++k) {
    const Extent s = level_extent(e0, k);
    if (blocks[size_t(k)].size() != level_bytes(format, s.width(), s.height()))
      throw Error("pyramid_of_blocks: level " + std::to_string(k) + " has " + std::to_string(blocks[size_t(k)].size()) +
                  " bytes, not " + std::to_string(level_bytes(format, s.width(), s.height())));
    p.levels.push_back(decode_level(format, blocks[size_t(k)].data(), s.width(), s.height()));
  }
  p.blocks = std::move(blocks);
  return p;
}

Pyramid view_pyramid(const Pyramid& pyramid, int base_level, int max_level) {
  const int last = pyramid.last_level();
  if (base_level < 0 || base_level > last)
    throw Error("base level " + std::to_string(base_level) + ": this texture has levels 0 to " + std::to_string(last));
  if (max_level < base_level)
    throw Error("max level " + std::to_string(max_level) + " is below the base level " + std::to_string(base_level));
  const size_t b = size_t(base_level), e = size_t(std::min(max_level, last)) + 1;
  Pyramid v;
  v.mode = pyramid.mode;
  v.format = pyramid.format;
  v.srgb = pyramid.srgb;
  v.levels.assign(pyramid.levels.begin() + long(b), pyramid.levels.begin() + long(e));
  if (!pyramid.blocks.empty()) v.blocks.assign(pyramid.blocks.begin() + long(b), pyramid.blocks.begin() + long(e));
  if (!pyramid.codes.empty()) v.codes.assign(pyramid.codes.begin() + long(b), pyramid.codes.begin() + long(e));
  return v;
}

Image mip_layout(const Pyramid& pyramid) {
  const Image& l0 = pyramid.levels[0];
  Image canvas(2 * l0.width, 2 * l0.height, l0.channel_bits);
  const uint16_t opaque = uint16_t((1u << l0.channel_bits) - 1);
  for (auto& t : canvas.texels) t = {0, 0, 0, opaque};
  for (const Image& lvl : pyramid.levels) {
    const int w = lvl.width, h = lvl.height;
    const int origin[3][2] = {{w, 0}, {0, h}, {w, h}};  // R, G, B quadrants
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          Texel& t = canvas.at(origin[c][0] + x, origin[c][1] + y);
          t = {0, 0, 0, opaque};
          t[c] = lvl.at(x, y)[c];
        }
  }
  return canvas;
}

}  // namespace tex

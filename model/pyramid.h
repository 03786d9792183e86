// The mip pyramid: level 0 and its 2x2 box-filtered reductions down to 1x1.
#pragma once
#include <cstdint>
#include <vector>

#include "block_formats.h"
#include "formats.h"
#include "image.h"

namespace tex {

// Level geometry of docs/numerics.md: a side that reaches 1 stays 1.
struct LevelShape {
  int log2_w = 0, log2_h = 0;
  int width() const { return 1 << log2_w; }
  int height() const { return 1 << log2_h; }
};
inline int level_count(int log2_w0, int log2_h0) { return (log2_w0 > log2_h0 ? log2_w0 : log2_h0) + 1; }
inline LevelShape level_shape(int log2_w0, int log2_h0, int k) {
  return {log2_w0 > k ? log2_w0 - k : 0, log2_h0 > k ? log2_h0 - k : 0};
}

struct Pyramid {
  std::vector<Image> levels;  // levels[0] is the texture (a compressed texture's levels decoded)
  PyramidMode mode = PyramidMode::Exact;
  // How memory holds the texture. A block format keeps each level's 4x4 blocks as stored (the
  // cached unit reads them; its decoder gives what `levels` holds); RGBA8 has no `blocks`.
  TexelFormat format = TexelFormat::Rgba8;
  std::vector<std::vector<uint8_t>> blocks;
  // sRGB-encoded texels (model/srgb.h): memory holds 8-bit codes (`codes`, or `blocks` of a block
  // format), and `levels` hold them decoded, linear unorm16, as the filter takes them.
  bool srgb = false;
  std::vector<Image> codes;  // an sRGB RGBA8 texture's levels as stored
  // Bits per channel in memory: 8 for a block format or an sRGB texture, else the levels' own.
  int memory_channel_bits() const { return srgb || is_compressed(format) ? 8 : levels[0].channel_bits; }
  int log2_w0() const { return log2_exact(levels[0].width); }
  int log2_h0() const { return log2_exact(levels[0].height); }
  int last_level() const { return int(levels.size()) - 1; }
};

// exact: every texel is the rounded mean of its whole level-0 footprint (maketx --filter box).
// cascade: every level from its rounded parent, as a simple hardware generator does.
// Takes level 0 by value: pass a temporary (or std::move) to build without copying it.
Pyramid build_pyramid(Image level0, PyramidMode mode = PyramidMode::Exact);

// A block-format texture as stored: one vector of blocks per level of a full chain (level k of
// level_bytes(format, w_k, h_k) bytes), each level decoded into `levels`. Throws tex::Error for an
// RGBA8 format, a missing level or a level of the wrong size.
Pyramid pyramid_of_blocks(TexelFormat format, int log2_w0, int log2_h0, std::vector<std::vector<uint8_t>> blocks);

}  // namespace tex

namespace tex {
// The paper's Figure 1: a 2W x 2H canvas with the R, G and B planes of level 0 in the upper-right,
// lower-left and lower-right quadrants, and the next level recursively in the upper-left one.
// Each plane is drawn in its own colour. Exact for square textures; for non-square ones, levels
// past the point where the short side is 1 overlap their parent's slot.
Image mip_layout(const Pyramid& pyramid);
}  // namespace tex

// The mip pyramid: level 0 and its 2x2 box-filtered reductions down to 1x1.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "block_formats.h"
#include "formats.h"
#include "image.h"

namespace tex {

// (Level geometry, level_count and level_extent: formats.h.)
// The repeat seam (docs/numerics.md stage 3): a side n that is not a power of two is stored with
// one more texel, a copy of texel 0 at index n, which the second tap of the seam pair (n-1, 0) reads
// so that the pair sits in two parity banks. Memory side of a level side n:
inline int stored_side(int n) { return is_power_of_two(n) ? n : n + 1; }
// Where that copy sits in a level's memory: index n, or 0 where the side has none.
inline int seam_copy(int n) { return is_power_of_two(n) ? 0 : n; }
// Calls put(x, y) for texel (x, y) of a level and again for each of its repeat-seam copies: where
// x (y) is 0 and the side has a copy, at column copy_x (row copy_y); 0: the side has none. (Every
// store of a level writes through this: the model's memories with seam_copy, the external memory
// image with MemoryLayout::seam_x/y, the on-chip RTL's loader.)
template <class Put>
void with_seam_copies(int x, int y, int copy_x, int copy_y, Put&& put) {
  put(x, y);
  const bool cx = x == 0 && copy_x != 0, cy = y == 0 && copy_y != 0;
  if (cx) put(copy_x, y);
  if (cy) put(x, copy_y);
  if (cx && cy) put(copy_x, copy_y);
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
  // Why a depth compare cannot read it ("" if it can): its R is no depth where its texels are
  // sRGB colours or EAC's (a colour format: Vulkan compares depth formats only; the unit's formats
  // configuration compares 8-bit depths).
  std::string depth_problem() const {
    if (srgb) return "an sRGB texture (a depth is no colour)";
    if (is_eac(format)) return std::string("an ") + format_info(format).name + " texture (EAC is a colour format, not a depth one)";
    return "";
  }
  Extent extent0() const { return {levels[0].width, levels[0].height}; }
  int last_level() const { return int(levels.size()) - 1; }
};

// A view of a pyramid (GL's TEXTURE_BASE_LEVEL and TEXTURE_MAX_LEVEL, Vulkan's baseMipLevel and
// levelCount): its levels base_level .. min(max_level, last), as a pyramid of its own. Level b's
// sides and every level after it are GL's sizes of the chain from b (max(1, n >> (b + k)) =
// max(1, (n >> b) >> k)), so the units sample a view as a texture whose level 0 is level b and
// whose chain may stop early (the descriptor's level count). Throws tex::Error naming the value:
// a base level beyond the last level, a max level below the base.
Pyramid view_pyramid(const Pyramid& pyramid, int base_level, int max_level);

// exact: every texel is the rounded mean of its whole level-0 footprint (maketx --filter box),
// weighted by area where a side is not a power of two (docs/numerics.md, the pyramid).
// cascade: every level from its rounded parent, as a simple hardware generator does (a 2-tap box,
// or for an odd parent side the 3-tap polyphase box of the area weights).
// Takes level 0 by value: pass a temporary (or std::move) to build without copying it.
Pyramid build_pyramid(Image level0, PyramidMode mode = PyramidMode::Exact);

// A block-format texture as stored: one vector of blocks per level of a full chain (level k of
// level_bytes(format, w_k, h_k) bytes), each level decoded into `levels`. Throws tex::Error for an
// RGBA8 format, a missing level or a level of the wrong size.
Pyramid pyramid_of_blocks(TexelFormat format, Extent extent0, std::vector<std::vector<uint8_t>> blocks);

// One axis of an area mean from `src` texels to `dst`: output texel i covers source texels
// first[i] .. first[i] + weight[i].size() - 1 with integer weights, the overlaps of [i*src, (i+1)*src)
// and [j*dst, (j+1)*dst), which sum to src (a power-of-two ratio: equal weights; an odd source side:
// the 3-tap polyphase box (dst - i, dst, i + 1)).
struct AxisWeights {
  std::vector<int> first;
  std::vector<std::vector<uint32_t>> weight;
};
AxisWeights axis_weights(int src, int dst);

// The area-weighted mean of `src` over each texel of a w x h image covering the same square (each
// output texel the exact mean of the source area under it, rounded half up): the box filter of any
// sizes. Exposed for tests.
Image area_reduce(const Image& src, int w, int h);

}  // namespace tex

namespace tex {
// The paper's Figure 1: a 2W x 2H canvas with the R, G and B planes of level 0 in the upper-right,
// lower-left and lower-right quadrants, and the next level recursively in the upper-left one.
// Each plane is drawn in its own colour. Exact for square textures; for non-square ones, levels
// past the point where the short side is 1 overlap their parent's slot.
Image mip_layout(const Pyramid& pyramid);
}  // namespace tex

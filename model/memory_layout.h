// The pyramid in external memory (docs/memory.md §1): each level cut into blocks of BW x BH texels,
// one block per cache line, blocks in row-major or Morton order, levels one after another from a
// base address. A level side that is not a power of two carries the repeat seam's copy of texel
// column (row) 0 after its last one (seam_x: at the side itself, or for a block format a whole
// block column at the side rounded up to the format's block). The model builds the memory image the
// cached RTL reads. A block-compressed texture (model/block_formats.h) has lines of the same bytes,
// holding whole blocks, 2^a x 2^b of them: a BC1 line of 64 bytes holds 4 x 2 blocks (16 x 8
// texels), a BC7 line 2 x 2 blocks (8 x 8 texels), an ASTC 6x6 line 2 x 2 blocks (12 x 12 texels:
// a line's texels need not be a power of two; the block of texel x is x / 6).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pyramid.h"

namespace tex {

enum class BlockOrder : uint8_t { RowMajor = 0, Morton = 1 };
bool parse_block_order(const std::string& name, BlockOrder& out);  // "row-major", "morton"
std::string block_order_name(BlockOrder o);

struct LayoutParams {
  int block_w = 4, block_h = 4;  // RGBA8 texels per block (= cache line): 2, 4 or 8 each
  BlockOrder order = BlockOrder::RowMajor;
  uint32_t base = 0;  // byte address of level 0, a multiple of the line size
};
// "WxH" with W and H each 2, 4 or 8 into block_w, block_h; false for anything else.
bool parse_block_size(const std::string& text, LayoutParams& out);
std::string block_size_name(const LayoutParams& p);  // "4x4"

// Morton code: a bit i at bit 2i, b bit i at bit 2i + 1.
inline uint64_t interleave_bits(uint32_t a, uint32_t b) {
  // Spreads the 32 bits of v to the even bits of a 64-bit word, in five shift-and-mask steps
  // (the cache computes one per block lookup).
  auto spread = [](uint64_t v) {
    v = (v | v << 16) & 0x0000FFFF0000FFFFull;
    v = (v | v << 8) & 0x00FF00FF00FF00FFull;
    v = (v | v << 4) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | v << 2) & 0x3333333333333333ull;
    return (v | v << 1) & 0x5555555555555555ull;
  };
  return spread(a) | spread(b) << 1;
}

class MemoryLayout {
 public:
  // Throws tex::Error naming the bad value: a texture size or channel width the unit cannot have,
  // a block side, a base not aligned to the line, an image ending beyond the 32-bit address space,
  // a block format with channels other than 8 bits or a line smaller than one of its blocks.
  // `levels`: the chain's levels 0..levels-1 (Vulkan's mipLevels; 0: the full chain down to 1x1;
  // more than the full chain is an error). `layers`: an array texture's layers, 1..kMaxLayers, each
  // a whole pyramid, one after another from the base (layer l at base + l * layer_bytes()). A cube
  // map (TextureKind::Cube): 6 layers a cube, square faces, each level stored with its skirt
  // (cube_skirts): level k spans n_k + 2 texels a side, no repeat-seam copies; RGBA only.
  MemoryLayout(Extent size0, int channel_bits, const LayoutParams& params, TexelFormat format = TexelFormat::Rgba8,
               int levels = 0, int layers = 1, TextureKind kind = TextureKind::Texture2D);

  const LayoutParams& params() const { return params_; }
  Extent size0() const { return size0_; }
  Extent level_size(int level) const { return levels_[size_t(level)].size; }
  int channel_bits() const { return channel_bits_; }
  int levels() const { return int(levels_.size()); }
  TexelFormat format() const { return format_; }
  int texel_bytes() const { return texel_bytes_; }    // RGBA: 4 (channels <= 8 bits) or 8
  int line_bytes() const { return line_bytes_; }      // params' block_w * block_h * texel_bytes
  // Texels per line in this format (RGBA: the params' block; a block format: its blocks' texels).
  int block_w() const { return fw_ << log2_lbx_; }
  int block_h() const { return fh_ << log2_lby_; }
  // The line column (row) of stored texel column x (row y): x / block_w(). A block format's
  // footprint need not be a power of two (ASTC 5, 6, 10, 12): x / fw is a multiply by the footprint's
  // reciprocal, exact for every x below 2^16 (a hardware constant multiplier).
  uint32_t line_x(uint32_t x) const { return block_column(x) >> log2_lbx_; }
  uint32_t line_y(uint32_t y) const { return block_row(y) >> log2_lby_; }
  // The block grid of a level: NBX_k x NBY_k blocks, each at least 1, covering the level and its
  // seam copies (row-major: the row pitch; Morton orders the grid rounded up to powers of two).
  uint32_t blocks_x(int level) const { return levels_[size_t(level)].nbx; }
  uint32_t blocks_y(int level) const { return levels_[size_t(level)].nby; }
  // Where a level keeps texel column 0's copy that the repeat seam's second tap reads (stage::wrap's
  // index w_k, `seam` = seam_x != 0): w_k for texels, w_k rounded up to a whole block for a block
  // format (a copy of block column 0: no block is re-encoded). 0: the side has none, its seam tap is
  // index 0 (a power-of-two side, unless longer than an ASTC block that does not divide it).
  uint32_t seam_x(int level) const { return levels_[size_t(level)].seam_x; }
  uint32_t seam_y(int level) const { return levels_[size_t(level)].seam_y; }
  // The stored column (row) of a wrapped tap index: the seam index w_k moves to seam_x.
  uint32_t stored_x(int level, uint32_t x) const {
    const Level& l = levels_[size_t(level)];
    return x == uint32_t(l.size.w) ? l.seam_x : x;
  }
  uint32_t stored_y(int level, uint32_t y) const {
    const Level& l = levels_[size_t(level)];
    return y == uint32_t(l.size.h) ? l.seam_y : y;
  }
  uint32_t level_base(int level) const { return levels_[size_t(level)].base; }  // (of layer 0)
  int layers() const { return layers_; }
  TextureKind kind() const { return kind_; }
  uint32_t layer_bytes() const { return layer_bytes_; }  // one layer's pyramid: a whole number of lines
  uint64_t image_bytes() const { return uint64_t(layer_bytes_) * uint64_t(layers_); }  // every layer

  // Index of block (bx, by) within its level (row-major or Morton).
  uint32_t block_index(int level, uint32_t bx, uint32_t by) const;
  // Byte address of the line holding block (bx, by) of `level` (of layer `layer`).
  uint32_t block_address(int level, uint32_t bx, uint32_t by, int layer = 0) const {
    return level_base(level) + uint32_t(layer) * layer_bytes_ + block_index(level, bx, by) * uint32_t(line_bytes_);
  }
  // Byte address of the line holding stored texel (x, y) of `level` (stored_x/y of a tap index): below.
  // The layer, level and block of the line at `address`; false if no level's block starts there.
  bool locate_line(uint32_t address, int& layer, int& level, uint32_t& bx, uint32_t& by) const;
  uint32_t line_address(int level, uint32_t x, uint32_t y, int layer = 0) const {
    return block_address(level, line_x(x), line_y(y), layer);
  }
  // Byte offset of texel (x, y) inside its line; in a block format, of the block holding it.
  uint32_t texel_offset(uint32_t x, uint32_t y) const {
    const uint32_t bx = block_column(x) & ((1u << log2_lbx_) - 1), by = block_row(y) & ((1u << log2_lby_) - 1);
    return ((by << log2_lbx_) | bx) * uint32_t(block_bytes_ ? block_bytes_ : texel_bytes_);
  }
  // A block format's block of texel (x, y): its column and row in the level (RGBA: x, y), and the
  // texel's index in it (x mod fw + fw * (y mod fh)).
  uint32_t block_column(uint32_t x) const { return uint32_t((uint64_t(x) * recip_w_) >> 32); }
  uint32_t block_row(uint32_t y) const { return uint32_t((uint64_t(y) * recip_h_) >> 32); }
  int texel_in_block(uint32_t x, uint32_t y) const {
    return int(x - block_column(x) * uint32_t(fw_)) + fw_ * int(y - block_row(y) * uint32_t(fh_));
  }

 private:
  struct Level {
    Extent size;
    uint32_t nbx = 1, nby = 1;     // the block grid
    int log2_bx = 0, log2_by = 0;  // Morton: log2 of the grid rounded up to powers of two
    uint32_t seam_x = 0, seam_y = 0;
    uint32_t base = 0;
  };
  LayoutParams params_;
  Extent size0_;
  int channel_bits_;
  TexelFormat format_;
  int texel_bytes_, line_bytes_;
  int block_bytes_ = 0;   // a block format's bytes per block; 0 for RGBA
  int fw_ = 1, fh_ = 1;   // a block format's footprint (RGBA: a texel)
  uint64_t recip_w_ = uint64_t(1) << 32, recip_h_ = uint64_t(1) << 32;  // ceil(2^32 / fw), ceil(2^32 / fh)
  int log2_lbx_ = 0, log2_lby_ = 0;  // blocks (RGBA: texels) per line across and down, log2
  std::vector<Level> levels_;
  int layers_ = 1;
  uint32_t layer_bytes_ = 0;
  TextureKind kind_ = TextureKind::Texture2D;
};

// The layout of a pyramid as it is: its size, channel width in memory, format and level count (and
// of an array of `layers` such pyramids).
inline MemoryLayout layout_of(const Pyramid& pyramid, const LayoutParams& params, int layers = 1,
                              TextureKind kind = TextureKind::Texture2D) {
  return MemoryLayout(pyramid.extent0(), pyramid.memory_channel_bits(), params, pyramid.format,
                      int(pyramid.levels.size()), layers, kind);
}

// Calls texel(layer, level, x, y, value) for every texel of the level stored in the line at `address`
// (a cube face's: its own texels, (x, y) in the face; its skirt is copies)
// (`line`: its line_bytes() bytes as memory holds them; blocks decoded); padding is skipped, and so
// are the repeat seam's copies unless `seam_copies`: then each copy is reported as the texel it
// copies (column 0, row 0: the same value; a unit whose taps read the copy needs it even when the
// original's line was never read). `srgb`: the texture is sRGB (ASTC decodes other codes then).
// False if the address is not a line of the layout.
bool decode_line(const MemoryLayout& layout, uint32_t address, const uint8_t* line,
                 const std::function<void(int layer, int level, int x, int y, const Texel& t)>& texel,
                 bool seam_copies = false, bool srgb = false);

// The bytes at addresses base .. base + image_bytes - 1 (padding 0): texels, or a block format's
// blocks as the pyramids keep them, layer after layer (a cube's faces with their skirts). Throws tex::Error when a pyramid is not the
// one the layout was made for (sizes, channel width, format), or the layer counts differ.
std::vector<uint8_t> build_memory_image(const std::vector<const Pyramid*>& layers, const MemoryLayout& layout);
inline std::vector<uint8_t> build_memory_image(const Pyramid& pyramid, const MemoryLayout& layout) {
  return build_memory_image(std::vector<const Pyramid*>{&pyramid}, layout);
}

// The memory image file of `texsim mip --memory-image`: header (docs/memory.md §1), then the image.
std::vector<uint8_t> memory_image_file(const Pyramid& pyramid, const MemoryLayout& layout);

}  // namespace tex

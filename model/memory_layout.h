// The pyramid in external memory (docs/memory.md §1): each level cut into blocks of BW x BH texels,
// one block per cache line, blocks in row-major or Morton order, levels one after another from a
// base address. The model builds the memory image the cached RTL reads.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "pyramid.h"

namespace tex {

enum class BlockOrder : uint8_t { RowMajor = 0, Morton = 1 };
bool parse_block_order(const std::string& name, BlockOrder& out);  // "row-major", "morton"
std::string block_order_name(BlockOrder o);

struct LayoutParams {
  int block_w = 4, block_h = 4;  // texels per block (= cache line): 2, 4 or 8 each
  BlockOrder order = BlockOrder::RowMajor;
  uint32_t base = 0;  // byte address of level 0, a multiple of the line size
};

class MemoryLayout {
 public:
  // Throws tex::Error naming the bad value (block side, base alignment, image beyond 32 bits).
  MemoryLayout(int log2_w0, int log2_h0, int channel_bits, const LayoutParams& params);

  const LayoutParams& params() const { return params_; }
  int levels() const { return int(levels_.size()); }
  int texel_bytes() const { return texel_bytes_; }    // 4 (channels <= 8 bits) or 8
  int line_bytes() const { return line_bytes_; }      // block_w * block_h * texel_bytes
  int log2_blocks_x(int level) const { return levels_[size_t(level)].log2_bx; }
  int log2_blocks_y(int level) const { return levels_[size_t(level)].log2_by; }
  uint32_t level_base(int level) const { return levels_[size_t(level)].base; }
  uint64_t image_bytes() const { return image_bytes_; }

  // Index of block (bx, by) within its level (row-major or Morton).
  uint32_t block_index(int level, uint32_t bx, uint32_t by) const;
  // Byte address of the line holding block (bx, by) of `level`.
  uint32_t line_address(int level, uint32_t bx, uint32_t by) const {
    return level_base(level) + block_index(level, bx, by) * uint32_t(line_bytes_);
  }
  int log2_block_w() const { return log2_bw_; }
  int log2_block_h() const { return log2_bh_; }

 private:
  struct Level {
    int log2_bx = 0, log2_by = 0;  // log2 of the block grid
    uint32_t base = 0;
  };
  LayoutParams params_;
  int texel_bytes_, line_bytes_, log2_bw_, log2_bh_;
  std::vector<Level> levels_;
  uint64_t image_bytes_ = 0;
};

// The bytes at addresses base .. base + image_bytes - 1 (padding texels 0).
std::vector<uint8_t> build_memory_image(const Pyramid& pyramid, const MemoryLayout& layout);

// The memory image file of `texsim mip --memory-image`: header (docs/memory.md §1), then the image.
std::vector<uint8_t> memory_image_file(const Pyramid& pyramid, const MemoryLayout& layout);

// Morton code: a bit i at bit 2i, b bit i at bit 2i + 1.
inline uint64_t interleave_bits(uint32_t a, uint32_t b) {
  uint64_t r = 0;
  for (int i = 0; i < 32; ++i) r |= uint64_t((a >> i) & 1) << (2 * i) | uint64_t((b >> i) & 1) << (2 * i + 1);
  return r;
}

}  // namespace tex

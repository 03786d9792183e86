// The banked mip memory of the paper: one memory per level, each split into 4 banks by
// texel parity, so a 2x2 footprint in each of two levels is 8 reads in 8 different banks.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pyramid.h"

namespace tex {

struct BankStats {
  uint64_t reads = 0;                                  // words read, all levels and banks
  std::vector<std::array<uint64_t, 4>> bank_reads;     // [level][bank]
};

class BankedMipMemory {
 public:
  explicit BankedMipMemory(const Pyramid& pyramid);

  int levels() const { return int(levels_.size()); }
  Extent shape(int level) const { return levels_[level].shape; }

  // Word address of texel (x, y) inside its bank (stride = half the stored width, rounded up). A
  // level side n that is not a power of two is stored n + 1 wide (stored_side: index n is texel 0's
  // copy, read by the repeat seam's second tap).
  int word_of(int level, int32_t x, int32_t y) const;

  // The fetch stage (RTL: tex_fetch) of one level: the 2x2 footprint {(x0,y0), (x1,y0), (x0,y1),
  // (x1,y1)} of wrapped indices. Each bank is read at most once; `reads` counts the distinct
  // (bank, word) pairs. With only_first, just (x0, y0) is read (point sampling). A tap with an
  // index stage::kBorderTap (clamp to border, outside the level) reads nothing and takes `border`.
  std::array<Texel, 4> fetch(int level, int32_t x0, int32_t x1, int32_t y0, int32_t y1, bool only_first,
                             const Texel& border = {});

  // Replaces texel (x, y) of `level` and its seam copies (a unit that fills its memories from
  // elsewhere: the SystemC model backend in cached mode, from the lines it reads over the bus).
  void write(int level, int32_t x, int32_t y, const Texel& t);

  const BankStats& stats() const { return stats_; }
  void reset_stats();

 private:
  struct Level {
    Extent shape;
    int stored_w = 1, stored_h = 1;  // stored_side of the shape's sides
    std::array<std::vector<Texel>, 4> banks;
  };
  std::vector<Level> levels_;
  BankStats stats_;
};

}  // namespace tex

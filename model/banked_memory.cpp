#include "banked_memory.h"

#include <stdexcept>

#include "stages.h"

namespace tex {

BankedMipMemory::BankedMipMemory(const Pyramid& pyramid) {
  for (const Image& img : pyramid.levels) {
    Level lvl;
    lvl.shape = {img.width, img.height};
    lvl.stored_w = stored_side(img.width);
    lvl.stored_h = stored_side(img.height);
    const int words = ((lvl.stored_w + 1) / 2) * ((lvl.stored_h + 1) / 2);
    for (auto& b : lvl.banks) b.assign(size_t(words), Texel{});
    levels_.push_back(std::move(lvl));
    const int k = int(levels_.size()) - 1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) write(k, x, y, img.at(x, y));
  }
  reset_stats();
}

int BankedMipMemory::word_of(int level, int32_t x, int32_t y) const {
  const int stride = (levels_[size_t(level)].stored_w + 1) / 2;
  return (y >> 1) * stride + (x >> 1);
}

void BankedMipMemory::write(int level, int32_t x, int32_t y, const Texel& t) {
  Level& l = levels_[size_t(level)];
  with_seam_copies(x, y, seam_copy(l.shape.w), seam_copy(l.shape.h), [&](int32_t sx, int32_t sy) {
    l.banks[size_t(stage::bank(sx, sy))][size_t(word_of(level, sx, sy))] = t;
  });
}

std::array<Texel, 4> BankedMipMemory::fetch(int level, int32_t x0, int32_t x1, int32_t y0, int32_t y1,
                                                     bool only_first, const Texel& border) {
  const int32_t xs[4] = {x0, x1, x0, x1}, ys[4] = {y0, y0, y1, y1};
  std::array<Texel, 4> out{};
  std::array<int, 4> word_read = {-1, -1, -1, -1};  // which word each bank delivered this clock
  Level& lvl = levels_[level];
  for (int t = 0; t < (only_first ? 1 : 4); ++t) {
    if (xs[t] == stage::kBorderTap || ys[t] == stage::kBorderTap) {
      out[t] = border;
      continue;
    }
    const int bank = stage::bank(xs[t], ys[t]);
    const int word = word_of(level, xs[t], ys[t]);
    if (word_read[bank] < 0) {
      word_read[bank] = word;
      ++stats_.reads;
      ++stats_.bank_reads[level][bank];
    }
    // Two different words from one bank would need two clocks: the parity layout rules it out.
    if (word_read[bank] != word) throw std::logic_error("bank conflict in a 2x2 footprint");
    out[t] = lvl.banks[bank][word];
  }
  if (only_first) out[1] = out[2] = out[3] = out[0];
  return out;
}

void BankedMipMemory::reset_stats() {
  stats_.reads = 0;
  stats_.bank_reads.assign(levels_.size(), {0, 0, 0, 0});
}

}  // namespace tex

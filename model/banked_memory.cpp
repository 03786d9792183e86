#include "banked_memory.h"

#include <stdexcept>

#include "stages.h"

namespace tex {

BankedMipMemory::BankedMipMemory(const Pyramid& pyramid) {
  for (const Image& img : pyramid.levels) {
    Level lvl;
    lvl.shape = {log2_exact(img.width), log2_exact(img.height)};
    const int words = std::max(1, img.width / 2) * std::max(1, img.height / 2);
    for (auto& b : lvl.banks) b.assign(size_t(words), Texel{});
    levels_.push_back(std::move(lvl));
    const int k = int(levels_.size()) - 1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) levels_[k].banks[stage::bank(x, y)][word_of(k, x, y)] = img.at(x, y);
  }
  reset_stats();
}

int BankedMipMemory::word_of(int level, int32_t x, int32_t y) const {
  const int stride = std::max(1, levels_[level].shape.width() / 2);
  return (y >> 1) * stride + (x >> 1);
}

void BankedMipMemory::write(int level, int32_t x, int32_t y, const Texel& t) {
  levels_[size_t(level)].banks[size_t(stage::bank(x, y))][size_t(word_of(level, x, y))] = t;
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

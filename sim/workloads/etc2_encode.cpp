#include "workloads/etc2_encode.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>

#include "model/error.h"
#include "model/etc2.h"

namespace tex {

namespace {

using Rgb = std::array<int, 3>;
struct Texels {
  std::array<Rgb, 16> rgb;           // texel x + 4 y
  std::array<int, 16> alpha;
};

int clamp255(int v) { return std::clamp(v, 0, 255); }

// The best table and indices of one sub-block (8 texels) around a base colour: its squared error.
struct SubBlock {
  long error = LONG_MAX;
  int table = 0;
  std::array<int, 16> index{};  // per texel of the block (the sub-block's only)
};
SubBlock fit(const Texels& t, const std::vector<int>& texels, const Rgb& base) {
  SubBlock best;
  for (int table = 0; table < 8; ++table) {
    const int mods[4] = {kEtcModifiers[table][0], kEtcModifiers[table][1], -kEtcModifiers[table][0], -kEtcModifiers[table][1]};
    SubBlock s;
    s.table = table;
    s.error = 0;
    for (int i : texels) {
      long texel_best = LONG_MAX;
      for (int k = 0; k < 4; ++k) {
        long e = 0;
        for (int c = 0; c < 3; ++c) {
          const int d = clamp255(base[size_t(c)] + mods[k]) - t.rgb[size_t(i)][size_t(c)];
          e += long(d) * d;
        }
        if (e < texel_best) texel_best = e, s.index[size_t(i)] = k;
      }
      s.error += texel_best;
    }
    if (s.error < best.error) best = s;
  }
  return best;
}

std::array<uint8_t, 8> encode_colour(const Texels& t) {
  long best_error = LONG_MAX;
  std::array<uint8_t, 8> best{};
  for (int flip = 0; flip < 2; ++flip) {
    // The half block of texel i (x + 4 y): the lower 4x2 with flip, else the right 2x4.
    const auto second = [flip](int i) { return flip ? i / 4 >= 2 : i % 4 >= 2; };
    std::vector<int> sub[2];
    for (int i = 0; i < 16; ++i) sub[second(i)].push_back(i);
    std::array<double, 3> mean[2];
    for (int s = 0; s < 2; ++s)
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int i : sub[s]) sum += t.rgb[size_t(i)][size_t(c)];
        mean[s][size_t(c)] = sum / 8;
      }
    for (int differential = 0; differential < 2; ++differential) {
      std::array<int, 3> q[2];  // the stored base colours: 4 or 5 bits
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c)
          q[s][size_t(c)] = int(std::lround(mean[s][size_t(c)] * (differential ? 31.0 : 15.0) / 255.0));
      bool fits = true;
      for (int c = 0; c < 3 && differential; ++c) fits = fits && q[1][size_t(c)] - q[0][size_t(c)] >= -4 && q[1][size_t(c)] - q[0][size_t(c)] <= 3;
      if (!fits) continue;
      Rgb base[2];
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c) {
          const int v = q[s][size_t(c)];
          base[s][size_t(c)] = differential ? (v << 3 | v >> 2) : (v << 4 | v);
        }
      const SubBlock a = fit(t, sub[0], base[0]), b = fit(t, sub[1], base[1]);
      if (a.error + b.error >= best_error) continue;
      best_error = a.error + b.error;
      uint64_t w = 0;
      for (int c = 0; c < 3; ++c) {
        const uint64_t field = differential ? uint64_t(q[0][size_t(c)]) << 3 | uint64_t((q[1][size_t(c)] - q[0][size_t(c)]) & 7)
                                            : uint64_t(q[0][size_t(c)]) << 4 | uint64_t(q[1][size_t(c)]);
        w |= field << (56 - 8 * c);
      }
      w |= uint64_t(a.table) << 37 | uint64_t(b.table) << 34 | uint64_t(differential) << 33 | uint64_t(flip) << 32;
      for (int i = 0; i < 16; ++i) {
        const int k = (second(i) ? b : a).index[size_t(i)];
        const int p = 4 * (i % 4) + i / 4;  // (column-major)
        w |= uint64_t(k >> 1) << (16 + p) | uint64_t(k & 1) << p;
      }
      for (int i = 0; i < 8; ++i) best[size_t(i)] = uint8_t(w >> (56 - 8 * i));
    }
  }
  return best;
}

// An EAC block's search (alpha and R11 alike): the base given, every table and multiplier from
// `first_multiplier`, each texel's best index; `value(multiplier, modifier)` is what a texel of
// that index decodes to, compared with `want` in the same units.
template <class Value>
std::array<uint8_t, 8> eac_block(int base, int first_multiplier, const std::array<int, 16>& want, Value value) {
  long best_error = LONG_MAX;
  uint64_t best = 0;
  for (int table = 0; table < 16; ++table)
    for (int multiplier = first_multiplier; multiplier < 16; ++multiplier) {
      long error = 0;
      uint64_t w = uint64_t(base) << 56 | uint64_t(multiplier) << 52 | uint64_t(table) << 48;
      for (int i = 0; i < 16 && error < best_error; ++i) {
        long texel_best = LONG_MAX;
        int index = 0;
        for (int k = 0; k < 8; ++k) {
          const long d = value(multiplier, kEacModifiers[table][k]) - want[size_t(i)];
          if (d * d < texel_best) texel_best = d * d, index = k;
        }
        error += texel_best;
        w |= uint64_t(index) << (45 - 3 * (4 * (i % 4) + i / 4));
      }
      if (error < best_error) best_error = error, best = w;
    }
  std::array<uint8_t, 8> out{};
  for (int i = 0; i < 8; ++i) out[size_t(i)] = uint8_t(best >> (56 - 8 * i));
  return out;
}

// ETC2 RGBA8's alpha: the base at the mean alpha, multipliers 1..15.
std::array<uint8_t, 8> encode_alpha(const Texels& t) {
  double sum = 0;
  for (int a : t.alpha) sum += a;
  const int base = clamp255(int(std::lround(sum / 16)));
  return eac_block(base, 1, t.alpha, [&](int multiplier, int m) { return clamp255(base + m * multiplier); });
}

// An EAC R11 block (unsigned) for 16 values of `bits` bits: each aimed at v * 2047 / (2^bits - 1)
// in 11 bits; the base at their mean, multipliers 0 (steps of 1) to 15.
std::array<uint8_t, 8> encode_r11(const std::array<int, 16>& v, int bits) {
  std::array<int, 16> want{};
  double sum = 0;
  for (int i = 0; i < 16; ++i) sum += want[size_t(i)] = int(std::lround(v[size_t(i)] * 2047.0 / ((1 << bits) - 1)));
  const int base = clamp255(int(std::lround((sum / 16 - 4) / 8)));
  return eac_block(base, 0, want, [&](int multiplier, int m) {
    return std::clamp(base * 8 + 4 + (multiplier ? m * multiplier * 8 : m), 0, 2047);
  });
}

}  // namespace

std::vector<uint8_t> encode_etc2_level(const Image& level, TexelFormat format) {
  if (format == TexelFormat::EacR11 || format == TexelFormat::EacRg11) {
    const int bw = (level.width + 3) / 4, bh = (level.height + 3) / 4, channels = format_info(format).channels;
    std::vector<uint8_t> out(size_t(bw) * size_t(bh) * size_t(8 * channels));
    for (int by = 0; by < bh; ++by)
      for (int bx = 0; bx < bw; ++bx)
        for (int c = 0; c < channels; ++c) {
          std::array<int, 16> v{};
          for (int i = 0; i < 16; ++i)
            v[size_t(i)] = level.at(std::min(bx * 4 + i % 4, level.width - 1), std::min(by * 4 + i / 4, level.height - 1))[size_t(c)];
          const std::array<uint8_t, 8> block = encode_r11(v, level.channel_bits);
          std::copy(block.begin(), block.end(), &out[((size_t(by) * size_t(bw) + size_t(bx)) * size_t(channels) + size_t(c)) * 8]);
        }
    return out;
  }
  if (format != TexelFormat::Etc2Rgb && format != TexelFormat::Etc2Rgba)
    throw Error(std::string("no ") + format_info(format).name + " encoder (etc2, etc2a, eac_r11 and eac_rg11 are encoded)");
  const int bw = (level.width + 3) / 4, bh = (level.height + 3) / 4, bytes = format_info(format).block_bytes;
  std::vector<uint8_t> out(size_t(bw) * size_t(bh) * size_t(bytes));
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      Texels t;
      for (int i = 0; i < 16; ++i) {
        const Texel& v = level.at(std::min(bx * 4 + i % 4, level.width - 1), std::min(by * 4 + i / 4, level.height - 1));
        t.rgb[size_t(i)] = {int(v[0]), int(v[1]), int(v[2])};
        t.alpha[size_t(i)] = int(v[3]);
      }
      uint8_t* block = &out[(size_t(by) * size_t(bw) + size_t(bx)) * size_t(bytes)];
      const std::array<uint8_t, 8> colour = encode_colour(t);
      if (format == TexelFormat::Etc2Rgba) {
        const std::array<uint8_t, 8> alpha = encode_alpha(t);
        std::copy(alpha.begin(), alpha.end(), block);
        block += 8;
      }
      std::copy(colour.begin(), colour.end(), block);
    }
  return out;
}

}  // namespace tex

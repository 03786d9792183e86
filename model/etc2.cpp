#include "etc2.h"

#include <algorithm>

namespace tex {

namespace {

uint64_t be64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = v << 8 | p[i];
  return v;
}

// Bits hi..lo of the block's word.
uint32_t bits(uint64_t w, int hi, int lo) { return uint32_t(w >> lo & ((uint64_t(1) << (hi - lo + 1)) - 1)); }

int signed3(uint32_t v) { return v >= 4 ? int(v) - 8 : int(v); }
uint8_t clamp255(int v) { return uint8_t(std::clamp(v, 0, 255)); }

// n-bit colour components to 8 bits, by replicating their top bits.
int ext4(uint32_t v) { return int(v << 4 | v); }
int ext5(uint32_t v) { return int(v << 3 | v >> 2); }
int ext6(uint32_t v) { return int(v << 2 | v >> 4); }
int ext7(uint32_t v) { return int(v << 1 | v >> 6); }

// The T and H modes' distances.
constexpr int kDistances[8] = {3, 6, 11, 16, 23, 32, 41, 64};

struct Rgb {
  int r, g, b;
};

std::array<uint8_t, 4> opaque(const Rgb& c, int d = 0) {
  return {clamp255(c.r + d), clamp255(c.g + d), clamp255(c.b + d), 255};
}

}  // namespace

Etc2Mode etc2_mode_of(const uint8_t* block, bool punch_through) {
  const uint64_t w = be64(block);
  if (!punch_through && !(w >> 33 & 1)) return Etc2Mode::Individual;
  const int r = int(bits(w, 63, 59)) + signed3(bits(w, 58, 56));
  const int g = int(bits(w, 55, 51)) + signed3(bits(w, 50, 48));
  const int b = int(bits(w, 47, 43)) + signed3(bits(w, 42, 40));
  if (r < 0 || r > 31) return Etc2Mode::T;
  if (g < 0 || g > 31) return Etc2Mode::H;
  if (b < 0 || b > 31) return Etc2Mode::Planar;
  return Etc2Mode::Differential;
}

std::array<uint8_t, 4> etc2_colour_texel(const uint8_t* block, bool punch_through, int i) {
  const uint64_t w = be64(block);
  const int x = i % 4, y = i / 4, p = 4 * x + y;
  const int index = int((w >> (p + 16) & 1) << 1 | (w >> p & 1));  // (msb, lsb)
  // RGB8A1: bit 33 says "opaque"; where it is clear, index 2 is a transparent black texel.
  const bool transparent_index = punch_through && !(w >> 33 & 1) && index == 2;
  const Etc2Mode mode = etc2_mode_of(block, punch_through);
  if (transparent_index && mode != Etc2Mode::Planar) return {0, 0, 0, 0};
  switch (mode) {
    case Etc2Mode::Individual:
    case Etc2Mode::Differential: {
      const bool second = (w >> 32 & 1) ? y >= 2 : x >= 2;  // flip: 4x2 sub-blocks, else 2x4
      Rgb base;
      if (mode == Etc2Mode::Individual) {
        base = second ? Rgb{ext4(bits(w, 59, 56)), ext4(bits(w, 51, 48)), ext4(bits(w, 43, 40))}
                      : Rgb{ext4(bits(w, 63, 60)), ext4(bits(w, 55, 52)), ext4(bits(w, 47, 44))};
      } else {
        const uint32_t r = bits(w, 63, 59), g = bits(w, 55, 51), b = bits(w, 47, 43);
        base = second ? Rgb{ext5(uint32_t(int(r) + signed3(bits(w, 58, 56)))), ext5(uint32_t(int(g) + signed3(bits(w, 50, 48)))),
                            ext5(uint32_t(int(b) + signed3(bits(w, 42, 40))))}
                      : Rgb{ext5(r), ext5(g), ext5(b)};
      }
      const int* m = kEtcModifiers[second ? bits(w, 36, 34) : bits(w, 39, 37)];
      // RGB8A1 without its opaque bit: index 0 adds nothing (index 2 is transparent, above).
      const int small = punch_through && !(w >> 33 & 1) ? 0 : m[0];
      const int modifier[4] = {small, m[1], -small, -m[1]};
      return opaque(base, modifier[index]);
    }
    case Etc2Mode::T: {
      const Rgb c1{ext4(bits(w, 60, 59) << 2 | bits(w, 57, 56)), ext4(bits(w, 55, 52)), ext4(bits(w, 51, 48))};
      const Rgb c2{ext4(bits(w, 47, 44)), ext4(bits(w, 43, 40)), ext4(bits(w, 39, 36))};
      const int d = kDistances[bits(w, 35, 34) << 1 | bits(w, 32, 32)];
      switch (index) {
        case 0: return opaque(c1);
        case 1: return opaque(c2, d);
        case 2: return opaque(c2);
        default: return opaque(c2, -d);
      }
    }
    case Etc2Mode::H: {
      const uint32_t r1 = bits(w, 62, 59), g1 = bits(w, 58, 56) << 1 | bits(w, 52, 52),
                     b1 = bits(w, 51, 51) << 3 | bits(w, 49, 47);
      const uint32_t r2 = bits(w, 46, 43), g2 = bits(w, 42, 39), b2 = bits(w, 38, 35);
      // The distance's low bit is the order of the two colours.
      const uint32_t order = (r1 << 8 | g1 << 4 | b1) >= (r2 << 8 | g2 << 4 | b2);
      const int d = kDistances[bits(w, 34, 34) << 2 | bits(w, 32, 32) << 1 | order];
      const Rgb c1{ext4(r1), ext4(g1), ext4(b1)}, c2{ext4(r2), ext4(g2), ext4(b2)};
      switch (index) {
        case 0: return opaque(c1, d);
        case 1: return opaque(c1, -d);
        case 2: return opaque(c2, d);
        default: return opaque(c2, -d);
      }
    }
    case Etc2Mode::Planar: {
      const Rgb o{ext6(bits(w, 62, 57)), ext7(bits(w, 56, 56) << 6 | bits(w, 54, 49)),
                  ext6(bits(w, 48, 48) << 5 | bits(w, 44, 43) << 3 | bits(w, 41, 39))};
      const Rgb h{ext6(bits(w, 38, 34) << 1 | bits(w, 32, 32)), ext7(bits(w, 31, 25)), ext6(bits(w, 24, 19))};
      const Rgb v{ext6(bits(w, 18, 13)), ext7(bits(w, 12, 6)), ext6(bits(w, 5, 0))};
      // (an arithmetic shift: the sum may be negative)
      auto plane = [&](int co, int ch, int cv) { return clamp255((x * (ch - co) + y * (cv - co) + 4 * co + 2) >> 2); };
      return {plane(o.r, h.r, v.r), plane(o.g, h.g, v.g), plane(o.b, h.b, v.b), 255};
    }
  }
  return {0, 0, 0, 0};
}

uint8_t eac_alpha_texel(const uint8_t* block, int i) {
  const uint64_t w = be64(block);
  const int base = int(w >> 56), multiplier = int(w >> 52 & 15), table = int(w >> 48 & 15);
  const int p = 4 * (i % 4) + i / 4;  // (column-major)
  return clamp255(base + kEacModifiers[table][w >> (45 - 3 * p) & 7] * multiplier);
}

int eac_r11_value(const uint8_t* block, bool snorm, int i) {
  const uint64_t w = be64(block);
  const int multiplier = int(w >> 52 & 15), table = int(w >> 48 & 15);
  const int p = 4 * (i % 4) + i / 4;  // (column-major)
  const int modifier = kEacModifiers[table][w >> (45 - 3 * p) & 7];
  const int step = multiplier ? modifier * multiplier * 8 : modifier;
  if (!snorm) return std::clamp(int(w >> 56) * 8 + 4 + step, 0, 2047);
  const int base = std::max(int(int8_t(w >> 56)), -127);
  return std::clamp(base * 8 + step, -1023, 1023);
}

int eac_r11_widened(int v, bool snorm) {
  if (!snorm) return v << 5 | v >> 6;
  const int m = v < 0 ? -v : v;
  return (v < 0 ? -1 : 1) * (m << 5 | m >> 5);
}

uint16_t eac_r11_code(const uint8_t* block, bool snorm, int i) {
  return uint16_t(eac_r11_widened(eac_r11_value(block, snorm, i), snorm) + (snorm ? 32768 : 0));
}

}  // namespace tex

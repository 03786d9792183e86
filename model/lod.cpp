#include "lod.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "formats.h"

namespace tex {

int64_t fixed_log2_q10(uint64_t p) {
  const int msb = 63 - std::countl_zero(p);
  // Mantissa in [1, 2) as 1.31 fixed point.
  uint64_t m = msb >= 31 ? p >> (msb - 31) : p << (31 - msb);
  int64_t frac = 0;
  for (int i = 0; i < 10; ++i) {
    m = (m * m) >> 31;  // square: [1, 4) in 2.31
    frac <<= 1;
    if (m >= (uint64_t(2) << 31)) {
      frac |= 1;
      m >>= 1;
    }
  }
  return int64_t(msb) * 1024 + frac;
}

namespace {
// Q15.16 texels; 2^15 texels or more saturates (lambda is then past every level, and clamps to
// the last one, as in GL: near a horizon a pixel's footprint is that large).
bool to_q16(double texels, int64_t& out) {
  if (!std::isfinite(texels)) return false;
  constexpr int64_t kMax = (int64_t(1) << 31) - 1;
  out = std::fabs(texels) >= 32768.0 ? (texels < 0 ? -kMax : kMax) : std::llround(std::ldexp(texels, 16));
  return true;
}
}  // namespace

bool lod_from_derivatives(const Derivatives& d, int log2_w, int log2_h, int32_t& lod_q8) {
  const double w = std::ldexp(1.0, log2_w), h = std::ldexp(1.0, log2_h);
  int64_t ax, bx, ay, by;
  if (!to_q16(d.dudx * w, ax) || !to_q16(d.dvdx * h, bx) || !to_q16(d.dudy * w, ay) || !to_q16(d.dvdy * h, by))
    return false;
  const uint64_t px = uint64_t(ax * ax) + uint64_t(bx * bx);  // rho_x^2, Q32.32
  const uint64_t py = uint64_t(ay * ay) + uint64_t(by * by);
  const uint64_t p = px > py ? px : py;
  if (p == 0) {
    lod_q8 = kLodMin;
    return true;
  }
  // lambda = log2(rho) = (log2 p - 32) / 2; in Q8.8 that is 256 * (l10/1024 - 32) / 2
  // = (l10 - 32*1024) / 8, rounded half up.
  lod_q8 = int32_t((fixed_log2_q10(p) - 32 * 1024 + 4) >> 3);
  return true;
}

// log2(1 + j/32) in Q.16, j = 0..32, rounded: the table of tex_lod's log stage.
namespace {
constexpr std::array<uint32_t, 33> kLog2Table = {
    0,     2909,  5732,  8473,  11136, 13727, 16248, 18704, 21098, 23433, 25711,
    27936, 30109, 32234, 34312, 36346, 38336, 40286, 42196, 44068, 45904, 47705,
    49472, 51207, 52911, 54584, 56229, 57845, 59434, 60997, 62534, 64047, 65536};
}  // namespace

int64_t tex_lod_log2_q16(uint64_t p) {
  const int k = 63 - std::countl_zero(p);
  // The 32 bits below the leading one: 5 index the table, the next 16 interpolate.
  const uint64_t f = k >= 32 ? (p >> (k - 32)) & 0xFFFFFFFFull : (p << (32 - k)) & 0xFFFFFFFFull;
  const uint32_t i = uint32_t(f >> 27), t = uint32_t(f >> 11) & 0xFFFF;
  const uint32_t lo = kLog2Table[i], hi = kLog2Table[i + 1];
  return int64_t(k) * 65536 + lo + ((uint64_t(hi - lo) * t) >> 16);
}

int32_t tex_lod(const LodDerivatives& d, int log2_w, int log2_h) {
  // Magnitudes in level-0 texels, 24 fraction bits (< 2^31 * 2^13 = 2^44).
  auto texels = [](int32_t v, int log2_size) { return uint64_t(v < 0 ? -int64_t(v) : int64_t(v)) << log2_size; };
  uint64_t a[4] = {texels(d.dudx, log2_w), texels(d.dvdx, log2_h), texels(d.dudy, log2_w), texels(d.dvdy, log2_h)};
  const uint64_t m = std::max(std::max(a[0], a[1]), std::max(a[2], a[3]));
  if (m == 0) return kLodMin;
  // Block normalization: the largest to 16 bits; the others keep their bits at the same weight.
  const int s = std::max(0, (63 - std::countl_zero(m)) - 15);
  for (uint64_t& x : a) x >>= s;
  const uint64_t px = a[0] * a[0] + a[1] * a[1], py = a[2] * a[2] + a[3] * a[3];  // < 2^33
  // lambda = log2(rho) = log2(max(px, py)) / 2 + s - 24, in Q.16, then rounded to Q8.8.
  const int64_t lambda_q16 = tex_lod_log2_q16(std::max(px, py)) / 2 + (int64_t(s) - 24) * 65536;
  return int32_t((lambda_q16 + 128) >> 8);
}

}  // namespace tex

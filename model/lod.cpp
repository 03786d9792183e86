#include "lod.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "formats.h"

namespace tex {

bool to_lod_derivatives(const Derivatives& d, LodDerivatives& out) {
  const double in[4] = {d.dudx, d.dvdx, d.dudy, d.dvdy};
  int32_t* q[4] = {&out.dudx, &out.dvdx, &out.dudy, &out.dvdy};
  for (int k = 0; k < 4; ++k) {
    if (!std::isfinite(in[k])) return false;
    if (!to_coord_fixed(in[k], *q[k])) *q[k] = in[k] < 0 ? -INT32_MAX : INT32_MAX;  // +-128: saturate
  }
  return true;
}

bool lod_from_derivatives(const Derivatives& d, int log2_w, int log2_h, int32_t& lod_q8) {
  LodDerivatives q;
  if (!to_lod_derivatives(d, q)) return false;
  lod_q8 = tex_lambda(q, log2_w, log2_h);
  return true;
}

namespace {
// log2(1 + j/32) in Q.16, j = 0..32, rounded: the table of tex_lambda's log stage.
constexpr std::array<uint32_t, 33> kLog2Table = {
    0,     2909,  5732,  8473,  11136, 13727, 16248, 18704, 21098, 23433, 25711,
    27936, 30109, 32234, 34312, 36346, 38336, 40286, 42196, 44068, 45904, 47705,
    49472, 51207, 52911, 54584, 56229, 57845, 59434, 60997, 62534, 64047, 65536};

// log2(p) in Q.16 for p > 0: the leading one, then the interpolated table (the unit's log stage).
int64_t log2_q16(uint64_t p) {
  const int k = 63 - std::countl_zero(p);
  // The 32 bits below the leading one: 5 index the table, the next 16 interpolate.
  const uint64_t f = k >= 32 ? (p >> (k - 32)) & 0xFFFFFFFFull : (p << (32 - k)) & 0xFFFFFFFFull;
  const uint32_t i = uint32_t(f >> 27), t = uint32_t(f >> 11) & 0xFFFF;
  const uint32_t lo = kLog2Table[i], hi = kLog2Table[i + 1];
  return int64_t(k) * 65536 + lo + ((uint64_t(hi - lo) * t) >> 16);
}
}  // namespace

int32_t tex_lambda(const LodDerivatives& d, int log2_w, int log2_h) {
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
  const int64_t lambda_q16 = log2_q16(std::max(px, py)) / 2 + (int64_t(s) - 24) * 65536;
  return int32_t((lambda_q16 + 128) >> 8);
}

}  // namespace tex

#include "lod.h"

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

}  // namespace tex

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

bool lod_from_derivatives(const Derivatives& d, Extent size0, int32_t& lod_q8) {
  LodDerivatives q;
  if (!to_lod_derivatives(d, q)) return false;
  lod_q8 = tex_lambda(q, size0);
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

// The LOD unit's first clock: magnitudes in level-0 texels (24 fraction bits, < 2^31 * 2^13 =
// 2^44), block-normalized so that the largest keeps 16 bits, and the squared lengths of the x and y
// derivative vectors (< 2^33). `shift` is the normalization's; all zero gives px = py = 0.
struct NormalizedSquares {
  uint64_t px = 0, py = 0;
  int shift = 0;
};
NormalizedSquares normalized_squares(const LodDerivatives& d, Extent size0) {
  auto texels = [](int32_t v, int size) { return uint64_t(v < 0 ? -int64_t(v) : int64_t(v)) * uint64_t(size); };
  uint64_t a[4] = {texels(d.dudx, size0.w), texels(d.dvdx, size0.h), texels(d.dudy, size0.w), texels(d.dvdy, size0.h)};
  const uint64_t m = std::max(std::max(a[0], a[1]), std::max(a[2], a[3]));
  NormalizedSquares q;
  if (m == 0) return q;
  // Block normalization: the largest to 16 bits; the others keep their bits at the same weight.
  q.shift = std::max(0, (63 - std::countl_zero(m)) - 15);
  for (uint64_t& x : a) x >>= q.shift;
  q.px = a[0] * a[0] + a[1] * a[1];
  q.py = a[2] * a[2] + a[3] * a[3];
  return q;
}

constexpr std::array<int, kMaxAniso + 1> kAnisoLog2Q8 = {0,   0,   256, 406, 512, 594, 662, 719, 768,
                                                        812, 850, 886, 918, 947, 975, 1000, 1024};
constexpr std::array<int, kMaxAniso + 1> kAnisoReciprocal = {0,    65536, 32768, 21845, 16384, 13107,
                                                            10923, 9362,  8192,  7282,  6554,  5958,
                                                            5461,  5041,  4681,  4369,  4096};
}  // namespace

int aniso_log2_q8(int n) { return kAnisoLog2Q8.at(size_t(n)); }
int aniso_reciprocal(int n) { return kAnisoReciprocal.at(size_t(n)); }

// lambda from the first clock's squares (tex_lambda's second clock).
static int32_t lambda_of(const NormalizedSquares& q) {
  if (q.px == 0 && q.py == 0) return kLodMin;
  // lambda = log2(rho) = log2(max(px, py)) / 2 + s - 24, in Q.16, then rounded to Q8.8.
  const int64_t lambda_q16 = log2_q16(std::max(q.px, q.py)) / 2 + (int64_t(q.shift) - 24) * 65536;
  return int32_t((lambda_q16 + 128) >> 8);
}

int32_t tex_lambda(const LodDerivatives& d, Extent size0) { return lambda_of(normalized_squares(d, size0)); }

AnisoSetup tex_aniso(const LodDerivatives& d, Extent size0, int max_aniso, bool pow2) {
  AnisoSetup a;
  const NormalizedSquares q = normalized_squares(d, size0);
  a.lambda = lambda_of(q);
  const uint64_t pmax = std::max(q.px, q.py), pmin = std::min(q.px, q.py);
  int cap = std::clamp(max_aniso, 1, kMaxAniso);
  if (pow2) cap = int(std::bit_floor(unsigned(cap)));
  // A footprint up to 1/128 longer than k * Pmin still takes k probes (Pmax^2 less 1/64 of it), so
  // that rounding in the derivatives does not turn a square footprint into 2 probes.
  const uint64_t target = pmax - (pmax >> 6);
  int n = cap;  // Pmax / Pmin beyond every candidate (or Pmin = 0): the cap
  for (int k = 1; k < cap; ++k)
    if ((!pow2 || std::has_single_bit(unsigned(k))) && uint64_t(k * k) * pmin >= target) {
      n = k;
      break;
    }
  a.n = n;
  a.lambda -= kAnisoLog2Q8[size_t(n)];
  const bool major_x = q.px >= q.py;
  const int64_t au = major_x ? d.dudx : d.dudy, av = major_x ? d.dvdx : d.dvdy;
  a.step_u = int32_t((au * kAnisoReciprocal[size_t(n)]) >> 16);
  a.step_v = int32_t((av * kAnisoReciprocal[size_t(n)]) >> 16);
  return a;
}

int32_t aniso_probe_coord(int32_t coord, int32_t step, int i, int n) {
  const int64_t c = int64_t(coord) + ((int64_t(2 * i + 1 - n) * step) >> 1);
  return int32_t(std::clamp<int64_t>(c, INT32_MIN, INT32_MAX));
}

}  // namespace tex

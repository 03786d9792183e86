// Level of detail from screen-space derivatives (GL / Heckbert rho), in fixed point.
#pragma once
#include <cstdint>

namespace tex {

// Derivatives of normalized (u, v) per screen pixel.
struct Derivatives {
  double dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

// floor(1024 * log2(p)) for p > 0 by leading-one position and repeated squaring.
int64_t fixed_log2_q10(uint64_t p);

// lambda in Q8.8 for a texture of 2^log2_w x 2^log2_h level-0 texels (docs/numerics.md,
// stage 1b). A derivative of 2^15 texels or more saturates there (lambda >= 15, past every level:
// the filter clamps it to the last level). Returns false when a derivative is not finite.
bool lod_from_derivatives(const Derivatives& d, int log2_w, int log2_h, int32_t& lod_q8);

}  // namespace tex

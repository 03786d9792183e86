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

// ------------------------------------------------------------------ tex_lod (docs/numerics.md, stage 1c)
// The hardware LOD unit's specification (the RTL module of the same name is to follow it bit for
// bit): lambda from the four derivatives of normalized (u, v) per screen pixel, each signed Q8.24
// like u and v (2^-24 .. 128 texture widths per pixel; a converter saturates beyond). Scaled to
// level-0 texels, normalized as a block (the largest magnitude to 16 bits), squared exactly,
// rho^2 = max(|d(u,v)/dx|^2, |d(u,v)/dy|^2) (no square-root approximation), and log2 by a leading-
// one detector plus a 32-entry table with linear interpolation. Result: lambda in Q8.8, rounded to
// nearest; all derivatives 0 gives kLodMin (magnification past any clamp).
struct LodDerivatives {
  int32_t dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;  // Q8.24 texture widths / heights per pixel
};
int32_t tex_lod(const LodDerivatives& d, int log2_w, int log2_h);
// log2(p) in Q.16 for p > 0 by the leading one and the interpolated table (the unit's log stage).
int64_t tex_lod_log2_q16(uint64_t p);

}  // namespace tex

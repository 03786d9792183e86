// Level of detail from screen-space derivatives (GL / Heckbert rho), in fixed point.
#pragma once
#include <cstdint>

namespace tex {

// Derivatives of normalized (u, v) per screen pixel.
struct Derivatives {
  double dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

// lambda in Q8.8 for a texture of 2^log2_w x 2^log2_h level-0 texels: the derivatives in the LOD
// unit's Q8.24 format (to_lod_derivatives), then tex_lambda (docs/numerics.md, stage 1b). Returns
// false when a derivative is not finite.
bool lod_from_derivatives(const Derivatives& d, int log2_w, int log2_h, int32_t& lod_q8);

// ------------------------------------------------------------------ tex_lambda (docs/numerics.md, stage 1b)
// The hardware LOD unit's specification (the RTL module of the same name is to follow it bit for
// bit; scenes and derivative traces take their lambda from it): lambda from the four derivatives of normalized (u, v) per screen pixel, each signed Q8.24
// like u and v (2^-24 .. 128 texture widths per pixel; a converter saturates beyond). Scaled to
// level-0 texels, normalized as a block (the largest magnitude to 16 bits), squared exactly,
// rho^2 = max(|d(u,v)/dx|^2, |d(u,v)/dy|^2) (no square-root approximation), and log2 by a leading-
// one detector plus a 32-entry table with linear interpolation. Result: lambda in Q8.8, rounded to
// nearest; all derivatives 0 gives kLodMin (magnification past any clamp).
struct LodDerivatives {
  int32_t dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;  // Q8.24 texture widths / heights per pixel
};
int32_t tex_lambda(const LodDerivatives& d, int log2_w, int log2_h);
// Real derivatives to Q8.24, rounded to nearest; beyond +-128 texture widths per pixel they
// saturate (lambda is then past every level). False when one is not finite.
bool to_lod_derivatives(const Derivatives& d, LodDerivatives& out);

}  // namespace tex

// Level of detail from screen-space derivatives (GL / Heckbert rho), in fixed point.
#pragma once
#include <cstdint>

#include "formats.h"

namespace tex {

// Derivatives of normalized (u, v) per screen pixel.
struct Derivatives {
  double dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

// lambda in Q8.8 for a texture of size0 level-0 texels: the derivatives in the LOD
// unit's Q8.24 format (to_lod_derivatives), then tex_lambda (docs/numerics.md, stage 1b). Returns
// false when a derivative is not finite.
bool lod_from_derivatives(const Derivatives& d, Extent size0, int32_t& lod_q8);

// ------------------------------------------------------------------ tex_lambda (docs/numerics.md, stage 1b)
// The hardware LOD unit's specification (rtl/tex_lambda.sv follows it bit for bit, RtlLambda.*;
// scenes and derivative traces take their lambda from it): lambda from the four derivatives of normalized (u, v) per screen pixel, each signed Q8.24
// like u and v (2^-24 .. 128 texture widths per pixel; a converter saturates beyond). Scaled to
// level-0 texels (|d| * w0 or * h0: a multiply, the paper's shift where the size is a power of two), normalized as a block (the largest magnitude to 16 bits), squared exactly,
// rho^2 = max(|d(u,v)/dx|^2, |d(u,v)/dy|^2) (no square-root approximation), and log2 by a leading-
// one detector plus a 33-entry table (32 intervals) with linear interpolation. Result: lambda in Q8.8, rounded to
// nearest; all derivatives 0 gives kLodMin (magnification past any clamp).
struct LodDerivatives {
  int32_t dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;  // Q8.24 texture widths / heights per pixel
};
int32_t tex_lambda(const LodDerivatives& d, Extent size0);

// ------------------------------------------------------------------ tex_aniso (docs/numerics.md, stage 1c)
// EXT_texture_filter_anisotropic from the same normalized squares as tex_lambda:
// Px^2, Py^2 = |d(u,v)/dx|^2, |d(u,v)/dy|^2; N = min(ceil(Pmax / Pmin), max_aniso), found as the
// least n with n^2 * Pmin^2 >= Pmax^2 - floor(Pmax^2 / 64) (a footprint up to 1/128 longer than
// n * Pmin takes n probes; Pmin = 0: the cap); with `pow2` the least such power of two, capped at
// the largest power of two <= max_aniso. lambda' = tex_lambda - round(256 log2 N), in Q8.8.
// The N probes are spread evenly along the major axis (the x derivatives when Px^2 >= Py^2):
// step = floor(axis * round(2^16 / N) / 2^16) per component, Q8.24; probe i sits at
// coord + floor((2i + 1 - N) * step / 2), saturated to the Q8.24 range (aniso_probe_coord).
struct AnisoSetup {
  int n = 1;               // probes, 1..16
  int32_t lambda = 0;      // Q8.8, lambda' (before bias and clamp)
  int32_t step_u = 0, step_v = 0;  // Q8.24, spacing of the probes
};
AnisoSetup tex_aniso(const LodDerivatives& d, Extent size0, int max_aniso, bool pow2);
int32_t aniso_probe_coord(int32_t coord, int32_t step, int i, int n);
// The tables the RTL holds as constants (tests/model/test_lod.cpp checks them against their definitions).
int aniso_log2_q8(int n);     // round(256 * log2 n), n = 1..16
int aniso_reciprocal(int n);  // round(2^16 / n), n = 1..16
// Real derivatives to Q8.24, rounded to nearest; beyond +-128 texture widths per pixel they
// saturate (lambda is then past every level). False when one is not finite.
bool to_lod_derivatives(const Derivatives& d, LodDerivatives& out);

}  // namespace tex

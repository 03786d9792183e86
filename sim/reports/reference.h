// The real-valued reference of the scenes and the metrics that compare a rendering with it
// (docs/scenes.md). Independent of the model: it reads only level 0, in double precision.
#pragma once
#include <vector>

#include "model/image.h"
#include "workloads/scenes.h"

namespace tex {

// The real-valued reference of every query, in double precision from level 0 only:
// pixel scenes: stratified sub-pixel positions through the exact mapping, nx across and ny down
// (reference_sub_positions: at least `samples_per_axis`, and enough that a sub-pixel step moves
// (u, v) by at most one texel, up to kReferenceMaxSubPositions), each averaging the level-0 texels
// (as a piecewise-constant image, with the wrap modes) over the bounding box of the sub-pixel's
// footprint widened by one texel (which makes a point footprint exactly bilinear);
// mesh scenes: the same average over the vertex's footprint (its spacing to the next vertex).
std::vector<Rgba> reference_values(const SceneFrame& frame, const Image& level0, Wrap wrap_u, Wrap wrap_v,
                                   int samples_per_axis = 4);
constexpr int kReferenceMaxSubPositions = 64;
// Sub-pixel positions along one screen axis whose pixel step is `step_texels` (the larger of its
// u and v steps, in level-0 texels): ceil(step_texels) within [samples_per_axis, max(that, 64)].
int reference_sub_positions(double step_texels, int samples_per_axis);

struct ErrorStats {
  double psnr_db = 0;         // over R, G, B of the covered pixels, peak 1.0 (infinite: 999)
  double max_error_lsb = 0;   // largest |difference| of one channel, in 8-bit steps
  double mean_error_lsb = 0;  // mean |difference| over R, G, B of the covered pixels
};
ErrorStats compare_images(const RgbaImage& image, const RgbaImage& reference);

// Error heat map: per pixel the largest R, G, B error, 0 (black) to `full_scale_lsb` (white) via red/yellow.
Image error_heat_map(const RgbaImage& image, const RgbaImage& reference, double full_scale_lsb);

// Mesh scenes, judged in vertex space rather than through the shaded picture: the error of each
// sampled vertex position (X, Y, Z) against the reference's, as the Euclidean distance in level-0
// texel spacings (value * `texels_per_unit`, the map's width: X = 1 is the map's full width).
// Split by where the vertex is: on a face's border (i or j = 0 or q) the pyramid's clamp-to-edge
// continues level l's edge texel, centred 2^(l-1) texels inside, whereas the reference continues
// level 0's edge texel; the interior vertices measure the filtering alone.
struct VertexErrorStats {
  struct Part {
    double rms_texels = 0;  // sqrt(mean |P - P_ref|^2)
    double max_texels = 0;  // max |P - P_ref|
    size_t vertices = 0;
  };
  Part all, interior, border;
};
// `frame` gives the faces' layout (consecutive (q+1) x (q+1) vertex grids, u step 1/q).
VertexErrorStats compare_vertices(const SceneFrame& frame, const std::vector<Rgba>& values,
                                  const std::vector<Rgba>& reference, double texels_per_unit);

// Temporal aliasing of a mesh animation in vertex space. A face's grid resolution q changes as it
// shrinks, so vertices do not correspond from frame to frame; instead each face is the bilinear patch
// through its (q+1) x (q+1) vertices, evaluated at the same `samples_per_axis`^2 (u, v) points in
// every frame. Per frame step: mean |S(t+1) - S(t)| of the variant, of the reference, and the excess
// mean |(S(t+1) - S(t)) - (R(t+1) - R(t))|, in texels as above. `frames` give the faces' layout.
struct SurfaceJitterStats {
  std::vector<double> change, reference_change, excess;
  double mean_change = 0, mean_reference_change = 0, mean_excess = 0;
  // The same pooled over the (u, v) points inside both frames' inner quads (clear of the border vertices).
  double mean_interior_change = 0, mean_interior_reference_change = 0, mean_interior_excess = 0;
};
SurfaceJitterStats mesh_jitter(const std::vector<SceneFrame>& frames, const std::vector<std::vector<Rgba>>& values,
                               const std::vector<std::vector<Rgba>>& reference, double texels_per_unit,
                               int samples_per_axis = 33);

// Temporal aliasing of an animation (frames of one variant and of the reference, same size).
struct FlickerStats {
  std::vector<double> change;            // per frame step: mean |F(t+1) - F(t)|, 8-bit steps
  std::vector<double> reference_change;  // the same for the reference
  std::vector<double> excess;            // mean |(F(t+1) - F(t)) - (R(t+1) - R(t))|: change the reference lacks
  double mean_change = 0, mean_reference_change = 0, mean_excess = 0;
};
FlickerStats flicker(const std::vector<RgbaImage>& frames, const std::vector<RgbaImage>& reference_frames);

}  // namespace tex

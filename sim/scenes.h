// Scenes: a camera and a surface that turn every pixel (or every mesh vertex) into one texture
// query. Each scene reproduces an experiment of Williams 1983 (docs/scenes.md).
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/formats.h"
#include "model/image.h"
#include "model/trace.h"

namespace tex {

using Rgba = std::array<double, 4>;  // a colour with channels normalized to [0, 1]

// A real-valued RGBA image (channels in [0, 1]); `covered` marks the pixels a metric looks at.
struct RgbaImage {
  int width = 0, height = 0;
  std::vector<Rgba> pixels;
  std::vector<bool> covered;
};

// Where a screen point lands on the surface.
enum class Hit { None, Extended, Surface };
// Maps screen position (sx, sy), in pixels with (0, 0) the top-left corner, to normalized (u, v).
// Extended: the point misses the surface but (u, v) continues the surface's mapping smoothly
// (used for derivatives and the reference at silhouettes); None: no (u, v) at all.
using UvMap = std::function<Hit(double sx, double sy, double& u, double& v)>;

struct SceneOptions {
  int width = 640, height = 480;
  int frame = 0, frames = 1;  // animation: frame `frame` of `frames` (0-based)
};

struct SceneFrame {
  int width = 0, height = 0;
  std::vector<int> pixel;      // pixel index (y * width + x) of each query; mesh scenes: vertex index
  std::vector<Query> queries;  // normalized (u, v) and derivatives (or explicit lambda) per query
  Texel background{};          // pixels without a query

  std::string default_texture;               // texture spec used when the user names none
  std::shared_ptr<const Image> own_texture;  // the scene's own map (reflect, mesh): replaces --texture
  bool clamp_edges = false;                  // the map is not periodic: sample with clamp-to-edge

  UvMap map;  // pixel scenes: the exact screen -> (u, v) mapping (the reference integrates over it)
  // Mesh scenes: draws the image from one value per vertex (filtered X, Y, Z in [0, 1]).
  std::function<RgbaImage(const std::vector<Rgba>& vertex_values)> draw;
  bool is_mesh() const { return bool(draw); }
};

const std::vector<std::string>& scene_names();

// Throws tex::Error for an unknown scene, a bad size or a bad frame number.
SceneFrame make_scene(const std::string& name, const SceneOptions& options);
SceneFrame make_scene(const std::string& name, int width, int height);

// The texture a frame samples: its own map, else `user_spec` when given, else its default.
Image scene_texture(const SceneFrame& frame, const std::string& user_spec, bool resize = false);

// The final picture from sampled texels (one per query). Pixel scenes place the texels bit-exactly
// (channel_bits wide); mesh scenes draw the filtered mesh (8 bits).
Image compose(const SceneFrame& frame, const std::vector<Texel>& texels, int channel_bits);

// Real-valued versions, for comparisons: the picture from values in [0, 1] per query.
std::vector<Rgba> texels_to_values(const std::vector<Texel>& texels, int channel_bits);
RgbaImage render_values(const SceneFrame& frame, const std::vector<Rgba>& values);
Image to_image8(const RgbaImage& img);

// The procedural maps of the reflect and mesh scenes (also used by the tests).
Image make_reflectance_map(int size);      // 9 lights on a sphere-projected environment (fig. 17)
Image make_face_xyz_map(int size, int channel_bits);  // X, Y, Z of a face-like height field (fig. 20-23)

// ---- Reference and metrics (sim/scenes/reference.cpp) ----

// The real-valued reference of every query, in double precision from level 0 only:
// pixel scenes: `samples_per_axis`^2 stratified sub-pixel positions through the exact mapping, each
// averaging the level-0 texels (as a piecewise-constant image, with the wrap modes) over the
// sub-pixel's footprint widened by one texel (which makes a point footprint exactly bilinear);
// mesh scenes: the same average over the vertex's footprint (its spacing to the next vertex).
std::vector<Rgba> reference_values(const SceneFrame& frame, const Image& level0, Wrap wrap_u, Wrap wrap_v,
                                   int samples_per_axis = 4);

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

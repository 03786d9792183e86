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
#include "model/pyramid.h"
#include "workloads/query_trace.h"
#include "workloads/texture_files.h"

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

// The order in which a pixel scene issues its queries (a rasterizer's walk; mesh scenes keep vertex
// order): rows top to bottom, or square tiles row by row with scanline order inside each tile.
enum class PixelOrder { Scanline, Tiled };
PixelOrder parse_pixel_order(const std::string& name);  // scanline | tiled; throws tex::Error

struct SceneOptions {
  int width = 640, height = 480;
  int frame = 0, frames = 1;  // animation: frame `frame` of `frames` (0-based)
  PixelOrder order = PixelOrder::Scanline;
  int tile = 8;  // tiled order: tile side in pixels (power of two, 2 to 256)
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
// Scenes that sample once per mesh vertex, in vertex order (no pixel walk).
bool scene_samples_vertices(const std::string& name);

// Throws tex::Error for an unknown scene, a bad size or a bad frame number.
SceneFrame make_scene(const std::string& name, const SceneOptions& options);
SceneFrame make_scene(const std::string& name, int width, int height);

// The texture a frame samples: its own map, else `user_spec` when given, else its default.
Image scene_texture(const SceneFrame& frame, const std::string& user_spec, bool resize = false);
// The same texture's pyramid, as the options make it (workloads/texture_files.h: a DDS/KTX file,
// or the box pyramid in options.format).
Pyramid scene_pyramid(const SceneFrame& frame, const std::string& user_spec, const TextureOptions& options);

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

}  // namespace tex

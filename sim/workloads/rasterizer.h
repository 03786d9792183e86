// The rasterizer of real frames, as GPUs do it (docs/scenes.md): clipping in homogeneous space,
// 8 sub-pixel bits, the top-left fill rule, back faces culled unless double-sided, a depth buffer
// filled before shading so that only the visible surface samples, and 2x2 quads whose
// derivatives are the differences inside the quad (coarse dFdx/dFdy). Lanes of a quad that the
// visible primitive does not cover are helper lanes: they sample too, and are counted apart.
#pragma once
#include <cstdint>
#include <vector>

#include "workloads/camera.h"
#include "workloads/mesh_scene.h"
#include "workloads/query_trace.h"
#include "workloads/scenes.h"

namespace tex {

struct RasterOptions {
  int width = 640, height = 480;
  PixelOrder order = PixelOrder::Tiled;  // quads of a primitive: 8x8-pixel tiles, or quad rows
  int tile = 8;                          // tiled order: tile side in pixels (even, 2 to 256)
  // Reflection mapping (the paper's §4, render --envmap): every mesh a mirror. A visible lane
  // queries the cube map (texture 0) along the view ray reflected by the interpolated normal,
  // R = I - 2 (N.I) N, its derivatives the quad's differences of R; every pixel no mesh covers
  // queries the environment along the view ray itself (its quads, helper lanes where a mesh is).
  bool reflect = false;
};

struct RasterFrame {
  int width = 0, height = 0;
  // Four per quad, lanes in the order (x, y), (x+1, y), (x, y+1), (x+1, y+1); each carries its
  // texture id, quad number, pixel and helper flag. u and v are perspective-correct at the pixel
  // centre (helper lanes: the primitive's plane extended), the derivatives the quad's.
  std::vector<Query> queries;
  uint64_t quads = 0, helper_samples = 0;
  uint64_t primitives = 0, culled = 0;  // primitives after clipping that reached the screen; back faces culled
};

// Throws tex::Error for a size the options cannot have. Primitives are drawn in the mesh order of
// the scene, each one's quads in the walk order of `options`.
RasterFrame rasterize(const MeshScene& scene, const Camera& camera, const RasterOptions& options);

// The picture: each visible lane's texel (RGB, opaque) at its pixel, `background` elsewhere.
Image compose_frame(const RasterFrame& frame, const std::vector<Texel>& texels, int channel_bits,
                    const Texel& background);

}  // namespace tex

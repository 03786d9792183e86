// `texsim figures`: renders every scene's variants through an engine, compares them with the
// real-valued reference, measures temporal aliasing, and writes images, metrics.json and index.md.
#pragma once
#include <string>
#include <vector>

#include "engines/engine.h"
#include "reports/reference.h"
#include "workloads/scenes.h"

namespace tex {

// One scene frame sampled through an engine (the scene's texture, repeat wrap unless the scene
// asks for clamp-to-edge), as a real-valued picture; `texels` keeps the raw engine output.
struct VariantRender {
  SceneFrame frame;
  std::vector<Texel> texels;
  int channel_bits = 8;
  RgbaImage image;
};
// `max_aniso`: the anisotropic filter's probe cap (SamplerConfig::max_aniso), 1..16.
VariantRender render_variant(const std::string& scene, const SceneOptions& options, const std::string& filter,
                             const std::string& engine, int max_aniso = kMaxAniso);
// The real-valued reference value of every query of a scene frame (reference_values of the scene's
// level 0; the mesh's reference is the 16-bit map), and the picture drawn from them.
std::vector<Rgba> reference_query_values(const std::string& scene, const SceneOptions& options,
                                         int samples_per_axis = 4);
RgbaImage render_reference(const std::string& scene, const SceneOptions& options, int samples_per_axis = 4);

struct FiguresOptions {
  std::string out_dir = "out/figures";
  std::string engine = "model";
  int width = 256, height = 192;             // still figures
  int anim_width = 160, anim_height = 120;   // animations (flicker)
  int frames = 24;
  int reference_samples = 4;                 // reference sub-pixel positions per axis, at least (reference_values)
};

// Returns 0; throws tex::Error on bad options or a failed write.
int make_figures(const FiguresOptions& options);

}  // namespace tex

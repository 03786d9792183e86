// texsim render --model / --scene-file: real frames of textured 3D models (docs/scenes.md).
#pragma once
#include "cli/frame_store.h"
#include <string>

#include "cli/sampling.h"
#include "workloads/scenes.h"

namespace tex {

struct ModelRenderArgs {
  std::string model, scene_file;      // exactly one of them
  std::string camera, camera_path;    // at most one; neither: the orbit
  std::string out, trace_queries;
  std::string envmap;                 // render the model as a mirror of this environment (a cube map)
  int width = 640, height = 480;
  int frame = 0, frames = 1;
  bool all_frames = false;            // --frames M without --frame: every frame to OUT_000.png ...
  bool wrap_given = false;            // --wrap* replace the model's wrap modes
  bool filter_given = false;          // --filter, --min-filter, ... replace the model's (glTF) filters
  PixelOrder order = PixelOrder::Tiled;
  int tile = 8;
  FrameStore* store = nullptr;        // --store: the one frame kept in (or taken from) the results store
};

int cmd_render_model(const SamplingOptions& o, const ModelRenderArgs& a);

}  // namespace tex

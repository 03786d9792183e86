// Scenes: a camera and a surface that turn every pixel into one texture query.
#pragma once
#include <string>
#include <vector>

#include "model/image.h"
#include "model/trace.h"

namespace tex {

struct SceneFrame {
  int width = 0, height = 0;
  std::vector<int> pixel;      // pixel index (y * width + x) of each query
  std::vector<Query> queries;  // normalized (u, v) and derivatives per screen pixel
  Texel background{};          // pixels without a query
};

const std::vector<std::string>& scene_names();

// Throws tex::Error for an unknown scene or a bad size.
SceneFrame make_scene(const std::string& name, int width, int height);

// Places the sampled texels (one per query) on the frame's background.
Image compose(const SceneFrame& frame, const std::vector<Texel>& texels, int channel_bits);

}  // namespace tex

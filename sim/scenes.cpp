#include "scenes.h"

#include <cmath>
#include <functional>

#include "model/error.h"

namespace tex {

const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names = {"plane"};
  return names;
}

namespace {

using UvMap = std::function<bool(double sx, double sy, double& u, double& v)>;

// One query per pixel whose centre maps onto the surface. Derivatives are central differences
// of the mapping over one pixel, as a GPU quad computes them.
SceneFrame sample_map(int width, int height, const UvMap& map, Texel background) {
  SceneFrame f;
  f.width = width;
  f.height = height;
  f.background = background;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double u, v, ul, vl, ur, vr, ua, va, ub, vb;
      if (!map(x + 0.5, y + 0.5, u, v)) continue;
      Query q;
      q.u = u;
      q.v = v;
      q.explicit_lod = false;
      if (map(x, y + 0.5, ul, vl) && map(x + 1, y + 0.5, ur, vr) && map(x + 0.5, y, ua, va) &&
          map(x + 0.5, y + 1, ub, vb))
        q.deriv = {ur - ul, vr - vl, ub - ua, vb - va};
      else
        q.deriv = {0, 0, 0, 0};
      f.pixel.push_back(y * width + x);
      f.queries.push_back(q);
    }
  return f;
}

// An infinite textured floor seen from eye height 1, looking at the horizon (paper fig. 7).
SceneFrame plane(int width, int height) {
  const double focal = 0.5 * width;  // 90-degree horizontal field of view
  const double horizon = 0.3 * height;
  const double tiles_per_unit = 0.25;  // texture repeats every 4 world units
  auto map = [=](double sx, double sy, double& u, double& v) {
    const double dy = sy - horizon;
    if (dy < 0.5) return false;  // sky, or too close to the horizon to hit the floor
    const double z = focal / dy;  // eye height 1
    const double x = (sx - 0.5 * width) * z / focal;
    u = x * tiles_per_unit + 0.5;
    v = z * tiles_per_unit;
    return std::fabs(u) < 100 && std::fabs(v) < 100;
  };
  return sample_map(width, height, map, Texel{140, 180, 230, 255});
}

}  // namespace

SceneFrame make_scene(const std::string& name, int width, int height) {
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside 1x1 to 8192x8192");
  if (name == "plane") return plane(width, height);
  std::string list;
  for (const auto& n : scene_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown scene '" + name + "' (known: " + list + ")");
}

Image compose(const SceneFrame& frame, const std::vector<Texel>& texels, int channel_bits) {
  Image img(frame.width, frame.height, channel_bits);
  for (auto& t : img.texels) t = frame.background;
  for (size_t i = 0; i < frame.pixel.size(); ++i) img.texels[frame.pixel[i]] = texels[i];
  return img;
}

}  // namespace tex

#include "image.h"

#include <algorithm>
#include <cmath>

#include "error.h"

namespace tex {

const std::vector<std::string>& pattern_names() {
  static const std::vector<std::string> names = {"checker", "testcard", "noise", "gradient"};
  return names;
}

void check_texture_size(int w, int h, const std::string& what, const std::string& hint) {
  const int max = 1 << kMaxLog2Size;
  const std::string size = what + ": size " + std::to_string(w) + "x" + std::to_string(h);
  const std::string tail = hint.empty() ? "" : " (" + hint + ")";
  if (w < 1 || h < 1) throw Error(size + " is empty: each side must be at least 1");
  if (w > max || h > max) throw Error(size + " is too large: at most " + std::to_string(max) + " per side" + tail);
}

namespace {

Texel rgb(int r, int g, int b) {
  return {uint16_t(r), uint16_t(g), uint16_t(b), 255};
}

// SMPTE-like colour bars, a grey ramp, a fine checker and a circle: features at every scale,
// so each mip level shows something different.
Texel testcard_texel(int x, int y, int w, int h) {
  static const Texel bars[8] = {rgb(235, 235, 235), rgb(235, 235, 16), rgb(16, 235, 235), rgb(16, 235, 16),
                                rgb(235, 16, 235),  rgb(235, 16, 16),  rgb(16, 16, 235),  rgb(16, 16, 16)};
  const double fx = (x + 0.5) / w, fy = (y + 0.5) / h;
  const double dx = fx - 0.5, dy = (fy - 0.5) * h / std::max(w, h) * (double(std::max(w, h)) / w);
  const double r = std::sqrt(dx * dx + dy * dy);
  if (std::abs(r - 0.4) < 0.012) return rgb(255, 255, 255);
  if (fy < 0.5) return bars[std::min(7, int(fx * 8))];
  if (fy < 0.625) {
    const int g = std::min(255, int(fx * 256));
    return rgb(g, g, g);
  }
  if (fy < 0.75) {  // checkers of 1, 2, 4, 8 texels across the row
    const int cell = 1 << std::min(3, int(fx * 4));
    const int on = ((x / cell) + (y / cell)) & 1;
    return on ? rgb(255, 255, 255) : rgb(0, 0, 0);
  }
  if (fy < 0.875) {  // sine zone plate in x: frequency rises to the right
    const double s = 0.5 + 0.5 * std::cos(M_PI * fx * fx * w / 2);
    const int g = int(std::lround(s * 255));
    return rgb(g, g / 2, 255 - g);
  }
  return ((x / 8 + y / 8) & 1) ? rgb(200, 40, 40) : rgb(40, 40, 200);
}

uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

}  // namespace

Image make_pattern(const std::string& name, int w, int h) {
  check_texture_size(w, h, "pattern " + name);
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Texel& t = img.at(x, y);
      if (name == "checker") {
        const int cell = std::max(1, std::max(w, h) / 16);
        t = ((x / cell + y / cell) & 1) ? rgb(240, 240, 240) : rgb(20, 20, 140);
      } else if (name == "testcard") {
        t = testcard_texel(x, y, w, h);
      } else if (name == "noise") {
        const uint32_t r = hash32(uint32_t(y) * 0x9E3779B1U + uint32_t(x));
        t = {uint16_t(r & 255), uint16_t((r >> 8) & 255), uint16_t((r >> 16) & 255), uint16_t(r >> 24)};
      } else if (name == "gradient") {
        t = rgb(x * 255 / std::max(1, w - 1), y * 255 / std::max(1, h - 1), 128);
      } else {
        std::string list;
        for (const auto& n : pattern_names()) list += (list.empty() ? "" : ", ") + n;
        throw Error("unknown pattern '" + name + "' (known: " + list + ")");
      }
    }
  return img;
}

}  // namespace tex

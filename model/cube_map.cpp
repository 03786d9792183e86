#include "cube_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "error.h"
#include "srgb.h"

namespace tex {

CubeTexel cube_neighbour(int face, int x, int y, int n) {
  // The centre of (x, y) in face coordinates, then the direction it stands for on the unit cube.
  const double sc = 2.0 * (x + 0.5) / n - 1.0, tc = 2.0 * (y + 0.5) / n - 1.0;
  double r[3] = {0, 0, 0};
  switch (face) {
    case 0: r[0] = 1, r[1] = -tc, r[2] = -sc; break;
    case 1: r[0] = -1, r[1] = -tc, r[2] = sc; break;
    case 2: r[0] = sc, r[1] = 1, r[2] = tc; break;
    case 3: r[0] = sc, r[1] = -1, r[2] = -tc; break;
    case 4: r[0] = sc, r[1] = -tc, r[2] = 1; break;
    default: r[0] = -sc, r[1] = -tc, r[2] = -1; break;
  }
  // Its face by the major axis (no ties: the point is half a texel beyond an edge, off the diagonal).
  const double ax = std::fabs(r[0]), ay = std::fabs(r[1]), az = std::fabs(r[2]);
  double s2 = 0, t2 = 0, rc = 0;
  CubeTexel out;
  if (az >= ax && az >= ay) {
    out.face = r[2] >= 0 ? 4 : 5;
    s2 = r[2] >= 0 ? r[0] : -r[0], t2 = -r[1], rc = az;
  } else if (ay >= ax) {
    out.face = r[1] >= 0 ? 2 : 3;
    s2 = r[0], t2 = r[1] >= 0 ? r[2] : -r[2], rc = ay;
  } else {
    out.face = r[0] >= 0 ? 0 : 1;
    s2 = r[0] >= 0 ? -r[2] : r[2], t2 = -r[1], rc = ax;
  }
  out.x = std::clamp(int(std::floor((s2 / rc + 1) / 2 * n)), 0, n - 1);
  out.y = std::clamp(int(std::floor((t2 / rc + 1) / 2 * n)), 0, n - 1);
  return out;
}

std::vector<Pyramid> cube_skirts(const std::vector<const Pyramid*>& faces) {
  if (faces.empty() || faces.size() % 6 != 0)
    throw Error(std::to_string(faces.size()) + " faces: a cube map has 6 (+X, -X, +Y, -Y, +Z, -Z) per cube");
  const Pyramid& f0 = *faces[0];
  if (is_compressed(f0.format))
    throw Error(std::string("a cube map in ") + format_info(f0.format).name +
                ": the unit holds cube maps in RGBA (a skirt would need its blocks encoded again)");
  if (f0.extent0().w != f0.extent0().h)
    throw Error("cube faces of " + std::to_string(f0.extent0().w) + "x" + std::to_string(f0.extent0().h) +
                " texels: a cube's faces are square");
  for (const Pyramid* f : faces)
    if (f->extent0() != f0.extent0() || f->levels.size() != f0.levels.size() || f->srgb != f0.srgb ||
        f->levels[0].channel_bits != f0.levels[0].channel_bits || f->format != f0.format)
      throw Error("cube faces of different sizes, level counts or formats (" + std::to_string(f->extent0().w) + "x" +
                  std::to_string(f->extent0().h) + " beside " + std::to_string(f0.extent0().w) + "x" +
                  std::to_string(f0.extent0().h) + ")");
  std::vector<Pyramid> out;
  for (size_t cube = 0; cube < faces.size(); cube += 6)
    for (int face = 0; face < 6; ++face) {
      Pyramid p;
      p.mode = f0.mode;
      p.format = f0.format;
      p.srgb = f0.srgb;
      // What memory holds: an sRGB cube's codes (averaged as codes, then decoded), else the levels.
      auto stored = [&](int f, size_t k) -> const Image& {
        const Pyramid& src = *faces[cube + size_t(f)];
        return src.srgb ? src.codes[k] : src.levels[k];
      };
      for (size_t k = 0; k < f0.levels.size(); ++k) {
        const Image& own = stored(face, k);
        const int n = own.width;
        Image img(n + 2, n + 2, own.channel_bits);
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) img.at(x + 1, y + 1) = own.at(x, y);
        auto neighbour = [&](int x, int y) {
          const CubeTexel c = cube_neighbour(face, x, y, n);
          return stored(c.face, k).at(c.x, c.y);
        };
        for (int i = 0; i < n; ++i) {
          img.at(0, i + 1) = neighbour(-1, i);
          img.at(n + 1, i + 1) = neighbour(n, i);
          img.at(i + 1, 0) = neighbour(i, -1);
          img.at(i + 1, n + 1) = neighbour(i, n);
        }
        // A corner: the face's corner texel and its two skirt neighbours, averaged (rounded to the
        // nearest; a sum's thirds are never a half).
        for (const auto& [cx, cy, ox, oy] : {std::array<int, 4>{0, 0, 1, 1}, {n + 1, 0, n, 1}, {0, n + 1, 1, n},
                                            {n + 1, n + 1, n, n}}) {
          Texel& t = img.at(cx, cy);
          const Texel &a = img.at(ox, oy), &b = img.at(cx, oy), &c = img.at(ox, cy);
          for (size_t ch = 0; ch < 4; ++ch) t[ch] = uint16_t((uint32_t(a[ch]) + b[ch] + c[ch] + 1) / 3);
        }
        p.levels.push_back(std::move(img));
      }
      if (p.srgb) {
        p.srgb = false;
        decode_srgb_levels(p);  // (codes := the skirted codes, levels := decoded)
      }
      out.push_back(std::move(p));
    }
  return out;
}

}  // namespace tex

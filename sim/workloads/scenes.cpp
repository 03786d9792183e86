#include "workloads/scenes.h"

#include <algorithm>
#include <cmath>

#include "model/error.h"
#include "workloads/texture_io.h"

namespace tex {

const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names = {"magnify", "minify", "plane", "panel", "reflect", "mesh"};
  return names;
}

bool scene_samples_vertices(const std::string& name) { return name == "mesh" || name == "mesh16"; }

PixelOrder parse_pixel_order(const std::string& name) {
  if (name == "scanline") return PixelOrder::Scanline;
  if (name == "tiled") return PixelOrder::Tiled;
  throw Error("unknown pixel order '" + name + "' (known: scanline, tiled)");
}

namespace {

// Animation time of a frame in [0, 1] (0 for a single frame).
double frame_time(const SceneOptions& o) { return o.frames > 1 ? double(o.frame) / (o.frames - 1) : 0.0; }

// The pixels of the image in the order the rasterizer visits them.
std::vector<std::pair<int, int>> pixel_walk(const SceneOptions& o) {
  const int tile_w = o.order == PixelOrder::Tiled ? o.tile : o.width;
  const int tile_h = o.order == PixelOrder::Tiled ? o.tile : 1;
  std::vector<std::pair<int, int>> walk;
  walk.reserve(size_t(o.width) * o.height);
  for (int ty = 0; ty < o.height; ty += tile_h)
    for (int tx = 0; tx < o.width; tx += tile_w)
      for (int y = ty; y < std::min(ty + tile_h, o.height); ++y)
        for (int x = tx; x < std::min(tx + tile_w, o.width); ++x) walk.emplace_back(x, y);
  return walk;
}

// One query per pixel whose centre lands on the surface. Derivatives are central differences of
// the mapping over one pixel, as a GPU quad computes them; where a neighbour has no (u, v) at all
// the one-sided difference (doubled) stands in.
SceneFrame sample_map(const SceneOptions& o, const UvMap& map, Texel background) {
  SceneFrame f;
  f.width = o.width;
  f.height = o.height;
  f.background = background;
  f.map = map;
  for (const auto& [x, y] : pixel_walk(o)) {
    const double cx = x + 0.5, cy = y + 0.5;
    double u, v;
    if (map(cx, cy, u, v) != Hit::Surface) continue;
    auto diff = [&](double ax, double ay, double bx, double by, double& du, double& dv) {
      double ua, va, ub, vb;
      const bool a = map(ax, ay, ua, va) != Hit::None, b = map(bx, by, ub, vb) != Hit::None;
      if (a && b) du = ub - ua, dv = vb - va;
      else if (b) du = 2 * (ub - u), dv = 2 * (vb - v);
      else if (a) du = 2 * (u - ua), dv = 2 * (v - va);
      else du = dv = 0;
    };
    Query q;
    q.u = u;
    q.v = v;
    q.explicit_lod = false;
    diff(cx - 0.5, cy, cx + 0.5, cy, q.deriv.dudx, q.deriv.dvdx);
    diff(cx, cy - 0.5, cx, cy + 0.5, q.deriv.dudy, q.deriv.dvdy);
    f.pixel.push_back(y * o.width + x);
    f.queries.push_back(q);
  }
  return f;
}

// Fig. 3/4: a 16-texel-wide region of the test card (the grey ramp over the 1- and 2-texel checkers)
// blown up to the whole image; the region pans by 1/10 texel per frame.
SceneFrame magnify(const SceneOptions& o) {
  const double texels = 256, span_u = 16 / texels, span_v = span_u * o.height / o.width;
  const double u0 = 0.21 + 0.1 / texels * o.frame, v0 = 0.60;
  auto map = [=](double sx, double sy, double& u, double& v) {
    u = u0 + sx / o.width * span_u;
    v = v0 + sy / o.height * span_v;
    return Hit::Surface;
  };
  SceneFrame f = sample_map(o, map, Texel{0, 0, 0, 255});
  f.default_texture = "testcard:256x256";
  return f;
}

// Fig. 5/6: the test card shrunk 6.3 times (about 2.6 levels of minification), turned by 8 degrees
// so that point sampling beats against the pixel grid; it drifts by 0.37 pixel per frame.
SceneFrame minify(const SceneOptions& o) {
  const double texels = 512, per_pixel = 6.3 / texels, angle = 8 * M_PI / 180;
  const double c = std::cos(angle), s = std::sin(angle), shift = 0.37 * o.frame;
  auto map = [=](double sx, double sy, double& u, double& v) {
    const double x = sx + shift, y = sy;
    u = (c * x - s * y) * per_pixel;
    v = (s * x + c * y) * per_pixel;
    return Hit::Surface;
  };
  SceneFrame f = sample_map(o, map, Texel{0, 0, 0, 255});
  f.default_texture = "testcard:512x512";
  return f;
}

// Fig. 7: an infinite textured floor seen from eye height 1, looking at the horizon. The camera
// moves forward 0.15 world units per frame (for the flicker measurement).
SceneFrame plane(const SceneOptions& o) {
  const int width = o.width, height = o.height;
  const double focal = 0.5 * width;  // 90-degree horizontal field of view
  const double horizon = 0.3 * height;
  const double tiles_per_unit = 0.25;  // texture repeats every 4 world units
  const double forward = 0.15 * o.frame;
  auto map = [=](double sx, double sy, double& u, double& v) {
    const double dy = sy - horizon;
    if (dy < 0.5) return Hit::None;  // sky, or too close to the horizon to hit the floor
    const double z = focal / dy;     // eye height 1
    const double x = (sx - 0.5 * width) * z / focal;
    u = x * tiles_per_unit + 0.5;
    v = (z + forward) * tiles_per_unit;
    return std::fabs(u) < 100 && std::fabs(v) < 100 ? Hit::Surface : Hit::None;
  };
  SceneFrame f = sample_map(o, map, Texel{140, 180, 230, 255});
  f.default_texture = "checker:256x256";
  return f;
}

// Fig. 8-11: a square panel (the texture twice across) turning about its vertical axis from
// face-on (frame 0) to 1 degree short of edge-on (last frame); a single frame shows 60 degrees.
SceneFrame panel(const SceneOptions& o) {
  const double angle = (o.frames > 1 ? 89.0 * frame_time(o) : 60.0) * M_PI / 180;
  const double focal = 1.2 * o.height, distance = 3.2, half = 1.0, repeats = 2.0;
  const double cx = 0.5 * o.width, cy = 0.5 * o.height;
  const double nx = std::sin(angle), nz = -std::cos(angle);  // panel normal (towards the camera)
  const double ex = std::cos(angle), ez = std::sin(angle);   // panel's u axis
  auto map = [=](double sx, double sy, double& u, double& v) {
    const double dx = (sx - cx) / focal, dy = (sy - cy) / focal;  // ray (dx, dy, 1)
    const double denom = dx * nx + nz;
    if (std::fabs(denom) < 1e-12) return Hit::None;
    const double t = distance * nz / denom;  // ray meets the plane through (0, 0, distance)
    if (t <= 0) return Hit::None;
    const double px = t * dx, py = t * dy, pz = t - distance;
    const double a = px * ex + pz * ez, b = py;
    u = (a / half * 0.5 + 0.5) * repeats;
    v = (b / half * 0.5 + 0.5) * repeats;
    return std::fabs(a) <= half && std::fabs(b) <= half ? Hit::Surface : Hit::Extended;
  };
  SceneFrame f = sample_map(o, map, Texel{30, 30, 40, 255});
  f.default_texture = "testcard:256x256";
  return f;
}

// Fig. 12, 17-19: rows of mirror spheres, each row 0.6 times the radius of the one above, down to
// about one pixel, under a reflectance map indexed by the surface normal's x and y. The spheres
// drift right by 0.23 pixel per frame.
SceneFrame reflect(const SceneOptions& o) {
  struct Row {
    double top, radius, spacing;
  };
  std::vector<Row> rows;
  double y = 0.02 * o.height;
  for (double r = 0.12 * o.height; r >= 0.8 && y + 2 * r <= o.height; r *= 0.6) {
    rows.push_back({y, r, 2.4 * r});
    y += 2.5 * r;
  }
  const double drift = 0.23 * o.frame;
  auto map = [=](double sx, double sy, double& u, double& v) {
    for (const Row& row : rows) {
      if (sy < row.top - 0.25 * row.radius || sy > row.top + 2.25 * row.radius) continue;
      const double cy = row.top + row.radius;
      const double k = std::floor((sx - drift) / row.spacing);
      const double cx = drift + (k + 0.5) * row.spacing;
      const double nx = (sx - cx) / row.radius, ny = (sy - cy) / row.radius;  // normal's x, y (y down)
      u = 0.5 + 0.5 * nx;
      v = 0.5 + 0.5 * ny;
      return nx * nx + ny * ny <= 1 ? Hit::Surface : Hit::Extended;
    }
    return Hit::None;
  };
  SceneFrame f = sample_map(o, map, Texel{25, 25, 35, 255});
  static const std::shared_ptr<const Image> map_image = std::make_shared<Image>(make_reflectance_map(256));
  f.own_texture = map_image;
  f.clamp_edges = true;
  return f;
}

// Fig. 20-23: the face height field stored as an X, Y, Z map, drawn as four faces whose sizes halve
// from left to right (shrinking by 1.5% per frame). Each face is a grid of q x q quads with q set by
// its projected size (a quad about 6 pixels across); every vertex samples the map with derivatives
// equal to the grid step, so lambda = log2(texels between neighbouring vertices).
SceneFrame mesh(const SceneOptions& o, int map_bits) {
  struct Face {
    double x0, y0, size;
    int quads;
  };
  std::vector<Face> faces;
  const double scale = std::pow(0.985, o.frame);
  double size = std::min(0.9 * o.height, 0.85 * o.width / 1.875) * scale, x = 0.02 * o.width;
  for (int k = 0; k < 4; ++k, size *= 0.5) {
    const int quads = std::max(1, int(std::lround(size / 6.0)));
    faces.push_back({x, 0.5 * o.height - 0.5 * size, size, quads});
    x += size + 0.03 * o.width;
  }
  SceneFrame f;
  f.width = o.width;
  f.height = o.height;
  f.background = Texel{40, 40, 48, 255};
  f.clamp_edges = true;
  f.own_texture = std::make_shared<Image>(make_face_xyz_map(256, map_bits));
  for (size_t k = 0; k < faces.size(); ++k) {
    const int q = faces[k].quads;
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= q; ++i) {
        Query query;
        // n = q + 1 vertices per side at the centres of n equal cells of the map: at lambda =
        // log2(W / n) they are the texel centres of that level, where the pyramid holds its
        // box-filtered samples (and an edge vertex is the edge texel's centre, not the map's edge).
        const int n = q + 1;
        query.u = (i + 0.5) / n;
        query.v = (j + 0.5) / n;
        query.explicit_lod = false;
        query.deriv = {1.0 / n, 0, 0, 1.0 / n};
        f.pixel.push_back(int(f.queries.size()));
        f.queries.push_back(query);
      }
  }
  const int width = o.width, height = o.height;
  const Texel bg = f.background;
  f.draw = [=](const std::vector<Rgba>& values) {
    RgbaImage img;
    img.width = width;
    img.height = height;
    img.pixels.assign(size_t(width) * height, Rgba{bg[0] / 255.0, bg[1] / 255.0, bg[2] / 255.0, 1});
    img.covered.assign(img.pixels.size(), true);
    std::vector<bool> wire(img.pixels.size(), false);
    size_t base = 0;
    const double lx = -0.35, ly = -0.5, lz = 0.79;  // light from the upper left, towards the viewer
    for (const Face& face : faces) {
      const int q = face.quads, n = q + 1;
      struct P {
        double x, y, z;
      };
      std::vector<P> p(size_t(n) * n);
      std::vector<bool> drawn(size_t(q) * q, false);
      const double flat_z = 0.5 / 255 * 0.9;  // half an 8-bit step of Z
      for (int i = 0; i < n * n; ++i) {
        const Rgba& val = values[base + i];
        p[i] = {face.x0 + val[0] * face.size, face.y0 + val[1] * face.size, val[2] * face.size * 0.9};
      }
      auto triangle = [&](const P& a, const P& b, const P& c) {
        // Normal with x right, y down, z towards the viewer; flat Lambert shading.
        const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
        double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
        const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
        if (len == 0) return;
        if (nz < 0) nx = -nx, ny = -ny, nz = -nz;
        const double shade = 0.15 + 0.85 * std::max(0.0, (nx * lx + ny * ly + nz * lz) / len);
        const Rgba colour{0.92 * shade, 0.78 * shade, 0.66 * shade, 1};
        const int xmin = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        const int xmax = std::min(width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
        const int ymin = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        const int ymax = std::min(height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
        const double area = ux * vy - uy * vx;
        if (area == 0) return;
        for (int py = ymin; py <= ymax; ++py)
          for (int px = xmin; px <= xmax; ++px) {
            const double sx = px + 0.5, sy = py + 0.5;
            const double w0 = ((b.x - sx) * (c.y - sy) - (b.y - sy) * (c.x - sx)) / area;
            const double w1 = ((c.x - sx) * (a.y - sy) - (c.y - sy) * (a.x - sx)) / area;
            const double w2 = 1 - w0 - w1;
            if (w0 >= 0 && w1 >= 0 && w2 >= 0) img.pixels[size_t(py) * width + px] = colour;
          }
      };
      auto line = [&](const P& a, const P& b) {
        const int steps = 1 + int(2 * std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y)));
        for (int s = 0; s <= steps; ++s) {
          const double t = double(s) / steps;
          const int px = int(std::floor(a.x + t * (b.x - a.x))), py = int(std::floor(a.y + t * (b.y - a.y)));
          if (px >= 0 && py >= 0 && px < width && py < height) wire[size_t(py) * width + px] = true;
        }
      };
      for (int j = 0; j < q; ++j)
        for (int i = 0; i < q; ++i) {
          const P &a = p[j * n + i], &b = p[j * n + i + 1], &c = p[(j + 1) * n + i + 1], &d = p[(j + 1) * n + i];
          // Only the face is drawn: a quad flat on the base (Z = 0 at all corners) is background.
          if (std::max({a.z, b.z, c.z, d.z}) < flat_z * face.size) continue;
          drawn[j * q + i] = true;
          triangle(a, b, c);
          triangle(a, c, d);
        }
      // Wireframe: the edges of the drawn quads.
      for (int j = 0; j < q; ++j)
        for (int i = 0; i < q; ++i)
          if (drawn[j * q + i]) {
            const P &a = p[j * n + i], &b = p[j * n + i + 1], &c = p[(j + 1) * n + i + 1], &d = p[(j + 1) * n + i];
            line(a, b), line(b, c), line(c, d), line(d, a);
          }
      base += size_t(n) * n;
    }
    for (size_t i = 0; i < wire.size(); ++i)
      if (wire[i])
        for (int c = 0; c < 3; ++c) img.pixels[i][c] *= 0.6;  // wireframe: shows the mesh resolution
    return img;
  };
  return f;
}

double smooth_bump(double x, double y, double cx, double cy, double sx, double sy) {
  const double dx = (x - cx) / sx, dy = (y - cy) / sy;
  return std::exp(-0.5 * (dx * dx + dy * dy));
}

}  // namespace

Image make_reflectance_map(int size) {
  // Nine light directions (x right, y down, z towards the viewer) of decreasing brightness and
  // slightly different tints. A texel is a normal (x, y) = 2 (u, v) - 1 of a mirror sphere seen
  // from +z; its value is the light reflected towards the viewer.
  struct Light {
    double x, y, z, r, g, b;
  };
  std::vector<Light> lights;
  const double pos[9][2] = {{-0.55, -0.6}, {0.05, -0.7},  {0.6, -0.5}, {-0.7, 0.0}, {0.0, -0.1},
                            {0.65, 0.1},   {-0.45, 0.6}, {0.1, 0.55}, {0.55, 0.7}};
  const double tint[3][3] = {{1.0, 0.95, 0.85}, {0.85, 0.92, 1.0}, {1.0, 1.0, 1.0}};
  for (int i = 0; i < 9; ++i) {
    const double x = pos[i][0], y = pos[i][1], z = std::sqrt(std::max(0.05, 1 - x * x - y * y));
    const double len = std::sqrt(x * x + y * y + z * z), brightness = 1.0 - 0.085 * i;
    lights.push_back({x / len, y / len, z / len, brightness * tint[i % 3][0], brightness * tint[i % 3][1],
                      brightness * tint[i % 3][2]});
  }
  Image img(size, size);
  for (int ty = 0; ty < size; ++ty)
    for (int tx = 0; tx < size; ++tx) {
      const double nx = 2 * (tx + 0.5) / size - 1, ny = 2 * (ty + 0.5) / size - 1, r2 = nx * nx + ny * ny;
      Texel& t = img.at(tx, ty);
      if (r2 > 1) {  // outside the sphere: unused
        t = {0, 0, 0, 255};
        continue;
      }
      const double nz = std::sqrt(1 - r2);
      const double rx = 2 * nz * nx, ry = 2 * nz * ny, rz = 2 * nz * nz - 1;  // reflected view ray
      double c[3] = {0.08 + 0.12 * nz, 0.08 + 0.12 * nz, 0.1 + 0.16 * nz};  // dim sky-like ambient
      for (const Light& l : lights) {
        const double s = std::pow(std::max(0.0, rx * l.x + ry * l.y + rz * l.z), 60.0);
        c[0] += s * l.r, c[1] += s * l.g, c[2] += s * l.b;
      }
      for (int k = 0; k < 3; ++k) t[k] = uint16_t(std::lround(255 * std::min(1.0, c[k])));
      t[3] = 255;
    }
  return img;
}

Image make_face_xyz_map(int size, int channel_bits) {
  if (channel_bits < 1 || channel_bits > kMaxChannelBits)
    throw Error("mesh map channel width " + std::to_string(channel_bits) + " is outside 1 to 16 bits");
  Image img(size, size, channel_bits);
  const double maxv = (1 << channel_bits) - 1;
  for (int ty = 0; ty < size; ++ty)
    for (int tx = 0; tx < size; ++tx) {
      // The vertex of texel (tx, ty) sits at its centre; the map holds X, Y, Z in [0, 1].
      const double x = (tx + 0.5) / size, y = (ty + 0.5) / size;
      const double ex = (x - 0.5) / 0.38, ey = (y - 0.52) / 0.46, e = 1 - ex * ex - ey * ey;
      double z = e > 0 ? 0.5 * std::sqrt(e) : 0;
      if (e > 0) {
        z += 0.16 * smooth_bump(x, y, 0.5, 0.56, 0.045, 0.1);                                         // nose
        z -= 0.07 * (smooth_bump(x, y, 0.36, 0.43, 0.06, 0.04) + smooth_bump(x, y, 0.64, 0.43, 0.06, 0.04));  // eyes
        z += 0.04 * (smooth_bump(x, y, 0.36, 0.43, 0.025, 0.02) + smooth_bump(x, y, 0.64, 0.43, 0.025, 0.02));
        z += 0.05 * smooth_bump(x, y, 0.5, 0.35, 0.2, 0.025);                                         // brow
        z += 0.05 * (smooth_bump(x, y, 0.5, 0.73, 0.09, 0.018) + smooth_bump(x, y, 0.5, 0.775, 0.08, 0.018));  // lips
        z -= 0.03 * smooth_bump(x, y, 0.5, 0.753, 0.1, 0.006);
        if (y < 0.3) z += 0.03 * std::min(1.0, e * 4) * (0.5 + 0.5 * std::sin(2 * M_PI * 40 * x));  // fine hair ridges
      }
      Texel& t = img.at(tx, ty);
      t = {uint16_t(std::lround(x * maxv)), uint16_t(std::lround(y * maxv)),
           uint16_t(std::lround(std::clamp(z, 0.0, 1.0) * maxv)), uint16_t(maxv)};
    }
  return img;
}

SceneFrame make_scene(const std::string& name, const SceneOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 8192 || o.height > 8192)
    throw Error("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                " is outside 1x1 to 8192x8192");
  if (o.frames < 1 || o.frames > 100000 || o.frame < 0 || o.frame >= o.frames)
    throw Error("frame " + std::to_string(o.frame) + " of " + std::to_string(o.frames) +
                " is not within 0 to frames-1 (frames from 1 to 100000)");
  if (o.order == PixelOrder::Tiled && (o.tile < 2 || o.tile > 256 || (o.tile & (o.tile - 1)) != 0))
    throw Error("tile size " + std::to_string(o.tile) + " is not a power of two from 2 to 256");
  if (o.order == PixelOrder::Tiled && scene_samples_vertices(name))
    throw Error("scene " + name + " samples per vertex, in vertex order: --order tiled does not apply");
  if (name == "magnify") return magnify(o);
  if (name == "minify") return minify(o);
  if (name == "plane") return plane(o);
  if (name == "panel") return panel(o);
  if (name == "reflect") return reflect(o);
  if (name == "mesh") return mesh(o, 8);
  if (name == "mesh16") return mesh(o, 16);  // 16-bit X, Y, Z: the model only (the RTL is built for 8)
  std::string list;
  for (const auto& n : scene_names()) list += n + ", ";
  throw Error("unknown scene '" + name + "' (known: " + list + "mesh16)");
}

SceneFrame make_scene(const std::string& name, int width, int height) {
  SceneOptions o;
  o.width = width;
  o.height = height;
  return make_scene(name, o);
}

Image scene_texture(const SceneFrame& frame, const std::string& user_spec, bool resize) {
  if (frame.own_texture) {
    if (!user_spec.empty())
      throw Error("this scene samples its own map; --texture '" + user_spec + "' does not apply");
    return *frame.own_texture;
  }
  return load_texture(user_spec.empty() ? frame.default_texture : user_spec, resize);
}

Pyramid scene_pyramid(const SceneFrame& frame, const std::string& user_spec, const TextureOptions& options) {
  if (frame.own_texture || user_spec.empty()) return make_pyramid(scene_texture(frame, user_spec, options.resize), options);
  return load_pyramid(user_spec, options);
}

std::vector<Rgba> texels_to_values(const std::vector<Texel>& texels, int channel_bits) {
  const double maxv = (1 << channel_bits) - 1;
  std::vector<Rgba> out(texels.size());
  for (size_t i = 0; i < texels.size(); ++i)
    for (int c = 0; c < 4; ++c) out[i][c] = texels[i][c] / maxv;
  return out;
}

RgbaImage render_values(const SceneFrame& frame, const std::vector<Rgba>& values) {
  if (frame.is_mesh()) return frame.draw(values);
  RgbaImage img;
  img.width = frame.width;
  img.height = frame.height;
  const Texel& bg = frame.background;
  img.pixels.assign(size_t(frame.width) * frame.height, Rgba{bg[0] / 255.0, bg[1] / 255.0, bg[2] / 255.0, bg[3] / 255.0});
  img.covered.assign(img.pixels.size(), false);
  for (size_t i = 0; i < frame.pixel.size(); ++i) {
    img.pixels[frame.pixel[i]] = values[i];
    img.covered[frame.pixel[i]] = true;
  }
  return img;
}

Image to_image8(const RgbaImage& img) {
  Image out(img.width, img.height, 8);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) out.texels[i][c] = uint16_t(std::lround(255 * std::clamp(img.pixels[i][c], 0.0, 1.0)));
  return out;
}

Image compose(const SceneFrame& frame, const std::vector<Texel>& texels, int channel_bits) {
  if (frame.is_mesh()) return to_image8(frame.draw(texels_to_values(texels, channel_bits)));
  Image img(frame.width, frame.height, channel_bits);
  for (auto& t : img.texels) t = frame.background;
  for (size_t i = 0; i < frame.pixel.size(); ++i) img.texels[frame.pixel[i]] = texels[i];
  return img;
}

}  // namespace tex

#include "workloads/rasterizer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "model/error.h"

namespace tex {

namespace {

constexpr int kSubBits = 8;  // sub-pixel precision of vertex positions, as GPUs snap them
constexpr double kSub = 1 << kSubBits;
// Guard band: primitives are clipped to |x|, |y| <= kGuard * w in clip space (a few thousand
// screens), so snapped coordinates stay far inside int64 edge arithmetic.
constexpr double kGuard = 4096.0;

struct ClipVertex {
  glm::dvec4 clip;
  glm::dvec2 uv;
  glm::dvec3 pos{0.0}, normal{0.0};  // world space (a mirror's)
};

// One plane a * sx + b * sy + c over screen positions, sx, sy in pixels.
struct Plane {
  double a = 0, b = 0, c = 0;
  double at(double sx, double sy) const { return a * sx + b * sy + c; }
};

// A clipped primitive on screen: a convex polygon with snapped vertices, and its attribute planes
// (u/w, v/w, 1/w and depth z/w are affine over the screen, so any three vertices define them).
struct Primitive {
  std::vector<std::array<int64_t, 2>> v;  // snapped positions, kSubBits fraction bits, clockwise on screen
  std::vector<int64_t> bias;              // per edge: 0 for top and left edges, 1 otherwise (fill rule)
  Plane u_w, v_w, q, z;                   // q = 1/w
  std::array<Plane, 6> pn_w;              // a mirror's world position and normal over w
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;     // pixel bounding box, inclusive, inside the screen
};

// Sutherland-Hodgman against the plane dot(k, clip) >= 0 (interpolating clip position and uv).
std::vector<ClipVertex> clip_against(const std::vector<ClipVertex>& in, const glm::dvec4& k) {
  std::vector<ClipVertex> out;
  for (size_t i = 0; i < in.size(); ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % in.size()];
    const double da = glm::dot(k, a.clip), db = glm::dot(k, b.clip);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      const double t = da / (da - db);
      out.push_back({a.clip + (b.clip - a.clip) * t, a.uv + (b.uv - a.uv) * t, a.pos + (b.pos - a.pos) * t,
                     a.normal + (b.normal - a.normal) * t});
    }
  }
  return out;
}

// Edge function of edge a -> b at p (all snapped): > 0 inside a primitive with positive area.
int64_t edge(const std::array<int64_t, 2>& a, const std::array<int64_t, 2>& b, int64_t px, int64_t py) {
  return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
}

// Sets up a clipped polygon; false if it is degenerate or (unless double-sided) a back face.
bool setup(const std::vector<ClipVertex>& poly, int width, int height, bool double_sided, bool& culled,
           Primitive& p) {
  culled = false;
  std::vector<glm::dvec2> screen;  // in pixels
  p.v.clear();
  for (const ClipVertex& c : poly) {
    // NDC (y up) to pixels (y down, row 0 at the top), then snapped.
    const double sx = (c.clip.x / c.clip.w + 1) * 0.5 * width, sy = (1 - c.clip.y / c.clip.w) * 0.5 * height;
    p.v.push_back({std::llround(sx * kSub), std::llround(sy * kSub)});
    screen.emplace_back(sx, sy);  // attributes from the exact positions: only coverage is snapped
  }
  // Twice the signed area on screen; counter-clockwise in NDC (GL's front face) is negative here.
  int64_t area = 0;
  for (size_t i = 0; i < p.v.size(); ++i) {
    const auto& a = p.v[i];
    const auto& b = p.v[(i + 1) % p.v.size()];
    area += a[0] * b[1] - b[0] * a[1];
  }
  if (area == 0) return false;
  if (area > 0) {  // clockwise in NDC: a back face
    if (!double_sided) {
      culled = true;
      return false;
    }
  } else {
    std::reverse(p.v.begin(), p.v.end());
    std::reverse(screen.begin(), screen.end());
  }
  // Now clockwise on screen (y down): edge functions are positive inside. Top edge: horizontal with
  // the inside below (dy == 0, dx > 0); left edge: going up (dy < 0).
  p.bias.clear();
  for (size_t i = 0; i < p.v.size(); ++i) {
    const auto& a = p.v[i];
    const auto& b = p.v[(i + 1) % p.v.size()];
    const int64_t dx = b[0] - a[0], dy = b[1] - a[1];
    p.bias.push_back((dy == 0 && dx > 0) || dy < 0 ? 0 : 1);
  }
  // Attribute planes from the three vertices spanning the largest area (the best conditioned).
  std::vector<std::array<double, 10>> attr;  // u/w, v/w, 1/w, z/w, position/w, normal/w per vertex
  for (const ClipVertex& c : poly)
    attr.push_back({c.uv.x / c.clip.w, c.uv.y / c.clip.w, 1 / c.clip.w, c.clip.z / c.clip.w, c.pos.x / c.clip.w,
                    c.pos.y / c.clip.w, c.pos.z / c.clip.w, c.normal.x / c.clip.w, c.normal.y / c.clip.w,
                    c.normal.z / c.clip.w});
  if (area < 0) std::reverse(attr.begin(), attr.end());
  size_t bi = 1, bj = 2;
  double best = 0;
  for (size_t i = 1; i + 1 < screen.size(); ++i)
    for (size_t j = i + 1; j < screen.size(); ++j) {
      const glm::dvec2 e1 = screen[i] - screen[0], e2 = screen[j] - screen[0];
      const double a2 = std::fabs(e1.x * e2.y - e1.y * e2.x);
      if (a2 > best) best = a2, bi = i, bj = j;
    }
  const glm::dvec2 e1 = screen[bi] - screen[0], e2 = screen[bj] - screen[0];
  const double det = e1.x * e2.y - e1.y * e2.x;
  auto plane = [&](int k) {
    const double d1 = attr[bi][k] - attr[0][k], d2 = attr[bj][k] - attr[0][k];
    Plane pl;
    pl.a = (d1 * e2.y - d2 * e1.y) / det;
    pl.b = (d2 * e1.x - d1 * e2.x) / det;
    pl.c = attr[0][k] - pl.a * screen[0].x - pl.b * screen[0].y;
    return pl;
  };
  p.u_w = plane(0);
  p.v_w = plane(1);
  p.q = plane(2);
  p.z = plane(3);
  for (int k = 0; k < 6; ++k) p.pn_w[size_t(k)] = plane(4 + k);
  // Bounding box of the pixel centres that can be inside.
  int64_t lo_x = INT64_MAX, lo_y = INT64_MAX, hi_x = INT64_MIN, hi_y = INT64_MIN;
  for (const auto& v : p.v) {
    lo_x = std::min(lo_x, v[0]), hi_x = std::max(hi_x, v[0]);
    lo_y = std::min(lo_y, v[1]), hi_y = std::max(hi_y, v[1]);
  }
  auto pixel = [](int64_t s) { return int64_t(std::floor(double(s) / kSub - 0.5)); };
  p.x0 = int(std::clamp<int64_t>(pixel(lo_x), 0, width - 1));
  p.x1 = int(std::clamp<int64_t>(pixel(hi_x) + 1, 0, width - 1));
  p.y0 = int(std::clamp<int64_t>(pixel(lo_y), 0, height - 1));
  p.y1 = int(std::clamp<int64_t>(pixel(hi_y) + 1, 0, height - 1));
  return true;
}

// The top-left rule: a pixel centre on an edge belongs to the primitive only for top and left edges.
bool covers(const Primitive& p, int x, int y) {
  const int64_t px = int64_t(x) * int64_t(kSub) + int64_t(kSub) / 2, py = int64_t(y) * int64_t(kSub) + int64_t(kSub) / 2;
  for (size_t i = 0; i < p.v.size(); ++i)
    if (edge(p.v[i], p.v[(i + 1) % p.v.size()], px, py) - p.bias[i] < 0) return false;
  return true;
}

// The primitives of the scene after transform, clipping and culling, in draw order.
struct ScenePrimitive {
  Primitive prim;
  int texture = 0;
};

std::vector<ScenePrimitive> setup_scene(const MeshScene& scene, const glm::dmat4& vp, int width, int height,
                                        RasterFrame& frame) {
  static const glm::dvec4 planes[] = {{0, 0, 1, 1},  {0, 0, -1, 1},     {1, 0, 0, kGuard},
                                      {-1, 0, 0, kGuard}, {0, 1, 0, kGuard}, {0, -1, 0, kGuard}};
  std::vector<ScenePrimitive> out;
  for (const DrawMesh& m : scene.meshes) {
    std::vector<glm::dvec4> clip(m.positions.size());
    for (size_t i = 0; i < clip.size(); ++i) clip[i] = vp * glm::dvec4(m.positions[i], 1.0);
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      std::vector<ClipVertex> poly;
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = m.indices[t + k];
        poly.push_back({clip[i], m.uvs[i], m.positions[i], m.normals.empty() ? glm::dvec3(0.0) : m.normals[i]});
      }
      for (const glm::dvec4& k : planes) {
        poly = clip_against(poly, k);
        if (poly.size() < 3) break;
      }
      if (poly.size() < 3) continue;
      ScenePrimitive sp;
      sp.texture = m.texture;
      bool culled;
      if (setup(poly, width, height, m.double_sided, culled, sp.prim)) out.push_back(std::move(sp));
      frame.culled += culled;
    }
  }
  frame.primitives = out.size();
  return out;
}

// Moves each lane's coordinate by whole periods of the wrap mode, after the quad's derivatives are
// taken (the sampled texels do not change: repeat by any integer, mirror by an even one), so that
// the hardware's Q8.24 range holds it; a clamped axis is limited to [-64, 64] (every tap is the
// edge texel far before that). Helper lanes near a primitive's horizon reach hundreds of periods.
void reduce(std::array<double, 4>& c, Wrap w) {
  const double period = w == Wrap::Mirror ? 2.0 : 1.0;
  for (double& x : c) x = w == Wrap::Clamp ? std::clamp(x, -64.0, 64.0) : x - std::floor(x / period) * period;
}

}  // namespace

RasterFrame rasterize(const MeshScene& scene, const Camera& camera, const RasterOptions& o) {
  if (o.width < 2 || o.height < 2 || o.width > 16384 || o.height > 16384)
    throw Error("frame size " + std::to_string(o.width) + "x" + std::to_string(o.height) + " is outside 2..16384");
  if (o.order == PixelOrder::Tiled && (o.tile < 2 || o.tile > 256 || (o.tile & (o.tile - 1))))
    throw Error("--tile " + std::to_string(o.tile) + " is not a power of two from 2 to 256");
  RasterFrame frame;
  frame.width = o.width;
  frame.height = o.height;
  const glm::dmat4 vp = view_projection(camera, double(o.width) / o.height, scene.bounds_min, scene.bounds_max);
  const std::vector<ScenePrimitive> prims = setup_scene(scene, vp, o.width, o.height, frame);

  // Depth pass: the nearest primitive of every pixel (GL_LESS; the first drawn wins a tie).
  const size_t pixels = size_t(o.width) * o.height;
  std::vector<double> depth(pixels, std::numeric_limits<double>::infinity());
  std::vector<int32_t> owner(pixels, -1);
  for (size_t i = 0; i < prims.size(); ++i) {
    const Primitive& p = prims[i].prim;
    for (int y = p.y0; y <= p.y1; ++y)
      for (int x = p.x0; x <= p.x1; ++x) {
        if (!covers(p, x, y)) continue;
        const double z = p.z.at(x + 0.5, y + 0.5);
        const size_t at = size_t(y) * o.width + x;
        if (z < depth[at]) depth[at] = z, owner[at] = int32_t(i);
      }
  }

  // A quad of cube-map queries: each lane's direction (a helper lane beyond the primitive's horizon
  // takes the first live lane's), the quad's differences its derivatives.
  auto cube_quad = [&](int qx, int qy, const std::array<bool, 4>& live, std::array<glm::dvec3, 4> r,
                       const std::array<bool, 4>& valid) {
    int first = 0;
    while (!live[size_t(first)]) ++first;
    for (int l = 0; l < 4; ++l)
      if (!valid[size_t(l)]) r[size_t(l)] = r[size_t(first)];
    const glm::dvec3 dx = r[1] - r[0], dy = r[2] - r[0];
    for (int l = 0; l < 4; ++l) {
      Query qr;
      qr.cube = true;
      qr.u = r[size_t(l)].x;
      qr.v = r[size_t(l)].y;
      qr.w = r[size_t(l)].z;
      qr.explicit_lod = false;
      qr.deriv = {dx.x, dx.y, dy.x, dy.y};
      qr.dwdx = dx.z;
      qr.dwdy = dy.z;
      qr.texture = 0;
      qr.quad = uint32_t(frame.quads);
      qr.x = qx + (l & 1);
      qr.y = qy + (l >> 1);
      qr.helper = !live[size_t(l)];
      qr.line = int(frame.queries.size() + 1);
      frame.queries.push_back(qr);
      frame.helper_samples += qr.helper;
    }
    ++frame.quads;
  };
  // A mirror's quad: the view ray reflected by the normal, R = I - 2 (N.I) N (unit vectors).
  auto mirror_quad = [&](const Primitive& p, int qx, int qy, const std::array<bool, 4>& live) {
    std::array<glm::dvec3, 4> r;
    std::array<bool, 4> valid{};
    for (int l = 0; l < 4; ++l) {
      const double sx = qx + (l & 1) + 0.5, sy = qy + (l >> 1) + 0.5, q = p.q.at(sx, sy);
      const glm::dvec3 pos(p.pn_w[0].at(sx, sy) / q, p.pn_w[1].at(sx, sy) / q, p.pn_w[2].at(sx, sy) / q);
      const glm::dvec3 n(p.pn_w[3].at(sx, sy) / q, p.pn_w[4].at(sx, sy) / q, p.pn_w[5].at(sx, sy) / q);
      const glm::dvec3 view = pos - camera.eye;
      const double ln = glm::length(n), lv = glm::length(view);
      valid[size_t(l)] = q > 0 && std::isfinite(ln) && ln > 0 && std::isfinite(lv) && lv > 0;
      if (!valid[size_t(l)]) continue;
      const glm::dvec3 in = view / lv, nn = n / ln;
      r[size_t(l)] = in - 2 * glm::dot(nn, in) * nn;
    }
    cube_quad(qx, qy, live, r, valid);
  };

  // Shading pass: every quad with a visible lane of the primitive, in the walk order.
  const int tile = o.order == PixelOrder::Tiled ? o.tile : 0;
  for (size_t i = 0; i < prims.size(); ++i) {
    const Primitive& p = prims[i].prim;
    const SceneTexture* tex = o.reflect ? nullptr : &scene.textures[size_t(prims[i].texture)];  // (a mirror has none)
    auto shade_quad = [&](int qx, int qy) {
      std::array<bool, 4> live{};
      bool any = false;
      for (int l = 0; l < 4; ++l) {
        const int x = qx + (l & 1), y = qy + (l >> 1);
        live[l] = x < o.width && y < o.height && owner[size_t(y) * o.width + x] == int32_t(i);
        any |= live[l];
      }
      if (!any) return;
      if (o.reflect) return mirror_quad(p, qx, qy, live);
      std::array<double, 4> u, v;
      for (int l = 0; l < 4; ++l) {
        const double sx = qx + (l & 1) + 0.5, sy = qy + (l >> 1) + 0.5;
        const double q = p.q.at(sx, sy);
        u[l] = p.u_w.at(sx, sy) / q;
        v[l] = p.v_w.at(sx, sy) / q;
      }
      // A helper lane beyond the primitive's horizon (1/w <= 0 there) has no (u, v): it takes
      // the quad's first live lane's, so that its differences are 0 rather than undefined.
      int first_live = 0;
      while (!live[size_t(first_live)]) ++first_live;
      for (int l = 0; l < 4; ++l)
        if (!(p.q.at(qx + (l & 1) + 0.5, qy + (l >> 1) + 0.5) > 0) || !std::isfinite(u[l]) || !std::isfinite(v[l]))
          u[l] = u[size_t(first_live)], v[l] = v[size_t(first_live)];
      // Coarse derivatives: one per quad, from its top row and left column.
      Derivatives d{u[1] - u[0], v[1] - v[0], u[2] - u[0], v[2] - v[0]};
      reduce(u, tex->wrap_u);
      reduce(v, tex->wrap_v);
      for (int l = 0; l < 4; ++l) {
        Query qr;
        qr.u = u[l];
        qr.v = v[l];
        qr.explicit_lod = false;
        qr.deriv = d;
        qr.texture = prims[i].texture;
        qr.quad = uint32_t(frame.quads);
        qr.x = qx + (l & 1);
        qr.y = qy + (l >> 1);
        qr.helper = !live[l];
        qr.line = int(frame.queries.size() + 1);
        frame.queries.push_back(qr);
        frame.helper_samples += qr.helper;
      }
      ++frame.quads;
    };
    const int qx0 = p.x0 & ~1, qy0 = p.y0 & ~1;
    if (tile == 0) {
      for (int qy = qy0; qy <= p.y1; qy += 2)
        for (int qx = qx0; qx <= p.x1; qx += 2) shade_quad(qx, qy);
    } else {
      for (int ty = p.y0 / tile * tile; ty <= p.y1; ty += tile)
        for (int tx = p.x0 / tile * tile; tx <= p.x1; tx += tile)
          for (int qy = std::max(ty, qy0); qy < std::min(ty + tile, p.y1 + 1); qy += 2)
            for (int qx = std::max(tx, qx0); qx < std::min(tx + tile, p.x1 + 1); qx += 2) shade_quad(qx, qy);
    }
  }
  if (o.reflect) {  // the environment behind: the view ray of every pixel no mesh covers
    const glm::dmat4 inv = glm::inverse(vp);
    auto ray = [&](int x, int y) {
      const double nx = 2.0 * (x + 0.5) / o.width - 1, ny = 1 - 2.0 * (y + 0.5) / o.height;
      const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
      return glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
    };
    for (int qy = 0; qy < o.height; qy += 2)
      for (int qx = 0; qx < o.width; qx += 2) {
        std::array<bool, 4> live{};
        bool any = false;
        std::array<glm::dvec3, 4> r;
        for (int l = 0; l < 4; ++l) {
          const int x = qx + (l & 1), y = qy + (l >> 1);
          live[size_t(l)] = x < o.width && y < o.height && owner[size_t(y) * o.width + x] < 0;
          any = any || live[size_t(l)];
          r[size_t(l)] = ray(x, y);
        }
        if (any) cube_quad(qx, qy, live, r, {true, true, true, true});
      }
  }
  return frame;
}

Image compose_frame(const RasterFrame& frame, const std::vector<Texel>& texels, int channel_bits,
                    const Texel& background) {
  Image img(frame.width, frame.height, channel_bits);
  std::fill(img.texels.begin(), img.texels.end(), background);
  const uint16_t opaque = uint16_t((1u << channel_bits) - 1);
  for (size_t i = 0; i < frame.queries.size() && i < texels.size(); ++i) {
    const Query& q = frame.queries[i];
    if (q.helper) continue;
    Texel t = texels[i];
    t[3] = opaque;
    img.at(q.x, q.y) = t;
  }
  return img;
}

}  // namespace tex

// The rasterizer of real frames (sim/workloads/rasterizer.cpp) against an independent analytic
// camera: a ray per pixel centre built from gluPerspective's definition, intersected with planes.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <map>
#include <set>

#include "model/error.h"
#include "workloads/rasterizer.h"

using namespace tex;

namespace {

// A square in the plane through `origin` spanned by `du`, `dv` (world units per unit of u, v), with
// texture coordinates uv0 + (s, t) * uv_span over s, t in [0, 1]: two triangles, counter-clockwise
// seen from the side the normal du x dv points to.
DrawMesh square(glm::dvec3 origin, glm::dvec3 du, glm::dvec3 dv, glm::dvec2 uv0, double uv_span, int texture = 0) {
  DrawMesh m;
  m.name = "square";
  for (int k = 0; k < 4; ++k) {
    const double s = k & 1, t = k >> 1;
    m.positions.push_back(origin + du * s + dv * t);
    m.uvs.push_back(uv0 + glm::dvec2(s, t) * uv_span);
  }
  m.indices = {0, 1, 3, 0, 3, 2};
  m.texture = texture;
  return m;
}

MeshScene scene_of(std::vector<DrawMesh> meshes, int textures = 1) {
  MeshScene s;
  s.meshes = std::move(meshes);
  s.textures.resize(size_t(textures));
  s.bounds_min = glm::dvec3(1e300);
  s.bounds_max = glm::dvec3(-1e300);
  for (const DrawMesh& m : s.meshes)
    for (const glm::dvec3& p : m.positions) s.bounds_min = glm::min(s.bounds_min, p), s.bounds_max = glm::max(s.bounds_max, p);
  return s;
}

// The ray through pixel centre (sx, sy) per gluLookAt + gluPerspective, intersected with the
// plane y = 0 of the floor below: uv = (x, z) / 4 (the floor's mapping in the tests).
struct AnalyticCamera {
  Camera cam;
  int w, h;
  glm::dvec3 ray(double sx, double sy) const {
    const glm::dvec3 f = glm::normalize(cam.target - cam.eye);
    const glm::dvec3 s = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
    const glm::dvec3 up = glm::cross(s, f);
    const double t = std::tan(cam.fovy_deg * M_PI / 360.0), aspect = double(w) / h;
    const double nx = 2 * sx / w - 1, ny = 1 - 2 * sy / h;
    return f + s * (nx * t * aspect) + up * (ny * t);
  }
  glm::dvec2 floor_uv(double sx, double sy) const {
    const glm::dvec3 d = ray(sx, sy);
    const glm::dvec3 p = cam.eye + d * (-cam.eye.y / d.y);
    return glm::dvec2(p.x, p.z) / 4.0;
  }
};

// The floor: y = 0, x and z in [-40, 40], uv = (x, z) / 4, facing up (+y).
DrawMesh floor_mesh() {
  DrawMesh m = square({-40, 0, -40}, {0, 0, 80}, {80, 0, 0}, {-10, -10}, 20);  // normal (0,0,1)x(1,0,0) = +y
  for (glm::dvec2& uv : m.uvs) uv = glm::dvec2(uv.y, uv.x);  // u follows x, v follows z
  return m;
}

}  // namespace

// Every lane on the floor (helpers too: the plane extended) has the analytic (u, v) of its pixel
// centre, and the quad's derivatives are the analytic differences across the quad; in the
// hardware's Q8.24 they are within one rounding of the analytic values.
TEST(Rasterizer, PerspectiveCorrectUvAndQuadDerivativesOnAPlane) {
  const MeshScene scene = scene_of({floor_mesh()});
  const Camera cam{{0.3, 1.5, 6.0}, {0.1, 0.0, -4.0}, 50.0};
  RasterOptions o;
  o.width = 96;
  o.height = 64;
  const RasterFrame f = rasterize(scene, cam, o);
  const AnalyticCamera a{cam, o.width, o.height};
  ASSERT_GT(f.quads, 500u);
  ASSERT_EQ(f.queries.size(), 4 * f.quads);
  double worst_uv = 0, worst_d = 0;
  for (size_t i = 0; i < f.queries.size(); i += 4) {
    const Query& q0 = f.queries[i];
    const glm::dvec2 p00 = a.floor_uv(q0.x + 0.5, q0.y + 0.5);
    const glm::dvec2 p10 = a.floor_uv(q0.x + 1.5, q0.y + 0.5);
    const glm::dvec2 p01 = a.floor_uv(q0.x + 0.5, q0.y + 1.5);
    const double d[4] = {p10.x - p00.x, p10.y - p00.y, p01.x - p00.x, p01.y - p00.y};
    for (int l = 0; l < 4; ++l) {
      const Query& q = f.queries[i + size_t(l)];
      ASSERT_EQ(q.quad, q0.quad);
      ASSERT_EQ(q.x, q0.x + (l & 1));
      ASSERT_EQ(q.y, q0.y + (l >> 1));
      const glm::dvec2 e = a.floor_uv(q.x + 0.5, q.y + 0.5);
      // repeat wrap: the rasterizer may move a quad by whole texture periods
      const double du = q.u - e.x, dv = q.v - e.y;
      worst_uv = std::max({worst_uv, std::fabs(du - std::round(du)), std::fabs(dv - std::round(dv))});
      const double got[4] = {q.deriv.dudx, q.deriv.dvdx, q.deriv.dudy, q.deriv.dvdy};
      Request r = to_request(q, "test", 0);
      const int32_t fixed[4] = {r.deriv.dudx, r.deriv.dvdx, r.deriv.dudy, r.deriv.dvdy};
      for (int k = 0; k < 4; ++k) {
        worst_d = std::max(worst_d, std::fabs(got[k] - d[k]));
        EXPECT_LE(std::fabs(fixed[k] - d[k] * 16777216.0), 0.5 + 1e-3) << "quad " << q.quad << " derivative " << k;
      }
    }
  }
  EXPECT_LT(worst_uv, 1e-9);
  EXPECT_LT(worst_d, 1e-9);
}

// The top-left rule on a square whose edges pass exactly through pixel centres (fovy 90 at
// distance 1: one pixel is 2/64 world units): columns and rows 10..19 are inside, 20 is not.
TEST(Rasterizer, TopLeftFillRuleAndBackFaces) {
  auto at = [](double px) { return (px) / 32.0 - 1.0; };  // world x of screen x px (64-pixel frame)
  const double x0 = at(10.5), x1 = at(20.5), y0 = -at(10.5), y1 = -at(20.5);
  // du = +x, dv = +y: the normal +z faces the camera (counter-clockwise as the camera sees it).
  const DrawMesh front = square({x0, y1, -1}, {x1 - x0, 0, 0}, {0, y0 - y1, 0}, {0, 0}, 1);
  const Camera cam{{0, 0, 0}, {0, 0, -1}, 90.0};
  RasterOptions o;
  o.width = o.height = 64;
  MeshScene scene = scene_of({front});
  scene.bounds_min.z = -2;  // the box in front of the eye
  scene.bounds_max.z = -0.5;
  const RasterFrame f = rasterize(scene, cam, o);
  std::set<std::pair<int, int>> covered;
  for (const Query& q : f.queries)
    if (!q.helper) covered.insert({q.x, q.y});
  EXPECT_EQ(covered.size(), 100u);
  EXPECT_TRUE(covered.count({10, 10}));
  EXPECT_TRUE(covered.count({19, 19}));
  EXPECT_FALSE(covered.count({20, 15}));
  EXPECT_FALSE(covered.count({15, 20}));
  EXPECT_EQ(f.culled, 0u);
  // Quads 2x2 aligned: columns 10..19 = 5 quads, rows 10..19 = 5 quads; the five quads on the
  // diagonal between the two triangles (pixel (11, 19) on it, x + y = 30) are shaded once per
  // triangle, with 1 + 3 helper lanes in all: 30 quads, 20 helpers.
  EXPECT_EQ(f.quads, 30u);
  EXPECT_EQ(f.helper_samples, 20u);

  // Wound the other way it is a back face: culled, unless the material is double-sided.
  MeshScene back = scene;
  for (size_t t = 0; t < back.meshes[0].indices.size(); t += 3) std::swap(back.meshes[0].indices[t + 1], back.meshes[0].indices[t + 2]);
  const RasterFrame fb = rasterize(back, cam, o);
  EXPECT_EQ(fb.queries.size(), 0u);
  EXPECT_EQ(fb.culled, 2u);
  back.meshes[0].double_sided = true;
  EXPECT_EQ(rasterize(back, cam, o).queries.size(), f.queries.size());
}

// A grid of triangles filling the screen: every pixel is covered by exactly one visible lane (no
// gaps, no double coverage on shared edges), so there are no helpers either.
TEST(Rasterizer, SharedEdgesCoverEveryPixelOnce) {
  std::vector<DrawMesh> meshes;
  DrawMesh grid;
  grid.name = "grid";
  const int n = 7;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      // irregular spacing so that edges cross pixels at odd places
      const double x = -1.6 + 3.2 * (i + 0.37 * std::sin(i * 1.7 + j) * (i > 0 && i < n)) / n;
      const double y = -1.3 + 2.6 * (j + 0.29 * std::cos(j * 2.3 + i) * (j > 0 && j < n)) / n;
      grid.positions.push_back({x, y, -1.0});
      grid.uvs.push_back({x, y});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      grid.indices.insert(grid.indices.end(), {a, b, d, a, d, c});
    }
  MeshScene scene = scene_of({grid});
  const Camera cam{{0, 0, 0.2}, {0, 0, -1}, 80.0};
  RasterOptions o;
  o.width = 50;
  o.height = 38;
  const RasterFrame f = rasterize(scene, cam, o);
  std::map<std::pair<int, int>, int> count;
  for (const Query& q : f.queries)
    if (!q.helper) ++count[{q.x, q.y}];
  EXPECT_EQ(count.size(), size_t(o.width * o.height));
  for (const auto& [p, c] : count) ASSERT_EQ(c, 1) << "pixel " << p.first << "," << p.second;
  EXPECT_GT(f.helper_samples, 0u);  // quads on the triangles' edges
  EXPECT_EQ(f.primitives, size_t(2 * n * n));
}

// Depth: a near square drawn after a far one hides it; only the visible surface samples, and a
// quad on the border of the two has helper lanes.
TEST(Rasterizer, OnlyTheVisibleSurfaceSamples) {
  const DrawMesh far = square({-3, -3, -3}, {6, 0, 0}, {0, 6, 0}, {0, 0}, 1, 0);
  const DrawMesh near = square({-0.2, -0.2, -2}, {0.4, 0, 0}, {0, 0.4, 0}, {0, 0}, 1, 1);
  MeshScene scene = scene_of({far, near}, 2);
  const Camera cam{{0, 0, 0}, {0, 0, -1}, 60.0};
  RasterOptions o;
  o.width = o.height = 64;
  const RasterFrame f = rasterize(scene, cam, o);
  std::map<std::pair<int, int>, int> visible;  // pixel -> texture
  for (const Query& q : f.queries) {
    if (!q.helper) {
      ASSERT_TRUE(visible.emplace(std::make_pair(q.x, q.y), q.texture).second);
    }
  }
  // The centre pixels see the near square, the corners the far one.
  EXPECT_EQ(visible.at({32, 32}), 1);
  EXPECT_EQ(visible.at({2, 2}), 0);
  // The far square's quads skip the hidden centre entirely.
  for (const Query& q : f.queries) {
    if (q.texture == 0) {
      EXPECT_FALSE(q.x >= 30 && q.x <= 33 && q.y >= 30 && q.y <= 33);
    }
  }
  EXPECT_GT(f.helper_samples, 0u);
}

// Tiled order: a screen-filling primitive's first 16 quads are the first 8x8 tile; scanline order
// walks quad rows.
TEST(Rasterizer, QuadsWalkTilesOrRows) {
  DrawMesh wall;  // one triangle over the whole frame
  wall.positions = {{-10, -10, -1}, {30, -10, -1}, {-10, 30, -1}};
  wall.uvs = {{0, 0}, {1, 0}, {0, 1}};
  wall.indices = {0, 1, 2};
  MeshScene scene = scene_of({wall});
  const Camera cam{{0, 0, 0}, {0, 0, -1}, 60.0};
  RasterOptions o;
  o.width = 32;
  o.height = 16;
  const RasterFrame tiled = rasterize(scene, cam, o);
  ASSERT_EQ(tiled.quads, 16u * 8u);
  for (size_t k = 0; k < 16; ++k) {
    EXPECT_LT(tiled.queries[4 * k].x, 8);
    EXPECT_LT(tiled.queries[4 * k].y, 8);
  }
  o.order = PixelOrder::Scanline;
  const RasterFrame rows = rasterize(scene, cam, o);
  for (size_t k = 0; k < 16; ++k) {
    EXPECT_EQ(rows.queries[4 * k].y, 0);
    EXPECT_EQ(rows.queries[4 * k].x, int(2 * k));
  }
}

TEST(Rasterizer, BadOptionsAndCameras) {
  MeshScene scene = scene_of({floor_mesh()});
  RasterOptions o;
  o.width = 1;
  EXPECT_THROW(rasterize(scene, Camera{}, o), Error);
  o.width = 64;
  o.tile = 6;
  EXPECT_THROW(rasterize(scene, Camera{}, o), Error);
  EXPECT_THROW(parse_camera("1,2,3,4,5,6"), Error);
  EXPECT_THROW(parse_camera("1,2,3,4,5,6,200"), Error);
  EXPECT_THROW(parse_camera("0,0,0,0,0,0,45"), Error);
  EXPECT_THROW(parse_camera("0,0,0,0,5,0,45"), Error);  // straight up
  EXPECT_THROW(parse_camera("0,0,nan,0,0,-1,45"), Error);
  const Camera c = parse_camera("1,2,3,4,5,6.5,30");
  EXPECT_EQ(c.eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(c.target, glm::dvec3(4, 5, 6.5));
  EXPECT_EQ(c.fovy_deg, 30);
}

// The default orbit frames the whole bounding box: every corner projects inside the frame.
TEST(Rasterizer, OrbitFramesTheBox) {
  const glm::dvec3 lo(-3, 0, -1), hi(5, 2, 4);
  for (int frame = 0; frame < 8; ++frame) {
    const Camera c = orbit_camera(lo, hi, 4.0 / 3.0, frame, 8);
    const glm::dmat4 vp = view_projection(c, 4.0 / 3.0, lo, hi);
    for (int k = 0; k < 8; ++k) {
      const glm::dvec4 p = vp * glm::dvec4(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z, 1.0);
      EXPECT_GT(p.w, 0);
      EXPECT_LE(std::fabs(p.x / p.w), 1.0);
      EXPECT_LE(std::fabs(p.y / p.w), 1.0);
      EXPECT_LE(std::fabs(p.z / p.w), 1.0);
    }
  }
}

// --camera-path: keyframes spread evenly over the frames, interpolated linearly; a single frame
// or a single keyframe is that keyframe.
TEST(Rasterizer, CameraPathInterpolatesKeyframes) {
  const std::vector<Camera> keys = {{{0, 0, 10}, {0, 0, 0}, 40}, {{10, 0, 0}, {0, 1, 0}, 60}, {{0, 4, -10}, {0, 0, 0}, 20}};
  EXPECT_EQ(camera_on_path(keys, 0, 5).eye, keys[0].eye);
  EXPECT_EQ(camera_on_path(keys, 4, 5).eye, keys[2].eye);
  EXPECT_EQ(camera_on_path(keys, 2, 5).eye, keys[1].eye);  // frame 2 of 5: the middle keyframe
  const Camera mid = camera_on_path(keys, 1, 5);          // halfway between keyframes 0 and 1
  EXPECT_EQ(mid.eye, glm::dvec3(5, 0, 5));
  EXPECT_EQ(mid.target, glm::dvec3(0, 0.5, 0));
  EXPECT_EQ(mid.fovy_deg, 50);
  EXPECT_EQ(camera_on_path(keys, 3, 1).eye, keys[0].eye);
  EXPECT_EQ(camera_on_path({keys[1]}, 3, 7).fovy_deg, 60);
}

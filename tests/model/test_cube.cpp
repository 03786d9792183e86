// Cube maps (stage::cube_face, cube_reciprocal, cube_derivatives, cube_reproject, cube_skirts): the face and its
// coordinates against long double arithmetic of the specification's table (the tie rules at
// exact ties); the reciprocal tex_cube divides by; the derivatives by the quotient rule in long double; the skirts hold the texels
// across each edge (each skirt texel the neighbour's texel whose centre is nearest the skirt
// texel's direction) and the average of three at the corners; a sample inside a face away from its
// edges is the face's own 2D sample.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/cube_map.h"
#include "model/memory_layout.h"
#include "model/texture_cache.h"
#include "model/error.h"
#include "model/image.h"
#include "model/sampler.h"
#include "model/stages.h"

using namespace tex;

namespace {
constexpr long double kOne = 16777216.0L;

// The table in long double: face, sc, tc, rc.
void table(long double x, long double y, long double z, int& face, long double& sc, long double& tc, long double& rc) {
  const long double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
  if (az >= ax && az >= ay) {
    face = z >= 0 ? 4 : 5, sc = z >= 0 ? x : -x, tc = -y, rc = z;
  } else if (ay >= ax) {
    face = y >= 0 ? 2 : 3, sc = x, tc = y >= 0 ? z : -z, rc = y;
  } else {
    face = x >= 0 ? 0 : 1, sc = x >= 0 ? -z : z, tc = -y, rc = x;
  }
}
}  // namespace

TEST(CubeFace, FaceAndCoordinatesAsTheTableGivesThem) {
  std::mt19937_64 rng(21);
  int checked = 0;
  for (int i = 0; i < 400000; ++i) {
    int32_t d[3];
    for (int32_t& c : d) {
      switch (rng() % 4) {
        case 0: c = int32_t(uint32_t(rng())); break;                              // any
        case 1: c = int32_t(rng() % (2u << 24)) - (1 << 24); break;              // in [-1, 1)
        case 2: c = (rng() % 2 ? 1 : -1) * int32_t(1 << 24); break;               // +-1
        default: c = int32_t(rng() % 5) - 2; break;                               // near 0
      }
    }
    if (rng() % 8 == 0) d[1] = rng() % 2 ? d[0] : -d[0];  // ties between axes
    if (rng() % 8 == 0) d[2] = rng() % 2 ? d[1] : -d[1];
    const stage::CubeFace f = stage::cube_face(d[0], d[1], d[2]);
    int face = 0;
    long double sc = 0, tc = 0, rc = 0;
    table(d[0], d[1], d[2], face, sc, tc, rc);
    ASSERT_EQ(f.face, face) << d[0] << " " << d[1] << " " << d[2];
    if (rc == 0) {
      EXPECT_EQ(f.s, 1 << 23);
      continue;
    }
    for (const auto& [got, c] : {std::pair<int32_t, long double>{f.s, sc}, {f.t, tc}}) {
      const long double exact = (c / std::fabs(rc) + 1) / 2 * kOne;
      if (std::fabs(exact - std::floor(exact) - 0.5L) < 1e-9L) continue;  // (a half: long double may miss it)
      ASSERT_EQ(got, int32_t(std::floor(exact + 0.5L))) << d[0] << " " << d[1] << " " << d[2];
      ++checked;
    }
  }
  EXPECT_GT(checked, 700000);
  // The ties: rz over ry and rx, ry over rx.
  EXPECT_EQ(stage::cube_face(5, 5, 5).face, 4);
  EXPECT_EQ(stage::cube_face(5, -5, 3).face, 3);
  EXPECT_EQ(stage::cube_face(-5, 0, -5).face, 5);
  EXPECT_EQ(stage::cube_face(0, 0, 0).face, 4);
}

// tex_cube's reciprocal of the major axis, normalized to D in [2^31, 2^32): never above 2^62 / D
// and within 2^-25 of it, so that the quotient X R / 2^39 it estimates for s and t (X <= 2^33, the
// quotient <= 2^24) is at most 1 below the exact rounded quotient, which tex_cube's correction step
// (the remainder against 2D) then reaches: checked at every table interval's ends and 2 M random D.
TEST(CubeFace, ReciprocalIsWithinTheCorrectionStepsReach) {
  std::mt19937_64 rng(23);
  std::vector<uint32_t> ds;
  for (uint64_t i = 0; i < 128; ++i) {
    const uint64_t lo = (128 + i) << 24, hi = ((129 + i) << 24) - 1;
    for (uint64_t d : {lo, lo + 1, hi - 1, hi}) ds.push_back(uint32_t(d));
  }
  for (int i = 0; i < 2000000; ++i) ds.push_back(uint32_t(rng()) | 0x80000000u);
  long double worst = 0;
  int max_gap = 0;
  for (const uint32_t d : ds) {
    const uint32_t r = stage::cube_reciprocal(d);
    ASSERT_LE(__int128(r) * d, __int128(1) << 62) << d;  // from below
    const long double rel = 1.0L - (long double)r * d / 4611686018427387904.0L;
    worst = std::max(worst, rel);
    ASSERT_LT(rel, 1.0L / 33554432.0L) << d;
    // The estimate at the largest X (2D: s = 1) and at random X, against the exact quotient.
    for (const uint64_t x : {uint64_t(d) * 2, rng() % (uint64_t(d) * 2 + 1)}) {
      const uint64_t q = uint64_t((__int128(x) * 16777216 + d) / (2 * __int128(d)));
      const uint64_t est = uint64_t((__int128(x) * r + (__int128(1) << 38)) >> 39);
      ASSERT_LE(est, q) << d << " " << x;
      max_gap = std::max(max_gap, int(q - est));
    }
  }
  EXPECT_EQ(max_gap, 1);  // (one correction step: needed, and enough)
  RecordProperty("worst_relative_error_log2", std::to_string(std::log2(double(worst))));
}

// The derivatives by the quotient rule, against the exact rational in long double: within tex_cube's
// block floating point (within 2^-13 of the axis' largest term), for directions of any length.
TEST(CubeFace, DerivativesByTheQuotientRule) {
  std::mt19937_64 rng(22);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const int scale = int(rng() % 8);  // directions and derivatives of many magnitudes
    const int32_t d[3] = {int32_t(rng() % (4u << 24)) - (2 << 24), int32_t(rng() % (4u << 24)) - (2 << 24),
                          int32_t(rng() % (4u << 24)) - (2 << 24)};
    int32_t dir[3], dx[3];
    for (int c = 0; c < 3; ++c) {
      dir[c] = d[c] >> scale;
      dx[c] = int32_t(rng() % (1u << 22)) - (1 << 21);
      if (rng() % 4 == 0) dx[c] = int32_t(uint32_t(rng()));  // any
    }
    const stage::CubeFace f = stage::cube_face(dir[0], dir[1], dir[2]);
    if (f.rc == 0) continue;
    // The face's (dsc, dtc, drc), by the specification's table.
    long double dsc = 0, dtc = 0, drc = 0;
    const long double x = dx[0], y = dx[1], z = dx[2];
    switch (f.face) {
      case 0: dsc = -z, dtc = -y, drc = x; break;
      case 1: dsc = z, dtc = -y, drc = x; break;
      case 2: dsc = x, dtc = z, drc = y; break;
      case 3: dsc = x, dtc = -z, drc = y; break;
      case 4: dsc = x, dtc = -y, drc = z; break;
      default: dsc = -x, dtc = -y, drc = z; break;
    }
    const long double arc = std::fabs((long double)f.rc), sign = f.rc < 0 ? -1 : 1;
    const std::array<int32_t, 2> got = stage::cube_derivatives(f, dx[0], dx[1], dx[2]);
    const long double largest = std::max({std::fabs(dsc), std::fabs(dtc), std::fabs(drc)});
    for (int axis = 0; axis < 2; ++axis) {
      const long double c = axis == 0 ? (long double)f.sc : (long double)f.tc, dc = axis == 0 ? dsc : dtc;
      const long double exact = (dc * arc - c * sign * drc) / (2 * arc * arc) * kOne;
      if (std::fabs(exact) > 2e9L) continue;  // (saturates)
      const long double tol = largest / (2 * arc) * kOne / 8192 + 1;  // 2^-13 of the largest term, and the rounding
      ASSERT_NEAR((long double)got[size_t(axis)], exact, tol) << "face " << f.face << " axis " << axis;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300000);
}

// Every skirt texel is the neighbour's texel nearest its direction; the corners average three.
TEST(CubeSkirts, EdgesHoldTheNeighboursAndCornersTheAverageOfThree) {
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) {
    Image img(4, 4, 8);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) img.at(x, y) = {uint16_t(f * 40 + x), uint16_t(y), uint16_t(f), 255};
    faces.push_back(build_pyramid(std::move(img)));
  }
  std::vector<const Pyramid*> p;
  for (const Pyramid& f : faces) p.push_back(&f);
  const std::vector<Pyramid> s = cube_skirts(p);
  ASSERT_EQ(s.size(), 6u);
  // +Z's left edge (-x side) is -X's right column... by the table: +Z texel (-1, j) lies on -X.
  const CubeTexel left = cube_neighbour(4, -1, 2, 4);
  EXPECT_EQ(left.face, 1);
  EXPECT_EQ(left.x, 3);  // -X's column nearest +Z (its s = 1 side: sc = +rz)
  EXPECT_EQ(left.y, 2);
  EXPECT_EQ(s[4].levels[0].at(0, 3), faces[1].levels[0].at(3, 2));
  // +Z's top edge (t < 0, ry > 0) lies on +Y, whose t = 1 row meets +Z (tc = rz).
  const CubeTexel top = cube_neighbour(4, 1, -1, 4);
  EXPECT_EQ(top.face, 2);
  EXPECT_EQ(top.y, 3);
  EXPECT_EQ(top.x, 1);
  // Every edge texel of every face and level: the neighbour's texel, which in turn has this
  // face's edge texel as its neighbour (the adjacency is symmetric).
  for (int f = 0; f < 6; ++f)
    for (size_t k = 0; k < faces[0].levels.size(); ++k) {
      const int n = faces[0].levels[k].width;
      for (int i = 0; i < n; ++i)
        for (const auto& [x, y] : {std::pair<int, int>{-1, i}, {n, i}, {i, -1}, {i, n}}) {
          const CubeTexel c = cube_neighbour(f, x, y, n);
          ASSERT_NE(c.face, f);
          EXPECT_EQ(s[size_t(f)].levels[k].at(x + 1, y + 1), faces[size_t(c.face)].levels[k].at(c.x, c.y));
          // Back across: from the neighbour's texel one step towards this face lands on (x, y) clamped.
          bool back = false;
          for (const auto& [dx, dy] : {std::pair<int, int>{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
            const int bx = c.x + dx, by = c.y + dy;
            if (bx >= 0 && bx < n && by >= 0 && by < n) continue;
            const CubeTexel b = cube_neighbour(c.face, bx, by, n);
            back = back || (b.face == f && b.x == std::clamp(x, 0, n - 1) && b.y == std::clamp(y, 0, n - 1));
          }
          EXPECT_TRUE(back) << "face " << f << " (" << x << ", " << y << ") level " << k;
        }
      const Image& img = s[size_t(f)].levels[k];
      const Texel &a = img.at(1, 1), &b = img.at(0, 1), &c = img.at(1, 0), &corner = img.at(0, 0);
      for (size_t ch = 0; ch < 4; ++ch) EXPECT_EQ(corner[ch], (a[ch] + b[ch] + c[ch] + 1) / 3);
    }
  std::vector<const Pyramid*> five(p.begin(), p.begin() + 5);
  EXPECT_THROW(cube_skirts(five), Error);
  const Pyramid wide = build_pyramid(Image(8, 4, 8));
  EXPECT_THROW(cube_skirts({&wide, &wide, &wide, &wide, &wide, &wide}), Error);
}

// Inside a face, away from its edges, a cube sample is the face's 2D sample at (s, t).
TEST(CubeSkirts, InsideAFaceIsTheFacesOwnSample) {
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) faces.push_back(build_pyramid(make_pattern("noise", 32, 32)));
  for (int f = 0; f < 6; ++f)
    for (Texel& t : faces[size_t(f)].levels[0].texels) t[0] = uint16_t((t[0] + 37 * f) & 255);
  for (Pyramid& p : faces) p = build_pyramid(p.levels[0]);
  std::vector<const Pyramid*> cube;
  for (const Pyramid& p : faces) cube.push_back(&p);
  std::mt19937_64 rng(23);
  SamplerConfig cfg;
  Sampler s(cube, cfg, SamplerPaths::Both, TextureKind::Cube);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    Request r;
    r.u = int32_t(rng() % (2u << 24)) - (1 << 24);
    r.v = int32_t(rng() % (2u << 24)) - (1 << 24);
    r.w = int32_t(rng() % (2u << 24)) - (1 << 24);
    r.lod = int32_t(rng() % 256);  // levels 0 and 1: footprints of 2 texels of 32 or 16
    int face = 0;
    const Request q = cube_face_request(r, face);
    const int32_t margin = 3 << 20;  // 3/16 of the face: away from the edges at levels 0..1
    if (q.u < margin || q.u > (1 << 24) - margin || q.v < margin || q.v > (1 << 24) - margin) continue;
    Sampler flat(faces[size_t(face)], cfg);
    ASSERT_EQ(s.sample(r), flat.sample(q)) << "face " << face;
    ++checked;
  }
  EXPECT_GT(checked, 5000);
}

// A cube's memory image: each face's level k as (n_k + 2)^2 skirted texels at the layout's lines
// (decode_line gives back every face texel; the skirt bytes are cube_skirts'), and a cold cache's
// misses for a request are the lines of the taps its face, level and cube_taps name.
TEST(CubeSkirts, MemoryImageAndCacheLines) {
  std::vector<Pyramid> faces;
  for (int f = 0; f < 12; ++f) {  // a cube array of two
    Image img = make_pattern("noise", 8, 8);
    for (Texel& t : img.texels) t[1] = uint16_t((t[1] + 19 * f) & 255);
    faces.push_back(build_pyramid(std::move(img)));
  }
  std::vector<const Pyramid*> p;
  for (const Pyramid& f : faces) p.push_back(&f);
  LayoutParams params;
  params.base = 1 << 16;
  const MemoryLayout layout = layout_of(faces[0], params, 12, TextureKind::Cube);
  const std::vector<uint8_t> image = build_memory_image(p, layout);
  const std::vector<Pyramid> skirted = cube_skirts(p);
  int texels = 0;
  for (uint64_t off = 0; off < image.size(); off += uint64_t(layout.line_bytes()))
    decode_line(layout, params.base + uint32_t(off), &image[off], [&](int layer, int k, int x, int y, const Texel& t) {
      ASSERT_EQ(t, faces[size_t(layer)].levels[size_t(k)].at(x, y));
      ++texels;
    });
  EXPECT_EQ(texels, 12 * (64 + 16 + 4 + 1));
  for (int layer : {0, 7})
    for (int k = 0; k < layout.levels(); ++k) {
      const int n = layout.level_size(k).w;
      for (const auto& [x, y] : {std::pair<int, int>{0, 0}, {n + 1, 1}, {0, n + 1}, {n + 1, n + 1}}) {
        const uint32_t a = layout.line_address(k, uint32_t(x), uint32_t(y), layer) - params.base + layout.texel_offset(uint32_t(x), uint32_t(y));
        const Texel& want = skirted[size_t(layer)].levels[size_t(k)].at(x, y);
        for (size_t c = 0; c < 4; ++c) EXPECT_EQ(image[a + c], want[c]) << "layer " << layer << " level " << k;
      }
    }
  std::mt19937_64 rng(24);
  SamplerConfig cfg;
  for (int i = 0; i < 3000; ++i) {
    Request r;
    for (int32_t* c : {&r.u, &r.v, &r.w}) *c = int32_t(rng() % (2u << 24)) - (1 << 24);
    r.lod = int32_t(rng() % 1024) - 128;
    r.layer = int32_t(rng() % 2) << 16;
    TextureCache cache(layout, CacheParams{}, cfg);
    std::vector<uint32_t> misses;
    cache.lookup_sample(r, &misses);
    // The taps, from the stage functions: the face, the levels and their 2x2 footprints.
    int face = 0;
    const Request q = cube_face_request(r, face);
    const stage::LevelSelect sel = stage::lod(q.lod, 0, cfg.min_lod, cfg.max_lod, cfg.filter.mip, layout.levels() - 1);
    std::vector<uint32_t> want;
    for (int s = 0; s < (sel.f != 0 ? 2 : 1); ++s) {
      const int k = s == 0 ? sel.d : sel.d1, n = layout.level_size(k).w;
      const TexelFilter tf = stage::texel_filter(sel, cfg.filter);
      const stage::WrappedTaps tu = stage::cube_taps(q.u, n, tf), tv = stage::cube_taps(q.v, n, tf);
      for (int32_t y : {tv.i0, tv.i1})
        for (int32_t x : {tu.i0, tu.i1}) {
          if ((x == tu.i1 && tu.w == 0) || (y == tv.i1 && tv.w == 0)) continue;
          const uint32_t a = layout.line_address(k, uint32_t(x), uint32_t(y), (r.layer >> 16) * 6 + face);
          if (std::find(want.begin(), want.end(), a) == want.end()) want.push_back(a);
        }
    }
    std::sort(misses.begin(), misses.end());
    std::sort(want.begin(), want.end());
    ASSERT_EQ(misses, want) << "request " << i << " face " << face;
  }
}

// The derivative rule itself, against finite differences of the face coordinates in long double:
// s(P + h dP) - s(P - h dP) over 2h, on the same face, for random directions and derivatives.
TEST(CubeFace, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(25);
  int checked = 0;
  for (int i = 0; i < 100000; ++i) {
    long double p[3], dp[3];
    for (long double& c : p) c = (long double)(int64_t(rng() % 4000001) - 2000000) / 1e6L;
    for (long double& c : dp) c = (long double)(int64_t(rng() % 2001) - 1000) / 1e5L;  // |d| < 0.01
    int face = 0, face_a = 0, face_b = 0;
    long double sc, tc, rc, sca, tca, rca, scb, tcb, rcb;
    table(p[0], p[1], p[2], face, sc, tc, rc);
    const long double h = 1e-6L;
    table(p[0] + h * dp[0], p[1] + h * dp[1], p[2] + h * dp[2], face_a, sca, tca, rca);
    table(p[0] - h * dp[0], p[1] - h * dp[1], p[2] - h * dp[2], face_b, scb, tcb, rcb);
    if (face_a != face || face_b != face || std::fabs(rc) < 0.05L) continue;  // (near a seam or the origin)
    const long double ds = ((sca / std::fabs(rca) + 1) / 2 - (scb / std::fabs(rcb) + 1) / 2) / (2 * h);
    const long double dt = ((tca / std::fabs(rca) + 1) / 2 - (tcb / std::fabs(rcb) + 1) / 2) / (2 * h);
    Request r;
    r.u = int32_t(std::lround(p[0] * kOne));
    r.v = int32_t(std::lround(p[1] * kOne));
    r.w = int32_t(std::lround(p[2] * kOne));
    r.has_derivatives = true;
    r.deriv.dudx = int32_t(std::lround(dp[0] * kOne));
    r.deriv.dvdx = int32_t(std::lround(dp[1] * kOne));
    r.dwdx = int32_t(std::lround(dp[2] * kOne));
    int f = 0;
    const Request q = cube_face_request(r, f);
    ASSERT_EQ(f, face);
    // Within the Q8.24 rounding of the inputs (relative 2^-24 of values up to 1/|rc| < 20) and of the output.
    const long double tol = 64 / kOne + 1e-4L * (std::fabs(ds) + std::fabs(dt));
    ASSERT_NEAR((long double)q.deriv.dudx / kOne, ds, tol) << "face " << face;
    ASSERT_NEAR((long double)q.deriv.dvdx / kOne, dt, tol) << "face " << face;
    ++checked;
  }
  EXPECT_GT(checked, 50000);
}

// Directed cases: lambda boundaries, last level, 1-texel levels, clamp edges, mirror boundaries,
// negative coordinates. Each is compared with the model in lockstep; where the answer follows
// from the definition alone (point sampling, 1x1 level), it is also checked against the texels of
// the pyramid directly, independent of the model's sampler.
#include <gtest/gtest.h>

#include "lockstep.h"
#include "model/image.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

constexpr int32_t kOne = 1 << kCoordFracBits;

// Centre of texel i of an n-texel side, Q8.24 (i may be outside [0, n)).
int32_t centre(int64_t i, int n) { return int32_t(((2 * i + 1) * int64_t(kOne)) / (2 * n)); }

struct Fixture {
  std::unique_ptr<rtl::Driver> unit;
  Pyramid pyr;
  Fixture(int mw, int mh, const char* pattern, int w, int h, PyramidMode mode = PyramidMode::Exact)
      : unit(make_unit(mw, mh, 7)), pyr(build_pyramid(make_pattern(pattern, w, h), mode)) {
    unit->load(pyr, LoadMethod::Port);
  }
  // Lockstep against the model, and returns the RTL's texels (ideal and heavy timing agree).
  std::vector<Texel> run(const SamplerConfig& cfg, const std::vector<Request>& reqs) {
    std::vector<Texel> out(reqs.size());
    unit->configure(cfg, pyr);
    rtl::stream(*unit, reqs.data(), reqs.size(), rtl::Timing{}, 1,
                [&](size_t i, uint64_t p) { out[i] = rtl::unpack_rgba(p, 8); });
    const LockstepResult r = lockstep(*unit, pyr, cfg, reqs, rtl::Timing{0.6, 6, 0.6, 6, 0, 0}, 99);
    EXPECT_TRUE(r.ok()) << describe(cfg) << "\n" << r.report;
    EXPECT_EQ(r.compared, reqs.size());
    return out;
  }
};

Request req(int32_t u, int32_t v, int32_t lod) { return lambda_request(u, v, lod); }

}  // namespace

TEST(RtlDirected, LodBoundariesEveryFilter) {
  Fixture f(6, 3, "noise", 64, 8);
  const int last = f.pyr.last_level();  // 6
  std::vector<int32_t> lods = {kLodMin, -32767, -513, -257, -256, -255, -2, -1, 0, 1, 2, 126, 127, 128, 129, 130,
                               254, 255, 256, 257, 383, 384, 385, kLodMax, kLodMax - 1};
  for (int k = 1; k <= last + 2; ++k)
    for (int d : {-129, -128, -127, -1, 0, 1, 127, 128, 129}) lods.push_back(k * 256 + d);
  std::vector<Request> reqs;
  for (int32_t l : lods)
    for (int i = -3; i < 70; i += 7)
      for (int j = -2; j < 10; j += 3) reqs.push_back(req(centre(i, 64) + 37, centre(j, 8) - 91, l));
  for (const Filter& flt : all_filters())
    for (int32_t bias : {0, 1, -1, 256}) {
      SamplerConfig cfg;
      cfg.filter = flt;
      cfg.lod_bias = bias;
      f.run(cfg, reqs);
    }
  // Clamps at the same boundaries.
  for (int32_t lo : {-1, 0, 1, 255, 256})
    for (int32_t hi : {lo, lo + 1, 256 * last, 256 * last + 1}) {
      SamplerConfig cfg;
      cfg.min_lod = lo;
      cfg.max_lod = hi;
      f.run(cfg, reqs);
    }
}

TEST(RtlDirected, PointSamplingReturnsTheTexelAtEveryLevel) {
  // nearest_mipmap_nearest at texel centres: the texel of level d itself, d = ceil(lambda + 1/2) - 1.
  Fixture f(6, 3, "noise", 64, 8);
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Nearest, MipMode::Nearest};
  for (int d = 0; d <= f.pyr.last_level(); ++d) {
    const Image& lvl = f.pyr.levels[size_t(d)];
    // lambda in (d - 1/2, d + 1/2] picks level d (lambda <= 0 magnifies: level 0).
    const int32_t lod = d == 0 ? 128 : d * 256 + (d % 2 ? 128 : -127);
    std::vector<Request> reqs;
    for (int y = 0; y < lvl.height; ++y)
      for (int x = 0; x < lvl.width; ++x) reqs.push_back(req(centre(x, lvl.width), centre(y, lvl.height), lod));
    const auto got = f.run(cfg, reqs);
    size_t i = 0;
    for (int y = 0; y < lvl.height; ++y)
      for (int x = 0; x < lvl.width; ++x, ++i) ASSERT_EQ(got[i], lvl.at(x, y)) << "level " << d << " texel " << x << "," << y;
  }
}

TEST(RtlDirected, LastLevelIsTheOneByOneTexel) {
  Fixture f(4, 4, "noise", 16, 4);
  const Texel last = f.pyr.levels.back().at(0, 0);
  std::vector<Request> reqs;
  for (int32_t l : {4 * 256, 4 * 256 + 1, 4 * 256 + 200, 5 * 256, 100 * 256, int32_t(kLodMax)})
    for (int32_t u : {0, -kOne * 50, kOne / 3, kOne - 1, INT32_MIN, INT32_MAX}) reqs.push_back(req(u, -u / 7, l));
  for (const Filter& flt : all_filters()) {
    if (flt.mip == MipMode::None) continue;
    for (int w = 0; w < 3; ++w) {
      SamplerConfig cfg;
      cfg.filter = flt;
      cfg.wrap_u = cfg.wrap_v = Wrap(w);
      const auto got = f.run(cfg, reqs);
      for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], last) << describe(cfg) << " " << describe(reqs[i]);
    }
  }
}

TEST(RtlDirected, OneTexelWideLevelsAndTextures) {
  // A 1-texel side maps every index to 0 under every wrap mode; bilinear blends along y only.
  for (auto [w, h] : {std::pair{1, 16}, std::pair{16, 1}, std::pair{1, 1}}) {
    Fixture f(4, 4, "noise", w, h);
    std::vector<Request> reqs;
    for (int i = -20; i <= 36; ++i)
      for (int32_t l : {-256, 0, 128, 256, 700, 1024})
        reqs.push_back(req(i * (kOne / 16) + (i & 3) * 1000, (i * 5 % 37) * (kOne / 16) - kOne, l));
    for (const Filter& flt : all_filters())
      for (int wu = 0; wu < 3; ++wu)
        for (int wv = 0; wv < 3; ++wv) {
          SamplerConfig cfg;
          cfg.filter = flt;
          cfg.wrap_u = Wrap(wu);
          cfg.wrap_v = Wrap(wv);
          const auto got = f.run(cfg, reqs);
          if (flt.texel != TexelFilter::Nearest || flt.mip != MipMode::None) continue;
          for (size_t i = 0; i < reqs.size(); ++i) {
            // Point sampling of level 0: texel floor(u * n), wrapped; n = 1 gives texel 0.
            auto idx = [](int32_t c, int n, Wrap m) {
              const int64_t t = (int64_t(c) * n) >> kCoordFracBits;
              if (m == Wrap::Repeat) return int(((t % n) + n) % n);
              if (m == Wrap::Clamp) return int(std::clamp<int64_t>(t, 0, n - 1));
              const int64_t p = ((t % (2 * n)) + 2 * n) % (2 * n);
              return int(p < n ? p : 2 * n - 1 - p);
            };
            const Texel want = f.pyr.levels[0].at(idx(reqs[i].u, w, Wrap(wu)), idx(reqs[i].v, h, Wrap(wv)));
            ASSERT_EQ(got[i], want) << w << "x" << h << " " << describe(cfg) << " " << describe(reqs[i]);
          }
        }
  }
}

TEST(RtlDirected, ClampEdgesMirrorBoundariesNegativeCoordinates) {
  Fixture f(6, 3, "noise", 64, 8, PyramidMode::Cascade);
  const Image& l0 = f.pyr.levels[0];
  SamplerConfig point;
  point.filter = {TexelFilter::Nearest, MipMode::None};

  // Clamp: far left/right/top/bottom and just inside or outside the edge.
  point.wrap_u = point.wrap_v = Wrap::Clamp;
  std::vector<Request> reqs;
  std::vector<Texel> want;
  for (int y = 0; y < 8; ++y) {
    for (int32_t u : {-100 * kOne, -kOne, -1, INT32_MIN}) {
      reqs.push_back(req(u, centre(y, 8), 0));
      want.push_back(l0.at(0, y));
    }
    for (int32_t u : {kOne, kOne + 1, 100 * kOne, INT32_MAX, kOne - 1}) {
      reqs.push_back(req(u, centre(y, 8), 0));
      want.push_back(l0.at(63, y));
    }
  }
  auto got = f.run(point, reqs);
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "clamp " << describe(reqs[i]);

  // Mirror: [1, 2) reads the texture backwards; [-1, 0) too; period 2.
  point.wrap_u = point.wrap_v = Wrap::Mirror;
  reqs.clear();
  want.clear();
  for (int x = 0; x < 64; ++x) {
    reqs.push_back(req(kOne + centre(x, 64), centre(2, 8), 0));
    want.push_back(l0.at(63 - x, 2));
    reqs.push_back(req(-kOne + centre(x, 64), centre(2, 8), 0));
    want.push_back(l0.at(63 - x, 2));
    reqs.push_back(req(-2 * kOne + centre(x, 64), -kOne + centre(5, 8), 0));
    want.push_back(l0.at(x, 2));
  }
  // Exactly on the mirror lines: u = 1.0 is the first texel of the reversed copy (texel 63).
  reqs.push_back(req(kOne, 0, 0));
  want.push_back(l0.at(63, 0));
  reqs.push_back(req(kOne - 1, 0, 0));
  want.push_back(l0.at(63, 0));
  reqs.push_back(req(0, 0, 0));
  want.push_back(l0.at(0, 0));
  reqs.push_back(req(-1, -1, 0));  // index -1 mirrors to 0 on both axes
  want.push_back(l0.at(0, 0));
  got = f.run(point, reqs);
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "mirror " << describe(reqs[i]);

  // Repeat with negative coordinates: u = -0.25 is texel 48 of 64.
  point.wrap_u = point.wrap_v = Wrap::Repeat;
  reqs = {req(-kOne / 4, -kOne / 8, 0), req(-kOne / 4 - 1, -1, 0), req(-99 * kOne + centre(5, 64), 0, 0)};
  want = {l0.at(48, 7), l0.at(47, 7), l0.at(5, 0)};
  got = f.run(point, reqs);
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "repeat " << describe(reqs[i]);

  // Every linear filter and wrap mode at the same edge positions, against the model.
  std::vector<Request> edge;
  for (int32_t base : {-kOne, 0, kOne, 2 * kOne, -37 * kOne})
    for (int d = -300; d <= 300; d += 23)
      for (int32_t l : {-10, 0, 1, 255, 256, 700, 1500})
        edge.push_back(req(base + d, base / 2 + centre(0, 8) + d, l));
  for (const Filter& flt : all_filters())
    for (int w = 0; w < 3; ++w) {
      SamplerConfig cfg;
      cfg.filter = flt;
      cfg.wrap_u = Wrap(w);
      cfg.wrap_v = Wrap((w + 1) % 3);
      f.run(cfg, edge);
    }
}

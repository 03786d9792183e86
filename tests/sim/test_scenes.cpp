// Scenes of the paper (sim/workloads/scenes.cpp, sim/reports/), their real-valued reference and metrics, and the texsim
// render command's scene errors. Small images: the RTL engine simulates every cycle.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.h"
#include "workloads/scenes.h"
#include "reports/figures.h"

using namespace tex;
namespace fs = std::filesystem;

namespace {

SceneOptions small(int w = 48, int h = 36, int frame = 0, int frames = 1) {
  SceneOptions o;
  o.width = w;
  o.height = h;
  o.frame = frame;
  o.frames = frames;
  return o;
}

struct CliRun {
  int exit_code = -1;
  std::string err;
};

CliRun texsim(const std::string& args, const std::string& prefix = "") {
  const fs::path err = fs::temp_directory_path() / ("scenes_err_" + std::to_string(::getpid()));
  const std::string cmd = prefix + std::string(TEXSIM_PATH) + " " + args + " >/dev/null 2>" + err.string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  fs::remove(err);
  return r;
}

int line_count(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST(Scenes, EverySceneRendersWithTheModel) {
  for (const std::string& name : scene_names()) {
    SCOPED_TRACE(name);
    const VariantRender r = render_variant(name, small(), "trilinear", "model");
    ASSERT_FALSE(r.frame.queries.empty());
    ASSERT_EQ(r.texels.size(), r.frame.queries.size());
    ASSERT_EQ(r.image.width, 48);
    ASSERT_EQ(r.image.height, 36);
    // Something other than the background is drawn.
    const Image img = compose(r.frame, r.texels, r.channel_bits);
    int differing = 0;
    for (const Texel& t : img.texels)
      if (t[0] != img.texels[0][0] || t[1] != img.texels[0][1] || t[2] != img.texels[0][2]) ++differing;
    EXPECT_GT(differing, 48 * 36 / 20);
  }
}

TEST(Scenes, BadNameSizeAndFrameAreOneLineErrors) {
  const fs::path out = fs::temp_directory_path() / "scenes_bad.png";
  fs::remove(out);
  CliRun r = texsim("render --scene bogus --out " + out.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("unknown scene 'bogus'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reflect"), std::string::npos) << "the message lists the known scenes: " << r.err;
  r = texsim("render --scene plane --width 0 --height 10 --out " + out.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("0x10"), std::string::npos) << r.err;
  r = texsim("render --scene panel --width 16 --height 16 --frame 4 --frames 4 --out " + out.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("frame 4 of 4"), std::string::npos) << r.err;
  r = texsim("render --scene reflect --texture checker --width 16 --height 16 --out " + out.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--texture"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_THROW(make_scene("plane", 9000, 10), Error);
}

TEST(Scenes, RenderWritesEveryFrameOfAnAnimation) {
  const fs::path dir = fs::temp_directory_path() / ("scenes_anim_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const CliRun r = texsim("render --scene panel --width 24 --height 18 --frames 3 --out " + (dir / "panel.png").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"panel_000.png", "panel_001.png", "panel_002.png"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "panel_003.png"));
  fs::remove_all(dir);
}

TEST(Scenes, TiledOrderVisitsEachTileBeforeTheNextAndDrawsTheSamePicture) {
  SceneOptions scan;
  scan.width = 20;  // 3 tiles across, the last one 4 wide; 2 tile rows, the last one 4 high
  scan.height = 12;
  SceneOptions tiled = scan;
  tiled.order = PixelOrder::Tiled;
  const SceneFrame a = make_scene("magnify", scan), b = make_scene("magnify", tiled);  // every pixel covered
  ASSERT_EQ(a.pixel.size(), 240u);
  ASSERT_EQ(b.pixel.size(), 240u);
  for (int i = 0; i < 240; ++i) EXPECT_EQ(a.pixel[size_t(i)], i);  // scanline: rows top to bottom
  // Tiled: tile (tx, ty) holds its pixels in scanline order, tiles row by row.
  std::vector<int> expected;
  for (int ty = 0; ty < 12; ty += 8)
    for (int tx = 0; tx < 20; tx += 8)
      for (int y = ty; y < std::min(ty + 8, 12); ++y)
        for (int x = tx; x < std::min(tx + 8, 20); ++x) expected.push_back(y * 20 + x);
  EXPECT_EQ(b.pixel, expected);
  // The same query for each pixel, whatever the order.
  for (size_t i = 0; i < b.pixel.size(); ++i) {
    const Query& q = b.queries[i];
    const Query& r = a.queries[size_t(b.pixel[i])];
    EXPECT_EQ(q.u, r.u);
    EXPECT_EQ(q.v, r.v);
    EXPECT_EQ(q.deriv.dudx, r.deriv.dudx);
    EXPECT_EQ(q.deriv.dvdy, r.deriv.dvdy);
  }
  EXPECT_EQ(parse_pixel_order("tiled"), PixelOrder::Tiled);
  EXPECT_THROW(parse_pixel_order("hilbert"), Error);
  tiled.tile = 6;
  EXPECT_THROW(make_scene("plane", tiled), Error);
  tiled.tile = 4;
  EXPECT_THROW(make_scene("mesh", tiled), Error);
}

TEST(Scenes, PixelOrderOptionsAreCheckedBeforeAnyWork) {
  const fs::path out = fs::temp_directory_path() / "scenes_order.png";
  fs::remove(out);
  for (const char* bad : {"--order hilbert", "--order tiled --tile 12", "--order scanline --tile 16",
                          "--scene mesh --order tiled"}) {
    const CliRun r = texsim(std::string("render --width 16 --height 16 ") + bad + " --out " + out.string());
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_EQ(line_count(r.err), 1) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
  const CliRun r = texsim("render --width 16 --height 16 --order hilbert --out " + out.string());
  EXPECT_NE(r.err.find("'hilbert' (known: scanline, tiled)"), std::string::npos) << r.err;
}

// The reference's box integral against values worked out by hand: columns 0, 255, 0, 255 (4x4).
TEST(SceneReference, BoxFilterFollowsTheWrapModes) {
  Image stripes(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) stripes.at(x, y) = {uint16_t(x & 1 ? 255 : 0), 100, 0, 255};
  SceneFrame f;  // no mapping: every query averages its own footprint
  f.width = 1;
  f.height = 1;
  Query q;
  q.explicit_lod = false;
  q.u = 0.0;  // the left edge of texel 0; one texel of footprint, widened by one: [-1, 1] texels
  q.v = 0.5;
  q.deriv = {0.25, 0, 0, 0};
  f.queries = {q};
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Repeat, Wrap::Repeat)[0][0], 0.5, 1e-12);  // texels 3 and 0
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Clamp, Wrap::Clamp)[0][0], 0.0, 1e-12);   // texel 0 twice
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Mirror, Wrap::Mirror)[0][0], 0.0, 1e-12);  // texel 0 mirrored
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Repeat, Wrap::Repeat)[0][1], 100 / 255.0, 1e-12);
  // A point footprint is the bilinear interpolation: u = 0.3 -> x = 1.2 texels, between the centres
  // of texel 0 (0.5) and texel 1 (1.5) at 0.7 of the way: 0.7 * 255.
  f.queries[0].u = 0.3;
  f.queries[0].deriv = {0, 0, 0, 0};
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Repeat, Wrap::Repeat)[0][0], 0.7, 1e-12);
  // Eight texels wide around the centre of texel 0 (x = 0.5), widened to 9: [-4, 5], the whole
  // columns -4..4, of which -3, -1, 1, 3 are 255: 4/9.
  f.queries[0].u = 0.125;
  f.queries[0].deriv = {2.0, 0, 0, 0};
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Repeat, Wrap::Repeat)[0][0], 4.0 / 9, 1e-12);
}

// A long, thin footprint lying along a diagonal stripe (56 texels along it, 0.7 across, in the middle
// of an 8-texel-wide stripe) averages the stripe alone: the reference's sub-pixel shares are at most
// ~2 texels a side. With a fixed S x S they were the bounding box of 1/S of the footprint (S = 4:
// 11 x 11 texels, reaching the black stripes: 0.59 instead of 1; S = 6: 0.76).
TEST(SceneReference, ThinObliqueFootprintIsNotWidened) {
  Image stripes(64, 64);  // white where (x - y) mod 16 < 8: stripes along (1, 1)
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint16_t c = ((x - y + 64) % 16) < 8 ? 255 : 0;
      stripes.at(x, y) = {c, c, c, 255};
    }
  SceneFrame f;
  f.width = f.height = 1;
  f.pixel = {0};
  // Pixel (0, 0): centre at texel point (36, 32), x - y = 4 (mid-stripe); a step in x moves
  // (0.5, -0.5) texels (across the stripe), a step in y (40, 40) (along it).
  f.map = [](double sx, double sy, double& u, double& v) {
    u = (36 + (sx - 0.5) * 0.5 + (sy - 0.5) * 40) / 64;
    v = (32 - (sx - 0.5) * 0.5 + (sy - 0.5) * 40) / 64;
    return Hit::Surface;
  };
  Query q;
  q.explicit_lod = false;
  f.map(0.5, 0.5, q.u, q.v);
  q.deriv = {0.5 / 64, -0.5 / 64, 40.0 / 64, 40.0 / 64};
  f.queries = {q};
  EXPECT_NEAR(reference_values(f, stripes, Wrap::Repeat, Wrap::Repeat, 4)[0][0], 1.0, 1e-9);
  EXPECT_EQ(reference_sub_positions(0.5, 4), 4);    // at least samples_per_axis
  EXPECT_EQ(reference_sub_positions(40.0, 4), 40);  // one texel per sub-pixel step
  EXPECT_EQ(reference_sub_positions(1e9, 4), kReferenceMaxSubPositions);
  EXPECT_EQ(reference_sub_positions(1e9, 100), 100);
}

// Mip-mapping is closer to the real-valued reference than point sampling, by a wide margin.
TEST(SceneReference, FilteringBeatsPointSampling) {
  const SceneOptions o = small(96, 72);
  auto psnr = [&](const char* scene, const char* filter) {
    return compare_images(render_variant(scene, o, filter, "model").image, render_reference(scene, o)).psnr_db;
  };
  const double minify_point = psnr("minify", "point"), minify_tri = psnr("minify", "trilinear");
  EXPECT_GT(minify_tri, minify_point + 6) << minify_point << " " << minify_tri;
  const double mag_point = psnr("magnify", "point"), mag_bil = psnr("magnify", "bilinear");
  EXPECT_GT(mag_bil, 30) << mag_bil;  // bilinear is the reference's reconstruction, but for the pixel area
  EXPECT_GT(mag_bil, mag_point + 20) << mag_point;
  EXPECT_GT(psnr("plane", "trilinear"), psnr("plane", "point") + 5);
}

TEST(SceneReference, PanelFlickersLessWithTrilinear) {
  const int frames = 8;
  std::vector<RgbaImage> point, tri, ref;
  for (int f = 0; f < frames; ++f) {
    const SceneOptions o = small(64, 48, f, frames);
    point.push_back(render_variant("panel", o, "point", "model").image);
    tri.push_back(render_variant("panel", o, "trilinear", "model").image);
    ref.push_back(render_reference("panel", o));
  }
  const FlickerStats p = flicker(point, ref), t = flicker(tri, ref);
  ASSERT_EQ(p.excess.size(), size_t(frames - 1));
  EXPECT_LT(t.mean_excess * 2, p.mean_excess) << t.mean_excess << " vs " << p.mean_excess;
  // The reference against itself has no excess change.
  EXPECT_EQ(flicker(ref, ref).mean_excess, 0.0);
}

TEST(SceneMaps, ReflectanceMapIsASphereOfLights) {
  const Image m = make_reflectance_map(64);
  EXPECT_EQ(m.at(0, 0), (Texel{0, 0, 0, 255}));     // outside the sphere: unused
  EXPECT_EQ(m.at(63, 63), (Texel{0, 0, 0, 255}));
  int bright = 0;
  for (const Texel& t : m.texels) bright += t[0] > 200;
  EXPECT_GT(bright, 9);  // the highlights
}

TEST(SceneMaps, MeshMapHoldsXYZ) {
  const Image m = make_face_xyz_map(32, 16);
  EXPECT_EQ(m.channel_bits, 16);
  EXPECT_EQ(m.at(0, 0)[0], uint16_t(std::lround(0.5 / 32 * 65535)));   // X of texel 0 is its centre
  EXPECT_EQ(m.at(31, 5)[0], uint16_t(std::lround(31.5 / 32 * 65535)));
  EXPECT_EQ(m.at(3, 31)[1], uint16_t(std::lround(31.5 / 32 * 65535)));  // Y
  EXPECT_EQ(m.at(0, 0)[2], 0);                                             // Z: flat outside the face
  EXPECT_GT(m.at(16, 18)[2], 20000);                                       // the nose stands out
  // The 8-bit and 16-bit meshes have the same vertices.
  EXPECT_EQ(make_scene("mesh", small()).queries.size(), make_scene("mesh16", small()).queries.size());
}

// Vertex-space metrics against distances worked out by hand (texels_per_unit 256: 1/256 = 1 texel),
// on one face of 2 x 2 quads: 9 vertices, the centre one (index 4) interior, 8 on the border.
TEST(SceneReference, VertexErrorsAreDistancesInTexels) {
  SceneFrame f;
  for (int k = 0; k < 9; ++k) {
    Query q;
    q.explicit_lod = false;
    q.u = (k % 3 + 0.5) / 3, q.v = (k / 3 + 0.5) / 3;  // the scene's grid: n = 3 vertices at cell centres
    q.deriv = {1.0 / 3, 0, 0, 1.0 / 3};
    f.queries.push_back(q);
  }
  const std::vector<Rgba> reference(9, Rgba{0.5, 0.5, 0.1, 1});
  std::vector<Rgba> values = reference;
  values[4] = {0.5 + 3 / 256.0, 0.5 + 4 / 256.0, 0.1, 1};  // off by (3, 4, 0) texels: 5
  values[0] = {0.5, 0.5, 0.1 + 1 / 256.0, 0};              // off by 1 texel in Z; alpha ignored
  const VertexErrorStats s = compare_vertices(f, values, reference, 256);
  EXPECT_EQ(s.all.vertices, 9u);
  EXPECT_EQ(s.interior.vertices, 1u);
  EXPECT_EQ(s.border.vertices, 8u);
  EXPECT_NEAR(s.all.max_texels, 5.0, 1e-9);
  EXPECT_NEAR(s.all.rms_texels, std::sqrt((25.0 + 1.0) / 9), 1e-9);
  EXPECT_NEAR(s.interior.rms_texels, 5.0, 1e-9);
  EXPECT_NEAR(s.border.rms_texels, std::sqrt(1.0 / 8), 1e-9);
  EXPECT_NEAR(s.border.max_texels, 1.0, 1e-9);
  values.pop_back();
  EXPECT_THROW(compare_vertices(f, values, reference, 256), Error);
}

// A one-quad face whose surface moves 2 texels in X between frames while the reference stays put:
// change 2, reference change 0, excess 2; moving with the reference leaves no excess.
TEST(SceneReference, MeshJitterIsTheSurfaceMotionTheReferenceLacks) {
  SceneFrame f;
  for (int k = 0; k < 4; ++k) {
    Query q;
    q.explicit_lod = false;
    q.u = (k % 2 + 0.5) / 2, q.v = (k / 2 + 0.5) / 2;
    q.deriv = {0.5, 0, 0, 0.5};  // q = 1: a 2 x 2 vertex grid (n = 2)
    f.queries.push_back(q);
  }
  f.draw = [](const std::vector<Rgba>&) { return RgbaImage{}; };
  const std::vector<Rgba> still(4, Rgba{0.5, 0.5, 0.2, 1}), moved(4, Rgba{0.5 + 2 / 256.0, 0.5, 0.2, 1});
  SurfaceJitterStats s = mesh_jitter({f, f}, {still, moved}, {still, still}, 256, 5);
  ASSERT_EQ(s.excess.size(), 1u);
  EXPECT_NEAR(s.mean_change, 2.0, 1e-9);
  EXPECT_NEAR(s.mean_reference_change, 0.0, 1e-12);
  EXPECT_NEAR(s.mean_excess, 2.0, 1e-9);
  s = mesh_jitter({f, f}, {still, moved}, {still, moved}, 256, 5);
  EXPECT_NEAR(s.mean_excess, 0.0, 1e-12);
}

// Section 5's point, in vertex space at the size `make figures` uses for stills: sampling the X, Y, Z
// pyramid with trilinear interpolation at the mesh's own density is closer to the ideal prefiltered
// surface than point sampling level 0, over all vertices, the border ones and the interior ones, with
// the 8-bit map too (whose shaded picture scores below point's). The vertices sit at the centres of
// n equal cells (docs/scenes.md): at lambda = log2(W / n) those are the level's texel centres, so an
// edge vertex reads the edge texel where the pyramid put it instead of clamping past it.
TEST(SceneReference, MeshTrilinearVerticesAreCloserThanPoint) {
  const SceneOptions o = small(320, 240);
  const std::vector<Rgba> reference = reference_query_values("mesh", o);
  auto errors = [&](const char* scene, const char* filter) {
    const VariantRender r = render_variant(scene, o, filter, "model");
    return compare_vertices(r.frame, texels_to_values(r.texels, r.channel_bits), reference, 256);
  };
  const VertexErrorStats point = errors("mesh", "point"), tri = errors("mesh", "trilinear");
  const VertexErrorStats point16 = errors("mesh16", "point"), tri16 = errors("mesh16", "trilinear");
  for (const auto& [t, p] : {std::pair{tri, point}, {tri16, point16}}) {
    EXPECT_LT(t.all.rms_texels, p.all.rms_texels) << "trilinear " << t.all.rms_texels << " vs point " << p.all.rms_texels;
    EXPECT_LT(t.interior.rms_texels, p.interior.rms_texels)
        << "trilinear " << t.interior.rms_texels << " vs point " << p.interior.rms_texels;
    // No border bias: trilinear's border vertices are closer than point sampling's, too.
    EXPECT_LT(t.border.rms_texels, p.border.rms_texels)
        << "trilinear " << t.border.rms_texels << " vs point " << p.border.rms_texels;
  }
}

// The mesh animation in vertex space: the trilinear surface moves less beyond the reference's own
// change than the point-sampled one (popping as grids change), over all points and the interior.
TEST(SceneReference, MeshTrilinearJittersLessThanPoint) {
  const int frames = 24;  // the animation of `make figures`
  std::vector<SceneFrame> layout;
  std::vector<std::vector<Rgba>> point, tri, reference;
  for (int f = 0; f < frames; ++f) {
    const SceneOptions o = small(160, 120, f, frames);
    layout.push_back(make_scene("mesh", o));
    reference.push_back(reference_query_values("mesh", o));
    for (auto [filter, out] : {std::pair{"point", &point}, {"trilinear", &tri}}) {
      const VariantRender r = render_variant("mesh", o, filter, "model");
      out->push_back(texels_to_values(r.texels, r.channel_bits));
    }
  }
  const SurfaceJitterStats p = mesh_jitter(layout, point, reference, 256), t = mesh_jitter(layout, tri, reference, 256);
  ASSERT_EQ(p.excess.size(), size_t(frames - 1));
  EXPECT_GT(p.mean_reference_change, 0);  // the grids do change resolution in these frames
  EXPECT_LT(t.mean_interior_excess, p.mean_interior_excess) << t.mean_interior_excess << " vs " << p.mean_interior_excess;
  EXPECT_LT(t.mean_excess, p.mean_excess) << t.mean_excess << " vs " << p.mean_excess;
  EXPECT_EQ(mesh_jitter(layout, reference, reference, 256).mean_excess, 0.0);
}

// The anisotropic filter on the receding plane (fig. 7), at the size `make figures` uses for stills:
// probes along the footprint's major axis read a sharper level than trilinear's lambda = log2 of the
// major axis, so the checks survive towards the horizon. Against the real-valued reference (which
// refines its sub-pixel positions along long footprints, docs/scenes.md) it gains at least 3 dB over
// trilinear, and over a short stretch of the camera's forward motion it flickers no more. With one
// probe (max_aniso 1) the filter is trilinear again and the 3 dB are gone: the margin is the probes'.
TEST(SceneReference, PlaneAnisotropicBeatsTrilinear) {
  const SceneOptions o = small(320, 240);
  const RgbaImage reference = render_reference("plane", o);
  auto psnr = [&](const char* filter, int max_aniso) {
    return compare_images(render_variant("plane", o, filter, "model", max_aniso).image, reference).psnr_db;
  };
  const double tri = psnr("trilinear", kMaxAniso), aniso = psnr("anisotropic", kMaxAniso);
  EXPECT_GE(aniso, tri + 3) << "anisotropic " << aniso << " dB vs trilinear " << tri << " dB";
  const double one_probe = psnr("anisotropic", 1);
  EXPECT_LT(one_probe, tri + 3) << "one probe " << one_probe << " dB vs trilinear " << tri << " dB";

  // Flicker: the first frames of the 24-frame animation of `make figures`, at 160x120.
  const int frames = 24, steps = 3;
  std::vector<RgbaImage> tri_frames, aniso_frames, ref_frames;
  for (int f = 0; f <= steps; ++f) {
    const SceneOptions a = small(160, 120, f, frames);
    tri_frames.push_back(render_variant("plane", a, "trilinear", "model").image);
    aniso_frames.push_back(render_variant("plane", a, "anisotropic", "model").image);
    ref_frames.push_back(render_reference("plane", a));
  }
  const FlickerStats t = flicker(tri_frames, ref_frames), an = flicker(aniso_frames, ref_frames);
  ASSERT_EQ(an.excess.size(), size_t(steps));
  EXPECT_GT(an.mean_reference_change, 1.0);  // the camera does move: the reference changes
  EXPECT_LE(an.mean_excess, t.mean_excess) << "anisotropic " << an.mean_excess << " vs trilinear " << t.mean_excess;
}

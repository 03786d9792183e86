// Textured 3D models (sim/workloads/mesh_scene): Assimp's test models (Debian assimp-testmodels),
// OBJ+MTL and glTF 2.0 files written here with known texels, scene files and bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "model/error.h"
#include "workloads/image_module.h"
#include "workloads/mesh_scene.h"

using namespace tex;
namespace fs = std::filesystem;

namespace {

const fs::path kModels = "/usr/share/assimp/models";  // assimp-testmodels (scripts/install-deps.sh)

using Rgba = std::array<uint8_t, 4>;

// A scratch directory per test, removed afterwards.
struct TempDir {
  fs::path path;
  TempDir() {
    static int count = 0;
    path = fs::temp_directory_path() / ("mesh_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(count++));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path operator/(const std::string& name) const { return path / name; }
};

void write_text(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

std::string read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// An RGBA8 PNG, rows top to bottom as PNG stores them (OpenImageIO, through texsim's image module).
void write_png(const fs::path& p, int w, int h, const std::vector<Rgba>& texels) {
  tex::images::Pixels px{w, h, 4, false, {}};
  for (const Rgba& t : texels) px.values.insert(px.values.end(), t.begin(), t.end());
  std::string error;
  ASSERT_TRUE(tex::images::module().write(p.string(), p.string(), px, error)) << error;
}

// Eight distinct colours (and alphas) of a 4x2 image: row 0 is the top.
const std::vector<Rgba> kTexels4x2 = {{255, 0, 0, 255},   {0, 255, 0, 200},   {0, 0, 255, 255}, {255, 255, 255, 100},
                                      {0, 255, 255, 255}, {255, 0, 255, 255}, {255, 255, 0, 50}, {10, 20, 30, 255}};

Texel texel(const Rgba& c) { return {c[0], c[1], c[2], c[3]}; }

std::string base64(const std::string& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint8_t(bytes[i + 2]);
    out += abc[(n >> 18) & 63];
    out += abc[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? abc[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? abc[n & 63] : '=';
  }
  return out;
}

// The quad of the hand-written models: positions and texture coordinates as the file writes them
// (values exact in float, so the loaded ones compare exactly).
const std::vector<glm::dvec3> kQuadPositions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
const std::vector<glm::dvec2> kQuadUvs = {{0.125, 0.25}, {0.875, 0.25}, {0.875, 0.75}, {0.125, 0.75}};

// An OBJ with one textured quad (material `material`, texture file `texture`, MTL map options
// `options`) in `dir`; with `bare_mesh` also a mesh without texture coordinates.
fs::path write_obj(const fs::path& dir, const std::string& name, const std::string& material, const std::string& texture,
                   const std::string& options = "", bool textured_mesh = true, bool bare_mesh = false) {
  write_text(dir / (name + ".mtl"), "newmtl " + material + "\nKd 1 1 1\nmap_Kd " + options + texture + "\n");
  std::string obj = "mtllib " + name + ".mtl\n";
  for (const glm::dvec3& p : kQuadPositions)
    obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  for (const glm::dvec2& t : kQuadUvs) obj += "vt " + std::to_string(t.x) + " " + std::to_string(t.y) + "\n";
  if (textured_mesh) obj += "g quad\nusemtl " + material + "\nf 1/1 2/2 3/3 4/4\n";
  if (bare_mesh) obj += "g bare\nusemtl " + material + "\nf 1 2 3\n";
  write_text(dir / (name + ".obj"), obj);
  return dir / (name + ".obj");
}

// A glTF 2.0 file with one quad (node translation (10, 0, 0), scale node_scale), everything inside it as data URIs:
// the buffer and the PNG `png`.
struct GltfQuad {
  std::vector<glm::dvec3> positions = kQuadPositions;
  std::vector<glm::dvec2> uvs = kQuadUvs;
  int wrap_s = 33071, wrap_t = 33648;  // GL's CLAMP_TO_EDGE, MIRRORED_REPEAT
  bool double_sided = true;
  glm::dvec3 node_scale{1.0};
};

fs::path write_gltf(const fs::path& path, const GltfQuad& q, const std::string& png) {
  std::string buffer;
  auto put = [&](const auto& value) { buffer.append(reinterpret_cast<const char*>(&value), sizeof value); };
  for (const glm::dvec3& p : q.positions) put(glm::vec3(p));
  for (const glm::dvec2& t : q.uvs) put(glm::vec2(t));
  for (uint16_t i : {0, 1, 2, 0, 2, 3}) put(i);
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0},
                  {"translation", {10.0, 0.0, 0.0}},
                  {"scale", {q.node_scale.x, q.node_scale.y, q.node_scale.z}}}}},
      {"meshes", {{{"name", "quad"},
                   {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
                                    {"indices", 2},
                                    {"material", 0}}}}}}},
      {"materials", {{{"name", "painted"}, {"doubleSided", q.double_sided},
                      {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"sampler", 0}, {"source", 0}}}},
      {"samplers", {{{"wrapS", q.wrap_s}, {"wrapT", q.wrap_t}}}},
      {"images", {{{"uri", "data:image/png;base64," + base64(png)}}}},
      {"buffers", {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  write_text(path, j.dump(1));
  return path;
}

// The texel that a coordinate selects, in the sampler's convention: v = 0 is image row 0.
Texel texel_at(const SceneTexture& t, const glm::dvec2& uv) {
  const int x = std::clamp(int(std::floor(uv.x * t.image.width)), 0, t.image.width - 1);
  const int y = std::clamp(int(std::floor(uv.y * t.image.height)), 0, t.image.height - 1);
  return t.image.at(x, y);
}

bool has_note(const MeshScene& s, const std::string& text) {
  return std::any_of(s.notes.begin(), s.notes.end(),
                     [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// What holds for every loaded scene, checked against the files themselves where it can.
void check_scene(const MeshScene& s) {
  ASSERT_FALSE(s.meshes.empty());
  ASSERT_FALSE(s.textures.empty());
  for (int axis = 0; axis < 3; ++axis) {
    bool min_hit = false, max_hit = false;  // the box is tight: some vertex lies on each face
    for (const DrawMesh& m : s.meshes) {
      SCOPED_TRACE(m.name);
      ASSERT_EQ(m.uvs.size(), m.positions.size());
      ASSERT_FALSE(m.indices.empty());
      ASSERT_EQ(m.indices.size() % 3, 0u);
      for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
      ASSERT_GE(m.texture, 0);
      ASSERT_LT(size_t(m.texture), s.textures.size());
      for (const glm::dvec2& t : m.uvs) ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y));
      for (const glm::dvec3& p : m.positions) {
        ASSERT_LE(s.bounds_min[axis], p[axis]);
        ASSERT_GE(s.bounds_max[axis], p[axis]);
        min_hit |= p[axis] == s.bounds_min[axis];
        max_hit |= p[axis] == s.bounds_max[axis];
      }
    }
    EXPECT_TRUE(min_hit && max_hit) << "axis " << axis;
  }
  for (const SceneTexture& t : s.textures) {
    SCOPED_TRACE(t.source);
    EXPECT_EQ(t.image.texels.size(), size_t(t.image.width) * t.image.height);
    EXPECT_EQ(t.image.channel_bits, 8);
    if (t.source.find("#embedded:") == std::string::npos) {  // a file: its size as OpenImageIO reads it
      tex::images::Pixels px;
      std::string error;
      ASSERT_TRUE(tex::images::module().read(t.source, nullptr, 0, UINT64_MAX, px, error)) << error;
      EXPECT_EQ(t.file_width, px.width);
      EXPECT_EQ(t.file_height, px.height);
    }
    // the file's size, whatever it is (no test model has a side beyond 8192)
    EXPECT_EQ(t.image.width, t.file_width);
    EXPECT_EQ(t.image.height, t.file_height);
    EXPECT_FALSE(t.resized);
  }
}

glm::dvec3 centroid(const DrawMesh& m) {
  glm::dvec3 c(0.0);
  for (const glm::dvec3& p : m.positions) c += p;
  return c / double(m.positions.size());
}

std::set<std::string> file_names(const MeshScene& s) {
  std::set<std::string> names;
  for (const SceneTexture& t : s.textures) names.insert(fs::path(t.source).filename().string());
  return names;
}

// `f` throws tex::Error with one line that contains every one of `parts`; nothing goes to stderr.
void expect_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  std::string message;
  try {
    f();
  } catch (const Error& e) {
    message = e.what();
  }
  const std::string err = testing::internal::GetCapturedStderr() + testing::internal::GetCapturedStdout();
  ASSERT_FALSE(message.empty()) << "no tex::Error thrown";
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
  EXPECT_EQ(err, "") << "the library printed something";
}

}  // namespace

// glTF 1.0: the truck's body and its wheels (one mesh under two nodes) share one 2048x2048
// texture; glass and window trim have colours only and are skipped with a note.
TEST(MeshScene, CesiumMilkTruckGltf1) {
  const fs::path path = kModels / "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf";
  ASSERT_TRUE(fs::exists(path)) << "install assimp-testmodels (scripts/install-deps.sh)";
  const MeshScene s = load_model(path.string());
  check_scene(s);
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(file_names(s), std::set<std::string>{"CesiumMilkTruck.png"});
  EXPECT_EQ(s.textures[0].wrap_u, Wrap::Repeat);  // the file's sampler: wrapS = wrapT = 10497 (REPEAT)
  EXPECT_EQ(s.textures[0].wrap_v, Wrap::Repeat);
  EXPECT_FALSE(s.textures[0].srgb);  // glTF 1.0 does not say: linear
  EXPECT_TRUE(has_note(s, "glass"));
  EXPECT_TRUE(has_note(s, "window_trim"));
  // The two wheel nodes differ only in translation x: 1.43267 and -1.35233 in the file.
  ASSERT_EQ(s.meshes[1].positions.size(), s.meshes[2].positions.size());
  const glm::dvec3 d = centroid(s.meshes[1]) - centroid(s.meshes[2]);
  EXPECT_NEAR(d.x, 1.43267 + 1.35233, 1e-4);
  EXPECT_NEAR(d.y, 0.0, 1e-4);
  EXPECT_NEAR(d.z, 0.0, 1e-4);
}

// glTF 2.0: a cube of side 1 with the 211x211 Cesium logo; the sampler mirrors S, clamps T.
TEST(MeshScene, BoxTexturedGltf2) {
  const MeshScene s = load_model((kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf").string());
  check_scene(s);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 36u);  // 6 faces, 2 triangles each
  EXPECT_FALSE(s.meshes[0].double_sided);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(file_names(s), std::set<std::string>{"CesiumLogoFlat.png"});
  EXPECT_FALSE(s.textures[0].resized);
  EXPECT_EQ(s.textures[0].image.width, 211);       // sampled as it is
  EXPECT_EQ(s.textures[0].wrap_u, Wrap::Mirror);  // wrapS 33648
  EXPECT_EQ(s.textures[0].wrap_v, Wrap::Clamp);   // wrapT 33071
  EXPECT_EQ(s.textures[0].gltf_mag_filter, 9729);  // LINEAR
  EXPECT_EQ(s.textures[0].gltf_min_filter, 9986);  // NEAREST_MIPMAP_LINEAR
  EXPECT_TRUE(s.textures[0].srgb);  // glTF 2.0's base colour is sRGB
  // The texture's sampler: the file's filters and wrap modes, unless the command line gives them.
  SamplerConfig cli;
  cli.filter = Filter(TexelFilter::Linear, MipMode::Nearest);
  cli.wrap_u = cli.wrap_v = Wrap::Border;
  const SamplerConfig file = file_sampler(s.textures[0], cli, false, false);
  EXPECT_EQ(file.filter.texel, TexelFilter::Nearest);
  EXPECT_EQ(file.filter.mip, MipMode::Linear);
  EXPECT_EQ(file.filter.mag, TexelFilter::Linear);
  EXPECT_EQ(file.wrap_u, Wrap::Mirror);
  EXPECT_EQ(file.wrap_v, Wrap::Clamp);
  const SamplerConfig kept = file_sampler(s.textures[0], cli, true, true);
  EXPECT_EQ(kept.filter, cli.filter);
  EXPECT_EQ(kept.wrap_u, Wrap::Border);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(s.bounds_min[axis], -0.5, 1e-6);
    EXPECT_NEAR(s.bounds_max[axis], 0.5, 1e-6);
  }
}

// COLLADA: one mesh, the 512x512 TGA next to it, no resampling.
TEST(MeshScene, DuckCollada) {
  const MeshScene s = load_model((kModels / "Collada/duck.dae").string());
  check_scene(s);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(file_names(s), std::set<std::string>{"duckCM.tga"});
  EXPECT_FALSE(s.textures[0].resized);
  EXPECT_EQ(s.textures[0].wrap_u, Wrap::Repeat);
  EXPECT_FALSE(s.textures[0].srgb);  // COLLADA does not say: linear
  EXPECT_TRUE(s.notes.empty());
}

// OBJ: 19 groups, materials naming textures as ".\name.jpg" (Windows); the four used ones are
// 249x250, 250x250, 768x768 and 128x128, kept as they are. Brusttex (wal69ar_small.jpg) is unused.
TEST(MeshScene, SpiderObj) {
  const MeshScene s = load_model((kModels / "OBJ/spider.obj").string());
  check_scene(s);
  EXPECT_EQ(s.meshes.size(), 19u);
  EXPECT_EQ(s.textures.size(), 4u);
  EXPECT_EQ(file_names(s),
            (std::set<std::string>{"SpiderTex.jpg", "wal67ar_small.jpg", "drkwood2.jpg", "engineflare1.jpg"}));
  EXPECT_EQ(s.meshes.front().name, "HLeib01");  // the file's order
  EXPECT_EQ(s.meshes.back().name, "Duplicate05");
  EXPECT_EQ(std::count_if(s.notes.begin(), s.notes.end(), [](auto& n) { return n.find("resampled") != n.npos; }), 0);
}

// OBJ puts v = 0 at the image's bottom: the loaded v is 1 - v, and the texel each corner selects
// is the one at the file's coordinates counted from the bottom row.
TEST(MeshScene, ObjQuadFlipsV) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  const MeshScene s = load_model(write_obj(dir.path, "quad", "paint", "tex.png").string());
  check_scene(s);
  ASSERT_EQ(s.meshes.size(), 1u);
  const DrawMesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "quad");
  ASSERT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.indices.size(), 6u);
  ASSERT_EQ(s.textures.size(), 1u);
  const SceneTexture& t = s.textures[0];
  EXPECT_EQ(t.material, "paint");
  EXPECT_EQ(fs::path(t.source), dir / "tex.png");
  EXPECT_EQ(t.wrap_u, Wrap::Repeat);
  EXPECT_EQ(t.wrap_v, Wrap::Repeat);
  EXPECT_FALSE(t.resized);
  ASSERT_EQ(t.image.width, 4);
  ASSERT_EQ(t.image.height, 2);
  for (size_t i = 0; i < kTexels4x2.size(); ++i) EXPECT_EQ(t.image.texels[i], texel(kTexels4x2[i])) << i;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const auto k = size_t(std::find(kQuadPositions.begin(), kQuadPositions.end(), m.positions[i]) - kQuadPositions.begin());
    ASSERT_LT(k, kQuadPositions.size()) << "position not in the file";
    EXPECT_EQ(m.uvs[i].x, kQuadUvs[k].x);
    EXPECT_EQ(m.uvs[i].y, 1.0 - kQuadUvs[k].y);
    const int x = int(kQuadUvs[k].x * 4), row_from_bottom = int(kQuadUvs[k].y * 2);
    EXPECT_EQ(texel_at(t, m.uvs[i]), texel(kTexels4x2[size_t((1 - row_from_bottom) * 4 + x)])) << "corner " << k;
  }
  for (size_t f = 0; f < m.indices.size(); f += 3) {  // the face is counter-clockwise seen from +z: still
    const glm::dvec3 a = m.positions[m.indices[f]], b = m.positions[m.indices[f + 1]], c = m.positions[m.indices[f + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0);
  }
  EXPECT_EQ(s.bounds_min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(s.bounds_max, glm::dvec3(2, 1, 0));
}

// glTF's (0, 0) is already the image's top-left: v stays; the sampler and doubleSided come through,
// the embedded PNG is decoded, the node's translation applied.
TEST(MeshScene, GltfQuadKeepsVAndSampler) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  const fs::path path = write_gltf(dir / "quad.gltf", GltfQuad{}, read_bytes(dir / "tex.png"));
  fs::remove(dir / "tex.png");  // the model must not need it
  const MeshScene s = load_model(path.string());
  check_scene(s);
  ASSERT_EQ(s.meshes.size(), 1u);
  const DrawMesh& m = s.meshes[0];
  EXPECT_TRUE(m.double_sided);
  ASSERT_EQ(s.textures.size(), 1u);
  const SceneTexture& t = s.textures[0];
  EXPECT_EQ(t.source, path.string() + "#embedded:0");
  EXPECT_EQ(t.material, "painted");
  EXPECT_EQ(t.wrap_u, Wrap::Clamp);
  EXPECT_EQ(t.wrap_v, Wrap::Mirror);
  ASSERT_EQ(t.image.width, 4);
  ASSERT_EQ(t.image.height, 2);
  for (size_t i = 0; i < kTexels4x2.size(); ++i) EXPECT_EQ(t.image.texels[i], texel(kTexels4x2[i])) << i;
  ASSERT_EQ(m.positions.size(), 4u);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3 file_pos = m.positions[i] - glm::dvec3(10, 0, 0);
    const auto k = size_t(std::find(kQuadPositions.begin(), kQuadPositions.end(), file_pos) - kQuadPositions.begin());
    ASSERT_LT(k, kQuadPositions.size()) << "position not in the file (+ node translation)";
    EXPECT_EQ(m.uvs[i], kQuadUvs[k]);
    const int x = int(kQuadUvs[k].x * 4), row_from_top = int(kQuadUvs[k].y * 2);
    EXPECT_EQ(texel_at(t, m.uvs[i]), texel(kTexels4x2[size_t(row_from_top * 4 + x)])) << "corner " << k;
  }
  EXPECT_EQ(s.bounds_min, glm::dvec3(10, 0, 0));
  EXPECT_EQ(s.bounds_max, glm::dvec3(12, 1, 0));
}

// A mirroring node (scale x by -1) turns the quad's counter-clockwise triangles clockwise; the
// loader swaps two corners so that the front face stays the front face.
TEST(MeshScene, MirroredNodeKeepsFrontFaces) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  GltfQuad q;
  q.node_scale = {-1, 1, 1};
  const MeshScene s = load_model(write_gltf(dir / "mirror.gltf", q, read_bytes(dir / "tex.png")).string());
  check_scene(s);
  const DrawMesh& m = s.meshes.at(0);
  EXPECT_EQ(s.bounds_min, glm::dvec3(8, 0, 0));  // translation after scale: x -> 10 - x
  EXPECT_EQ(s.bounds_max, glm::dvec3(10, 1, 0));
  ASSERT_EQ(m.indices.size(), 6u);
  for (size_t f = 0; f < m.indices.size(); f += 3) {
    const glm::dvec3 a = m.positions[m.indices[f]], b = m.positions[m.indices[f + 1]], c = m.positions[m.indices[f + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0);  // the file's triangles face +z
  }
}

// Any size is a texture: a 3x5 image is sampled as it is, texel for texel; a side beyond 8192
// (which no unit holds) is resampled down to 8192, with a note.
TEST(MeshScene, TexturesKeepTheirSize) {
  TempDir dir;
  std::vector<Rgba> texels(15);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = Rgba{uint8_t(i * 16), uint8_t(255 - i), 50, 255};
  write_png(dir / "odd.png", 3, 5, texels);
  const MeshScene s = load_model(write_obj(dir.path, "quad", "odd_paint", "odd.png").string());
  check_scene(s);
  const SceneTexture& t = s.textures.at(0);
  EXPECT_FALSE(t.resized);
  EXPECT_EQ(t.image.width, 3);
  EXPECT_EQ(t.image.height, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(t.image.at(x, y), texel(texels[size_t(y * 3 + x)])) << x << "," << y;
  EXPECT_TRUE(s.notes.empty());

  std::vector<Rgba> wide(size_t(8200) * 2, Rgba{10, 20, 30, 255});
  write_png(dir / "wide.png", 8200, 2, wide);
  const MeshScene w = load_model(write_obj(dir.path, "quad2", "wide_paint", "wide.png").string());
  const SceneTexture& tw = w.textures.at(0);
  EXPECT_TRUE(tw.resized);
  EXPECT_EQ(tw.image.width, 8192);
  EXPECT_EQ(tw.image.height, 2);
  EXPECT_EQ(tw.image.at(4000, 1), texel(wide[0]));
  EXPECT_TRUE(has_note(w, "texture " + (dir / "wide.png").string() + " (wide_paint): 8200x2 resampled to 8192x2"));
}

TEST(MeshScene, MeshWithoutUvsIsSkippedWithANote) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  const MeshScene s = load_model(write_obj(dir.path, "mixed", "paint", "tex.png", "", true, true).string());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "quad");
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("'bare'"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("texture coordinates"), std::string::npos) << s.notes[0];

  const fs::path only = write_obj(dir.path, "bare", "paint", "tex.png", "", false, true);
  expect_error([&] { load_model(only.string()); }, {only.string(), "nothing to draw", "'bare'"});
}

TEST(MeshSceneErrors, UnreadableModels) {
  TempDir dir;
  expect_error([&] { load_model((dir / "none.gltf").string()); }, {(dir / "none.gltf").string(), "no such file"});
  expect_error([&] { load_model(dir.path.string()); }, {dir.path.string(), "not a regular file"});
  std::string garbage;
  for (int i = 0; i < 4000; ++i) garbage += char((i * 7919 + 13) % 251);
  for (const std::string name : {"garbage.gltf", "garbage.glb", "garbage.obj", "garbage.dae", "garbage.3ds"}) {
    SCOPED_TRACE(name);
    write_text(dir / name, garbage);
    expect_error([&] { load_model((dir / name).string()); }, {(dir / name).string() + ": cannot read model: "});
  }
}

// An OFF header that claims more vertices or faces than its file can hold is refused before Assimp
// allocates for it (Debian's invalid/OutOfMemory.off claims 353 535 235 358 vertices in 309 bytes:
// Assimp alone grew to 7.5 GB), naming the file and the counts; a well-formed OFF still loads.
TEST(MeshSceneErrors, OffHeaderBeyondTheFileIsRefused) {
  const std::string oom = (kModels / "invalid/OutOfMemory.off").string();
  expect_error([&] { load_model(oom); }, {oom, "OFF header claims 353535235358 vertices", "309 bytes"});
  TempDir dir;
  write_text(dir / "big.off", "OFF\n# a comment\n100 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n");
  expect_error([&] { load_model((dir / "big.off").string()); }, {"big.off", "100 vertices"});
  write_text(dir / "tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n");
  expect_error([&] { load_model((dir / "tri.off").string()); }, {"tri.off"});  // untextured: Assimp's or ours, not the header's
  try {
    load_model((dir / "tri.off").string());
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("OFF header"), std::string::npos) << e.what();
  }
}

TEST(MeshSceneErrors, NonFiniteVertexData) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  write_text(dir / "m.mtl", "newmtl paint\nmap_Kd tex.png\n");
  write_text(dir / "nan.obj", "mtllib m.mtl\nv 0 0 0\nv nan 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                              "g broken\nusemtl paint\nf 1/1 2/2 3/3\n");
  expect_error([&] { load_model((dir / "nan.obj").string()); }, {(dir / "nan.obj").string(), "'broken'", "position"});

  GltfQuad q;  // OBJ's parser reads "nan" texture coordinates as 0: a glTF buffer holds them exactly
  q.uvs[2].y = std::numeric_limits<double>::quiet_NaN();
  const fs::path gltf = write_gltf(dir / "nan_uv.gltf", q, read_bytes(dir / "tex.png"));
  expect_error([&] { load_model(gltf.string()); }, {gltf.string(), "'quad'", "texture coordinates"});
  q = GltfQuad{};
  q.positions[1].z = std::numeric_limits<double>::infinity();
  write_gltf(gltf, q, read_bytes(dir / "tex.png"));
  expect_error([&] { load_model(gltf.string()); }, {gltf.string(), "'quad'", "position"});
}

TEST(MeshSceneErrors, MissingTexture) {
  TempDir dir;
  const fs::path obj = write_obj(dir.path, "quad", "ghost", "sub\\nothere%20x.png");
  expect_error([&] { load_model(obj.string()); }, {obj.string(), "'ghost'", (dir / "sub/nothere x.png").string()});
  // Escapes and Windows separators are only decoded to find a file that exists.
  fs::create_directories(dir / "sub");
  write_png(dir / "sub/nothere x.png", 4, 2, kTexels4x2);
  EXPECT_EQ(fs::path(load_model(obj.string()).textures.at(0).source), dir / "sub/nothere x.png");
}

// Texture paths of files made elsewhere (assimp-testmodels: 3DS/test1.3ds names IMAGE1.JPG beside
// IMAGE1.jpg, others absolute paths of their authors' machines): after the path as written, the file
// name, case aside, beside the model, then in its textures/ folder — each noted once; never a folder
// the path does not name.
TEST(MeshScene, TexturesFoundByTheirNames) {
  TempDir dir;
  write_png(dir / "test.png", 4, 2, kTexels4x2);
  fs::create_directories(dir / "Textures");
  write_png(dir / "Textures/wood.PNG", 4, 2, kTexels4x2);
  fs::create_directories(dir / "elsewhere");
  write_png(dir / "elsewhere/far.png", 4, 2, kTexels4x2);
  const MeshScene a = load_model(write_obj(dir.path, "upper", "paint", "TEST.PNG").string());
  ASSERT_EQ(a.textures.size(), 1u);
  EXPECT_EQ(fs::path(a.textures[0].source), dir / "test.png");
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_NE(a.notes[0].find("'TEST.PNG'"), std::string::npos) << a.notes[0];
  EXPECT_NE(a.notes[0].find((dir / "test.png").string()), std::string::npos) << a.notes[0];
  const MeshScene b = load_model(write_obj(dir.path, "absolute", "paint", "D:\\projects\\art\\wood.png").string());
  EXPECT_EQ(fs::path(b.textures.at(0).source), dir / "Textures/wood.PNG");
  // The name alone is looked for only beside the model and in its textures/: not in other folders.
  const fs::path far = write_obj(dir.path, "far", "paint", "e:/dev/far.png");
  expect_error([&] { load_model(far.string()); }, {far.string(), "texture file not found", "far.png"});
  // As written first: an exact path wins over a name match.
  write_png(dir / "elsewhere/TEST.PNG", 4, 2, kTexels4x2);
  const MeshScene c = load_model(write_obj(dir.path, "exact", "paint", "elsewhere/TEST.PNG").string());
  EXPECT_EQ(fs::path(c.textures.at(0).source), dir / "elsewhere/TEST.PNG");
  EXPECT_TRUE(c.notes.empty());
}

// A scene file places models: scale, rotation about x then y then z (degrees), translation.
TEST(MeshSceneFile, PlacesAndMergesModels) {
  TempDir dir;
  write_png(dir / "tex.png", 4, 2, kTexels4x2);
  write_obj(dir.path, "quad", "paint", "tex.png");
  write_obj(dir.path, "copy", "paint2", "./tex.png");
  write_obj(dir.path, "clamped", "paint3", "tex.png", "-clamp on ");
  write_text(dir / "scene.json", R"({"models": [
      {"file": "quad.obj"},
      {"file": "quad.obj", "translation": [5, 0, 0], "rotation": [90, 90, 0], "scale": 2},
      {"file": "copy.obj", "translation": [0, 0, 7]},
      {"file": "clamped.obj"}]})");
  const std::vector<ModelPlacement> placements = read_scene_file((dir / "scene.json").string());
  ASSERT_EQ(placements.size(), 4u);
  EXPECT_EQ(fs::path(placements[0].path), dir / "quad.obj");
  EXPECT_EQ(placements[0].scale, 1.0);
  EXPECT_EQ(placements[0].translation, glm::dvec3(0.0));
  EXPECT_EQ(placements[1].rotation_deg, glm::dvec3(90, 90, 0));
  EXPECT_EQ(placements[1].scale, 2.0);

  const MeshScene s = load_models(placements);
  check_scene(s);
  ASSERT_EQ(s.meshes.size(), 4u);
  // One image: quad and copy share it (one entry); clamped has other wrap modes (a second entry).
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_EQ(s.textures[0].source, s.textures[1].source);
  EXPECT_EQ(s.textures[1].wrap_u, Wrap::Clamp);
  EXPECT_EQ(s.textures[1].wrap_v, Wrap::Clamp);
  EXPECT_EQ(s.meshes[0].texture, 0);
  EXPECT_EQ(s.meshes[1].texture, 0);
  EXPECT_EQ(s.meshes[2].texture, 0);
  EXPECT_EQ(s.meshes[3].texture, 1);
  // (x, y, z) scaled by 2, turned 90 degrees about x: (2x, -2z, 2y), then about y: (2y, -2z, -2x); + (5, 0, 0).
  std::vector<glm::dvec3> expected;
  for (const glm::dvec3& p : kQuadPositions) expected.push_back(glm::dvec3(2 * p.y + 5, -2 * p.z, -2 * p.x));
  ASSERT_EQ(s.meshes[1].positions.size(), 4u);
  for (const glm::dvec3& p : s.meshes[1].positions)
    EXPECT_TRUE(std::any_of(expected.begin(), expected.end(),
                            [&](const glm::dvec3& e) { return glm::distance(p, e) < 1e-9; }))
        << p.x << " " << p.y << " " << p.z;
  for (const glm::dvec3& p : s.meshes[2].positions) EXPECT_EQ(p.z, 7.0);
  EXPECT_NEAR(s.bounds_min.z, -4.0, 1e-9);
  EXPECT_NEAR(s.bounds_max.x, 7.0, 1e-9);
  EXPECT_NEAR(s.bounds_max.z, 7.0, 1e-9);
}

TEST(MeshSceneFile, BadSceneFiles) {
  TempDir dir;
  const fs::path scene = dir / "scene.json";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"models": [{"file": "a.obj", "scal": 2}]})", "scal"},
      {R"({"models": [{"file": "a.obj"}], "camera": {}})", "camera"},
      {R"({"models": [{"file": "a.obj", "translation": [0, 1e999, 0]}]})", "translation"},
      {R"({"models": [{"file": "a.obj", "rotation": [0, 0]}]})", "rotation"},
      {R"({"models": [{"file": "a.obj", "scale": 0}]})", "scale"},
      {R"({"models": [{"file": "a.obj", "scale": "big"}]})", "scale"},
      {R"({"models": [{"file": 3}]})", "file"},
      {R"({"models": [{"scale": 1}]})", "file"},
      {R"({"models": []})", "models"},
      {R"({"model": []})", "model"},
      {R"({})", "models"},
      {R"([1, 2])", "models"},
      {R"({"models": [)", "JSON"},
  };
  for (const auto& [text, key] : cases) {
    SCOPED_TRACE(text);
    write_text(scene, text);
    expect_error([&] { read_scene_file(scene.string()); }, {scene.string(), key});
  }
  expect_error([&] { read_scene_file((dir / "none.json").string()); }, {(dir / "none.json").string()});
  ModelPlacement p;
  p.path = (dir / "a.obj").string();
  p.scale = 0;
  expect_error([&] { load_models({p}); }, {"scale"});
  expect_error([&] { load_models({}); }, {"no models"});
}

// Textured 3D models as the rasterizer takes them (docs/scenes.md, "Real frames"): triangles in
// world space with texture coordinate set 0, one texture per material, loaded through Assimp
// (geometry) and OpenImageIO (textures, from files next to the model or embedded in glTF/GLB).
#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/formats.h"
#include "model/image.h"
#include "model/sampler.h"

namespace tex {

// A scene file's sampler for one model's textures ("sampler": {...}): each field it gives replaces
// the model file's and the command line's.
struct SamplerOverride {
  std::optional<Wrap> wrap_u, wrap_v;
  std::optional<TexelFilter> min_filter, mag_filter;
  std::optional<MipMode> mipmap_mode;
  std::optional<BorderColor> border_color;
  std::optional<Reduction> reduction;
  std::string key() const;  // equal for equal overrides (textures are told apart by it)
};

// A texture of the scene: one descriptor-table entry of the hardware (its index is the texture id).
struct SceneTexture {
  std::string material;     // the material that names it (first one, for messages)
  std::string source;       // its file path, or "<model>#embedded:N" for an image inside the model
  Image image;              // RGBA8, the file's size (resampled down to 8192 if a side was larger)
  int file_width = 0, file_height = 0;  // as stored in the file
  bool resized = false;     // a side of file_width/height was beyond 8192
  Wrap wrap_u = Wrap::Repeat, wrap_v = Wrap::Repeat;  // glTF sampler modes; repeat where the format has none
  // The glTF sampler's magFilter and minFilter (GL's codes: 9728 NEAREST, 9729 LINEAR, 9984..9987
  // NEAREST_MIPMAP_NEAREST .. LINEAR_MIPMAP_LINEAR); 0 where the file has none.
  int gltf_mag_filter = 0, gltf_min_filter = 0;
  SamplerOverride scene_sampler;  // its model's "sampler" in the scene file
  bool srgb = false;        // its texels are sRGB codes: glTF 2's base colour (the spec says so)
};

// The sampler a texture's file gives it, over `base` (the command line's): its filters unless
// `keep_filter` (--filter, --min-filter, --mag-filter or --mipmap-mode given), its wrap modes
// unless `keep_wrap` (--wrap* given); then its scene file's sampler fields over all of these. A
// minFilter without MIPMAP samples level 0 only, as in GL.
SamplerConfig file_sampler(const SceneTexture& t, SamplerConfig base, bool keep_filter, bool keep_wrap);

// One drawable mesh: triangles (three indices each) with world-space positions and texture
// coordinates; v = 0 is the top row of the texture image (the rasterizer's and the sampler's
// convention: docs/scenes.md says how each format's coordinates are turned into it).
struct DrawMesh {
  std::string name;             // mesh name in the file (or "mesh N"), for messages
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec2> uvs;  // one per position
  std::vector<glm::dvec3> normals;  // world space, one per position (a mirror's: load_model's `mirror`)
  std::vector<uint32_t> indices;
  int texture = 0;              // index into MeshScene::textures
  bool double_sided = false;    // material: no back-face culling
};

struct MeshScene {
  std::vector<DrawMesh> meshes;        // in draw order (the file's order, then the scene file's)
  std::vector<SceneTexture> textures;  // distinct textures, in first-use order
  glm::dvec3 bounds_min{0.0}, bounds_max{0.0};  // world-space bounding box of every drawn vertex
  std::vector<std::string> notes;      // one line each: skipped meshes, resampled textures
};

// One model placed in the world (scene files): uniform scale, then rotation (Euler angles in
// degrees, applied about x, then y, then z), then translation.
struct ModelPlacement {
  std::string path;
  glm::dvec3 translation{0.0};
  glm::dvec3 rotation_deg{0.0};
  double scale = 1.0;
  SamplerOverride sampler;  // "sampler": the sampler of the model's textures
};

// Loads one model (any format Assimp reads) with its node transforms applied. Throws tex::Error
// with one line: a file Assimp cannot read (its message and the file name), a missing or unreadable
// texture (material and path), NaN or infinite vertex data (mesh name), nothing textured left.
// Meshes without texture coordinates (or whose material has no base-colour/diffuse texture) are
// skipped with a note.
// `mirror` (render --envmap): every triangle mesh is kept, textured or not (texture 0, no texture
// loaded), with smooth world-space normals (the file's, or Assimp's where it has none).
MeshScene load_model(const std::string& path, bool mirror = false);

// Several models in one world: the placements in order, their textures merged (the same file
// used twice is one texture).
MeshScene load_models(const std::vector<ModelPlacement>& models);

// A scene file (JSON): {"models": [{"file": "a.gltf", "translation": [x, y, z],
// "rotation": [rx, ry, rz], "scale": s, "sampler": {"wrap": "clamp", "wrap_u": ..., "wrap_v":
// ..., "min_filter": "nearest" (or a GL minification name), "mag_filter": "linear",
// "mipmap_mode": "none", "border_color": "opaque-white"}}, ...]} (every key but file optional);
// relative files are relative to the scene file.
// Throws tex::Error naming the file and the bad key or value.
std::vector<ModelPlacement> read_scene_file(const std::string& path);

}  // namespace tex

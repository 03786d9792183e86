// Textured 3D models: geometry and materials through Assimp, textures through texture_io
// (OpenImageIO). Everything the rasterizer needs is copied out of Assimp's scene here.
#include "workloads/mesh_scene.h"

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <tuple>

#include "model/error.h"
#include "workloads/limits.h"
#include "workloads/output_files.h"
#include "workloads/text.h"
#include "workloads/texture_io.h"

namespace tex {

namespace fs = std::filesystem;

namespace {

// A library's message (Assimp's, nlohmann's) on one line: every control character a space.
std::string one_line(std::string s) {
  std::replace_if(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; }, ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// Throws unless `path` is a regular file (a directory or a FIFO would hang or confuse the readers).
void check_regular_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw Error(path + ": cannot read " + what + ": no such file");
  if (!fs::is_regular_file(st)) throw Error(path + ": cannot read " + what + ": not a regular file");
}

Wrap to_wrap(int mode) {
  switch (mode) {
    case aiTextureMapMode_Clamp:
    case aiTextureMapMode_Decal: return Wrap::Clamp;  // decal: no texel outside [0, 1]; clamp is closest
    case aiTextureMapMode_Mirror: return Wrap::Mirror;
    default: return Wrap::Repeat;
  }
}

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  glm::dmat4 r;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) r[col][row] = m[row][col];  // Assimp is row-major, GLM column-major
  return r;
}

// A texture name as the model writes it -> the file: relative to the model's directory, Windows
// separators (spider.mtl: ".\SpiderTex.jpg") as '/', and URI escapes (glTF: "my%20tex.png") decoded
// when the name as written does not exist.
fs::path literal_texture(const fs::path& dir, std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  const fs::path literal = (dir / name).lexically_normal();
  if (fs::exists(literal) || name.find('%') == std::string::npos) return literal;
  auto hex = [&](size_t i) { return i < name.size() && std::isxdigit(static_cast<unsigned char>(name[i])); };
  std::string decoded;
  for (size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '%' && hex(i + 1) && hex(i + 2)) {
      decoded += char(std::stoi(name.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += name[i];
    }
  }
  return (dir / decoded).lexically_normal();
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The regular file in `dir` whose name is `name` but for case (the exact name first, then the first
// in name order), or empty.
fs::path file_named(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return {};
  if (fs::is_regular_file(dir / name, ec)) return dir / name;
  std::vector<fs::path> found;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec))
    if (lower(e.path().filename().string()) == lower(name) && e.is_regular_file(ec)) found.push_back(e.path());
  if (found.empty()) return {};
  std::sort(found.begin(), found.end());
  return found[0];
}

// The texture file a model names (viewers' rules for files made on other machines): the path as
// written (literal_texture); else its file name, case aside, next to the model, then in the model
// folder's textures/ folder (case aside too). Never elsewhere: a path that names another folder is
// found there or by its name in the model's own folder. `by_name`: the second way found it.
fs::path resolve_texture(const fs::path& dir, const std::string& name, bool& by_name) {
  by_name = false;
  const fs::path literal = literal_texture(dir, name);
  if (fs::exists(literal)) return literal;
  std::string written = name;
  std::replace(written.begin(), written.end(), '\\', '/');
  const std::string file = fs::path(written).filename().string();
  if (file.empty() || file == "." || file == "..") return literal;
  std::vector<fs::path> places = {dir};
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec))
    if (lower(e.path().filename().string()) == "textures" && e.is_directory(ec)) places.push_back(e.path());
  for (const fs::path& place : places)
    if (const fs::path found = file_named(place, file); !found.empty()) {
      by_name = true;
      return found.lexically_normal();
    }
  return literal;
}

// Textures of a scene, each image once per pair of wrap modes (the same file with other wrap
// modes is another descriptor), in first-use order.
class SceneTextureSet {
 public:
  explicit SceneTextureSet(MeshScene& scene) : scene_(scene) {}

  // The index of the entry for (source, sampler of the file, sRGB or not), or -1.
  int find(const SceneTexture& t) const {
    const auto it = ids_.find(id_key(t));
    return it == ids_.end() ? -1 : it->second;
  }
  // An image already decoded for `source` (with other wrap modes), or null.
  const SceneTexture* any(const std::string& source) const {
    const std::string k = key(source);
    for (const auto& [entry, id] : ids_)
      if (std::get<0>(entry) == k) return &scene_.textures[size_t(id)];
    return nullptr;
  }
  int add(SceneTexture t) {
    const int id = int(scene_.textures.size());
    ids_[id_key(t)] = id;
    scene_.textures.push_back(std::move(t));
    return id;
  }

 private:
  // Two models may name one file by different relative paths.
  static std::string key(const std::string& source) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(source, ec);
    return ec ? source : p.string();
  }
  using IdKey = std::tuple<std::string, Wrap, Wrap, int, int, std::string, bool>;
  static IdKey id_key(const SceneTexture& t) {
    return {key(t.source), t.wrap_u, t.wrap_v, t.gltf_mag_filter, t.gltf_min_filter, t.scene_sampler.key(), t.srgb};
  }
  MeshScene& scene_;
  std::map<IdKey, int> ids_;
};

// Assimp 5.2's glTF 1.0 importer composes a node's translation, rotation and scale as R·S·T (the
// translation turned by the rotation: CesiumMilkTruck's front and rear wheels end up 0.49 apart
// in height); glTF says T·R·S. For such files the nodes' matrices are rebuilt from the JSON, walked alongside
// Assimp's node tree (same shape: scene nodes under the root, then "children" in order).
using NodeTransforms = std::map<const aiNode*, glm::dmat4>;

void gltf1_transforms(const nlohmann::json& nodes, const std::string& id, const aiNode& ai, NodeTransforms& out) {
  const nlohmann::json& n = nodes.at(id);
  if (id != ai.mName.C_Str() && n.value("name", id) != ai.mName.C_Str()) return;  // not the tree we expected
  if (!n.contains("matrix") && (n.contains("translation") || n.contains("rotation") || n.contains("scale"))) {
    const auto v = [&](const char* key, std::vector<double> fallback) { return n.value(key, fallback); };
    const std::vector<double> t = v("translation", {0, 0, 0}), r = v("rotation", {0, 0, 0, 1}), s = v("scale", {1, 1, 1});
    if (t.size() == 3 && r.size() == 4 && s.size() == 3)
      out[&ai] = glm::translate(glm::dmat4(1.0), glm::dvec3(t[0], t[1], t[2])) *
                 glm::mat4_cast(glm::dquat(r[3], r[0], r[1], r[2])) *  // glTF writes x, y, z, w
                 glm::scale(glm::dmat4(1.0), glm::dvec3(s[0], s[1], s[2]));
  }
  const std::vector<std::string> children = n.value("children", std::vector<std::string>{});
  if (children.size() == ai.mNumChildren)
    for (size_t i = 0; i < children.size(); ++i) gltf1_transforms(nodes, children[i], *ai.mChildren[i], out);
}

// The importer that read the file, as Assimp records it ("glTF Importer" for glTF 1.0, "glTF2
// Importer" for 2.0, ...); "" if it does not say.
std::string source_format(const aiScene& ai) {
  aiString format;
  if (!ai.mMetaData || !ai.mMetaData->Get("SourceAsset_Format", format)) return "";
  return format.C_Str();
}

NodeTransforms gltf1_transforms(const aiScene& ai, const std::string& path) {
  if (source_format(ai) != "glTF Importer") return {};
  NodeTransforms out;
  try {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    const nlohmann::json& nodes = j.at("nodes");
    const auto roots = j.at("scenes").at(j.at("scene").get<std::string>()).at("nodes").get<std::vector<std::string>>();
    if (roots.size() == 1) gltf1_transforms(nodes, roots[0], *ai.mRootNode, out);  // the root itself
    else if (roots.size() == ai.mRootNode->mNumChildren)
      for (size_t i = 0; i < roots.size(); ++i) gltf1_transforms(nodes, roots[i], *ai.mRootNode->mChildren[i], out);
  } catch (const nlohmann::json::exception&) {
    return {};  // Assimp read it; a shape this walk does not know keeps Assimp's matrices
  }
  return out;
}

void compute_bounds(MeshScene& scene) {
  bool first = true;
  for (const DrawMesh& m : scene.meshes)
    for (const glm::dvec3& p : m.positions) {
      scene.bounds_min = first ? p : glm::min(scene.bounds_min, p);
      scene.bounds_max = first ? p : glm::max(scene.bounds_max, p);
      first = false;
    }
}

class ModelLoader {
 public:
  ModelLoader(const aiScene& ai, const std::string& path, MeshScene& out, bool mirror = false)
      : mirror_(mirror), ai_(ai), path_(path), dir_(fs::path(path).parent_path()), out_(out), textures_(out),
        material_texture_(ai.mNumMaterials, kUnknown), mesh_noted_(ai.mNumMeshes, false),
        fixed_transforms_(gltf1_transforms(ai, path)), gltf2_(source_format(ai) == "glTF2 Importer") {}

  // Draw order: the node tree depth first, each node's meshes in its list order, then its
  // children in order (a mesh that several nodes reference is drawn once per node, as placed).
  void walk(const aiNode& node, const glm::dmat4& parent) {
    const auto fixed = fixed_transforms_.find(&node);
    const glm::dmat4 world = parent * (fixed != fixed_transforms_.end() ? fixed->second : to_glm(node.mTransformation));
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
      if (node.mMeshes[i] < ai_.mNumMeshes) add_mesh(node.mMeshes[i], world);
    for (unsigned i = 0; i < node.mNumChildren; ++i)
      if (node.mChildren[i]) walk(*node.mChildren[i], world);
  }

 private:
  static constexpr int kUnknown = -2, kNone = -1;

  void skip(unsigned index, const std::string& name, const std::string& why) {
    if (!mesh_noted_[index]) out_.notes.push_back(path_ + ": mesh " + quote_name(name) + " skipped: " + why);
    mesh_noted_[index] = true;
  }

  void add_mesh(unsigned index, const glm::dmat4& world) {
    const aiMesh& m = *ai_.mMeshes[index];
    DrawMesh d;
    d.name = m.mName.length ? m.mName.C_Str() : "mesh " + std::to_string(index);
    if (mirror_) return add_mirror(m, index, world, std::move(d));
    if (!m.HasTextureCoords(0)) return skip(index, d.name, "no texture coordinates");
    if (m.mMaterialIndex >= ai_.mNumMaterials) return skip(index, d.name, "no material");
    d.texture = texture_of(m.mMaterialIndex);
    if (d.texture == kNone)
      return skip(index, d.name, "material " + quote_name(material_name(m.mMaterialIndex)) +
                                     " has no base-colour or diffuse texture");
    int two_sided = 0;
    ai_.mMaterials[m.mMaterialIndex]->Get(AI_MATKEY_TWOSIDED, two_sided);
    d.double_sided = two_sided != 0;

    d.positions.reserve(m.mNumVertices);
    d.uvs.reserve(m.mNumVertices);
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiVector3D& p = m.mVertices[i];
      const aiVector3D& t = m.mTextureCoords[0][i];
      const glm::dvec3 w(world * glm::dvec4(p.x, p.y, p.z, 1.0));
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
        throw Error(path_ + ": mesh " + quote_name(d.name) + ": vertex " + std::to_string(i) + " has a non-finite position");
      if (!std::isfinite(t.x) || !std::isfinite(t.y))
        throw Error(path_ + ": mesh " + quote_name(d.name) + ": vertex " + std::to_string(i) +
                    " has non-finite texture coordinates");
      d.positions.push_back(w);
      d.uvs.emplace_back(t.x, t.y);  // FlipUVs made v = 0 the image's top row
    }
    // A mirroring transform turns counter-clockwise (front) triangles clockwise: swap two corners.
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines the sort step left in a mixed mesh
      const unsigned* i = face.mIndices;
      if (std::max({i[0], i[1], i[2]}) >= m.mNumVertices) continue;
      d.indices.insert(d.indices.end(), {i[0], mirrored ? i[2] : i[1], mirrored ? i[1] : i[2]});
    }
    if (d.indices.empty()) return skip(index, d.name, "no triangles");
    out_.meshes.push_back(std::move(d));
  }

  // A mirror's mesh: positions and world-space normals (by the inverse transpose), no texture.
  void add_mirror(const aiMesh& m, unsigned index, const glm::dmat4& world, DrawMesh d) {
    if (!m.HasNormals()) return skip(index, d.name, "no normals");
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiVector3D& p = m.mVertices[i];
      const aiVector3D& n = m.mNormals[i];
      const glm::dvec3 w(world * glm::dvec4(p.x, p.y, p.z, 1.0)), wn = normal_matrix * glm::dvec3(n.x, n.y, n.z);
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) || !std::isfinite(wn.x) ||
          !std::isfinite(wn.y) || !std::isfinite(wn.z))
        throw Error(path_ + ": mesh " + quote_name(d.name) + ": vertex " + std::to_string(i) + " has a non-finite position or normal");
      d.positions.push_back(w);
      d.uvs.emplace_back(0.0, 0.0);
      d.normals.push_back(wn);
    }
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;
      const unsigned* i = face.mIndices;
      if (std::max({i[0], i[1], i[2]}) >= m.mNumVertices) continue;
      d.indices.insert(d.indices.end(), {i[0], mirrored ? i[2] : i[1], mirrored ? i[1] : i[2]});
    }
    if (d.indices.empty()) return skip(index, d.name, "no triangles");
    d.texture = 0;
    out_.meshes.push_back(std::move(d));
  }

  std::string material_name(unsigned index) const {
    const aiString name = ai_.mMaterials[index]->GetName();
    return name.length ? name.C_Str() : "material " + std::to_string(index);
  }

  // The material's base-colour texture (glTF 2), else its diffuse one (glTF 1, OBJ, COLLADA, ...;
  // Assimp 5.2 also lists glTF 2's base colour as diffuse): its index in the table, or kNone.
  // glTF 2's base colour is sRGB-encoded (glTF 2.0 §3.9.2); the other formats do not say, and
  // their textures are taken as linear unless `--srgb`.
  int texture_of(unsigned material) {
    int& id = material_texture_[material];
    if (id != kUnknown) return id;
    const aiMaterial& mat = *ai_.mMaterials[material];
    id = kNone;
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
      aiString name;
      if (mat.GetTextureCount(type) == 0 || mat.GetTexture(type, 0, &name) != AI_SUCCESS || name.length == 0) continue;
      int u = aiTextureMapMode_Wrap, v = aiTextureMapMode_Wrap;  // formats without sampler modes repeat
      mat.Get(AI_MATKEY_MAPPINGMODE_U(type, 0), u);
      mat.Get(AI_MATKEY_MAPPINGMODE_V(type, 0), v);
      int mag = 0, min = 0;  // glTF's sampler filters (Assimp's glTF importers set them when the file has them)
      mat.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), mag);
      mat.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MIN(type, 0), min);
      int uv_set = 0;
      if (mat.Get(AI_MATKEY_UVWSRC(type, 0), uv_set) == AI_SUCCESS && uv_set != 0)
        out_.notes.push_back(path_ + ": material " + quote_name(material_name(material)) + " names texture coordinate set " +
                             std::to_string(uv_set) + "; set 0 is used");
      id = texture(material, name.C_Str(), to_wrap(u), to_wrap(v), mag, min, gltf2_);
      break;
    }
    return id;
  }

  int texture(unsigned material, const std::string& name, Wrap wrap_u, Wrap wrap_v, int mag, int min, bool srgb) {
    SceneTexture t;
    t.material = material_name(material);
    t.wrap_u = wrap_u;
    t.wrap_v = wrap_v;
    t.gltf_mag_filter = mag;
    t.gltf_min_filter = min;
    t.srgb = srgb;
    const auto [embedded, embedded_index] = ai_.GetEmbeddedTextureAndIndex(name.c_str());
    if (embedded) {
      t.source = path_ + "#embedded:" + std::to_string(embedded_index);
    } else if (name[0] == '*') {
      throw Error(path_ + ": material " + quote_name(t.material) + ": embedded texture " + name + " does not exist");
    } else {
      bool by_name = false;
      t.source = resolve_texture(dir_, name, by_name).string();
      if (!fs::exists(t.source))
        throw Error(path_ + ": material " + quote_name(t.material) + ": texture file not found: " + t.source +
                    " (nor " + fs::path(name).filename().string() + ", case aside, beside the model or in its textures/)");
      if (by_name && std::find(resolved_.begin(), resolved_.end(), name) == resolved_.end()) {
        resolved_.push_back(name);
        out_.notes.push_back(path_ + ": material " + quote_name(t.material) + " names texture " + quote_name(name) +
                             ", not there as written; found by its name: " + t.source);
      }
    }
    if (const int id = textures_.find(t); id >= 0) return id;

    if (const SceneTexture* same = textures_.any(t.source)) {  // decoded already, other wrap modes
      t.image = same->image;
      t.file_width = same->file_width;
      t.file_height = same->file_height;
      t.resized = same->resized;
      return textures_.add(std::move(t));
    }
    ModelTexture loaded;
    try {
      if (!embedded) {
        check_regular_file(t.source, "texture");
        loaded = load_model_texture(t.source);
      } else if (embedded->mHeight == 0) {  // compressed: mWidth bytes of a PNG, JPEG, ...
        loaded = decode_model_texture(t.source, embedded->pcData, embedded->mWidth, embedded->achFormatHint);
      } else {  // mWidth x mHeight texels, ARGB8888
        Image img(int(embedded->mWidth), int(embedded->mHeight));
        for (size_t i = 0; i < img.texels.size(); ++i) {
          const aiTexel& p = embedded->pcData[i];
          img.texels[i] = {p.r, p.g, p.b, p.a};
        }
        loaded = model_texture(t.source, std::move(img));
      }
    } catch (const Error& e) {
      throw Error(path_ + ": material " + quote_name(t.material) + ": " + e.what());
    }
    t.image = std::move(loaded.image);
    t.file_width = loaded.file_width;
    t.file_height = loaded.file_height;
    t.resized = loaded.resized;
    if (t.resized)
      out_.notes.push_back("texture " + t.source + " (" + t.material + "): " + std::to_string(t.file_width) + "x" +
                           std::to_string(t.file_height) + " resampled to " + std::to_string(t.image.width) + "x" +
                           std::to_string(t.image.height));
    return textures_.add(std::move(t));
  }

  bool mirror_;                        // render --envmap: every mesh, with normals, no texture
  const aiScene& ai_;
  const std::string& path_;
  fs::path dir_;
  MeshScene& out_;
  SceneTextureSet textures_;
  std::vector<int> material_texture_;  // per material: texture index, kNone or kUnknown (not asked yet)
  std::vector<std::string> resolved_;   // texture names found by their file name (noted once each)
  std::vector<bool> mesh_noted_;       // per Assimp mesh: skip note written
  NodeTransforms fixed_transforms_;    // glTF 1.0: node matrices as the file means them
  bool gltf2_;                         // glTF 2.0: base colour textures are sRGB
};

glm::dmat4 placement_matrix(const ModelPlacement& p) {
  // Column vectors: the rightmost factor applies first (scale, rotation x, y, z, translation).
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), p.translation);
  m = glm::rotate(m, glm::radians(p.rotation_deg.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(p.rotation_deg.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(p.rotation_deg.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, glm::dvec3(p.scale));
}

}  // namespace

// An OFF file's header counts against what the file can hold, before Assimp allocates for them
// (Assimp 5.2's OFF importer reserves the header's vertex count: a 309-byte file claiming 3.5
// billion vertices took 7.5 GB). ASCII OFF: each vertex is at least "0 0 0\n" (6 bytes), each face
// at least "3 0 1 2\n" (8 bytes). Other formats pass unchanged.
void check_off_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  in >> magic;
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0) return;
  std::string token;
  uint64_t counts[2] = {0, 0};
  for (int i = 0; i < 2 && in >> token;) {
    if (token[0] == '#') {
      std::getline(in, token);
      continue;
    }
    if (token.find_first_not_of("0123456789") != std::string::npos || token.size() > 19) return;  // Assimp's to judge
    counts[i++] = std::stoull(token);
  }
  const uint64_t size = fs::file_size(path);
  if (counts[0] > size / 6 || counts[1] > size / 8)
    throw Error(path + ": OFF header claims " + std::to_string(counts[0]) + " vertices and " +
                std::to_string(counts[1]) + " faces; the file's " + std::to_string(size) +
                " bytes hold at most " + std::to_string(size / 6) + " and " + std::to_string(size / 8));
}

// The bytes an import reads: the file, and a .gltf's external buffers (a .gltf is a few KB of JSON
// that names its geometry's .bin files; data: URIs are in the file already).
uint64_t import_input_bytes(const std::string& path) {
  std::error_code ec;
  uint64_t bytes = fs::file_size(path, ec);
  if (ec) return 0;
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".gltf" || bytes > (uint64_t(64) << 20)) return bytes;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);  // (no exceptions: Assimp judges the file)
  if (!j.is_object() || !j.contains("buffers") || !j["buffers"].is_array()) return bytes;
  for (const nlohmann::json& b : j["buffers"]) {
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    const std::string uri = b["uri"].get<std::string>();
    if (uri.rfind("data:", 0) == 0) continue;
    const uint64_t size = fs::file_size(fs::path(path).parent_path() / uri, ec);
    if (!ec) bytes += size;
  }
  return bytes;
}

// Stops the run if an import outlives its time (workloads/limits.h): Assimp's importers cannot be
// interrupted, so the run ends here with one line, its staged outputs removed.
class ImportWatchdog {
 public:
  ImportWatchdog(const std::string& path, double seconds)
      : thread_([this, path, seconds] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (done_changed_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; })) return;
          std::fprintf(stderr, "texsim: error: %s: Assimp's import has run %g s, longer than a file of this size needs; "
                       "stopped (--import-timeout)\n", path.c_str(), seconds);
          exit_removing_outputs(1);
        }) {}
  ~ImportWatchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    done_changed_.notify_one();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_changed_;
  bool done_ = false;
  std::thread thread_;  // (last: it starts once the members it uses exist)
};

MeshScene load_model(const std::string& path, bool mirror) {
  check_regular_file(path, "model");
  check_off_header(path);
  // No Assimp DefaultLogger is created: Assimp stays silent, the one error line is ours.
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                         aiProcess_ValidateDataStructure |  // bad indices etc. fail the import, not us
                         aiProcess_FlipUVs |  // Assimp's v = 0 is the image's bottom (GL); ours is its top
                         (mirror ? aiProcess_GenSmoothNormals : 0u);  // (a mirror's normals, where the file has none)
  const aiScene* ai = nullptr;
  // The import within its memory and time (workloads/limits.h). An allocation past its budget or
  // the data limit fails inside the importer, which reports it as its error string.
  const uint64_t input = import_input_bytes(path);
  const uint64_t budget_bytes = import_memory(input);
  bool over_budget = false;
  const auto out_of_memory = [&] {
    if (!over_budget || budget_bytes >= memory_limit())
      return Error(path + ": Assimp ran out of memory importing it (more than --max-memory allows: " +
                   memory_words(memory_limit()) + ")");
    return Error(path + ": Assimp's import needs more than " + memory_words(budget_bytes) + " (--import-memory" +
                 (import_memory_given() ? "" : "'s default: 256 MiB plus 64 times the " + std::to_string(input) + " bytes it reads") +
                 ")");
  };
  try {
    const ImportWatchdog watchdog(path, import_timeout(input));
    const AllocationBudget budget(budget_bytes);
    try {
      ai = importer.ReadFile(path, flags);
    } catch (...) {
      over_budget = budget.exceeded();
      throw;
    }
    over_budget = budget.exceeded();
  } catch (const std::bad_alloc&) {
    throw out_of_memory();
  } catch (const std::exception& e) {
    throw Error(path + ": cannot read model: " + one_line(e.what()));
  }
  if (!ai || !ai->mRootNode) {
    const std::string why = one_line(importer.GetErrorString());
    if (over_budget || why.find("bad_alloc") != std::string::npos) throw out_of_memory();
    throw Error(path + ": cannot read model: " + (why.empty() ? "no scene" : why));
  }
  MeshScene scene;
  ModelLoader(*ai, path, scene, mirror).walk(*ai->mRootNode, glm::dmat4(1.0));
  if (scene.meshes.empty()) {  // say why, from the first skip note ("<path>: mesh 'x' skipped: ...")
    std::string why = "no meshes";
    for (const std::string& note : scene.notes)
      if (note.rfind(path + ": mesh ", 0) == 0) {
        why = note.substr(path.size() + 2);
        break;
      }
    throw Error(path + ": nothing to draw: " + why + " (" + std::to_string(ai->mNumMeshes) + " meshes in the file)");
  }
  compute_bounds(scene);
  return scene;
}

MeshScene load_models(const std::vector<ModelPlacement>& models) {
  if (models.empty()) throw Error("no models to load");
  MeshScene out;
  SceneTextureSet table(out);
  std::map<std::string, MeshScene> cache;  // a model placed twice is read once
  for (const ModelPlacement& p : models) {
    const glm::dvec3 tr = p.translation, rot = p.rotation_deg;
    for (double x : {tr.x, tr.y, tr.z, rot.x, rot.y, rot.z, p.scale})
      if (!std::isfinite(x)) throw Error(p.path + ": placement has a non-finite number");
    if (!(p.scale > 0)) throw Error(p.path + ": placement scale must be greater than 0");

    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(p.path, ec);
    auto [it, inserted] = cache.try_emplace(ec ? p.path : canonical.string());
    if (inserted) {
      it->second = load_model(p.path);
      out.notes.insert(out.notes.end(), it->second.notes.begin(), it->second.notes.end());
    }
    const MeshScene& model = it->second;
    std::vector<int> ids;  // the model's texture index -> the merged scene's
    for (SceneTexture t : model.textures) {
      t.scene_sampler = p.sampler;
      const int id = table.find(t);
      ids.push_back(id >= 0 ? id : table.add(t));
    }
    const glm::dmat4 m = placement_matrix(p);
    for (DrawMesh d : model.meshes) {
      for (glm::dvec3& v : d.positions) v = glm::dvec3(m * glm::dvec4(v, 1.0));
      d.texture = ids[size_t(d.texture)];
      out.meshes.push_back(std::move(d));
    }
  }
  compute_bounds(out);
  return out;
}

std::vector<ModelPlacement> read_scene_file(const std::string& path) {
  check_regular_file(path, "scene file");
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open scene file");
  check_json_memory(path);
  nlohmann::json j;
  std::string last_key;  // where a syntax error or a number too large for a double (1e999) is
  try {
    j = nlohmann::json::parse(in, [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
      if (event == nlohmann::json::parse_event_t::key) last_key = parsed.get<std::string>();
      return true;
    });
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not a valid JSON scene file" + (last_key.empty() ? "" : " (after key " + quote_clipped(last_key) + ")") +
                ": " + one_line(e.what()));
  }
  auto fail = [&](const std::string& where, const std::string& what) { throw Error(path + ": " + where + ": " + what); };
  auto number = [&](const nlohmann::json& v, const std::string& where) {
    if (!v.is_number()) fail(where, "must be a number, not " + one_line(v.dump()));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(where, "must be a finite number");
    return x;
  };
  auto vec3 = [&](const nlohmann::json& v, const std::string& where) {
    if (!v.is_array() || v.size() != 3) fail(where, "must be a list of 3 numbers, not " + one_line(v.dump()));
    return glm::dvec3(number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]"));
  };

  if (!j.is_object()) fail("top level", "must be an object {\"models\": [...]}");
  for (const auto& [key, value] : j.items())
    if (key != "models") fail(quote_name(key), "unknown key (the scene file has \"models\")");
  if (!j.contains("models")) fail("\"models\"", "missing");
  const nlohmann::json& list = j["models"];
  if (!list.is_array()) fail("models", "must be a list of models");
  if (list.empty()) fail("models", "is empty: give at least one model");

  const fs::path dir = fs::path(path).parent_path();
  std::vector<ModelPlacement> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = "models[" + std::to_string(i) + "]";
    const nlohmann::json& m = list[i];
    if (!m.is_object()) fail(where, "must be an object {\"file\": ...}");
    ModelPlacement p;
    for (const auto& [key, value] : m.items()) {
      const std::string at = where + "." + key;
      if (key == "file") {
        if (!value.is_string() || value.get<std::string>().empty()) fail(at, "must be a file name");
        const fs::path file = value.get<std::string>();
        p.path = (file.is_relative() ? dir / file : file).string();  // relative to the scene file
      } else if (key == "translation") {
        p.translation = vec3(value, at);
      } else if (key == "rotation") {
        p.rotation_deg = vec3(value, at);
      } else if (key == "scale") {
        p.scale = number(value, at);
        if (p.scale <= 0) fail(at, "must be greater than 0, not " + value.dump());
      } else if (key == "sampler") {
        if (!value.is_object()) fail(at, "must be an object {\"wrap\": ..., \"min_filter\": ..., ...}");
        for (const auto& [field, v] : value.items()) {
          const std::string fat = at + "." + field;
          if (!v.is_string()) fail(fat, "must be a name, not " + one_line(v.dump()));
          const std::string name = v.get<std::string>();
          SamplerOverride& o = p.sampler;
          if (field == "wrap" || field == "wrap_u" || field == "wrap_v") {
            Wrap w;
            if (!parse_wrap(name, w)) fail(fat, "unknown address mode " + quote_clipped(name) + " (" + kWrapNames + ")");
            if (field != "wrap_v") o.wrap_u = w;
            if (field != "wrap_u") o.wrap_v = w;
          } else if (field == "min_filter") {
            TexelFilter t;
            std::optional<MipMode> mip;  // a GL minification name gives the mipmap mode too
            if (!parse_min_filter(name, t, mip))
              fail(fat, "unknown minification filter " + quote_clipped(name) + " (nearest, linear, or a GL name)");
            o.min_filter = t;
            if (mip && !o.mipmap_mode) o.mipmap_mode = mip;
          } else if (field == "mag_filter") {
            TexelFilter t;
            if (!parse_texel_filter(name, t)) fail(fat, "unknown magnification filter " + quote_clipped(name) + " (nearest, linear)");
            o.mag_filter = t;
          } else if (field == "mipmap_mode") {
            MipMode m;
            if (!parse_mip_mode(name, m)) fail(fat, "unknown mipmap mode " + quote_clipped(name) + " (none, nearest, linear)");
            o.mipmap_mode = m;
          } else if (field == "border_color") {
            BorderColor b;
            if (!parse_border_color(name, b)) fail(fat, "unknown border colour " + quote_clipped(name) + " (transparent-black, opaque-black, opaque-white)");
            o.border_color = b;
          } else if (field == "reduction") {
            Reduction r;
            if (!parse_reduction(name, r)) fail(fat, "unknown reduction " + quote_clipped(name) + " (weighted-average, min, max)");
            o.reduction = r;
          } else {
            fail(fat, "unknown sampler field (wrap, wrap_u, wrap_v, min_filter, mag_filter, mipmap_mode, border_color, "
                      "reduction)");
          }
        }
      } else {
        fail(at, "unknown key (a model has file, translation, rotation, scale, sampler)");
      }
    }
    if (p.path.empty()) fail(where + ".file", "missing");
    out.push_back(std::move(p));
  }
  return out;
}

std::string SamplerOverride::key() const {
  std::string k;
  auto add = [&](bool has, int v) { k += has ? std::to_string(v) + "," : "-,"; };
  add(wrap_u.has_value(), wrap_u ? int(*wrap_u) : 0);
  add(wrap_v.has_value(), wrap_v ? int(*wrap_v) : 0);
  add(min_filter.has_value(), min_filter ? int(*min_filter) : 0);
  add(mag_filter.has_value(), mag_filter ? int(*mag_filter) : 0);
  add(mipmap_mode.has_value(), mipmap_mode ? int(*mipmap_mode) : 0);
  add(border_color.has_value(), border_color ? int(*border_color) : 0);
  add(reduction.has_value(), reduction ? int(*reduction) : 0);
  return k;
}

SamplerConfig file_sampler(const SceneTexture& t, SamplerConfig base, bool keep_filter, bool keep_wrap) {
  if (!keep_wrap) {
    base.wrap_u = t.wrap_u;
    base.wrap_v = t.wrap_v;
  }
  if (!keep_filter) {
    switch (t.gltf_mag_filter) {  // GL_NEAREST, GL_LINEAR
      case 9728: base.filter.mag = TexelFilter::Nearest; break;
      case 9729: base.filter.mag = TexelFilter::Linear; break;
    }
    const int min = t.gltf_min_filter;
    if (min == 9728 || min == 9729) {  // no MIPMAP: level 0 only
      base.filter.texel = min == 9728 ? TexelFilter::Nearest : TexelFilter::Linear;
      base.filter.mip = MipMode::None;
    } else if (min >= 9984 && min <= 9987) {  // {NEAREST, LINEAR}_MIPMAP_{NEAREST, LINEAR}
      base.filter.texel = (min - 9984) % 2 ? TexelFilter::Linear : TexelFilter::Nearest;
      base.filter.mip = min >= 9986 ? MipMode::Linear : MipMode::Nearest;
    }
  }
  const SamplerOverride& o = t.scene_sampler;
  if (o.wrap_u) base.wrap_u = *o.wrap_u;
  if (o.wrap_v) base.wrap_v = *o.wrap_v;
  if (o.min_filter) base.filter.texel = *o.min_filter;
  if (o.mag_filter) base.filter.mag = *o.mag_filter;
  if (o.mipmap_mode) base.filter.mip = *o.mipmap_mode;
  if (o.border_color) base.border = *o.border_color;
  if (o.reduction) base.reduction = *o.reduction;
  return base;
}

}  // namespace tex

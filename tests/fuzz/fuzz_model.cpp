// Model files (workloads/mesh_scene.h, render --model): Assimp's import, then the loader's own
// checks of what it returns (header pre-checks, indices, NaN, textures, the mirror's normals).
// The first byte picks the file's extension (Assimp chooses its importer by it), and whether the
// model is loaded as a mirror; the rest is the file. (Debian's Assimp is not instrumented: the
// fuzzer's coverage is the loader's, its inputs any format's.)
#include "fuzz_target.h"
#include "workloads/mesh_scene.h"

namespace {
constexpr const char* kExtensions[] = {"obj", "off", "ply", "stl", "gltf", "glb", "dae", "3ds", "x", "lwo",
                                       "ase", "ms3d", "md2", "md3", "mdl", "smd", "nff", "ac", "b3d", "cob",
                                       "irrmesh", "q3o", "dxf", "fbx"};
constexpr size_t kFormats = sizeof kExtensions / sizeof kExtensions[0];
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const size_t format = (data[0] & 0x7F) % kFormats;
  const bool mirror = data[0] >= 128;
  const std::string path = tex::fuzz::input_file(data + 1, size - 1, std::string("model.") + kExtensions[format]);
  try {
    tex::load_model(path, mirror);
  } catch (const tex::Error& e) {
    tex::fuzz::check_error(e, path);
  }
  return 0;
}

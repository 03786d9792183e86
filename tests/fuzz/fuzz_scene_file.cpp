// Scene files (workloads/mesh_scene.h, render --scene-file): the JSON and every model's placement
// and sampler fields (the models they name are model files: fuzz_model's).
#include "fuzz_target.h"
#include "workloads/mesh_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = tex::fuzz::input_file(data, size, "scene.json");
  try {
    for (const tex::ModelPlacement& m : tex::read_scene_file(path)) m.sampler.key();
  } catch (const tex::Error& e) {
    tex::fuzz::check_error(e, path);
  }
  return 0;
}

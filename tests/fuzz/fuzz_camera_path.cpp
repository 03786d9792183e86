// Camera paths (workloads/camera.h, render --camera-path): JSON keyframes, then every frame's view.
#include "fuzz_target.h"
#include "workloads/camera.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = tex::fuzz::input_file(data, size, "camera.json");
  try {
    const std::vector<tex::Camera> keys = tex::read_camera_path(path);
    for (int frame = 0; frame < 8; ++frame) {
      const tex::Camera c = tex::camera_on_path(keys, frame, 8);
      tex::view_projection(c, 4.0 / 3.0, glm::dvec3(-1.0), glm::dvec3(1.0));
    }
  } catch (const tex::Error& e) {
    tex::fuzz::check_error(e, path);
  }
  return 0;
}

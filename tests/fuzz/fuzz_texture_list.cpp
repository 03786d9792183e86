// Texture lists (workloads/texture_list.h): every line's fields and sampler checks.
#include "fuzz_target.h"
#include "workloads/texture_list.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = tex::fuzz::input_file(data, size, "textures.txt");
  try {
    tex::read_texture_list(path, tex::SamplerConfig{});
  } catch (const tex::Error& e) {
    tex::fuzz::check_error(e, path);
  }
  return 0;
}

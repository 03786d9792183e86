// DDS, KTX 1 and KTX2 (workloads/texture_files.h): the header checks, then every image's pyramid
// decoded as the sampler reads it, through texsim's entry point (load_layers).
#include "fuzz_target.h"
#include "workloads/texture_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = tex::fuzz::input_file(data, size, "texture");
  try {
    const bool signature = tex::is_texture_file(path);
    tex::read_texture_file(path);
    if (!signature) std::abort();  // read, though is_texture_file said it is not a texture file
    tex::load_layers(path, tex::TextureOptions{});
  } catch (const tex::Error& e) {
    tex::fuzz::check_error(e, path);
  }
  return 0;
}

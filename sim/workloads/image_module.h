// The image module (libtexsim_images.so): OpenImageIO behind plain 8-bit buffers, and Mesa's BC7
// encoder (the one in Debian; libsquish stops at BC5). texsim loads it
// with dlopen on the first image file it reads or writes that is not a PNG or JPEG (those go
// through libpng and libjpeg: workloads/png_jpeg.h), so that a run without such files does not
// load OpenImageIO's 260 shared libraries (0.4 s).
// texture_io.cpp is its user in texsim (the CLI tests' fixture writes and reads images through it
// too); everything here is the module's ABI with the host (the same
// compiler and libstdc++: std::string and std::vector pass through).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tex::images {

// 8-bit pixels as stored: `channels` interleaved values per pixel, row by row.
struct Pixels {
  int width = 0, height = 0, channels = 0;
  bool floating_point = false;  // the file holds floats (the 8-bit values are clamped to 0..1)
  std::vector<uint8_t> values;
};

// Every function returns false and sets `error` (one line, no file name) on failure.
struct Module {
  // The first subimage of `file`, or of the `size` bytes at `data` (then `file` only names the
  // format by its extension), as 8 bits per channel. Texels are data: unassociated alpha is kept as
  // stored (OpenImageIO would premultiply it). An image whose header's size needs more than
  // `max_bytes` once read (decoded_image_bytes, workloads/limits.h) is refused before any pixel is.
  bool (*read)(const std::string& file, const void* data, size_t size, uint64_t max_bytes, Pixels& out,
               std::string& error);
  // A float file's values outside 0..1: how many, the least and the largest (0 when none).
  bool (*float_range)(const std::string& file, size_t& outside, size_t& total, float& low, float& high);
  // Resamples to w x h (OpenImageIO's default filter), the channels kept.
  bool (*resize)(Pixels& pixels, int w, int h, std::string& error);
  // Whether OpenImageIO has a writer for the extension of `path`.
  bool (*can_write)(const std::string& path);
  // Writes RGBA8 `pixels` to `write_path` in the format of the extension of `format_path`.
  bool (*write)(const std::string& format_path, const std::string& write_path, const Pixels& pixels,
                std::string& error);
  // RGBA8 `pixels` as BC7 blocks (row-major 4x4 blocks), by Mesa's BPTC encoder through OSMesa
  // (glTexImage2D to GL_COMPRESSED_RGBA_BPTC_UNORM, then glGetCompressedTexImage).
  bool (*compress_bc7)(const Pixels& pixels, std::vector<uint8_t>& blocks, std::string& error);
};

// The host side: the module, loaded on the first call (TEXSIM_IMAGE_MODULE names another file).
// Throws tex::Error naming the file when it cannot be loaded.
const Module& module();

}  // namespace tex::images

// The module's one exported symbol.
extern "C" const tex::images::Module* texsim_images_module();

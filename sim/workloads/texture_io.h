// Texture files and pictures: PNG and JPEG through libpng and libjpeg, every other format through
// OpenImageIO (the model itself does no file I/O).
#pragma once
#include <cstddef>
#include <string>

#include "model/image.h"
#include "workloads/output_files.h"

namespace tex {

// A texture is an image file (PNG, JPEG, or any format OpenImageIO reads), or a built-in pattern: NAME or NAME:WxH
// (default 512x512). Files become RGBA8 (gray -> RGB, missing alpha -> opaque).
// Sizes may be anything from 1 to 8192 per side; with resize = true a side that is not a power of
// two is resampled (OpenImageIO, to the nearest power of two, at most 8192). Values of float images
// outside 0..1 are clamped, with one note on stderr. Throws tex::Error.
Image load_texture(const std::string& spec, bool resize = false);
// Whether `spec` names a built-in pattern (NAME or NAME:WxH) rather than a file.
bool is_pattern_spec(const std::string& spec);

// A texture of a 3D model (workloads/mesh_scene.h): RGBA8 as above, of the file's size (any); a
// side beyond 8192 is resampled down to 8192 with OpenImageIO's resize, and nothing is printed:
// the caller reports `resized`. Throws tex::Error naming `name`.
struct ModelTexture {
  Image image;
  int file_width = 0, file_height = 0;  // as stored
  bool resized = false;
};
// From an image file.
ModelTexture load_model_texture(const std::string& path);
// From an encoded image in memory (PNG, JPEG, ... bytes, e.g. embedded in a GLB); the format is
// recognised from the bytes (PNG, JPEG) or else taken from `format_hint`, a file extension.
ModelTexture decode_model_texture(const std::string& name, const void* data, size_t size,
                                  const std::string& format_hint);
// From 8-bit RGBA texels already decoded (e.g. Assimp's uncompressed embedded textures).
ModelTexture model_texture(const std::string& name, Image rgba8);

// Throws tex::Error unless OpenImageIO has a writer for the extension of `path` (check it before
// the work).
void check_image_path(const std::string& path);

// Writes 8-bit RGBA (channels wider than 8 bits are scaled) to out.write_path(), in the format of
// the extension of out.path(). Throws tex::Error.
void save_image(const Image& img, const OutputFile& out);

}  // namespace tex

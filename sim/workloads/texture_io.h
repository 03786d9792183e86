// Texture files and pictures through OpenImageIO (the model itself does no file I/O).
#pragma once
#include <string>

#include "model/image.h"
#include "workloads/output_files.h"

namespace tex {

// A texture is a file that OpenImageIO reads, or a built-in pattern: NAME or NAME:WxH
// (default 512x512). Files become RGBA8 (gray -> RGB, missing alpha -> opaque).
// Sizes must be powers of two from 1 to 8192 per side; with resize = true other sizes are
// resampled (OpenImageIO, to the nearest power of two, at most 8192). Values of float images
// outside 0..1 are clamped, with one note on stderr. Throws tex::Error.
Image load_texture(const std::string& spec, bool resize = false);

// Throws tex::Error unless OpenImageIO has a writer for the extension of `path` (check it before
// the work).
void check_image_path(const std::string& path);

// Writes 8-bit RGBA (channels wider than 8 bits are scaled) to out.write_path(), in the format of
// the extension of out.path(). Throws tex::Error.
void save_image(const Image& img, const OutputFile& out);

}  // namespace tex

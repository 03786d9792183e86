// Texture files and pictures through OpenImageIO (the model itself does no file I/O).
#pragma once
#include <string>

#include "model/image.h"

namespace tex {

// A texture is a file that OpenImageIO reads, or a built-in pattern: NAME or NAME:WxH
// (default 512x512). Files become RGBA8 (gray -> RGB, missing alpha -> opaque).
// Sizes must be powers of two from 1 to 2048 per side; with resize = true other sizes are
// resampled (OpenImageIO, to the nearest power of two, at most 2048). Throws tex::Error.
Image load_texture(const std::string& spec, bool resize = false);

// Writes 8-bit RGBA (channels wider than 8 bits are scaled) to PATH.partial.EXT, then renames it,
// so a failed write leaves nothing behind. Throws tex::Error.
void save_image(const Image& img, const std::string& path);

}  // namespace tex

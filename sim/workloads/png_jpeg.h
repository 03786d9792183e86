// PNG and JPEG, the common texture files, through libpng and libjpeg directly: reading one costs
// milliseconds, where loading the image module (OpenImageIO and its 260 libraries) costs 0.4 s
// at the start of every run (docs/performance.md, "Start-up"). texture_io.cpp tries these first
// and hands the image module whatever they do not take.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "workloads/image_module.h"

namespace tex::images {

// The outcome of a direct read: the pixels, a file these readers leave to OpenImageIO (16-bit PNG,
// a JPEG in CMYK, not a PNG or JPEG at all), or a broken file (then `error` says why in one line;
// the caller may still ask OpenImageIO, whose message is the one users know), or a header whose
// size needs more than `max_bytes` once read (decoded_image_bytes, workloads/limits.h: `error`
// says so; nothing was allocated for it).
enum class Direct { Read, NotMine, Broken, TooLarge };

// An 8-bit (or 1, 2, 4-bit) PNG of any colour type, palette and tRNS expanded, or a baseline or
// progressive JPEG in gray, RGB or YCbCr, from `file` or from the `size` bytes at `data`; the
// format is known by its first bytes. The values are what OpenImageIO gives for the same file
// (tests/sim/test_png_jpeg.cpp checks them equal on every PNG and JPEG of assimp-testmodels and on
// each PNG colour type and bit depth): as stored, no gamma applied, alpha unassociated, gray as
// one channel (two with alpha), palette as RGB (RGBA with tRNS), JPEG through libjpeg's default
// (islow) DCT and fancy upsampling.
Direct read_png_or_jpeg(const std::string& file, const void* data, size_t size, uint64_t max_bytes, Pixels& out,
                        std::string& error);

// Writes RGBA8 `pixels` as a PNG (no interlace, default compression) to `path`.
bool write_png(const std::string& path, const Pixels& pixels, std::string& error);

// Whether `path` names a PNG by its extension (.png, any case).
bool is_png_path(const std::string& path);

}  // namespace tex::images

// RGBA images of up to 16 bits per channel: loading (OpenImageIO), built-in patterns, saving.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "formats.h"

namespace tex {

struct Image {
  int width = 0;
  int height = 0;
  int channel_bits = kDefaultChannelBits;
  std::vector<Texel> texels;  // row-major, y = 0 is the top row

  Image() = default;
  Image(int w, int h, int bits = kDefaultChannelBits) : width(w), height(h), channel_bits(bits), texels(size_t(w) * h) {}
  Texel& at(int x, int y) { return texels[size_t(y) * width + x]; }
  const Texel& at(int x, int y) const { return texels[size_t(y) * width + x]; }
};

bool is_power_of_two(int n);
int log2_exact(int n);  // n must be a power of two

// Names of the built-in patterns, for --help and error messages.
const std::vector<std::string>& pattern_names();

// A texture is a file that OpenImageIO reads, or a built-in pattern: NAME or NAME:WxH
// (default 512x512). Files become RGBA8 (gray -> RGB, missing alpha -> opaque).
// Sizes must be powers of two from 1 to 2048 per side; with resize = true other sizes are
// resampled (OpenImageIO, to the nearest power of two, at most 2048). Throws tex::Error.
Image load_texture(const std::string& spec, bool resize = false);
Image make_pattern(const std::string& name, int width, int height);

// Writes 8-bit RGBA (channels wider than 8 bits are scaled). Writes to a temporary name and
// renames, so a failed write leaves nothing behind. Throws tex::Error.
void save_image(const Image& img, const std::string& path);

}  // namespace tex

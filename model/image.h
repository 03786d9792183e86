// RGBA images of up to 16 bits per channel and the built-in patterns (file I/O: sim/workloads/texture_io.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "formats.h"
#include "huge_pages.h"

namespace tex {

struct Image {
  int width = 0;
  int height = 0;
  int channel_bits = kDefaultChannelBits;
  BigVector<Texel> texels;  // row-major, y = 0 is the top row

  Image() = default;
  Image(int w, int h, int bits = kDefaultChannelBits) : width(w), height(h), channel_bits(bits), texels(size_t(w) * h) {}
  Texel& at(int x, int y) { return texels[size_t(y) * width + x]; }
  const Texel& at(int x, int y) const { return texels[size_t(y) * width + x]; }
};

inline int log2_exact(int n) { return log2_ceil(n); }  // n must be a power of two

// Names of the built-in patterns, for --help and error messages.
const std::vector<std::string>& pattern_names();

// Throws tex::Error unless both sides are 1 to kMaxSize texels; `hint` (if any) is appended in
// parentheses, e.g. how to resample.
void check_texture_size(int w, int h, const std::string& what, const std::string& hint = "");

// A built-in pattern (pattern_names()) of w x h texels. Throws tex::Error for a bad size.
Image make_pattern(const std::string& name, int width, int height);

}  // namespace tex

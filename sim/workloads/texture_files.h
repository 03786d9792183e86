// Textures stored the way GPUs read them: DDS (legacy and DX10 headers), KTX 1 and KTX2 (without
// supercompression), in RGBA8 or a block-compressed format (model/block_formats.h), with their mip
// levels. Read here without OpenImageIO: the blocks go to memory as they are.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/block_formats.h"
#include "model/pyramid.h"

namespace tex {

struct TextureFile {
  TexelFormat format = TexelFormat::Rgba8;
  bool srgb = false;
  int width = 0, height = 0;
  std::string format_name;                   // as the file names it, e.g. "DXGI_FORMAT_BC1_UNORM_SRGB"
  std::vector<std::vector<uint8_t>> levels;  // as stored: 4x4 blocks, or RGBA8 texels; level 0 first
};

// True if the file begins with a DDS, KTX 1 or KTX2 signature (false for anything else,
// including a missing file).
bool is_texture_file(const std::string& path);

// Reads every level the file has: one, or the whole chain down to 1x1. Throws tex::Error, one line
// naming the file and the value, for: a truncated file or bytes after the last level, a format
// this unit does not read (its DXGI, GL or Vulkan name), a cube map, array or volume, sides of 0
// or above 8192 (or, for a block format, not multiples of 4 at level 0), a partial mip chain (the level count named), KTX2 supercompression, sRGB on BC4/BC5.
TextureFile read_texture_file(const std::string& path);

// The pyramid of a texture file: its levels as stored, decoded for the sampler (an sRGB format's
// codes decoded to linear: model/srgb.h). A file with one level gets the rest of the chain from
// the box filter (`mode`; in linear space for sRGB), each level compressed again
// (compress_pyramid). Throws tex::Error.
Pyramid pyramid_of(const TextureFile& file, PyramidMode mode);

// Every level of an RGBA8 pyramid compressed to `format` by libsquish (BC1-BC5, cluster fit; BC4
// takes red, BC5 red and green) or by Mesa (BC7, through the image module), then decoded again
// into `levels`: the texture as the unit sees it. RGBA8 returns the pyramid as it is.
Pyramid compress_pyramid(Pyramid pyramid, TexelFormat format);

// How a texture becomes a pyramid (texsim's --resize, --pyramid, --format).
struct TextureOptions {
  bool resize = false;
  PyramidMode mode = PyramidMode::Exact;
  TexelFormat format = TexelFormat::Rgba8;
  bool format_given = false;  // --format: for an image file or pattern; a texture file has its own
  bool srgb = false;          // --srgb: an image file's or pattern's texels are sRGB codes
  // --base-level, --max-level: the view of the pyramid the units sample (view_pyramid: GL's
  // TEXTURE_BASE_LEVEL / TEXTURE_MAX_LEVEL, Vulkan's baseMipLevel / levelCount)
  int base_level = 0;
  int max_level = kMaxLevels - 1;
  // Where the view was given, for its error ("" = the options: "--base-level B --max-level M";
  // a texture list names its file, line and fields).
  std::string view_given_by;
};

// The pyramid of level 0 as the options make it: the box pyramid (in linear space for sRGB:
// model/srgb.h), each level compressed to options.format, then its view (base and max level).
// Throws tex::Error (sRGB BC4 or BC5; a base level beyond the last, a max level below the base:
// one line naming the option and both values).
Pyramid make_pyramid(Image level0, const TextureOptions& options);

// A texture's pyramid: a DDS/KTX file's levels and format, or an image file or pattern
// (workloads/texture_io.h) with its box pyramid, compressed to options.format. Throws tex::Error.
Pyramid load_pyramid(const std::string& spec, const TextureOptions& options);

}  // namespace tex

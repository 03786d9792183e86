// Textures stored the way GPUs read them: DDS (legacy and DX10 headers), KTX 1 and KTX2 (without
// supercompression), in RGBA8 or a block-compressed format (model/block_formats.h), with their mip
// levels: 2D textures, arrays, cube maps and cube arrays. Read here without OpenImageIO: the blocks
// go to memory as they are.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/block_formats.h"
#include "model/pyramid.h"

namespace tex {

// A texture file's images, each with the same levels. An array holds `layers` elements, a cube map
// 6 faces, a cube array `layers` cubes of 6 faces: layers x faces images, image i = layer * faces +
// face, faces in the order the files store them (+X, -X, +Y, -Y, +Z, -Z).
struct TextureFile {
  TexelFormat format = TexelFormat::Rgba8;
  bool srgb = false;
  int width = 0, height = 0;                 // level 0 of every image (a cube's faces: square)
  int layers = 1;                            // array elements (cubes of a cube array); 1: not an array
  int faces = 1;                             // 6: a cube map or cube array; else 1
  std::string format_name;                   // as the file names it, e.g. "DXGI_FORMAT_BC1_UNORM_SRGB"
  bool colour_space_given = true;            // false: an .astc file, linear unless --srgb says sRGB
  std::vector<std::vector<uint8_t>> levels;  // image 0 as stored: blocks, or RGBA8 texels; level 0 first
  std::vector<std::vector<std::vector<uint8_t>>> more_images;  // images 1 .. layers*faces-1, each like `levels`
};

// True if the file begins with a DDS, KTX 1, KTX2 or .astc (astcenc's) signature (false for anything
// else, including a missing file).
bool is_texture_file(const std::string& path);

// Reads every image and every level the file has: one level, or the whole chain down to 1x1, for
// each of its images. Accepts 2D textures, arrays of 1 to kMaxLayers (DDS DX10 arraySize, KTX 1
// numberOfArrayElements, KTX2 layerCount; 0 in KTX: not an array), cube maps (DDS caps2 with all six
// faces or DX10 miscFlag TEXTURECUBE, KTX numberOfFaces / faceCount 6) and cube arrays (the array
// count counts cubes). Throws tex::Error, one line naming the file, the field and the value, for: a
// truncated file or bytes after the last level (DDS, KTX 1), a format this unit does not read (its
// DXGI, GL or Vulkan name), a volume, a layer count outside those bounds, a face count other than 1
// or 6, a DDS cube map missing a face, a cube whose faces are not square, sides of 0 or above 8192
// (or, for a 4x4-block format, not multiples of 4 at level 0; ASTC takes any size, its last blocks
// cut), a partial mip chain (the level count named), a KTX 1 imageSize or KTX2 level length that is
// not the level's, KTX2 supercompression, sRGB on BC4/BC5; an .astc file of a 3D footprint or size,
// a footprint ASTC has not got, or blocks that are not its size's. Every range the header implies is checked against the file's size before any
// of it is copied: a header claiming more than the file holds allocates nothing.
TextureFile read_texture_file(const std::string& path);

// The pyramid of a texture file's image 0: its levels as stored, decoded for the sampler (an sRGB
// format's codes decoded to linear: model/srgb.h). A file with one level gets the rest of the
// chain from the box filter (`mode`; in linear space for sRGB), each level compressed again
// (compress_pyramid). Throws tex::Error.
Pyramid pyramid_of(const TextureFile& file, PyramidMode mode);

// The pyramid of every image of a texture file (layer-major, face-minor: image i = layer * faces +
// face), each built as pyramid_of builds image 0. Throws tex::Error (also when more_images does
// not hold layers * faces - 1 images).
std::vector<Pyramid> pyramids_of(const TextureFile& file, PyramidMode mode);

// Every level of an RGBA8 pyramid compressed to `format` by libsquish (BC1-BC5, cluster fit; BC4
// takes red, BC5 red and green), by Mesa (BC7, through the image module), by our ETC2 encoder or by
// astcenc (ASTC; `srgb`: the levels are sRGB codes, encoded and decoded in ASTC's sRGB mode), then
// decoded again into `levels`: the texture as the unit sees it. RGBA8 returns the pyramid as it is.
Pyramid compress_pyramid(Pyramid pyramid, TexelFormat format, bool srgb = false);

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
// (workloads/texture_io.h) with its box pyramid, compressed to options.format, then the options'
// view. Throws tex::Error; for a file of more than one image (an array or cube map), one line
// naming its layers and faces.
Pyramid load_pyramid(const std::string& spec, const TextureOptions& options);

// The layers of an array texture, as load_pyramid makes one pyramid (each with the options and
// their view): a DDS/KTX file's every image (image i = layer * faces + face), `*faces` set to the
// file's 1 or 6; an image file or pattern as one layer, `*faces` 1. Throws tex::Error.
std::vector<Pyramid> load_layers(const std::string& spec, const TextureOptions& options, int* faces = nullptr);

// An array texture's layers (texsim sample's --texture, --texture-layers, --cube): one spec's
// load_layers (an image, a DDS/KTX file of one image, an array, a cube map or cube array: `*kind`
// then Cube), or several specs' load_pyramid one layer each (`kind` as given: Cube for --cube's six
// faces a cube). Throws tex::Error, one line naming the file: a cube map file where `kind` is null,
// more than kMaxLayers layers, a layer whose size, format, sRGB flag or level count differs from
// layer 0's; for a cube, faces that are not square or a count that is not a multiple of 6.
std::vector<Pyramid> load_array(const std::vector<std::string>& specs, const TextureOptions& options,
                                TextureKind* kind = nullptr);

// An environment as a cube map (render --envmap): a DDS/KTX/KTX2 cube file, six images
// +X,-X,+Y,-Y,+Z,-Z (comma-separated), or one equirectangular image or pattern (longitude
// atan2(x, -z) across, u = 1/2 + longitude / 2 pi; latitude asin(y) down from the top row,
// v = 1/2 - latitude / pi) converted once: faces of the largest power of two up to a quarter of its
// width (1024 at most), each texel the bilinear of the image at its centre's direction, then their
// pyramids. `how` says which. Throws tex::Error, one line naming the file.
std::vector<Pyramid> load_envmap(const std::string& spec, const TextureOptions& options, std::string& how);

}  // namespace tex

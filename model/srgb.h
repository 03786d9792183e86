// sRGB-encoded textures (GL 4.6 §8.24 and §17.3.7; docs/numerics.md "sRGB"): the decode table
// the filter's inputs go through, and the pyramid of an sRGB texture, box-filtered in linear space
// as glGenerateMipmap does. Memory holds 8-bit sRGB codes; the filter takes linear unorm16.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "formats.h"
#include "image.h"

namespace tex {

constexpr int kLinearBits = 16;  // a decoded sRGB channel: unorm16 (the issue asks for >= 12 bits)

// The exact transfer functions on [0, 1]: sRGB code value -> linear, and back.
double srgb_to_linear(double c);
double linear_to_srgb(double l);

// The decode table (a 256-entry ROM in the RTL): round(65535 * srgb_to_linear(c / 255)).
const std::array<uint16_t, 256>& srgb_decode_table();
// An 8-bit sRGB code for a linear value in [0, 1]: round half up of 255 * linear_to_srgb(l).
uint8_t encode_srgb8(double linear);

// The stored levels of an sRGB texture (8-bit sRGB codes, level 0 first, level 0 as given): every
// other texel's R, G, B the encoding of the mean of its footprint's decoded values (exact mode:
// the whole level-0 footprint; cascade: the parent's 2x2, as decoded from its codes), its alpha
// (linear) the rounded mean as build_pyramid computes it. Throws tex::Error unless level 0 is 8-bit.
std::vector<Image> srgb_box_levels(const Image& level0, PyramidMode mode);

// A stored level as the filter sees it: R, G, B through the table, alpha widened exactly
// (a * 257); channel_bits kLinearBits.
Image decode_srgb_level(const Image& srgb8);

// A linear unorm16 result as 8-bit sRGB codes (R, G, B encoded, alpha rounded to 8 bits): what a
// picture of an sRGB texture's samples stores.
Texel encode_srgb_texel(const Texel& linear16);

struct Pyramid;
// The pyramid of an sRGB RGBA8 texture: `codes` = srgb_box_levels(level0, mode), `levels` their
// decoding (linear unorm16), `srgb` set.
Pyramid build_srgb_pyramid(const Image& level0, PyramidMode mode);
// Makes a pyramid whose `levels` hold 8-bit sRGB codes (a block format's: decoded from `blocks`)
// an sRGB pyramid: the codes kept as memory holds them (`codes`, unless `blocks` hold them), the
// levels decoded to linear for the filter, `srgb` set.
void decode_srgb_levels(Pyramid& pyramid);

}  // namespace tex

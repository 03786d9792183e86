// ETC2 and EAC blocks (OpenGL ES 3.0 specification, Annex C; Khronos Data Format Specification,
// "ETC2"): the decoders behind decode_texel for TexelFormat::Etc2Rgb, Etc2RgbA1 and Etc2Rgba
// (model/block_formats.h). An ETC2 colour block is a big-endian 64-bit word: ETC1's individual
// and differential modes, and the T, H and planar modes that ETC2 puts where the differential
// mode's red, green or blue sum leaves 0..31. Its pixel indices run down the columns (texel x, y
// is index 4 x + y). ETC2 RGBA8 puts an EAC alpha block (8 bytes) before the colour block.
// Every value is specified to the bit: Mesa decodes the same (tests/sim/test_block_formats_reference.cpp).
#pragma once
#include <array>
#include <cstdint>

namespace tex {

// How an ETC2 colour block decodes (functional coverage, tests).
enum class Etc2Mode : uint8_t { Individual, Differential, T, H, Planar };

// The mode of an ETC2 colour block (8 bytes). `punch_through`: ETC2 RGB8A1, which has no
// individual mode (its bit 33 says "opaque").
Etc2Mode etc2_mode_of(const uint8_t* colour_block, bool punch_through);

// Texel i (x + 4 y) of an ETC2 colour block as R, G, B, A: A is 255, or for `punch_through` 0
// where the block is not opaque and the texel's index is 2 (then R, G, B are 0 too).
std::array<uint8_t, 4> etc2_colour_texel(const uint8_t* colour_block, bool punch_through, int i);

// Texel i (x + 4 y) of an EAC block with 8-bit values (ETC2 RGBA8's alpha).
uint8_t eac_alpha_texel(const uint8_t* alpha_block, int i);

}  // namespace tex

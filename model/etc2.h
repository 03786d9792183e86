// ETC2 and EAC blocks (OpenGL ES 3.0 specification, Annex C; Khronos Data Format Specification,
// "ETC2"): the decoders behind decode_texel for TexelFormat::Etc2Rgb, Etc2RgbA1 and Etc2Rgba, and
// behind decode_block's 16-bit texels for the EAC formats EacR11, EacRg11 and their signed forms
// (model/block_formats.h). An ETC2 colour block is a big-endian 64-bit word: ETC1's individual
// and differential modes, and the T, H and planar modes that ETC2 puts where the differential
// mode's red, green or blue sum leaves 0..31. Its pixel indices run down the columns (texel x, y
// is index 4 x + y). ETC2 RGBA8 puts an EAC alpha block (8 bytes) before the colour block.
// Every value is specified to the bit: Mesa decodes the same (tests/sim/test_block_formats_reference.cpp).
#pragma once
#include <array>
#include <cstdint>

namespace tex {

// ETC1's intensity modifier pairs (a, b) by table codeword: +a, +b, -a, -b for pixel indices 0..3.
inline constexpr int kEtcModifiers[8][2] = {{2, 8}, {5, 17}, {9, 29}, {13, 42}, {18, 60}, {24, 80}, {33, 106}, {47, 183}};
// EAC's modifier tables, entry `index` (0..7) of table 0..15.
inline constexpr int kEacModifiers[16][8] = {
    {-3, -6, -9, -15, 2, 5, 8, 14}, {-3, -7, -10, -13, 2, 6, 9, 12}, {-2, -5, -8, -13, 1, 4, 7, 12},
    {-2, -4, -6, -13, 1, 3, 5, 12}, {-3, -6, -8, -12, 2, 5, 7, 11},  {-3, -7, -9, -11, 2, 6, 8, 10},
    {-4, -7, -8, -11, 3, 6, 7, 10}, {-3, -5, -8, -11, 2, 4, 7, 10},  {-2, -6, -8, -10, 1, 5, 7, 9},
    {-2, -5, -8, -10, 1, 4, 7, 9},  {-2, -4, -8, -10, 1, 3, 7, 9},   {-2, -5, -7, -10, 1, 4, 6, 9},
    {-3, -4, -7, -10, 2, 3, 6, 9},  {-1, -2, -3, -10, 0, 1, 2, 9},   {-4, -6, -8, -9, 3, 5, 7, 8},
    {-3, -5, -7, -9, 2, 4, 6, 8}};

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

// Texel i (x + 4 y) of an EAC R11 block (each channel of EAC R11 and RG11), as the specification
// gives it: 11 bits, unsigned 0..2047 (base x 8 + 4 + modifier x multiplier x 8, multiplier 0
// counting as 1/8), or signed -1023..1023 (`snorm`: base a signed byte with -128 read as -127, no
// + 4). Negative values only where `snorm`.
int eac_r11_value(const uint8_t* r11_block, bool snorm, int i);
// That value widened to 16 bits by replicating its top bits (the specification lets a decoder
// widen to any width; Mesa widens so): unsigned v -> v << 5 | v >> 6 (0..65535); signed
// -> the same of |v| on 10 bits, v << 5 | v >> 5, with v's sign (-32767..32767).
int eac_r11_widened(int value, bool snorm);
// The unit's code for it (the filter's arithmetic is unsigned): unsigned as it is, signed in
// offset binary, widened + 32768 (1..65535; 32768 is 0.0). Linear filtering, min/max and the
// mean of probes commute with the offset, so a filtered code - 32768 is the signed result.
uint16_t eac_r11_code(const uint8_t* r11_block, bool snorm, int i);

}  // namespace tex

// ASTC LDR blocks, 2D (Khronos Data Format Specification, "ASTC Compressed Texture Image Formats";
// KHR_texture_compression_astc_ldr): the decoder behind decode_texel for the TexelFormat::Astc*
// footprints (model/block_formats.h). Every block is 128 bits; the footprint (4x4 .. 12x12 texels)
// is the format's, not the block's. The decoder follows the specification's stages, which the
// hardware's decoder names the same (docs/numerics.md, "ASTC"):
//   block mode -> weight grid, weight range, dual plane;   partitions, colour endpoint modes (CEM);
//   integer sequence decode (trits, quints, bits) of the weights and of the endpoint values;
//   endpoint unquantization and interpretation (LDR modes 0, 1, 4, 5, 6, 8, 9, 10, 12, 13);
//   weight unquantization and infill (bilinear from the grid); the texel's partition (hash);
//   weight application: the 16-bit interpolation C of the specification.
// An illegal block, an HDR endpoint mode (that partition's texels) or an HDR void-extent block
// decodes to the error colour, opaque magenta. The unit is the LDR profile: it returns the top 8 bits
// of C (decode_unorm8, and the sRGB operation mode, whose endpoints expand with 0x80 below them).
// astcenc decodes the same (tests/sim/test_astc_reference.cpp).
#pragma once
#include <array>
#include <cstdint>

namespace tex {

// The 14 2D footprints of the LDR profile, in the order of the GL and Vulkan format enums.
struct AstcFootprint {
  int w, h;
};
inline constexpr AstcFootprint kAstcFootprints[14] = {{4, 4},  {5, 4},  {5, 5},  {6, 5},  {6, 6},  {8, 5},   {8, 6},
                                                      {8, 8},  {10, 5}, {10, 6}, {10, 8}, {10, 10}, {12, 10}, {12, 12}};

// How a block decodes (functional coverage, tests).
struct AstcMode {
  bool void_extent = false;
  bool error = false;       // an illegal block: every texel the error colour
  int grid_w = 0, grid_h = 0;
  int weight_levels = 0;    // the weights' range: 2 .. 32 values
  bool dual_plane = false;
  int ccs = 0;              // dual plane: the channel of plane 1 (R, G, B, A)
  int partitions = 0;       // 1 .. 4
  int partition_seed = 0;   // 10 bits
  std::array<int, 4> cem{}; // each partition's colour endpoint mode, 0 .. 15
  int colour_values = 0;    // endpoint values, 2 .. 18
  int colour_levels = 0;    // their range, 6 .. 256 values
  bool hdr = false;         // an HDR void extent or HDR endpoint mode: the LDR profile's error colour
};
AstcMode astc_mode_of(const uint8_t* block, int fw, int fh);

// The specification's C of texel (x, y) of a block of footprint fw x fh: per channel the 16-bit
// interpolation of the endpoints (expanded by bit replication, or for `srgb` with 0x80 below), or a
// void-extent block's colour; the error colour is (0xFFFF, 0, 0xFFFF, 0xFFFF).
using AstcTexel16 = std::array<uint16_t, 4>;
AstcTexel16 astc_texel16(const uint8_t* block, int fw, int fh, bool srgb, int x, int y);
// Every texel of a block, row-major (fw * fh of them): the same values, the block decoded once.
void astc_block16(const uint8_t* block, int fw, int fh, bool srgb, AstcTexel16* out);

// The unit's 8-bit texel: the top 8 bits of C (decode_unorm8; in sRGB mode the 8-bit code that the
// sRGB EOTF then takes).
inline std::array<uint8_t, 4> astc_unorm8(const AstcTexel16& c) {
  return {uint8_t(c[0] >> 8), uint8_t(c[1] >> 8), uint8_t(c[2] >> 8), uint8_t(c[3] >> 8)};
}

// The partition of texel (x, y) (the specification's select_partition, 2D), exposed for tests.
int astc_partition(int seed, int partitions, int x, int y, bool small_block);

}  // namespace tex

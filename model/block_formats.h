// Texel formats of a texture in memory: RGBA8 and the block-compressed formats BC1-BC5, BC7, ETC2,
// EAC and ASTC (Khronos Data Format Specification, "S3TC", "BPTC", "ETC2" and "ASTC"; D3D and GL names).
// A compressed level is a row-major array of blocks of 8 or 16 bytes, each 4x4 texels (ASTC: its
// footprint, 4x4 .. 12x12), the last column and row cut by the level's edge. The decoders here are the bit-level
// specification of the hardware's (docs/numerics.md, "Block-compressed formats"): every rounding
// is stated, and independent decoders (libsquish, OpenImageIO, Mesa) check them
// (tests/sim/test_block_formats_reference.cpp).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image.h"

namespace tex {

// ETC2 (model/etc2.h): Etc2Rgb is ETC2 RGB8 (and ETC1), Etc2RgbA1 ETC2 RGB8 with punch-through
// alpha, Etc2Rgba ETC2 RGBA8 (an EAC alpha block, then the colour block). EAC R11 and RG11, unsigned
// and signed (snorm): one or two 8-byte EAC blocks of 11-bit values, decoded to 16-bit channels.
// ASTC LDR (model/astc.h): one format per footprint, codes 16 + the footprint's index in
// kAstcFootprints (tex_pkg::FMT_ASTC_4X4 + i, tex_pkg::footprint in the RTL).
enum class TexelFormat : uint8_t {
  Rgba8 = 0, Bc1 = 1, Bc2 = 2, Bc3 = 3, Bc4 = 4, Bc5 = 5, Bc7 = 7, Etc2Rgb = 8, Etc2RgbA1 = 9, Etc2Rgba = 10,
  EacR11 = 11, EacR11Snorm = 12, EacRg11 = 13, EacRg11Snorm = 14,
  Astc4x4 = 16, Astc5x4, Astc5x5, Astc6x5, Astc6x6, Astc8x5, Astc8x6, Astc8x8, Astc10x5, Astc10x6, Astc10x8,
  Astc10x10, Astc12x10, Astc12x12 = 29
};

struct FormatInfo {
  TexelFormat format;
  const char* name;  // as the CLI takes it: rgba8, bc1, ...
  int block_bytes;   // bytes per block; 0 for RGBA8 (4 bytes per texel)
  int channels;      // channels the format stores (BC4: R; BC5: R, G)
  bool srgb_allowed; // sRGB variants exist (BC1, BC2, BC3, BC7, ETC2, ASTC, RGBA8)
  bool encoder;      // --format can make it from an image (libsquish, Mesa, workloads/etc2_encode.h,
                     // astcenc); not ETC2 RGB8A1
  int block_w = 4, block_h = 4;  // texels a block covers (RGBA8: 1 x 1)
  // Bits per channel of its decoded texels (decode_block into Texel): 8, or 16 for EAC, whose
  // 11-bit values the unit filters at full precision (its CW = 16 filter).
  int channel_bits = 8;
  // Signed normalized (EAC's signed forms): channels in offset binary, code - 2^(channel_bits-1).
  bool snorm = false;
};
constexpr int kMaxBlockTexels = 144;  // ASTC 12x12

const FormatInfo& format_info(TexelFormat f);
bool parse_texel_format(const std::string& name, TexelFormat& out);
// --format's value: a format with an encoder. Throws tex::Error: an unknown name (the names listed),
// or a format that is read from files only (ETC2 RGB8A1: KTX and KTX2).
TexelFormat parse_encodable_format(const std::string& name);
std::string texel_format_names();  // "rgba8 | bc1 | ..." (the formats with an encoder) for --help and errors
inline bool is_compressed(TexelFormat f) { return f != TexelFormat::Rgba8; }
inline bool is_etc2(TexelFormat f) { return f >= TexelFormat::Etc2Rgb && f <= TexelFormat::Etc2Rgba; }
inline bool is_eac(TexelFormat f) { return f >= TexelFormat::EacR11 && f <= TexelFormat::EacRg11Snorm; }
inline bool is_astc(TexelFormat f) { return f >= TexelFormat::Astc4x4; }

using Rgba8 = std::array<uint8_t, 4>;

// Texel i (x + block_w y) of one block. BC4 decodes to (R, 0, 0, 255) and BC5 to (R, G, 0, 255), as GL
// returns RED and RG textures. A BC7 block with the reserved mode 8 (low byte 0) decodes to
// (0, 0, 0, 0), as D3D11 specifies. `srgb`: the texture is sRGB, which changes how ASTC expands its
// endpoints (model/astc.h; the other formats decode the same codes either way). Not for EAC, whose
// channels are 16 bits (decode_block into Texel): throws tex::Error.
Rgba8 decode_texel(TexelFormat f, const uint8_t* block, int i, bool srgb = false);
// All block_w x block_h texels of one block into `out`, row-major (the values of decode_texel, faster).
void decode_block(TexelFormat f, const uint8_t* block, Rgba8* out, bool srgb = false);
// The same as the unit's filter takes them, in the format's channel_bits: decode_texel's values,
// or EAC's 16-bit codes (model/etc2.h eac_r11_code): R, G (R11: 0, signed 32768), B 0 (signed
// 32768), A 65535 -- GL's (R, G, 0, 1) for RED and RG textures.
void decode_block(TexelFormat f, const uint8_t* block, Texel* out, bool srgb = false);
// A level of blocks (row-major, ceil(w/block_w) x ceil(h/block_h) blocks) as an image of w x h
// texels of the format's channel_bits.
Image decode_level(TexelFormat f, const uint8_t* blocks, int width, int height, bool srgb = false);
// Bytes of a level of w x h texels in format f.
uint64_t level_bytes(TexelFormat f, int width, int height);

// The fields of a BC7 block that select how it decodes (functional coverage, tests).
struct Bc7Mode {
  int mode = 8;          // 0..7; 8 = reserved (low byte 0)
  int partition = 0;     // 0..63 (mode 0: 0..15)
  int subsets = 1;       // 1..3
  int rotation = 0;      // modes 4, 5
  int index_select = 0;  // mode 4
};
Bc7Mode bc7_mode_of(const uint8_t* block);

// The BPTC tables (ARB_texture_compression_bptc Table.P2, P3, A2, A3a, A3b): the subset of texel i
// in a partition, and the anchor texel of each subset.
int bc7_subset(int subsets, int partition, int texel);
int bc7_anchor(int subsets, int partition, int subset);

}  // namespace tex

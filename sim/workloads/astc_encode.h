// The ASTC encoder of --format astc4x4 .. astc12x12: Arm's astcenc (Debian's libastcenc, the
// Khronos reference codec), LDR profile, linear or sRGB, at its "fast" preset (docs/numerics.md,
// "ASTC": PSNR by preset).
#pragma once
#include <cstdint>
#include <vector>

#include "model/block_formats.h"
#include "model/image.h"

namespace tex {

// A level of 8-bit texels as ASTC blocks of the format's footprint, row-major, the last column and
// row of blocks cut by the level's edge. `srgb`: the texels are sRGB codes (astcenc's sRGB profile,
// which weighs the error as the decoder's sRGB mode expands the endpoints). Throws tex::Error for a
// format that is not ASTC, or when astcenc fails (its message).
std::vector<uint8_t> encode_astc_level(const Image& level, TexelFormat format, bool srgb);

}  // namespace tex

// An ETC2 and EAC encoder for --format etc2, etc2a, eac_r11 and eac_rg11: Debian packages none (no etcpak, ETCPACK,
// etc2comp or basis_universal; astcenc is ASTC only, libsquish BC only, Mesa decodes ETC2 but does
// not encode it). It searches ETC1's modes, which every ETC2 decoder reads: both sub-block
// orientations, the individual and the differential base colours, every modifier table per
// sub-block, each texel's best index. It does not try the T, H and planar modes, so its quality is
// ETC1's (docs/numerics.md, "ETC2"). EAC alpha, and EAC R11 (each channel of R11 and RG11, the
// unsigned forms): every table and multiplier around the mean value.
#pragma once
#include <cstdint>
#include <vector>

#include "model/block_formats.h"
#include "model/image.h"

namespace tex {

// A level of 8-bit texels as ETC2 RGB8 (TexelFormat::Etc2Rgb) or RGBA8 (Etc2Rgba) blocks, or of
// texels of up to 16 bits as EAC R11 (EacR11: R) or RG11 (EacRg11: R, G) blocks, row-major 4x4 blocks; texels past the level's edge repeat its
// last row and column. Throws tex::Error for another format.
std::vector<uint8_t> encode_etc2_level(const Image& level, TexelFormat format);

}  // namespace tex

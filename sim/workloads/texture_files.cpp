#include "workloads/texture_files.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <squish.h>
#include <fstream>
#include <iterator>

#include "model/astc.h"
#include "model/error.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "workloads/astc_encode.h"
#include "workloads/etc2_encode.h"
#include "workloads/image_module.h"
#include "workloads/limits.h"
#include "workloads/text.h"
#include "workloads/texture_io.h"

namespace tex {

namespace {

constexpr uint8_t kDdsMagic[4] = {'D', 'D', 'S', ' '};
constexpr uint8_t kKtx1Magic[12] = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
constexpr uint8_t kAstcMagic[4] = {0x13, 0xAB, 0xA1, 0x5C};  // astcenc's .astc: 0x5CA1AB13, little-endian
constexpr uint8_t kKtx2Magic[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};

// A format the unit reads, as a file format names it.
struct Known {
  uint32_t code;
  const char* name;
  TexelFormat format;
  bool srgb;
  bool supported;  // false: named in the error message only
};

// DXGI_FORMAT values (DX10 header).
constexpr Known kDxgi[] = {
    {2, "R32G32B32A32_FLOAT", TexelFormat::Rgba8, false, false},
    {10, "R16G16B16A16_FLOAT", TexelFormat::Rgba8, false, false},
    {11, "R16G16B16A16_UNORM", TexelFormat::Rgba8, false, false},
    {24, "R10G10B10A2_UNORM", TexelFormat::Rgba8, false, false},
    {27, "R8G8B8A8_TYPELESS", TexelFormat::Rgba8, false, false},
    {28, "R8G8B8A8_UNORM", TexelFormat::Rgba8, false, true},
    {29, "R8G8B8A8_UNORM_SRGB", TexelFormat::Rgba8, true, true},
    {61, "R8_UNORM", TexelFormat::Rgba8, false, false},
    {70, "BC1_TYPELESS", TexelFormat::Bc1, false, false},
    {71, "BC1_UNORM", TexelFormat::Bc1, false, true},
    {72, "BC1_UNORM_SRGB", TexelFormat::Bc1, true, true},
    {73, "BC2_TYPELESS", TexelFormat::Bc2, false, false},
    {74, "BC2_UNORM", TexelFormat::Bc2, false, true},
    {75, "BC2_UNORM_SRGB", TexelFormat::Bc2, true, true},
    {76, "BC3_TYPELESS", TexelFormat::Bc3, false, false},
    {77, "BC3_UNORM", TexelFormat::Bc3, false, true},
    {78, "BC3_UNORM_SRGB", TexelFormat::Bc3, true, true},
    {79, "BC4_TYPELESS", TexelFormat::Bc4, false, false},
    {80, "BC4_UNORM", TexelFormat::Bc4, false, true},
    {81, "BC4_SNORM", TexelFormat::Bc4, false, false},
    {82, "BC5_TYPELESS", TexelFormat::Bc5, false, false},
    {83, "BC5_UNORM", TexelFormat::Bc5, false, true},
    {84, "BC5_SNORM", TexelFormat::Bc5, false, false},
    {87, "B8G8R8A8_UNORM", TexelFormat::Rgba8, false, false},
    {91, "B8G8R8A8_UNORM_SRGB", TexelFormat::Rgba8, false, false},
    {94, "BC6H_TYPELESS", TexelFormat::Rgba8, false, false},
    {95, "BC6H_UF16", TexelFormat::Rgba8, false, false},
    {96, "BC6H_SF16", TexelFormat::Rgba8, false, false},
    {97, "BC7_TYPELESS", TexelFormat::Bc7, false, false},
    {98, "BC7_UNORM", TexelFormat::Bc7, false, true},
    {99, "BC7_UNORM_SRGB", TexelFormat::Bc7, true, true},
};

// glInternalFormat values (KTX 1).
constexpr Known kGl[] = {
    {0x8058, "GL_RGBA8", TexelFormat::Rgba8, false, true},
    {0x8C43, "GL_SRGB8_ALPHA8", TexelFormat::Rgba8, true, true},
    {0x83F0, "GL_COMPRESSED_RGB_S3TC_DXT1_EXT", TexelFormat::Bc1, false, false},
    {0x83F1, "GL_COMPRESSED_RGBA_S3TC_DXT1_EXT", TexelFormat::Bc1, false, true},
    {0x83F2, "GL_COMPRESSED_RGBA_S3TC_DXT3_EXT", TexelFormat::Bc2, false, true},
    {0x83F3, "GL_COMPRESSED_RGBA_S3TC_DXT5_EXT", TexelFormat::Bc3, false, true},
    {0x8C4C, "GL_COMPRESSED_SRGB_S3TC_DXT1_EXT", TexelFormat::Bc1, true, false},
    {0x8C4D, "GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT", TexelFormat::Bc1, true, true},
    {0x8C4E, "GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT", TexelFormat::Bc2, true, true},
    {0x8C4F, "GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT", TexelFormat::Bc3, true, true},
    {0x8DBB, "GL_COMPRESSED_RED_RGTC1", TexelFormat::Bc4, false, true},
    {0x8DBC, "GL_COMPRESSED_SIGNED_RED_RGTC1", TexelFormat::Bc4, false, false},
    {0x8DBD, "GL_COMPRESSED_RG_RGTC2", TexelFormat::Bc5, false, true},
    {0x8DBE, "GL_COMPRESSED_SIGNED_RG_RGTC2", TexelFormat::Bc5, false, false},
    {0x8E8C, "GL_COMPRESSED_RGBA_BPTC_UNORM", TexelFormat::Bc7, false, true},
    {0x8E8D, "GL_COMPRESSED_SRGB_ALPHA_BPTC_UNORM", TexelFormat::Bc7, true, true},
    {0x8E8E, "GL_COMPRESSED_RGB_BPTC_SIGNED_FLOAT", TexelFormat::Rgba8, false, false},
    {0x8E8F, "GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT", TexelFormat::Rgba8, false, false},
    {0x8D64, "GL_ETC1_RGB8_OES", TexelFormat::Etc2Rgb, false, true},  // (ETC1 is ETC2 RGB8's subset)
    {0x9274, "GL_COMPRESSED_RGB8_ETC2", TexelFormat::Etc2Rgb, false, true},
    {0x9275, "GL_COMPRESSED_SRGB8_ETC2", TexelFormat::Etc2Rgb, true, true},
    {0x9276, "GL_COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2", TexelFormat::Etc2RgbA1, false, true},
    {0x9277, "GL_COMPRESSED_SRGB8_PUNCHTHROUGH_ALPHA1_ETC2", TexelFormat::Etc2RgbA1, true, true},
    {0x9278, "GL_COMPRESSED_RGBA8_ETC2_EAC", TexelFormat::Etc2Rgba, false, true},
    {0x9279, "GL_COMPRESSED_SRGB8_ALPHA8_ETC2_EAC", TexelFormat::Etc2Rgba, true, true},
    {0x9270, "GL_COMPRESSED_R11_EAC", TexelFormat::EacR11, false, true},
    {0x9271, "GL_COMPRESSED_SIGNED_R11_EAC", TexelFormat::EacR11Snorm, false, true},
    {0x9272, "GL_COMPRESSED_RG11_EAC", TexelFormat::EacRg11, false, true},
    {0x9273, "GL_COMPRESSED_SIGNED_RG11_EAC", TexelFormat::EacRg11Snorm, false, true},
    {0x93B0, "GL_COMPRESSED_RGBA_ASTC_4x4_KHR", TexelFormat::Astc4x4, false, true},
    {0x93B1, "GL_COMPRESSED_RGBA_ASTC_5x4_KHR", TexelFormat::Astc5x4, false, true},
    {0x93B2, "GL_COMPRESSED_RGBA_ASTC_5x5_KHR", TexelFormat::Astc5x5, false, true},
    {0x93B3, "GL_COMPRESSED_RGBA_ASTC_6x5_KHR", TexelFormat::Astc6x5, false, true},
    {0x93B4, "GL_COMPRESSED_RGBA_ASTC_6x6_KHR", TexelFormat::Astc6x6, false, true},
    {0x93B5, "GL_COMPRESSED_RGBA_ASTC_8x5_KHR", TexelFormat::Astc8x5, false, true},
    {0x93B6, "GL_COMPRESSED_RGBA_ASTC_8x6_KHR", TexelFormat::Astc8x6, false, true},
    {0x93B7, "GL_COMPRESSED_RGBA_ASTC_8x8_KHR", TexelFormat::Astc8x8, false, true},
    {0x93B8, "GL_COMPRESSED_RGBA_ASTC_10x5_KHR", TexelFormat::Astc10x5, false, true},
    {0x93B9, "GL_COMPRESSED_RGBA_ASTC_10x6_KHR", TexelFormat::Astc10x6, false, true},
    {0x93BA, "GL_COMPRESSED_RGBA_ASTC_10x8_KHR", TexelFormat::Astc10x8, false, true},
    {0x93BB, "GL_COMPRESSED_RGBA_ASTC_10x10_KHR", TexelFormat::Astc10x10, false, true},
    {0x93BC, "GL_COMPRESSED_RGBA_ASTC_12x10_KHR", TexelFormat::Astc12x10, false, true},
    {0x93BD, "GL_COMPRESSED_RGBA_ASTC_12x12_KHR", TexelFormat::Astc12x12, false, true},
    {0x93D0, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_4x4_KHR", TexelFormat::Astc4x4, true, true},
    {0x93D1, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_5x4_KHR", TexelFormat::Astc5x4, true, true},
    {0x93D2, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_5x5_KHR", TexelFormat::Astc5x5, true, true},
    {0x93D3, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_6x5_KHR", TexelFormat::Astc6x5, true, true},
    {0x93D4, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_6x6_KHR", TexelFormat::Astc6x6, true, true},
    {0x93D5, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x5_KHR", TexelFormat::Astc8x5, true, true},
    {0x93D6, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x6_KHR", TexelFormat::Astc8x6, true, true},
    {0x93D7, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x8_KHR", TexelFormat::Astc8x8, true, true},
    {0x93D8, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x5_KHR", TexelFormat::Astc10x5, true, true},
    {0x93D9, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x6_KHR", TexelFormat::Astc10x6, true, true},
    {0x93DA, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x8_KHR", TexelFormat::Astc10x8, true, true},
    {0x93DB, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x10_KHR", TexelFormat::Astc10x10, true, true},
    {0x93DC, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_12x10_KHR", TexelFormat::Astc12x10, true, true},
    {0x93DD, "GL_COMPRESSED_SRGB8_ALPHA8_ASTC_12x12_KHR", TexelFormat::Astc12x12, true, true},
};

// VkFormat values (KTX2).
constexpr Known kVk[] = {
    {0, "VK_FORMAT_UNDEFINED (Basis Universal)", TexelFormat::Rgba8, false, false},
    {37, "VK_FORMAT_R8G8B8A8_UNORM", TexelFormat::Rgba8, false, true},
    {43, "VK_FORMAT_R8G8B8A8_SRGB", TexelFormat::Rgba8, true, true},
    {131, "VK_FORMAT_BC1_RGB_UNORM_BLOCK", TexelFormat::Bc1, false, false},
    {132, "VK_FORMAT_BC1_RGB_SRGB_BLOCK", TexelFormat::Bc1, true, false},
    {133, "VK_FORMAT_BC1_RGBA_UNORM_BLOCK", TexelFormat::Bc1, false, true},
    {134, "VK_FORMAT_BC1_RGBA_SRGB_BLOCK", TexelFormat::Bc1, true, true},
    {135, "VK_FORMAT_BC2_UNORM_BLOCK", TexelFormat::Bc2, false, true},
    {136, "VK_FORMAT_BC2_SRGB_BLOCK", TexelFormat::Bc2, true, true},
    {137, "VK_FORMAT_BC3_UNORM_BLOCK", TexelFormat::Bc3, false, true},
    {138, "VK_FORMAT_BC3_SRGB_BLOCK", TexelFormat::Bc3, true, true},
    {139, "VK_FORMAT_BC4_UNORM_BLOCK", TexelFormat::Bc4, false, true},
    {140, "VK_FORMAT_BC4_SNORM_BLOCK", TexelFormat::Bc4, false, false},
    {141, "VK_FORMAT_BC5_UNORM_BLOCK", TexelFormat::Bc5, false, true},
    {142, "VK_FORMAT_BC5_SNORM_BLOCK", TexelFormat::Bc5, false, false},
    {143, "VK_FORMAT_BC6H_UFLOAT_BLOCK", TexelFormat::Rgba8, false, false},
    {144, "VK_FORMAT_BC6H_SFLOAT_BLOCK", TexelFormat::Rgba8, false, false},
    {145, "VK_FORMAT_BC7_UNORM_BLOCK", TexelFormat::Bc7, false, true},
    {146, "VK_FORMAT_BC7_SRGB_BLOCK", TexelFormat::Bc7, true, true},
    {147, "VK_FORMAT_ETC2_R8G8B8_UNORM_BLOCK", TexelFormat::Etc2Rgb, false, true},
    {148, "VK_FORMAT_ETC2_R8G8B8_SRGB_BLOCK", TexelFormat::Etc2Rgb, true, true},
    {149, "VK_FORMAT_ETC2_R8G8B8A1_UNORM_BLOCK", TexelFormat::Etc2RgbA1, false, true},
    {150, "VK_FORMAT_ETC2_R8G8B8A1_SRGB_BLOCK", TexelFormat::Etc2RgbA1, true, true},
    {151, "VK_FORMAT_ETC2_R8G8B8A8_UNORM_BLOCK", TexelFormat::Etc2Rgba, false, true},
    {152, "VK_FORMAT_ETC2_R8G8B8A8_SRGB_BLOCK", TexelFormat::Etc2Rgba, true, true},
    {153, "VK_FORMAT_EAC_R11_UNORM_BLOCK", TexelFormat::EacR11, false, true},
    {154, "VK_FORMAT_EAC_R11_SNORM_BLOCK", TexelFormat::EacR11Snorm, false, true},
    {155, "VK_FORMAT_EAC_R11G11_UNORM_BLOCK", TexelFormat::EacRg11, false, true},
    {156, "VK_FORMAT_EAC_R11G11_SNORM_BLOCK", TexelFormat::EacRg11Snorm, false, true},
    {157, "VK_FORMAT_ASTC_4x4_UNORM_BLOCK", TexelFormat::Astc4x4, false, true},
    {158, "VK_FORMAT_ASTC_4x4_SRGB_BLOCK", TexelFormat::Astc4x4, true, true},
    {159, "VK_FORMAT_ASTC_5x4_UNORM_BLOCK", TexelFormat::Astc5x4, false, true},
    {160, "VK_FORMAT_ASTC_5x4_SRGB_BLOCK", TexelFormat::Astc5x4, true, true},
    {161, "VK_FORMAT_ASTC_5x5_UNORM_BLOCK", TexelFormat::Astc5x5, false, true},
    {162, "VK_FORMAT_ASTC_5x5_SRGB_BLOCK", TexelFormat::Astc5x5, true, true},
    {163, "VK_FORMAT_ASTC_6x5_UNORM_BLOCK", TexelFormat::Astc6x5, false, true},
    {164, "VK_FORMAT_ASTC_6x5_SRGB_BLOCK", TexelFormat::Astc6x5, true, true},
    {165, "VK_FORMAT_ASTC_6x6_UNORM_BLOCK", TexelFormat::Astc6x6, false, true},
    {166, "VK_FORMAT_ASTC_6x6_SRGB_BLOCK", TexelFormat::Astc6x6, true, true},
    {167, "VK_FORMAT_ASTC_8x5_UNORM_BLOCK", TexelFormat::Astc8x5, false, true},
    {168, "VK_FORMAT_ASTC_8x5_SRGB_BLOCK", TexelFormat::Astc8x5, true, true},
    {169, "VK_FORMAT_ASTC_8x6_UNORM_BLOCK", TexelFormat::Astc8x6, false, true},
    {170, "VK_FORMAT_ASTC_8x6_SRGB_BLOCK", TexelFormat::Astc8x6, true, true},
    {171, "VK_FORMAT_ASTC_8x8_UNORM_BLOCK", TexelFormat::Astc8x8, false, true},
    {172, "VK_FORMAT_ASTC_8x8_SRGB_BLOCK", TexelFormat::Astc8x8, true, true},
    {173, "VK_FORMAT_ASTC_10x5_UNORM_BLOCK", TexelFormat::Astc10x5, false, true},
    {174, "VK_FORMAT_ASTC_10x5_SRGB_BLOCK", TexelFormat::Astc10x5, true, true},
    {175, "VK_FORMAT_ASTC_10x6_UNORM_BLOCK", TexelFormat::Astc10x6, false, true},
    {176, "VK_FORMAT_ASTC_10x6_SRGB_BLOCK", TexelFormat::Astc10x6, true, true},
    {177, "VK_FORMAT_ASTC_10x8_UNORM_BLOCK", TexelFormat::Astc10x8, false, true},
    {178, "VK_FORMAT_ASTC_10x8_SRGB_BLOCK", TexelFormat::Astc10x8, true, true},
    {179, "VK_FORMAT_ASTC_10x10_UNORM_BLOCK", TexelFormat::Astc10x10, false, true},
    {180, "VK_FORMAT_ASTC_10x10_SRGB_BLOCK", TexelFormat::Astc10x10, true, true},
    {181, "VK_FORMAT_ASTC_12x10_UNORM_BLOCK", TexelFormat::Astc12x10, false, true},
    {182, "VK_FORMAT_ASTC_12x10_SRGB_BLOCK", TexelFormat::Astc12x10, true, true},
    {183, "VK_FORMAT_ASTC_12x12_UNORM_BLOCK", TexelFormat::Astc12x12, false, true},
    {184, "VK_FORMAT_ASTC_12x12_SRGB_BLOCK", TexelFormat::Astc12x12, true, true},
    {1000066000, "VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066001, "VK_FORMAT_ASTC_5x4_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066002, "VK_FORMAT_ASTC_5x5_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066003, "VK_FORMAT_ASTC_6x5_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066004, "VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066005, "VK_FORMAT_ASTC_8x5_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066006, "VK_FORMAT_ASTC_8x6_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066007, "VK_FORMAT_ASTC_8x8_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066008, "VK_FORMAT_ASTC_10x5_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066009, "VK_FORMAT_ASTC_10x6_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066010, "VK_FORMAT_ASTC_10x8_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066011, "VK_FORMAT_ASTC_10x10_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066012, "VK_FORMAT_ASTC_12x10_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
    {1000066013, "VK_FORMAT_ASTC_12x12_SFLOAT_BLOCK (HDR)", TexelFormat::Rgba8, false, false},
};

const char kSupported[] =
    "RGBA8, BC1 (with alpha), BC2, BC3, BC4 and BC5 (unorm), BC7, ETC2 RGB8 (and ETC1), RGB8A1 and RGBA8, EAC R11 "
    "and RG11 (unsigned and signed), ASTC LDR 4x4 to 12x12, and the sRGB variants";

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open the texture file");
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);  // (read, then its levels copied)
    if (!ec) check_memory(2 * size, path + ": a texture file of " + memory_words(size) + ", read,");
    bytes_.assign(std::istreambuf_iterator<char>(in), {});
  }
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + what); }
  size_t size() const { return bytes_.size(); }
  const uint8_t* at(uint64_t offset, uint64_t n, const std::string& what) const {
    if (offset > bytes_.size() || n > bytes_.size() - offset)
      fail("truncated: " + what + " needs " + std::to_string(n) + " bytes at offset " + std::to_string(offset) +
           ", the file has " + std::to_string(bytes_.size()));
    return bytes_.data() + offset;
  }
  uint32_t u32(uint64_t offset, const char* what) const {
    const uint8_t* p = at(offset, 4, what);
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  }
  uint64_t u64(uint64_t offset, const char* what) const {
    return u32(offset, what) | uint64_t(u32(offset + 4, what)) << 32;
  }

 private:
  std::string path_;
  std::vector<uint8_t> bytes_;
};

// The format a code names, or the one-line error naming it.
template <size_t N>
const Known& known(const Known (&table)[N], uint32_t code, const std::string& kind, const Reader& r,
                   const std::string& prefix = "") {
  for (const Known& k : table)
    if (k.code == code) {
      if (!k.supported) r.fail("format " + prefix + k.name + " is not supported (this unit reads " + kSupported + ")");
      return k;
    }
  r.fail(kind + " " + std::to_string(code) + " is not supported (this unit reads " + kSupported + ")");
}

// Checks the sizes and the level count, common to every container; returns the level count.
int check_shape(const Reader& r, TextureFile& t, uint32_t width, uint32_t height, uint32_t levels) {
  if (width == 0 || height == 0 || width > uint32_t(kMaxSize) || height > uint32_t(kMaxSize))
    r.fail(std::to_string(width) + "x" + std::to_string(height) + ": the unit takes sides from 1 to " +
           std::to_string(kMaxSize));
  t.width = int(width);
  t.height = int(height);
  if (is_compressed(t.format) && !is_astc(t.format) && (width % 4 || height % 4))
    r.fail(std::to_string(width) + "x" + std::to_string(height) + ": a " + format_info(t.format).name +
           " texture needs sides that are multiples of 4 at level 0");
  if (t.srgb && !format_info(t.format).srgb_allowed) r.fail("sRGB " + std::string(format_info(t.format).name) + " does not exist");
  const int full = level_count({t.width, t.height});
  if (levels == 0) levels = 1;
  if (int64_t(levels) != 1 && int64_t(levels) != full)
    r.fail(std::to_string(levels) + " mip levels: a partial chain (a " + std::to_string(width) + "x" + std::to_string(height) +
           " texture has 1 or " + std::to_string(full) + ")");
  return int(levels);
}

uint64_t bytes_of_level(const TextureFile& t, int k) {
  const Extent s = level_extent({t.width, t.height}, k);
  return level_bytes(t.format, s.width(), s.height());
}

std::string hex(uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%X", v);
  return b;
}

const char* const kFaceNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

// An array's element count from the header field `field` (in KTX, 0: not an array).
int check_layers(const Reader& r, const std::string& field, uint32_t count, bool zero_is_one) {
  if (count == 0 && zero_is_one) return 1;
  if (count < 1 || count > uint32_t(kMaxLayers))
    r.fail(field + " " + std::to_string(count) + ": an array texture has 1 to " + std::to_string(kMaxLayers) + " layers" +
           (zero_is_one ? " (0: not an array)" : ""));
  return int(count);
}

int check_faces(const Reader& r, const std::string& field, uint32_t faces) {
  if (faces != 1 && faces != 6) r.fail(field + " " + std::to_string(faces) + ": a texture has 1 face, or 6 (a cube map)");
  return int(faces);
}

// After check_shape: the layers and faces, and a cube's square faces. (Layers <= kMaxLayers and
// faces 1 or 6 keep layers x faces <= 6 x kMaxLayers.)
void set_images(const Reader& r, TextureFile& t, int layers, int faces) {
  t.layers = layers;
  t.faces = faces;
  if (faces == 6 && t.width != t.height)
    r.fail("width " + std::to_string(t.width) + ", height " + std::to_string(t.height) + ": a cube map's faces are square");
}

int image_count(const TextureFile& t) { return t.layers * t.faces; }

// "", "layer 3 ", "face -Y ", "layer 3 face -Y ": where an error is.
std::string image_name(const TextureFile& t, int i) {
  std::string s;
  if (t.layers > 1) s += "layer " + std::to_string(i / t.faces) + " ";
  if (t.faces > 1) s += "face " + std::string(kFaceNames[i % t.faces]) + " ";
  return s;
}

// The images of a level in words: "a bc1 level", "4 layers x 6 faces of a bc1 level".
std::string level_words(const TextureFile& t, int images) {
  const std::string one = std::string("a ") + format_info(t.format).name + " level";
  if (images == 1) return one;
  std::string s;
  if (t.layers > 1) s = std::to_string(t.layers) + " layers";
  if (t.faces > 1) s += (s.empty() ? "" : " x ") + std::to_string(t.faces) + " faces";
  return s + " of " + one;
}

// Copies image i's level k from offset_of(i, k), every image and level, after checking every range
// against the file first: a header claiming more than the file holds fails before anything is
// allocated.
template <class OffsetOf>
void take_images(const Reader& r, TextureFile& t, int levels, OffsetOf offset_of) {
  const int images = image_count(t);
  for (int i = 0; i < images; ++i)
    for (int k = 0; k < levels; ++k)
      r.at(offset_of(i, k), bytes_of_level(t, k), image_name(t, i) + "level " + std::to_string(k));
  t.levels.clear();
  t.more_images.assign(size_t(images - 1), {});
  for (int i = 0; i < images; ++i) {
    std::vector<std::vector<uint8_t>>& image = i == 0 ? t.levels : t.more_images[size_t(i - 1)];
    for (int k = 0; k < levels; ++k) {
      const uint64_t n = bytes_of_level(t, k);
      const uint8_t* p = r.at(offset_of(i, k), n, "level " + std::to_string(k));
      image.emplace_back(p, p + n);
    }
  }
}

TextureFile read_dds(const Reader& r) {
  TextureFile t;
  if (r.u32(4, "the DDS header") != 124) r.fail("not a DDS header (size " + std::to_string(r.u32(4, "")) + ", not 124)");
  const uint32_t flags = r.u32(8, "the DDS header"), height = r.u32(12, "the DDS header"), width = r.u32(16, "the DDS header");
  const uint32_t depth = r.u32(24, "the DDS header"), mips = r.u32(28, "the DDS header");
  const uint32_t pf_flags = r.u32(80, "the DDS header"), fourcc = r.u32(84, "the DDS header");
  const uint32_t caps2 = r.u32(112, "the DDS header");
  if ((caps2 & 0x200000) || ((flags & 0x800000) && depth > 1))
    r.fail("a volume texture (caps2 " + hex(caps2) + ", depth " + std::to_string(depth) +
           "): the unit reads 2D textures, arrays and cube maps");
  uint64_t offset = 128;
  int layers = 1, faces = 1;
  char cc[5] = {};
  std::memcpy(cc, r.at(84, 4, "the DDS header"), 4);
  const bool dx10 = (pf_flags & 0x4) && std::string(cc) == "DX10";
  if (!dx10 && (caps2 & 0x200)) {  // a legacy cube map: caps2 names the faces stored (0x400 +X .. 0x8000 -Z)
    std::string missing;
    int present = 0;
    for (int f = 0; f < 6; ++f) {
      if (caps2 & (0x400u << f)) ++present;
      else missing += (missing.empty() ? "" : ", ") + std::string(kFaceNames[f]);
    }
    if (present != 6)
      r.fail("caps2 " + hex(caps2) + ": a cube map with " + std::to_string(present) + " of its 6 faces (" + missing +
             " missing): the unit reads whole cubes");
    faces = 6;
  }
  if (dx10) {
    const uint32_t dxgi = r.u32(128, "the DX10 header"), dimension = r.u32(132, "the DX10 header");
    const uint32_t misc = r.u32(136, "the DX10 header"), array = r.u32(140, "the DX10 header");
    if (dimension != 3) r.fail("resource dimension " + std::to_string(dimension) + ": the unit reads 2D textures (3)");
    // The DX10 header decides (arraySize counts cubes); caps2 may repeat its cube flag, not contradict it.
    layers = check_layers(r, "arraySize", array, false);
    faces = (misc & 0x4) ? 6 : 1;
    if (faces == 1 && (caps2 & 0x200))
      r.fail("caps2 " + hex(caps2) + " marks a cube map, the DX10 header's miscFlag " + hex(misc) +
             " does not (TEXTURECUBE, 0x4)");
    const Known& k = known(kDxgi, dxgi, "DXGI format", r, "DXGI_FORMAT_");
    t.format = k.format;
    t.srgb = k.srgb;
    t.format_name = std::string("DXGI_FORMAT_") + k.name;
    offset = 148;
  } else if (pf_flags & 0x4) {
    const std::string code = cc;
    const struct {
      const char* fourcc;
      TexelFormat format;
    } legacy[] = {{"DXT1", TexelFormat::Bc1}, {"DXT3", TexelFormat::Bc2}, {"DXT5", TexelFormat::Bc3},
                  {"ATI1", TexelFormat::Bc4}, {"BC4U", TexelFormat::Bc4}, {"ATI2", TexelFormat::Bc5},
                  {"BC5U", TexelFormat::Bc5}};
    bool found = false;
    for (const auto& l : legacy)
      if (code == l.fourcc) {
        t.format = l.format;
        found = true;
      }
    const bool printable = std::all_of(code.begin(), code.end(), [](char c) { return c >= 32 && c < 127; }) && code.size() == 4;
    if (!found)
      r.fail("format " + (printable ? "FourCC '" + code + "'" : "D3DFORMAT " + std::to_string(fourcc)) +
             " is not supported (this unit reads " + kSupported + ")");
    t.format_name = code;
  } else {
    const uint32_t bits = r.u32(88, "the DDS header");
    const bool rgba8 = (pf_flags & 0x40) && (pf_flags & 0x1) && bits == 32 && r.u32(92, "") == 0xFF &&
                       r.u32(96, "") == 0xFF00 && r.u32(100, "") == 0xFF0000 && r.u32(104, "") == 0xFF000000;
    if (!rgba8)
      r.fail("an uncompressed pixel format of " + std::to_string(bits) +
             " bits other than RGBA8 (R in the low byte) is not supported (this unit reads " + kSupported + ")");
    t.format_name = "RGBA8";
  }
  const int levels = check_shape(r, t, width, height, mips);
  set_images(r, t, layers, faces);
  // Image after image (a cube's faces +X .. -Z, cube after cube), each with its whole chain.
  std::vector<uint64_t> in_chain(static_cast<size_t>(levels), 0);
  uint64_t chain = 0;
  for (int k = 0; k < levels; ++k) {
    in_chain[size_t(k)] = chain;
    chain += bytes_of_level(t, k);
  }
  const uint64_t first = offset;
  auto offset_of = [&](int i, int k) { return first + uint64_t(i) * chain + in_chain[size_t(k)]; };
  const uint64_t end = offset_of(image_count(t), 0);
  if (end < r.size())
    r.fail(std::to_string(r.size() - end) + " bytes after the last of " + std::to_string(levels) + " levels" +
           (image_count(t) > 1 ? " of " + std::to_string(image_count(t)) + " images" : "") +
           " (the block count does not match the size " + std::to_string(width) + "x" + std::to_string(height) + ")");
  take_images(r, t, levels, offset_of);  // (a file shorter than `end` fails there, naming the level)
  return t;
}

TextureFile read_ktx1(const Reader& r) {
  TextureFile t;
  const uint32_t endian = r.u32(12, "the KTX header");
  if (endian != 0x04030201) r.fail("a big-endian KTX file: not supported");
  const uint32_t internal = r.u32(28, "the KTX header"), width = r.u32(36, "the KTX header"),
                 height = r.u32(40, "the KTX header"), depth = r.u32(44, "the KTX header"),
                 array = r.u32(48, "the KTX header"), faces = r.u32(52, "the KTX header"),
                 mips = r.u32(56, "the KTX header"), kv = r.u32(60, "the KTX header");
  if (depth > 0)
    r.fail("pixelDepth " + std::to_string(depth) + " (a volume texture): the unit reads 2D textures, arrays and cube maps");
  const int layers = check_layers(r, "numberOfArrayElements", array, true);
  const int nfaces = check_faces(r, "numberOfFaces", faces);
  const Known& k = known(kGl, internal, "glInternalFormat", r);
  t.format = k.format;
  t.srgb = k.srgb;
  t.format_name = k.name;
  if (t.format == TexelFormat::Rgba8 && (r.u32(16, "") != 0x1401 || r.u32(24, "") != 0x1908))
    r.fail("glType/glFormat other than GL_UNSIGNED_BYTE/GL_RGBA for " + std::string(k.name));
  const int levels = check_shape(r, t, width, height, mips);
  set_images(r, t, layers, nfaces);
  // Level after level: imageSize, then every element's every face. A cube map that is not an array
  // is the exception: imageSize counts one face, and each face is padded to 4 bytes (cubePadding).
  const bool lone_cube = nfaces == 6 && array == 0;
  const int images = image_count(t);
  std::vector<uint64_t> level_at(static_cast<size_t>(levels)), stride(static_cast<size_t>(levels));
  uint64_t offset = 64 + uint64_t(kv);
  for (int l = 0; l < levels; ++l) {
    const uint64_t n = bytes_of_level(t, l);
    const uint64_t want = lone_cube ? n : n * uint64_t(images);
    const uint32_t stored = r.u32(offset, ("the imageSize of level " + std::to_string(l)).c_str());
    if (stored != want)
      r.fail("level " + std::to_string(l) + " has " + std::to_string(stored) + " bytes (imageSize); " +
             (lone_cube ? std::string("a ") + format_info(t.format).name + " face" : level_words(t, images)) +
             " of that size " + (images == 1 || lone_cube ? "has " : "have ") + std::to_string(want));
    level_at[size_t(l)] = offset + 4;
    stride[size_t(l)] = lone_cube ? (n + 3) / 4 * 4 : n;
    for (int i = 0; i < images; ++i)  // in the file's order, so a short file names where it ends
      r.at(level_at[size_t(l)] + uint64_t(i) * stride[size_t(l)], n, image_name(t, i) + "level " + std::to_string(l));
    offset += 4 + (uint64_t(images) * stride[size_t(l)] + 3) / 4 * 4;  // each level padded to 4 bytes
  }
  if (offset != r.size())
    r.fail(std::to_string(r.size() - offset) + " bytes after the last of " + std::to_string(levels) + " levels");
  take_images(r, t, levels, [&](int i, int l) { return level_at[size_t(l)] + uint64_t(i) * stride[size_t(l)]; });
  return t;
}

// astcenc's .astc file: the magic, the block footprint (x, y, z: a byte each), the size (x, y, z:
// 3 bytes each, little-endian), then the blocks of one 2D level, row-major. It names no colour
// space: linear, unless --srgb says sRGB (read_for).
TextureFile read_astc(const Reader& r) {
  TextureFile t;
  const uint8_t* h = r.at(0, 16, "the .astc header");
  const int bw = h[4], bh = h[5], bd = h[6];
  auto u24 = [&](int at) { return uint32_t(h[at]) | uint32_t(h[at + 1]) << 8 | uint32_t(h[at + 2]) << 16; };
  const uint32_t width = u24(7), height = u24(10), depth = u24(13);
  if (bd != 1 || depth != 1)
    r.fail("block " + std::to_string(bw) + "x" + std::to_string(bh) + "x" + std::to_string(bd) + ", depth " +
           std::to_string(depth) + ": a 3D ASTC texture (the unit reads 2D ASTC, the LDR profile)");
  bool found = false;
  for (int i = 0; i < 14; ++i)
    if (kAstcFootprints[i].w == bw && kAstcFootprints[i].h == bh) {
      t.format = TexelFormat(int(TexelFormat::Astc4x4) + i);
      found = true;
    }
  if (!found) r.fail("block footprint " + std::to_string(bw) + "x" + std::to_string(bh) + " is not one of ASTC's 2D footprints (4x4 .. 12x12)");
  t.format_name = std::string("ASTC ") + std::to_string(bw) + "x" + std::to_string(bh) + " (.astc, no colour space)";
  t.colour_space_given = false;
  check_shape(r, t, width, height, 1);
  const uint64_t want = bytes_of_level(t, 0);
  if (r.size() - 16 != want)
    r.fail(std::to_string(r.size() - 16) + " bytes of blocks; a " + std::to_string(width) + "x" + std::to_string(height) +
           " " + format_info(t.format).name + " level has " + std::to_string(want));
  take_images(r, t, 1, [](int, int) { return uint64_t(16); });
  return t;
}

TextureFile read_ktx2(const Reader& r) {
  TextureFile t;
  const uint32_t vk = r.u32(12, "the KTX2 header"), width = r.u32(20, "the KTX2 header"),
                 height = r.u32(24, "the KTX2 header"), depth = r.u32(28, "the KTX2 header"),
                 layers = r.u32(32, "the KTX2 header"), faces = r.u32(36, "the KTX2 header"),
                 mips = r.u32(40, "the KTX2 header"), scheme = r.u32(44, "the KTX2 header");
  if (scheme != 0) {
    const char* names[] = {"none", "BasisLZ", "Zstandard", "ZLIB"};
    r.fail("supercompression " + (scheme < 4 ? std::string(names[scheme]) : std::to_string(scheme)) +
           " is not supported (store the levels uncompressed)");
  }
  if (depth > 0)
    r.fail("pixelDepth " + std::to_string(depth) + " (a volume texture): the unit reads 2D textures, arrays and cube maps");
  const int nlayers = check_layers(r, "layerCount", layers, true);
  const int nfaces = check_faces(r, "faceCount", faces);
  const Known& k = known(kVk, vk, "vkFormat", r);
  t.format = k.format;
  t.srgb = k.srgb;
  t.format_name = k.name;
  const int levels = check_shape(r, t, width, height, mips);
  set_images(r, t, nlayers, nfaces);
  // The level index gives each level's place; a level holds every layer's every face, back to back.
  const int images = image_count(t);
  std::vector<uint64_t> level_at(static_cast<size_t>(levels));
  for (int l = 0; l < levels; ++l) {
    const uint64_t entry = 80 + 24 * uint64_t(l);
    const uint64_t offset = r.u64(entry, "the level index"), length = r.u64(entry + 8, "the level index");
    const uint64_t want = bytes_of_level(t, l) * uint64_t(images);
    if (length != want)
      r.fail("level " + std::to_string(l) + " has " + std::to_string(length) + " bytes (byteLength); " + level_words(t, images) +
             " of that size " + (images == 1 ? "has " : "have ") + std::to_string(want));
    r.at(offset, want, "level " + std::to_string(l));
    level_at[size_t(l)] = offset;
  }
  take_images(r, t, levels, [&](int i, int l) { return level_at[size_t(l)] + uint64_t(i) * bytes_of_level(t, l); });
  return t;
}

// libsquish's flags for a format (BC1 with its 1-bit alpha mode: weigh colour by alpha so that
// transparent texels take index 3 of a three-colour block).
int squish_flags(TexelFormat f) {
  switch (f) {
    case TexelFormat::Bc1: return squish::kDxt1 | squish::kColourClusterFit;
    case TexelFormat::Bc2: return squish::kDxt3 | squish::kColourClusterFit;
    case TexelFormat::Bc3: return squish::kDxt5 | squish::kColourClusterFit;
    case TexelFormat::Bc4: return squish::kBc4;
    case TexelFormat::Bc5: return squish::kBc5;
    default: return 0;
  }
}

std::vector<uint8_t> compress_level(const Image& img, TexelFormat f, bool srgb) {
  if (is_etc2(f) || is_eac(f)) return encode_etc2_level(img, f);  // (ours: Debian packages no ETC2 encoder)
  if (is_astc(f)) return encode_astc_level(img, f, srgb);
  std::vector<uint8_t> rgba(size_t(img.width) * img.height * 4);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) rgba[i * 4 + size_t(c)] = uint8_t(img.texels[i][size_t(c)]);
  if (f == TexelFormat::Bc7) {  // Mesa's encoder, in the image module
    const images::Pixels pixels{img.width, img.height, 4, false, std::move(rgba)};
    std::vector<uint8_t> blocks;
    std::string error;
    if (!images::module().compress_bc7(pixels, blocks, error)) throw Error("--format bc7: " + error);
    return blocks;
  }
  std::vector<uint8_t> blocks(level_bytes(f, img.width, img.height));
  squish::CompressImage(rgba.data(), img.width, img.height, blocks.data(), squish_flags(f));
  return blocks;
}

bool starts_with(const std::string& path, const uint8_t* magic, size_t n) {
  std::ifstream in(path, std::ios::binary);
  uint8_t head[12] = {};
  in.read(reinterpret_cast<char*>(head), std::streamsize(n));
  return in.gcount() == std::streamsize(n) && std::memcmp(head, magic, n) == 0;
}

}  // namespace

bool is_texture_file(const std::string& path) {
  return starts_with(path, kDdsMagic, 4) || starts_with(path, kKtx1Magic, 12) || starts_with(path, kKtx2Magic, 12) ||
         starts_with(path, kAstcMagic, 4);
}

TextureFile read_texture_file(const std::string& path) {
  const Reader r(path);
  const uint8_t* head = r.at(0, std::min<size_t>(r.size(), 12), "the signature");
  if (r.size() >= 4 && std::memcmp(head, kDdsMagic, 4) == 0) return read_dds(r);
  if (r.size() >= 12 && std::memcmp(head, kKtx1Magic, 12) == 0) return read_ktx1(r);
  if (r.size() >= 12 && std::memcmp(head, kKtx2Magic, 12) == 0) return read_ktx2(r);
  if (r.size() >= 4 && std::memcmp(head, kAstcMagic, 4) == 0) return read_astc(r);
  r.fail("not a DDS, KTX, KTX2 or .astc file");
}

Pyramid compress_pyramid(Pyramid pyramid, TexelFormat format, bool srgb) {
  if (format == TexelFormat::Rgba8) return pyramid;
  if (!format_info(format).encoder)
    throw Error(std::string("no ") + format_info(format).name + " encoder is built in to make the levels below level 0: "
                "give a file with its whole mip chain");
  if (pyramid.levels[0].channel_bits != 8 && !is_eac(format))  // (EAC encodes up to 16 bits: its own levels)
    throw Error("--format: block formats hold 8-bit channels");
  pyramid.format = format;
  pyramid.blocks.clear();
  for (Image& level : pyramid.levels) {
    pyramid.blocks.push_back(compress_level(level, format, srgb));
    level = decode_level(format, pyramid.blocks.back().data(), level.width, level.height, srgb);
  }
  return pyramid;
}

namespace {

// The box pyramid of level 0 as stored: 8-bit sRGB codes averaged in linear space, or as it is.
Pyramid box_pyramid(Image level0, PyramidMode mode, bool srgb) {
  if (!srgb) return build_pyramid(std::move(level0), mode);
  Pyramid p;
  p.mode = mode;
  p.levels = srgb_box_levels(level0, mode);
  return p;
}

}  // namespace

namespace {

// The options' view of a pyramid (the whole pyramid when they ask for none); view_pyramid's error
// named with the options.
Pyramid view_of(Pyramid p, const TextureOptions& o) {
  if (o.base_level == 0 && o.max_level >= p.last_level()) return p;
  try {
    return view_pyramid(p, o.base_level, o.max_level);
  } catch (const Error& e) {
    const std::string by = o.view_given_by.empty() ? "--base-level " + std::to_string(o.base_level) +
                                                         " --max-level " + std::to_string(o.max_level)
                                                   : o.view_given_by;
    throw Error(by + ": " + e.what());
  }
}

}  // namespace

Pyramid make_pyramid(Image level0, const TextureOptions& o) {
  if (!o.srgb) return view_of(compress_pyramid(box_pyramid(std::move(level0), o.mode, false), o.format), o);
  if (!format_info(o.format).srgb_allowed)
    throw Error(std::string("--srgb: an sRGB ") + format_info(o.format).name + " does not exist (" +
                format_info(o.format).name + " holds data, not colour)");
  Pyramid p = compress_pyramid(box_pyramid(std::move(level0), o.mode, true), o.format, true);
  decode_srgb_levels(p);
  return view_of(std::move(p), o);
}

namespace {

// A texture file as the options may take it: its format kept (--format and --srgb must agree).
TextureFile read_for(const std::string& spec, const TextureOptions& o) {
  TextureFile file = read_texture_file(spec);
  if (o.format_given && o.format != file.format)
    throw Error(spec + ": --format " + format_info(o.format).name + ", but the file holds " + file.format_name +
                " (a texture file keeps its format)");
  if (o.srgb && !file.colour_space_given) file.srgb = true;  // (.astc names none)
  if (is_astc(file.format)) {  // the unit is the LDR profile: say so where a file holds HDR blocks
    const FormatInfo& info = format_info(file.format);
    uint64_t hdr = 0, blocks = 0;
    auto count = [&](const std::vector<std::vector<uint8_t>>& levels) {
      for (const std::vector<uint8_t>& level : levels)
        for (size_t i = 0; i + 16 <= level.size(); i += 16, ++blocks)
          hdr += astc_mode_of(&level[i], info.block_w, info.block_h).hdr;
    };
    count(file.levels);
    for (const auto& image : file.more_images) count(image);
    if (hdr)
      std::fprintf(stderr, "texsim: note: %s: %llu of %llu ASTC blocks are HDR; the unit decodes the LDR profile, so "
                   "their texels are the error colour (magenta)\n", spec.c_str(), (unsigned long long)hdr,
                   (unsigned long long)blocks);
  }
  if (o.srgb && !file.srgb)
    throw Error(spec + ": --srgb, but the file holds " + file.format_name + ", not an sRGB format (a texture file keeps its own)");
  return file;
}

// One image's pyramid (`levels`: level 0 first, as stored), as pyramid_of describes.
Pyramid image_pyramid(const TextureFile& file, const std::vector<std::vector<uint8_t>>& levels, PyramidMode mode) {
  auto decoded = [&](int k) {
    const Extent s = level_extent({file.width, file.height}, k);
    if (!is_compressed(file.format)) {
      Image img(s.width(), s.height(), 8);
      for (size_t i = 0; i < img.texels.size(); ++i)
        for (int c = 0; c < 4; ++c) img.texels[i][size_t(c)] = levels[size_t(k)][i * 4 + size_t(c)];
      return img;
    }
    return decode_level(file.format, levels[size_t(k)].data(), s.width(), s.height(), file.srgb);
  };
  if (levels.size() == 1) {
    Pyramid p = compress_pyramid(box_pyramid(decoded(0), mode, file.srgb), file.format, file.srgb);
    if (is_compressed(file.format)) {  // level 0 as the file has it
      p.blocks[0] = levels[0];
      p.levels[0] = decoded(0);
    }
    if (file.srgb) decode_srgb_levels(p);
    return p;
  }
  Pyramid p;
  p.mode = mode;
  p.format = file.format;
  for (int k = 0; k < int(levels.size()); ++k) {
    p.levels.push_back(decoded(k));
    if (is_compressed(file.format)) p.blocks.push_back(levels[size_t(k)]);
  }
  if (file.srgb) decode_srgb_levels(p);
  return p;
}

// "an array of 4 layers", "a cube map (6 faces)", "a cube-map array of 3 cubes x 6 faces".
std::string shape_words(const TextureFile& f) {
  if (f.faces == 1) return "an array of " + std::to_string(f.layers) + " layers";
  if (f.layers == 1) return "a cube map (" + std::to_string(f.faces) + " faces)";
  return "a cube-map array of " + std::to_string(f.layers) + " cubes x " + std::to_string(f.faces) + " faces";
}

}  // namespace

Pyramid load_pyramid(const std::string& spec, const TextureOptions& o) {
  if (!is_texture_file(spec)) return make_pyramid(load_texture(spec, o.resize), o);
  const TextureFile file = read_for(spec, o);
  if (file.layers * file.faces > 1)
    throw Error(spec + ": " + shape_words(file) + ": this takes one 2D texture (texsim sample takes arrays)");
  try {
    return view_of(pyramid_of(file, o.mode), o);
  } catch (const Error& e) {
    throw Error(spec + ": " + e.what());
  }
}

std::vector<Pyramid> load_layers(const std::string& spec, const TextureOptions& o, int* faces) {
  if (faces) *faces = 1;
  if (!is_texture_file(spec)) return {make_pyramid(load_texture(spec, o.resize), o)};
  const TextureFile file = read_for(spec, o);
  std::vector<Pyramid> layers;
  try {
    layers = pyramids_of(file, o.mode);
    for (Pyramid& p : layers) p = view_of(std::move(p), o);
  } catch (const Error& e) {
    throw Error(spec + ": " + e.what());
  }
  if (faces) *faces = file.faces;
  return layers;
}

std::vector<Pyramid> load_array(const std::vector<std::string>& specs, const TextureOptions& o, TextureKind* kind) {
  if (specs.empty()) throw Error("an array texture needs at least one layer");
  std::vector<Pyramid> layers;
  if (specs.size() == 1 && !(kind && *kind == TextureKind::Cube)) {
    int faces = 1;
    layers = load_layers(specs[0], o, &faces);
    if (faces != 1 && !kind)
      throw Error(specs[0] + ": a cube map (" + std::to_string(layers.size() / 6) + " x 6 faces): this takes 2D textures");
    if (kind) *kind = faces == 6 ? TextureKind::Cube : TextureKind::Texture2D;
  } else {
    for (const std::string& spec : specs) layers.push_back(load_pyramid(spec, o));
  }
  if (layers.size() > size_t(kMaxLayers))
    throw Error(specs[0] + (specs.size() > 1 ? " ...: " : ": ") + std::to_string(layers.size()) +
                " layers: an array texture has 1 to " + std::to_string(kMaxLayers));
  auto shape = [](const Pyramid& p) {
    return std::to_string(p.extent0().w) + "x" + std::to_string(p.extent0().h) + " " + format_info(p.format).name +
           (p.srgb ? " sRGB" : "") + ", " + std::to_string(p.levels.size()) + " levels";
  };
  for (size_t l = 1; l < layers.size(); ++l) {
    const Pyramid &a = layers[0], &b = layers[l];
    if (b.extent0() != a.extent0() || b.format != a.format || b.srgb != a.srgb || b.levels.size() != a.levels.size() ||
        b.levels[0].channel_bits != a.levels[0].channel_bits)
      throw Error((specs.size() > 1 ? specs[l] : specs[0] + " layer " + std::to_string(l)) + ": " + shape(b) +
                  "; layer 0 (" + specs[0] + ") is " + shape(a) + ": an array's layers have one size, format and level count");
  }
  if (kind && *kind == TextureKind::Cube) {
    if (layers.size() % 6 != 0)
      throw Error(specs[0] + (specs.size() > 1 ? " ...: " : ": ") + std::to_string(layers.size()) +
                  " faces: a cube map has 6 (+X, -X, +Y, -Y, +Z, -Z) per cube");
    if (layers[0].extent0().w != layers[0].extent0().h)
      throw Error(specs[0] + ": cube faces of " + std::to_string(layers[0].extent0().w) + "x" +
                  std::to_string(layers[0].extent0().h) + " texels: a cube's faces are square");
    if (is_compressed(layers[0].format))
      throw Error(specs[0] + std::string(": a cube map in ") + format_info(layers[0].format).name +
                  ": the unit holds cube maps in RGBA (their skirts: docs/cube-maps.md)");
  }
  return layers;
}

std::vector<Pyramid> load_envmap(const std::string& spec, const TextureOptions& o, std::string& how) {
  TextureKind kind = TextureKind::Cube;
  if (spec.find(',') != std::string::npos) {  // six images (a face each)
    const std::vector<std::string> faces = split_commas(spec);
    how = std::to_string(faces.size()) + " face images";
    return load_array(faces, o, &kind);
  }
  if (is_texture_file(spec)) {
    TextureKind file_kind = TextureKind::Texture2D;
    std::vector<Pyramid> faces = load_array({spec}, o, &file_kind);
    if (file_kind != TextureKind::Cube || faces.size() != 6)
      throw Error(spec + ": not a cube map (" + std::to_string(faces.size()) + " images): --envmap takes a cube file, "
                  "six face images or an equirectangular image");
    how = "cube map file";
    return faces;
  }
  const Image equirect = load_texture(spec, false);
  int n = 1;
  while (n * 2 <= equirect.width / 4 && n * 2 <= 1024) n *= 2;
  how = "equirectangular " + std::to_string(equirect.width) + "x" + std::to_string(equirect.height) + " to 6 x " +
        std::to_string(n) + "x" + std::to_string(n);
  constexpr double kPi = 3.14159265358979323846;
  auto at = [&](int x, int y) -> const Texel& {
    x = ((x % equirect.width) + equirect.width) % equirect.width;  // longitude wraps, latitude clamps
    return equirect.at(x, std::clamp(y, 0, equirect.height - 1));
  };
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) {
    Image img(n, n, equirect.channel_bits);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double sc = 2.0 * (x + 0.5) / n - 1, tc = 2.0 * (y + 0.5) / n - 1;
        const double table[6][3] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
        const double* d = table[f];
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double u = 0.5 + std::atan2(d[0], -d[2]) / (2 * kPi), v = 0.5 - std::asin(d[1] / len) / kPi;
        const double px = u * equirect.width - 0.5, py = v * equirect.height - 0.5;
        const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
        const double fx = px - x0, fy = py - y0;
        Texel& t = img.at(x, y);
        for (size_t c = 0; c < 4; ++c) {
          const double top = at(x0, y0)[c] * (1 - fx) + at(x0 + 1, y0)[c] * fx;
          const double bottom = at(x0, y0 + 1)[c] * (1 - fx) + at(x0 + 1, y0 + 1)[c] * fx;
          t[c] = uint16_t(std::lround(top * (1 - fy) + bottom * fy));
        }
      }
    faces.push_back(make_pyramid(std::move(img), o));
  }
  return faces;
}

// The images' decoded pyramids against the memory limit: 8-byte texels, a third more for the
// levels below level 0.
static void check_decoded_memory(const TextureFile& file, uint64_t images) {
  const uint64_t bytes = images * uint64_t(file.width) * uint64_t(file.height) * 8 * 4 / 3;
  check_memory(bytes, std::to_string(images) + (images == 1 ? " image" : " images") + " of " + std::to_string(file.width) +
                          " x " + std::to_string(file.height) + ", decoded,");
}

Pyramid pyramid_of(const TextureFile& file, PyramidMode mode) {
  check_decoded_memory(file, 1);
  return image_pyramid(file, file.levels, mode);
}

std::vector<Pyramid> pyramids_of(const TextureFile& file, PyramidMode mode) {
  const size_t images = size_t(file.layers) * size_t(file.faces);
  if (file.layers < 1 || (file.faces != 1 && file.faces != 6) || file.more_images.size() + 1 != images)
    throw Error("pyramids_of: " + std::to_string(file.layers) + " layers x " + std::to_string(file.faces) + " faces, but " +
                std::to_string(file.more_images.size() + 1) + " images");
  check_decoded_memory(file, images);
  std::vector<Pyramid> out;
  out.reserve(images);
  out.push_back(image_pyramid(file, file.levels, mode));
  for (const auto& levels : file.more_images) out.push_back(image_pyramid(file, levels, mode));
  return out;
}

}  // namespace tex

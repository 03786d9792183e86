#include "block_formats.h"

#include <algorithm>

#include "astc.h"
#include "error.h"
#include "etc2.h"

namespace tex {

namespace {

constexpr FormatInfo kFormats[] = {
    {TexelFormat::Rgba8, "rgba8", 0, 4, true, true, 1, 1},
    {TexelFormat::Bc1, "bc1", 8, 4, true, true},
    {TexelFormat::Bc2, "bc2", 16, 4, true, true},
    {TexelFormat::Bc3, "bc3", 16, 4, true, true},
    {TexelFormat::Bc4, "bc4", 8, 1, false, true},
    {TexelFormat::Bc5, "bc5", 16, 2, false, true},
    {TexelFormat::Bc7, "bc7", 16, 4, true, true},
    {TexelFormat::Etc2Rgb, "etc2", 8, 3, true, true},
    {TexelFormat::Etc2RgbA1, "etc2a1", 8, 4, true, false},
    {TexelFormat::Etc2Rgba, "etc2a", 16, 4, true, true},
    {TexelFormat::EacR11, "eac_r11", 8, 1, false, true, 4, 4, 16},
    {TexelFormat::EacR11Snorm, "eac_r11_snorm", 8, 1, false, false, 4, 4, 16, true},
    {TexelFormat::EacRg11, "eac_rg11", 16, 2, false, true, 4, 4, 16},
    {TexelFormat::EacRg11Snorm, "eac_rg11_snorm", 16, 2, false, false, 4, 4, 16, true},
    {TexelFormat::Astc4x4, "astc4x4", 16, 4, true, true, 4, 4},
    {TexelFormat::Astc5x4, "astc5x4", 16, 4, true, true, 5, 4},
    {TexelFormat::Astc5x5, "astc5x5", 16, 4, true, true, 5, 5},
    {TexelFormat::Astc6x5, "astc6x5", 16, 4, true, true, 6, 5},
    {TexelFormat::Astc6x6, "astc6x6", 16, 4, true, true, 6, 6},
    {TexelFormat::Astc8x5, "astc8x5", 16, 4, true, true, 8, 5},
    {TexelFormat::Astc8x6, "astc8x6", 16, 4, true, true, 8, 6},
    {TexelFormat::Astc8x8, "astc8x8", 16, 4, true, true, 8, 8},
    {TexelFormat::Astc10x5, "astc10x5", 16, 4, true, true, 10, 5},
    {TexelFormat::Astc10x6, "astc10x6", 16, 4, true, true, 10, 6},
    {TexelFormat::Astc10x8, "astc10x8", 16, 4, true, true, 10, 8},
    {TexelFormat::Astc10x10, "astc10x10", 16, 4, true, true, 10, 10},
    {TexelFormat::Astc12x10, "astc12x10", 16, 4, true, true, 12, 10},
    {TexelFormat::Astc12x12, "astc12x12", 16, 4, true, true, 12, 12},
};

uint64_t le64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

// RGB 5:6:5 to 8 bits per channel by replicating the top bits (bit-exact for 0 and full scale).
Rgba8 expand565(uint32_t c) {
  const uint32_t r = c >> 11 & 31, g = c >> 5 & 63, b = c & 31;
  return {uint8_t(r << 3 | r >> 2), uint8_t(g << 2 | g >> 4), uint8_t(b << 3 | b >> 2), 255};
}

// The colour block of BC1 (and of BC2/BC3, which always take four colours): the 4-entry palette.
// Thirds and halves are rounded to nearest: (2 a + b + 1) / 3, (a + b + 1) / 2.
std::array<Rgba8, 4> colour_palette(const uint8_t* block, bool bc1) {
  const uint32_t c0 = block[0] | block[1] << 8, c1 = block[2] | block[3] << 8;
  std::array<Rgba8, 4> p{expand565(c0), expand565(c1), {}, {}};
  for (int ch = 0; ch < 3; ++ch) {
    const int a = p[0][size_t(ch)], b = p[1][size_t(ch)];
    if (!bc1 || c0 > c1) {
      p[2][size_t(ch)] = uint8_t((2 * a + b + 1) / 3);
      p[3][size_t(ch)] = uint8_t((a + 2 * b + 1) / 3);
    } else {
      p[2][size_t(ch)] = uint8_t((a + b + 1) / 2);
      p[3][size_t(ch)] = 0;
    }
  }
  p[2][3] = 255;
  p[3][3] = (!bc1 || c0 > c1) ? 255 : 0;  // BC1's three-colour mode: index 3 is transparent black
  return p;
}

// The 8-entry palette of a BC3 alpha / BC4 / BC5 channel block. Sevenths and fifths are rounded
// to nearest: ((7 - k) a0 + k a1 + 3) / 7, ((5 - k) a0 + k a1 + 2) / 5.
std::array<uint8_t, 8> channel_palette(const uint8_t* block) {
  const int a0 = block[0], a1 = block[1];
  std::array<uint8_t, 8> p{uint8_t(a0), uint8_t(a1)};
  if (a0 > a1) {
    for (int k = 1; k < 7; ++k) p[size_t(k + 1)] = uint8_t(((7 - k) * a0 + k * a1 + 3) / 7);
  } else {
    for (int k = 1; k < 5; ++k) p[size_t(k + 1)] = uint8_t(((5 - k) * a0 + k * a1 + 2) / 5);
    p[6] = 0;
    p[7] = 255;
  }
  return p;
}
int channel_index(const uint8_t* block, int i) { return int(le64(block) >> (16 + 3 * i) & 7); }
int colour_index(const uint8_t* block, int i) { return (block[4 + i / 4] >> (2 * (i % 4))) & 3; }

// ---- BC7 (BPTC) ----
// ARB_texture_compression_bptc Table.P2 (bit i: texel i is in subset 1), Table.P3 (2 bits per
// texel), and the anchor texels Table.A2, A3a, A3b.
constexpr uint16_t kPartition2[64] = {
    0xcccc, 0x8888, 0xeeee, 0xecc8, 0xc880, 0xfeec, 0xfec8, 0xec80,
    0xc800, 0xffec, 0xfe80, 0xe800, 0xffe8, 0xff00, 0xfff0, 0xf000,
    0xf710, 0x008e, 0x7100, 0x08ce, 0x008c, 0x7310, 0x3100, 0x8cce,
    0x088c, 0x3110, 0x6666, 0x366c, 0x17e8, 0x0ff0, 0x718e, 0x399c,
    0xaaaa, 0xf0f0, 0x5a5a, 0x33cc, 0x3c3c, 0x55aa, 0x9696, 0xa55a,
    0x73ce, 0x13c8, 0x324c, 0x3bdc, 0x6996, 0xc33c, 0x9966, 0x0660,
    0x0272, 0x04e4, 0x4e40, 0x2720, 0xc936, 0x936c, 0x39c6, 0x639c,
    0x9336, 0x9cc6, 0x817e, 0xe718, 0xccf0, 0x0fcc, 0x7744, 0xee22,
};
constexpr uint32_t kPartition3[64] = {
    0xaa685050, 0x6a5a5040, 0x5a5a4200, 0x5450a0a8, 0xa5a50000, 0xa0a05050,
    0x5555a0a0, 0x5a5a5050, 0xaa550000, 0xaa555500, 0xaaaa5500, 0x90909090,
    0x94949494, 0xa4a4a4a4, 0xa9a59450, 0x2a0a4250, 0xa5945040, 0x0a425054,
    0xa5a5a500, 0x55a0a0a0, 0xa8a85454, 0x6a6a4040, 0xa4a45000, 0x1a1a0500,
    0x0050a4a4, 0xaaa59090, 0x14696914, 0x69691400, 0xa08585a0, 0xaa821414,
    0x50a4a450, 0x6a5a0200, 0xa9a58000, 0x5090a0a8, 0xa8a09050, 0x24242424,
    0x00aa5500, 0x24924924, 0x24499224, 0x50a50a50, 0x500aa550, 0xaaaa4444,
    0x66660000, 0xa5a0a5a0, 0x50a050a0, 0x69286928, 0x44aaaa44, 0x66666600,
    0xaa444444, 0x54a854a8, 0x95809580, 0x96969600, 0xa85454a8, 0x80959580,
    0xaa141414, 0x96960000, 0xaaaa1414, 0xa05050a0, 0xa0a5a5a0, 0x96000000,
    0x40804080, 0xa9a8a9a8, 0xaaaaaa44, 0x2a4a5254,
};
constexpr uint8_t kAnchor2[64] = {
    15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
    15, 2, 8, 2, 2, 8, 8, 15, 2, 8, 2, 2, 8, 8, 2, 2,
    15, 15, 6, 8, 2, 8, 15, 15, 2, 8, 2, 2, 2, 15, 15, 6,
    6, 2, 6, 8, 15, 15, 2, 2, 15, 15, 15, 15, 15, 2, 2, 15,
};
constexpr uint8_t kAnchor3a[64] = {
    3, 3, 15, 15, 8, 3, 15, 15, 8, 8, 6, 6, 6, 5, 3, 3,
    3, 3, 8, 15, 3, 3, 6, 10, 5, 8, 8, 6, 8, 5, 15, 15,
    8, 15, 3, 5, 6, 10, 8, 15, 15, 3, 15, 5, 15, 15, 15, 15,
    3, 15, 5, 5, 5, 8, 5, 10, 5, 10, 8, 13, 15, 12, 3, 3,
};
constexpr uint8_t kAnchor3b[64] = {
    15, 8, 8, 3, 15, 15, 3, 8, 15, 15, 15, 15, 15, 15, 15, 8,
    15, 8, 15, 3, 15, 8, 15, 8, 3, 15, 6, 10, 15, 15, 10, 8,
    15, 3, 15, 10, 10, 8, 9, 10, 6, 15, 8, 15, 3, 6, 6, 8,
    15, 3, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 3, 15, 15, 8,
};

// ARB_texture_compression_bptc Table.M.
struct Bc7ModeInfo {
  int subsets, partition_bits, rotation_bits, index_select_bits, colour_bits, alpha_bits, endpoint_pbits,
      shared_pbits, index_bits, index2_bits;
};
constexpr Bc7ModeInfo kBc7Modes[8] = {
    {3, 4, 0, 0, 4, 0, 1, 0, 3, 0}, {2, 6, 0, 0, 6, 0, 0, 1, 3, 0}, {3, 6, 0, 0, 5, 0, 0, 0, 2, 0},
    {2, 6, 0, 0, 7, 0, 1, 0, 2, 0}, {1, 0, 2, 1, 5, 6, 0, 0, 2, 3}, {1, 0, 2, 0, 7, 8, 0, 0, 2, 2},
    {1, 0, 0, 0, 7, 7, 1, 0, 4, 0}, {2, 6, 0, 0, 5, 5, 1, 0, 2, 0},
};
// Interpolation weights in 64ths for 2-, 3- and 4-bit indices.
constexpr uint8_t kWeights2[4] = {0, 21, 43, 64};
constexpr uint8_t kWeights3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
constexpr uint8_t kWeights4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
int weight(int bits, int index) {
  return bits == 2 ? kWeights2[index] : bits == 3 ? kWeights3[index] : kWeights4[index];
}

// Reads a 128-bit block's fields from bit 0 up.
class BitReader {
 public:
  explicit BitReader(const uint8_t* block) : lo_(le64(block)), hi_(le64(block + 8)) {}
  uint32_t read(int n) {
    uint32_t v = 0;
    for (int k = 0; k < n; ++k, ++pos_) v |= uint32_t((pos_ < 64 ? lo_ >> pos_ : hi_ >> (pos_ - 64)) & 1) << k;
    return v;
  }

 private:
  uint64_t lo_, hi_;
  int pos_ = 0;
};

// A BC7 block unpacked: expanded 8-bit endpoints per subset, and each texel's indices.
struct Bc7Block {
  Bc7Mode m;
  std::array<std::array<Rgba8, 2>, 3> endpoints{};
  std::array<uint8_t, 16> index{}, index2{};
};

Bc7Block unpack_bc7(const uint8_t* block) {
  Bc7Block b;
  if (block[0] == 0) return b;  // reserved mode 8
  BitReader in(block);
  int mode = 0;
  while (!in.read(1)) ++mode;
  const Bc7ModeInfo& mi = kBc7Modes[mode];
  b.m.mode = mode;
  b.m.subsets = mi.subsets;
  b.m.partition = int(in.read(mi.partition_bits));
  b.m.rotation = int(in.read(mi.rotation_bits));
  b.m.index_select = int(in.read(mi.index_select_bits));
  // Endpoints: channel by channel, subset by subset, endpoint by endpoint.
  std::array<std::array<std::array<uint32_t, 4>, 2>, 3> raw{};
  for (int ch = 0; ch < 4; ++ch) {
    const int bits = ch < 3 ? mi.colour_bits : mi.alpha_bits;
    for (int s = 0; s < mi.subsets; ++s)
      for (int e = 0; e < 2; ++e) raw[size_t(s)][size_t(e)][size_t(ch)] = in.read(bits);
  }
  std::array<std::array<uint32_t, 2>, 3> pbit{};
  for (int s = 0; s < mi.subsets; ++s)
    for (int e = 0; e < 2; ++e)
      if (mi.endpoint_pbits) pbit[size_t(s)][size_t(e)] = in.read(1);
  for (int s = 0; s < mi.subsets; ++s)
    if (mi.shared_pbits) pbit[size_t(s)][0] = pbit[size_t(s)][1] = in.read(1);
  const bool has_pbit = mi.endpoint_pbits || mi.shared_pbits;
  // Each channel: the P-bit (if any) below the stored bits, then the top bits replicated to 8.
  for (int s = 0; s < mi.subsets; ++s)
    for (int e = 0; e < 2; ++e)
      for (int ch = 0; ch < 4; ++ch) {
        const int stored = ch < 3 ? mi.colour_bits : mi.alpha_bits;
        uint8_t& out = b.endpoints[size_t(s)][size_t(e)][size_t(ch)];
        if (stored == 0) {
          out = 255;  // no alpha in the mode: opaque
          continue;
        }
        uint32_t v = raw[size_t(s)][size_t(e)][size_t(ch)];
        int bits = stored;
        if (has_pbit) {
          v = v << 1 | pbit[size_t(s)][size_t(e)];
          ++bits;
        }
        v <<= 8 - bits;
        out = uint8_t(v | v >> bits);
      }
  // Indices in texel order; an anchor texel's index has one bit less (its top bit is 0).
  auto is_anchor = [&](int i) {
    for (int s = 0; s < mi.subsets; ++s)
      if (bc7_anchor(mi.subsets, b.m.partition, s) == i) return true;
    return false;
  };
  for (int i = 0; i < 16; ++i) b.index[size_t(i)] = uint8_t(in.read(mi.index_bits - is_anchor(i)));
  if (mi.index2_bits)
    for (int i = 0; i < 16; ++i) b.index2[size_t(i)] = uint8_t(in.read(mi.index2_bits - (i == 0)));
  return b;
}

Rgba8 bc7_texel(const Bc7Block& b, int i) {
  if (b.m.mode == 8) return {0, 0, 0, 0};
  const Bc7ModeInfo& mi = kBc7Modes[b.m.mode];
  const int s = bc7_subset(mi.subsets, b.m.partition, i);
  // Colour from the secondary indices when the index selection bit is 1; alpha from the
  // secondary ones when they exist and the bit is 0.
  int colour_bits = mi.index_bits, colour_index = b.index[size_t(i)];
  int alpha_bits = mi.index_bits, alpha_index = b.index[size_t(i)];
  if (mi.index2_bits) {
    if (b.m.index_select) {
      colour_bits = mi.index2_bits;
      colour_index = b.index2[size_t(i)];
    } else {
      alpha_bits = mi.index2_bits;
      alpha_index = b.index2[size_t(i)];
    }
  }
  Rgba8 t;
  for (int ch = 0; ch < 4; ++ch) {
    const int w = ch < 3 ? weight(colour_bits, colour_index) : weight(alpha_bits, alpha_index);
    const int e0 = b.endpoints[size_t(s)][0][size_t(ch)], e1 = b.endpoints[size_t(s)][1][size_t(ch)];
    t[size_t(ch)] = uint8_t(((64 - w) * e0 + w * e1 + 32) >> 6);
  }
  if (b.m.rotation) std::swap(t[3], t[size_t(b.m.rotation - 1)]);
  return t;
}

}  // namespace

int bc7_subset(int subsets, int partition, int texel) {
  if (subsets == 2) return kPartition2[partition] >> texel & 1;
  if (subsets == 3) return int(kPartition3[partition] >> (2 * texel) & 3);
  return 0;
}

int bc7_anchor(int subsets, int partition, int subset) {
  if (subset == 0) return 0;
  if (subsets == 2) return kAnchor2[partition];
  return subset == 1 ? kAnchor3a[partition] : kAnchor3b[partition];
}

Bc7Mode bc7_mode_of(const uint8_t* block) { return unpack_bc7(block).m; }

const FormatInfo& format_info(TexelFormat f) {
  for (const FormatInfo& i : kFormats)
    if (i.format == f) return i;
  throw Error("unknown texel format " + std::to_string(int(f)));
}

bool parse_texel_format(const std::string& name, TexelFormat& out) {
  for (const FormatInfo& i : kFormats)
    if (name == i.name) {
      out = i.format;
      return true;
    }
  return false;
}

TexelFormat parse_encodable_format(const std::string& name) {
  TexelFormat f = TexelFormat::Rgba8;
  if (!parse_texel_format(name, f))
    throw Error("unknown --format \"" + name.substr(0, 40) + (name.size() > 40 ? "...\"" : "\"") + " (" +
                texel_format_names() + ")");
  if (!format_info(f).encoder)
    throw Error("--format " + name + ": no " + name + " encoder is built in; " + name +
                " textures come from KTX and KTX2 files, read as they are");
  return f;
}

std::string texel_format_names() {
  std::string s;
  for (const FormatInfo& i : kFormats)
    if (i.encoder) s += (s.empty() ? "" : " | ") + std::string(i.name);
  return s;
}

Rgba8 decode_texel(TexelFormat f, const uint8_t* block, int i, bool srgb) {
  if (is_astc(f)) {
    const FormatInfo& info = format_info(f);
    return astc_unorm8(astc_texel16(block, info.block_w, info.block_h, srgb, i % info.block_w, i / info.block_w));
  }
  switch (f) {
    case TexelFormat::Bc1: return colour_palette(block, true)[size_t(colour_index(block, i))];
    case TexelFormat::Bc2: {
      Rgba8 t = colour_palette(block + 8, false)[size_t(colour_index(block + 8, i))];
      t[3] = uint8_t((le64(block) >> (4 * i) & 15) * 17);  // 4 bits replicated to 8
      return t;
    }
    case TexelFormat::Bc3: {
      Rgba8 t = colour_palette(block + 8, false)[size_t(colour_index(block + 8, i))];
      t[3] = channel_palette(block)[size_t(channel_index(block, i))];
      return t;
    }
    case TexelFormat::Bc4: return {channel_palette(block)[size_t(channel_index(block, i))], 0, 0, 255};
    case TexelFormat::Bc5:
      return {channel_palette(block)[size_t(channel_index(block, i))],
              channel_palette(block + 8)[size_t(channel_index(block + 8, i))], 0, 255};
    case TexelFormat::Bc7: return bc7_texel(unpack_bc7(block), i);
    case TexelFormat::Etc2Rgb: return etc2_colour_texel(block, false, i);
    case TexelFormat::Etc2RgbA1: return etc2_colour_texel(block, true, i);
    case TexelFormat::Etc2Rgba: {
      Rgba8 t = etc2_colour_texel(block + 8, false, i);
      t[3] = eac_alpha_texel(block, i);
      return t;
    }
    default: break;
  }
  throw Error("decode_texel: " + std::string(format_info(f).name) +
              (is_eac(f) ? " decodes to 16-bit channels (decode_block into Texel)" : " is not a block format"));
}

void decode_block(TexelFormat f, const uint8_t* block, Rgba8* out, bool srgb) {
  if (f == TexelFormat::Bc7) {
    const Bc7Block b = unpack_bc7(block);
    for (int i = 0; i < 16; ++i) out[i] = bc7_texel(b, i);
  } else if (is_astc(f)) {
    const FormatInfo& info = format_info(f);
    AstcTexel16 c[kMaxBlockTexels];
    astc_block16(block, info.block_w, info.block_h, srgb, c);
    for (int i = 0; i < info.block_w * info.block_h; ++i) out[i] = astc_unorm8(c[i]);
  } else {
    for (int i = 0; i < 16; ++i) out[i] = decode_texel(f, block, i);
  }
}

void decode_block(TexelFormat f, const uint8_t* block, Texel* out, bool srgb) {
  if (is_eac(f)) {
    const bool snorm = format_info(f).snorm, rg = f == TexelFormat::EacRg11 || f == TexelFormat::EacRg11Snorm;
    const uint16_t zero = snorm ? 32768 : 0;
    for (int i = 0; i < 16; ++i)
      out[i] = {eac_r11_code(block, snorm, i), rg ? eac_r11_code(block + 8, snorm, i) : zero, zero, 65535};
    return;
  }
  Rgba8 t[kMaxBlockTexels];
  decode_block(f, block, t, srgb);
  const FormatInfo& info = format_info(f);
  for (int i = 0; i < info.block_w * info.block_h; ++i) out[i] = {t[i][0], t[i][1], t[i][2], t[i][3]};
}

uint64_t level_bytes(TexelFormat f, int width, int height) {
  const FormatInfo& info = format_info(f);
  if (!info.block_bytes) return uint64_t(width) * uint64_t(height) * 4;
  return uint64_t((width + info.block_w - 1) / info.block_w) * uint64_t((height + info.block_h - 1) / info.block_h) *
         uint64_t(info.block_bytes);
}

Image decode_level(TexelFormat f, const uint8_t* blocks, int width, int height, bool srgb) {
  const FormatInfo& info = format_info(f);
  Image img(width, height, info.channel_bits);
  const int fw = info.block_w, fh = info.block_h;
  const int bw = (width + fw - 1) / fw, bh = (height + fh - 1) / fh;
  Texel t[kMaxBlockTexels];
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      decode_block(f, blocks + (size_t(by) * size_t(bw) + size_t(bx)) * size_t(info.block_bytes), t, srgb);
      for (int i = 0; i < fw * fh; ++i) {
        const int x = bx * fw + i % fw, y = by * fh + i / fw;
        if (x < width && y < height) img.at(x, y) = t[i];
      }
    }
  return img;
}

}  // namespace tex

// The model's block decoders (model/block_formats.h) against decoders no one here wrote:
// Mesa (OSMesa's softpipe: glCompressedTexImage2D, then glGetTexImage) for every format, libsquish
// for BC1-BC3 (libsquish 1.15 compresses BC4/BC5 but decodes them as BC1), OpenImageIO's DDS
// reader for BC1-BC5 and BC7. Random blocks, every BC7 mode equally
// often. Where the formats leave the rounding of interpolated values to the decoder (BC1-BC5),
// decoders may differ by 1 LSB; the counts of such texels are printed and docs/numerics.md
// explains them. BC7's rounding is specified: it must be identical.
#define GL_GLEXT_PROTOTYPES  // glGenerateMipmap
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <squish.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "model/block_formats.h"
#include "model/etc2.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "stimulus.h"
#include "workloads/etc2_encode.h"
#include "workloads/texture_io.h"

using namespace tex;

namespace {

constexpr int kSide = 256;  // texels: 64 x 64 = 4096 blocks per format
constexpr int kBlocks = (kSide / 4) * (kSide / 4);

// Random blocks of a format; BC7 blocks take modes 0..7 in turn (random bytes would give mode 0
// half the time), with random bits above the mode.
std::vector<uint8_t> random_blocks(TexelFormat f, uint64_t seed) {
  const int bytes = format_info(f).block_bytes;
  std::mt19937_64 rng(seed);
  std::vector<uint8_t> data(size_t(kBlocks) * bytes);
  for (uint8_t& b : data) b = uint8_t(rng());
  for (int k = 0; k < kBlocks; ++k) {
    uint8_t* block = &data[size_t(k) * bytes];
    if (f == TexelFormat::Bc7) {
      const int mode = k % 8;
      block[0] = uint8_t((block[0] << (mode + 1)) | (1 << mode));
    }
    // BC1: half the blocks in the three-colour mode (c0 <= c1), half in the four-colour one.
    if (f == TexelFormat::Bc1 && (k % 2 == 0) != (block[0] + block[1] * 256 > block[2] + block[3] * 256)) {
      std::swap(block[0], block[2]);
      std::swap(block[1], block[3]);
    }
  }
  return data;
}

struct Comparison {
  int texels = 0, differ = 0, max_diff = 0;
  void add(const Rgba8& want, const uint8_t* got, int channels) {
    ++texels;
    int d = 0;
    for (int c = 0; c < channels; ++c) d = std::max(d, std::abs(int(want[size_t(c)]) - int(got[c])));
    differ += d > 0;
    max_diff = std::max(max_diff, d);
  }
};

// Decodes `data` (kSide x kSide texels) with Mesa; false if the GL lacks the format.
bool mesa_decode(GLenum internal_format, const std::vector<uint8_t>& data, std::vector<uint8_t>& rgba) {
  static std::vector<uint8_t> buffer(16 * 16 * 4);
  static OSMesaContext ctx = [] {
    OSMesaContext c = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (c) OSMesaMakeCurrent(c, buffer.data(), GL_UNSIGNED_BYTE, 16, 16);
    return c;
  }();
  if (!ctx) return false;
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glCompressedTexImage2D(GL_TEXTURE_2D, 0, internal_format, kSide, kSide, 0, GLsizei(data.size()), data.data());
  if (glGetError() != GL_NO_ERROR) return false;
  rgba.assign(size_t(kSide) * kSide * 4, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glDeleteTextures(1, &tex);
  return glGetError() == GL_NO_ERROR;
}

// The same for EAC R11/RG11: Mesa's 16-bit channels (GL_RED or GL_RG; GL_UNSIGNED_SHORT, or
// GL_SHORT for the signed forms), 1 or 2 per texel.
bool mesa_decode16(GLenum internal_format, int channels, bool snorm, const std::vector<uint8_t>& data,
                   std::vector<uint16_t>& out) {
  std::vector<uint8_t> unused;
  if (!mesa_decode(internal_format, data, unused)) return false;  // (the context, and the format's support)
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glCompressedTexImage2D(GL_TEXTURE_2D, 0, internal_format, kSide, kSide, 0, GLsizei(data.size()), data.data());
  out.assign(size_t(kSide) * kSide * size_t(channels), 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, channels == 1 ? GL_RED : GL_RG, snorm ? GL_SHORT : GL_UNSIGNED_SHORT, out.data());
  glDeleteTextures(1, &tex);
  return glGetError() == GL_NO_ERROR;
}

Comparison compare_level(TexelFormat f, const std::vector<uint8_t>& data, const std::vector<uint8_t>& rgba,
                         int channels) {
  const Image ours = decode_level(f, data.data(), kSide, kSide);
  Comparison c;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const Texel& t = ours.at(x, y);
      c.add({uint8_t(t[0]), uint8_t(t[1]), uint8_t(t[2]), uint8_t(t[3])}, &rgba[(size_t(y) * kSide + x) * 4], channels);
    }
  return c;
}

void report(const char* who, TexelFormat f, const Comparison& c) {
  std::printf("  %s %s: %d of %d texels differ, by at most %d LSB\n", who, format_info(f).name, c.differ, c.texels,
              c.max_diff);
}

}  // namespace

TEST(BlockFormatsReference, MesaDecodesTheSame) {
  // softpipe: llvmpipe's BC3-alpha/BC4/BC5 decode is off by 2 LSB in places (a fixed-point
  // reciprocal of 7), more than the formats allow; softpipe decodes as the formats say.
  setenv("GALLIUM_DRIVER", "softpipe", 1);
  const struct {
    TexelFormat format;
    GLenum gl;
    int max_diff;  // the rounding the format leaves to the decoder (docs/numerics.md)
  } cases[] = {
      {TexelFormat::Bc1, GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, 1}, {TexelFormat::Bc2, GL_COMPRESSED_RGBA_S3TC_DXT3_EXT, 1},
      {TexelFormat::Bc3, GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, 1}, {TexelFormat::Bc4, GL_COMPRESSED_RED_RGTC1, 1},
      {TexelFormat::Bc5, GL_COMPRESSED_RG_RGTC2, 1},           {TexelFormat::Bc7, GL_COMPRESSED_RGBA_BPTC_UNORM, 0},
  };
  for (const auto& k : cases) {
    const std::vector<uint8_t> data = random_blocks(k.format, 1000 + uint64_t(k.format));
    std::vector<uint8_t> rgba;
    ASSERT_TRUE(mesa_decode(k.gl, data, rgba)) << "Mesa cannot decode " << format_info(k.format).name;
    const Comparison c = compare_level(k.format, data, rgba, 4);
    report("Mesa", k.format, c);
    EXPECT_LE(c.max_diff, k.max_diff) << format_info(k.format).name;
  }
}

// ETC2's colour blocks set to each mode in turn (individual, differential, T, H, planar: the last
// three are differential blocks whose red, green or blue sum leaves 0..31), random bits elsewhere.
std::vector<uint8_t> etc2_blocks(TexelFormat f, uint64_t seed) {
  std::vector<uint8_t> data = random_blocks(f, seed);
  const int bytes = format_info(f).block_bytes;
  std::mt19937_64 rng(seed + 1);
  for (int k = 0; k < kBlocks; ++k)
    stimulus::set_etc2_mode(rng, &data[size_t(k) * bytes + (f == TexelFormat::Etc2Rgba ? 8 : 0)], k % 5,
                            f == TexelFormat::Etc2RgbA1, k / 5 % 4 == 0);
  return data;
}

TEST(BlockFormatsReference, MesaDecodesEtc2TheSame) {
  setenv("GALLIUM_DRIVER", "softpipe", 1);
  const struct {
    TexelFormat format;
    GLenum gl;
  } cases[] = {{TexelFormat::Etc2Rgb, GL_COMPRESSED_RGB8_ETC2},
               {TexelFormat::Etc2RgbA1, GL_COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2},
               {TexelFormat::Etc2Rgba, GL_COMPRESSED_RGBA8_ETC2_EAC}};
  for (const auto& k : cases) {
    const std::vector<uint8_t> data = etc2_blocks(k.format, 2000 + uint64_t(k.format));
    // Every mode is decoded (RGB8A1 has no individual mode: its bit 33 says opaque, half the blocks).
    const int bytes = format_info(k.format).block_bytes, colour = k.format == TexelFormat::Etc2Rgba ? 8 : 0;
    int modes[5] = {}, see_through = 0;
    for (int b = 0; b < kBlocks; ++b) {
      const uint8_t* c = &data[size_t(b) * bytes + colour];
      ++modes[int(etc2_mode_of(c, k.format == TexelFormat::Etc2RgbA1))];
      see_through += k.format == TexelFormat::Etc2RgbA1 && !(c[3] & 2);
    }
    for (int m = k.format == TexelFormat::Etc2RgbA1 ? 1 : 0; m < 5; ++m)
      EXPECT_GT(modes[m], kBlocks / 8) << format_info(k.format).name << " mode " << m;
    if (k.format == TexelFormat::Etc2RgbA1) {
      EXPECT_GT(see_through, kBlocks / 4);
    }
    std::vector<uint8_t> rgba;
    ASSERT_TRUE(mesa_decode(k.gl, data, rgba)) << "Mesa cannot decode " << format_info(k.format).name;
    const Comparison c = compare_level(k.format, data, rgba, 4);
    report("Mesa", k.format, c);
    EXPECT_EQ(c.max_diff, 0) << format_info(k.format).name;  // ETC2 leaves no rounding to the decoder
  }
  // And an encoded real image: the test card through texsim's encoder (workloads/etc2_encode.h),
  // RGB8 and RGBA8, as a texture file of the encoder would hold it.
  const Image card = load_texture("testcard:" + std::to_string(kSide) + "x" + std::to_string(kSide));
  for (const auto& k : {cases[0], cases[2]}) {
    const std::vector<uint8_t> data = encode_etc2_level(card, k.format);
    std::vector<uint8_t> rgba;
    ASSERT_TRUE(mesa_decode(k.gl, data, rgba));
    const Comparison c = compare_level(k.format, data, rgba, 4);
    report("Mesa (the encoded test card)", k.format, c);
    EXPECT_EQ(c.max_diff, 0) << format_info(k.format).name;
  }
}

// EAC R11 and RG11, unsigned and signed: the model's 16-bit channels (decode_level; the signed
// ones' offset binary less 32768) against Mesa's R16/RG16 and R16_SNORM/RG16_SNORM, on random
// blocks (stimulus::random_eac_block: multiplier 0, the bases where values clamp) and on the test
// card through texsim's encoder (the unsigned forms).
TEST(BlockFormatsReference, MesaDecodesEacTheSame) {
  setenv("GALLIUM_DRIVER", "softpipe", 1);
  const struct {
    TexelFormat format;
    GLenum gl;
  } cases[] = {{TexelFormat::EacR11, GL_COMPRESSED_R11_EAC},
               {TexelFormat::EacR11Snorm, GL_COMPRESSED_SIGNED_R11_EAC},
               {TexelFormat::EacRg11, GL_COMPRESSED_RG11_EAC},
               {TexelFormat::EacRg11Snorm, GL_COMPRESSED_SIGNED_RG11_EAC}};
  const Image card = load_texture("testcard:" + std::to_string(kSide) + "x" + std::to_string(kSide));
  for (const auto& k : cases) {
    const FormatInfo& info = format_info(k.format);
    std::mt19937_64 rng(3000 + uint64_t(k.format));
    std::vector<uint8_t> data(size_t(kBlocks) * size_t(info.block_bytes));
    for (size_t i = 0; i < data.size(); i += 8) stimulus::random_eac_block(rng, &data[i]);
    for (int encoded = 0; encoded < (info.encoder ? 2 : 1); ++encoded) {
      if (encoded) data = encode_etc2_level(card, k.format);
      std::vector<uint16_t> mesa;
      ASSERT_TRUE(mesa_decode16(k.gl, info.channels, info.snorm, data, mesa)) << "Mesa cannot decode " << info.name;
      const Image ours = decode_level(k.format, data.data(), kSide, kSide);
      ASSERT_EQ(ours.channel_bits, 16);
      int differ = 0, max_diff = 0;
      for (size_t t = 0; t < ours.texels.size(); ++t)
        for (int c = 0; c < info.channels; ++c) {
          const int want = int(ours.texels[t][size_t(c)]) - (info.snorm ? 32768 : 0);
          const int got = info.snorm ? int(int16_t(mesa[t * size_t(info.channels) + size_t(c)]))
                                     : int(mesa[t * size_t(info.channels) + size_t(c)]);
          differ += want != got;
          max_diff = std::max(max_diff, std::abs(want - got));
        }
      std::printf("  Mesa%s %s: %d of %zu channels differ, by at most %d\n", encoded ? " (the encoded test card)" : "",
                  info.name, differ, ours.texels.size() * size_t(info.channels), max_diff);
      EXPECT_EQ(differ, 0) << info.name;  // EAC leaves no rounding to the decoder
    }
  }
}

TEST(BlockFormatsReference, LibsquishDecodesTheSame) {
  const struct {
    TexelFormat format;
    int flags, channels;
  } cases[] = {
      {TexelFormat::Bc1, squish::kDxt1, 4}, {TexelFormat::Bc2, squish::kDxt3, 4}, {TexelFormat::Bc3, squish::kDxt5, 4}};
  for (const auto& k : cases) {
    const std::vector<uint8_t> data = random_blocks(k.format, 2000 + uint64_t(k.format));
    const int bytes = format_info(k.format).block_bytes;
    Comparison c;
    for (int b = 0; b < kBlocks; ++b) {
      uint8_t rgba[64];
      squish::Decompress(rgba, &data[size_t(b) * bytes], k.flags);
      Rgba8 ours[16];
      decode_block(k.format, &data[size_t(b) * bytes], ours);
      for (int i = 0; i < 16; ++i) c.add(ours[i], &rgba[4 * i], k.channels);
    }
    report("libsquish", k.format, c);
    EXPECT_LE(c.max_diff, 1) << format_info(k.format).name;
  }
}

namespace {

// A DDS file of one level: the legacy header with a FourCC, or (fourcc "DX10") the DX10 header
// with DXGI format `dxgi` (OpenImageIO 2.4 reads BC1-BC5 from FourCCs, BC7 from DX10 only).
void write_dds(const std::filesystem::path& path, const char* fourcc, uint32_t dxgi, const std::vector<uint8_t>& data) {
  uint32_t h[32] = {};
  h[0] = 0x20534444;                      // "DDS "
  h[1] = 124;                             // header size
  h[2] = 0x1 | 0x2 | 0x4 | 0x1000 | 0x80000;  // caps, height, width, pixel format, linear size
  h[3] = kSide;
  h[4] = kSide;
  h[5] = uint32_t(data.size());
  h[7] = 1;                               // one level
  h[19] = 32;                             // pixel format size
  h[20] = 0x4;                            // FOURCC
  std::memcpy(&h[21], fourcc, 4);
  h[27] = 0x1000;                         // DDSCAPS_TEXTURE
  const uint32_t dx10[5] = {dxgi, 3, 0, 1, 0};  // format, TEXTURE2D, flags, array size, flags2
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(h), sizeof h);
  if (std::string(fourcc) == "DX10") out.write(reinterpret_cast<const char*>(dx10), sizeof dx10);
  out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
}

}  // namespace

TEST(BlockFormatsReference, OpenImageIoDdsReaderDecodesTheSame) {
  const struct {
    TexelFormat format;
    const char* fourcc;
    uint32_t dxgi;
    int channels;  // OpenImageIO gives BC4 as 1 channel, BC5 as 2
    int max_diff;
  } cases[] = {
      {TexelFormat::Bc1, "DXT1", 0, 4, 1},  {TexelFormat::Bc2, "DXT3", 0, 4, 1}, {TexelFormat::Bc3, "DXT5", 0, 4, 1},
      {TexelFormat::Bc4, "ATI1", 0, 1, 1},  {TexelFormat::Bc5, "ATI2", 0, 2, 1}, {TexelFormat::Bc7, "DX10", 98, 4, 0},
  };
  const auto path = std::filesystem::temp_directory_path() / ("blocks_" + std::to_string(getpid()) + ".dds");
  for (const auto& k : cases) {
    const std::vector<uint8_t> data = random_blocks(k.format, 3000 + uint64_t(k.format));
    write_dds(path, k.fourcc, k.dxgi, data);
    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    ASSERT_EQ(spec.width, kSide);
    ASSERT_EQ(spec.nchannels, k.channels) << format_info(k.format).name;
    std::vector<uint8_t> pixels(size_t(kSide) * kSide * size_t(k.channels));
    ASSERT_TRUE(in->read_image(0, 0, 0, k.channels, OIIO::TypeDesc::UINT8, pixels.data())) << in->geterror();
    std::vector<uint8_t> rgba(size_t(kSide) * kSide * 4);
    for (size_t t = 0; t < size_t(kSide) * kSide; ++t)
      for (int c = 0; c < k.channels; ++c) rgba[t * 4 + size_t(c)] = pixels[t * size_t(k.channels) + size_t(c)];
    const Comparison c = compare_level(k.format, data, rgba, k.channels);
    report("OpenImageIO", k.format, c);
    EXPECT_LE(c.max_diff, k.max_diff) << format_info(k.format).name;
  }
  std::filesystem::remove(path);
}

// The sRGB decode table against Mesa's (softpipe): a 256 x 1 GL_SRGB8_ALPHA8 texture of every code
// drawn with nearest filtering into a float framebuffer gives each code's linear value; and
// glGenerateMipmap of a random sRGB texture, which Mesa filters in linear space, against the
// model's cascade pyramid (srgb_box_levels: each level from its parent's codes).
TEST(BlockFormatsReference, MesaSrgbDecodeAndMipmaps) {
  setenv("GALLIUM_DRIVER", "softpipe", 1);
  std::vector<float> pixels(256 * 4, -1.0f);
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
  ASSERT_TRUE(ctx);
  ASSERT_TRUE(OSMesaMakeCurrent(ctx, pixels.data(), GL_FLOAT, 256, 1));
  std::vector<uint8_t> codes(256 * 4);
  for (int c = 0; c < 256; ++c) codes[size_t(c) * 4] = codes[size_t(c) * 4 + 1] = codes[size_t(c) * 4 + 2] = uint8_t(c), codes[size_t(c) * 4 + 3] = 255;
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, 256, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, codes.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glEnable(GL_TEXTURE_2D);
  glViewport(0, 0, 256, 1);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, 256, 0, 1, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glBegin(GL_QUADS);
  glTexCoord2f(0, 0); glVertex2f(0, 0);
  glTexCoord2f(1, 0); glVertex2f(256, 0);
  glTexCoord2f(1, 1); glVertex2f(256, 1);
  glTexCoord2f(0, 1); glVertex2f(0, 1);
  glEnd();
  glFinish();
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  int worst = 0;
  for (int c = 0; c < 256; ++c) {
    const long mesa = std::lround(double(pixels[size_t(c) * 4]) * 65535.0);
    worst = std::max(worst, int(std::labs(mesa - long(srgb_decode_table()[size_t(c)]))));
  }
  std::printf("  sRGB decode: the model's unorm16 table and Mesa's float decode differ by at most %d / 65535\n", worst);
  EXPECT_LE(worst, 1);

  // glGenerateMipmap in linear space against the model's cascade pyramid.
  constexpr int kMip = 64;
  std::mt19937_64 rng(9);
  Image level0(kMip, kMip, 8);
  std::vector<uint8_t> bytes(size_t(kMip) * kMip * 4);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(rng());
  for (size_t i = 0; i < level0.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) level0.texels[i][size_t(c)] = bytes[i * 4 + size_t(c)];
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, kMip, kMip, 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  const std::vector<Image> model = srgb_box_levels(level0, PyramidMode::Cascade);
  int differ = 0, total = 0, mip_worst = 0;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int k = 1; k < int(model.size()); ++k) {
    const Image& want = model[size_t(k)];
    std::vector<uint8_t> got(size_t(want.width) * want.height * 4);
    glGetTexImage(GL_TEXTURE_2D, k, GL_RGBA, GL_UNSIGNED_BYTE, got.data());
    for (size_t i = 0; i < want.texels.size(); ++i)
      for (int c = 0; c < 3; ++c) {  // (alpha: Mesa's blit rounds it its own way; the model's is build_pyramid's)
        const int d = std::abs(int(want.texels[i][size_t(c)]) - int(got[i * 4 + size_t(c)]));
        differ += d > 0;
        mip_worst = std::max(mip_worst, d);
        ++total;
      }
  }
  std::printf("  sRGB mipmaps: %d of %d R, G, B codes differ from Mesa's glGenerateMipmap, by at most %d\n", differ,
              total, mip_worst);
  EXPECT_LE(mip_worst, 1);
  glDeleteTextures(1, &tex);
  OSMesaDestroyContext(ctx);
}

// Texture files (sim/workloads/texture_files.h): DDS with legacy and DX10 headers, KTX 1 and KTX2
// with every level, read back block for block; OpenImageIO reads the same DDS files level by level
// and decodes them as the model does (within the 1 LSB of docs/numerics.md); every bad input is one
// error naming the file and the value; libsquish's BC1-BC5 keep the picture.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "model/error.h"
#include "model/srgb.h"
#include "workloads/texture_files.h"

using namespace tex;
namespace fs = std::filesystem;

namespace {

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("texture_files_" + std::to_string(getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  fs::path operator/(const std::string& name) const { return dir / name; }
};

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
void put64(std::vector<uint8_t>& out, uint64_t v) {
  put32(out, uint32_t(v));
  put32(out, uint32_t(v >> 32));
}
void save(const fs::path& p, const std::vector<uint8_t>& bytes) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Random levels of a w x h texture in format f (BC7: every mode in turn).
std::vector<std::vector<uint8_t>> random_levels(TexelFormat f, int w, int h, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<uint8_t>> levels;
  for (int k = 0; k < count; ++k) {
    const Extent s = level_extent({w, h}, k);
    std::vector<uint8_t> l(level_bytes(f, s.width(), s.height()));
    for (uint8_t& b : l) b = uint8_t(rng());
    if (f == TexelFormat::Bc7)
      for (size_t i = 0; i < l.size(); i += 16) l[i] = uint8_t(l[i] << (i / 16 % 8 + 1) | 1 << (i / 16 % 8));
    levels.push_back(l);
  }
  return levels;
}

// DDS: a FourCC, or "DX10" with a DXGI format.
std::vector<uint8_t> dds(const char* fourcc, uint32_t dxgi, int w, int h, const std::vector<std::vector<uint8_t>>& levels) {
  std::vector<uint8_t> out = {'D', 'D', 'S', ' '};
  const uint32_t head[31] = {124, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000, uint32_t(h), uint32_t(w), 0, 0, uint32_t(levels.size()),
                             0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // reserved
                             32, 0x4, 0, 0, 0, 0, 0, 0,        // pixel format (FourCC below)
                             0x1000 | 0x400000 | 0x8, 0, 0, 0, 0};
  for (uint32_t v : head) put32(out, v);
  std::memcpy(&out[84], fourcc, 4);
  if (std::string(fourcc) == "DX10")
    for (uint32_t v : {dxgi, 3u, 0u, 1u, 0u}) put32(out, v);
  for (const auto& l : levels) out.insert(out.end(), l.begin(), l.end());
  return out;
}

std::vector<uint8_t> ktx1(uint32_t internal, int w, int h, const std::vector<std::vector<uint8_t>>& levels) {
  std::vector<uint8_t> out = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
  const bool rgba8 = internal == 0x8058 || internal == 0x8C43;  // glType, glFormat: 0 when compressed
  for (uint32_t v : {0x04030201u, rgba8 ? 0x1401u : 0u, 1u, rgba8 ? 0x1908u : 0u, internal, 0x1908u, uint32_t(w),
                     uint32_t(h), 0u, 0u, 1u, uint32_t(levels.size()), 0u})
    put32(out, v);
  for (const auto& l : levels) {
    put32(out, uint32_t(l.size()));
    out.insert(out.end(), l.begin(), l.end());
    while (out.size() % 4) out.push_back(0);
  }
  return out;
}

std::vector<uint8_t> ktx2(uint32_t vk, int w, int h, const std::vector<std::vector<uint8_t>>& levels) {
  std::vector<uint8_t> out = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  for (uint32_t v : {vk, 1u, uint32_t(w), uint32_t(h), 0u, 0u, 1u, uint32_t(levels.size()), 0u}) put32(out, v);
  for (int i = 0; i < 4; ++i) put32(out, 0);  // no DFD, no key/value data
  put64(out, 0);
  put64(out, 0);
  // Level index (level 0 first), the data smallest level first, as KTX2 writers store it.
  uint64_t at = out.size() + 24 * levels.size();
  std::vector<uint64_t> offsets(levels.size());
  for (size_t k = levels.size(); k-- > 0;) {
    offsets[k] = at;
    at += levels[k].size();
  }
  for (size_t k = 0; k < levels.size(); ++k) {
    put64(out, offsets[k]);
    put64(out, levels[k].size());
    put64(out, levels[k].size());
  }
  for (size_t k = levels.size(); k-- > 0;) out.insert(out.end(), levels[k].begin(), levels[k].end());
  return out;
}

std::string error_of(const fs::path& p) {
  try {
    read_texture_file(p.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TextureFiles, EveryContainerGivesBackItsLevels) {
  Scratch s;
  const struct {
    TexelFormat format;
    const char* fourcc;
    uint32_t dxgi, gl, vk;
    bool srgb;
  } cases[] = {
      {TexelFormat::Bc1, "DXT1", 71, 0x83F1, 133, false}, {TexelFormat::Bc2, "DXT3", 74, 0x83F2, 135, false},
      {TexelFormat::Bc3, "DXT5", 77, 0x83F3, 137, false}, {TexelFormat::Bc4, "ATI1", 80, 0x8DBB, 139, false},
      {TexelFormat::Bc5, "ATI2", 83, 0x8DBD, 141, false}, {TexelFormat::Bc7, "DX10", 98, 0x8E8C, 145, false},
      {TexelFormat::Bc7, "DX10", 99, 0x8E8D, 146, true},  {TexelFormat::Rgba8, "DX10", 28, 0x8058, 37, false},
  };
  for (const auto& c : cases) {
    const auto levels = random_levels(c.format, 64, 16, 7, uint64_t(c.format) + 10 * c.srgb);
    const std::vector<std::pair<std::string, std::vector<uint8_t>>> files = {
        {"dx10.dds", dds("DX10", c.dxgi, 64, 16, levels)},
        {"a.ktx", ktx1(c.gl, 64, 16, levels)},
        {"a.ktx2", ktx2(c.vk, 64, 16, levels)},
        {"legacy.dds", dds(c.fourcc, 0, 64, 16, levels)}};
    for (const auto& [name, bytes] : files) {
      if (name == "legacy.dds" && std::string(c.fourcc) == "DX10") continue;
      save(s / name, bytes);
      ASSERT_TRUE(is_texture_file((s / name).string()));
      const TextureFile t = read_texture_file((s / name).string());
      EXPECT_EQ(t.format, c.format) << name;
      EXPECT_EQ(t.srgb, c.srgb) << name;
      EXPECT_EQ(t.width, 64);
      EXPECT_EQ(t.height, 16);
      EXPECT_EQ(t.levels, levels) << name << " " << t.format_name;
    }
  }
  save(s / "plain.png", {0x89, 'P', 'N', 'G'});
  EXPECT_FALSE(is_texture_file((s / "plain.png").string()));
}

// OpenImageIO's DDS reader decodes every level of the file as the model's decoders do.
TEST(TextureFiles, OpenImageIoReadsTheSameLevels) {
  Scratch s;
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc3, TexelFormat::Bc7}) {
    const auto levels = random_levels(f, 32, 32, 6, 40 + uint64_t(f));
    const fs::path p = s / "m.dds";
    save(p, f == TexelFormat::Bc7 ? dds("DX10", 98, 32, 32, levels) : dds(f == TexelFormat::Bc1 ? "DXT1" : "DXT5", 0, 32, 32, levels));
    const Pyramid pyr = pyramid_of(read_texture_file(p.string()), PyramidMode::Exact);
    ASSERT_EQ(pyr.levels.size(), 6u);
    EXPECT_EQ(pyr.format, f);
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    for (int k = 0; k < 6; ++k) {
      ASSERT_TRUE(in->seek_subimage(0, k)) << k;
      const int w = in->spec().width, h = in->spec().height;
      ASSERT_EQ(w, pyr.levels[size_t(k)].width);
      ASSERT_EQ(h, pyr.levels[size_t(k)].height);
      std::vector<uint8_t> px(size_t(w) * h * 4);
      ASSERT_TRUE(in->read_image(0, k, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
      int worst = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int(pyr.levels[size_t(k)].at(x, y)[size_t(c)]) - px[(size_t(y) * w + x) * 4 + size_t(c)]));
      EXPECT_LE(worst, f == TexelFormat::Bc7 ? 0 : 1) << format_info(f).name << " level " << k;
    }
  }
}

TEST(TextureFiles, BadFilesNameTheProblem) {
  Scratch s;
  const auto bc1 = random_levels(TexelFormat::Bc1, 16, 16, 5, 1);
  auto expect_error = [&](const std::string& name, const std::vector<uint8_t>& bytes, const std::string& want) {
    save(s / name, bytes);
    const std::string e = error_of(s / name);
    EXPECT_NE(e.find(want), std::string::npos) << name << ": " << e;
    EXPECT_NE(e.find(name), std::string::npos) << e;
  };
  std::vector<uint8_t> full = dds("DXT1", 0, 16, 16, bc1);
  expect_error("truncated.dds", std::vector<uint8_t>(full.begin(), full.end() - 3), "truncated: level 4 needs 8 bytes");
  std::vector<uint8_t> extra = full;
  extra.push_back(0);
  expect_error("extra.dds", extra, "1 bytes after the last of 5 levels");
  expect_error("bc6.dds", dds("DX10", 95, 16, 16, bc1), "DXGI_FORMAT_BC6H_UF16 is not supported");
  expect_error("unknown.dds", dds("DX10", 200, 16, 16, bc1), "DXGI format 200 is not supported");
  expect_error("snorm.ktx2", ktx2(140, 16, 16, bc1), "VK_FORMAT_BC4_SNORM_BLOCK is not supported");
  expect_error("bc6.ktx", ktx1(0x8E8F, 16, 16, bc1), "GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT is not supported");
  expect_error("partial.dds", dds("DXT1", 0, 16, 16, {bc1[0], bc1[1], bc1[2]}), "3 mip levels: a partial chain");
  expect_error("partial.ktx", ktx1(0x83F1, 16, 16, {bc1[0], bc1[1]}), "2 mip levels: a partial chain");
  expect_error("huge.dds", dds("DXT1", 0, 8196, 16, {bc1[0]}), "8196x16: the unit takes sides from 1 to 8192");
  // A side that is not a power of two is a texture like any other (GL's level sizes).
  const auto npot = random_levels(TexelFormat::Bc1, 12, 20, 5, 2);  // 12x20, 6x10, 3x5, 1x2, 1x1
  save(s / "npot.dds", dds("DXT1", 0, 12, 20, npot));
  EXPECT_EQ(error_of(s / "npot.dds"), "");
  expect_error("small.dds", dds("DXT1", 0, 2, 2, {bc1[4]}), "2x2: a bc1 texture needs sides that are multiples of 4");
  expect_error("fourcc.dds", dds("DXT2", 0, 16, 16, bc1), "FourCC 'DXT2' is not supported");
  std::vector<uint8_t> zstd = ktx2(133, 16, 16, bc1);
  zstd[44] = 2;
  expect_error("zstd.ktx2", zstd, "supercompression Zstandard is not supported");
  std::vector<uint8_t> cube = dds("DXT1", 0, 16, 16, bc1);
  cube[112] = 0x00;
  cube[113] = 0x02;  // caps2: cube map
  expect_error("cube.dds", cube, "a cube map");
  std::vector<uint8_t> bad_size = ktx1(0x83F1, 16, 16, bc1);
  bad_size[64] = 100;  // level 0's imageSize
  expect_error("size.ktx", bad_size, "level 0 has 100 bytes");
  expect_error("short.dds", {'D', 'D', 'S', ' ', 124, 0}, "truncated");
  // An sRGB file: its blocks kept, its levels decoded to linear (16 bits) for the filter; --srgb
  // on a file that is not sRGB is refused.
  save(s / "srgb.dds", dds("DX10", 72, 16, 16, bc1));
  EXPECT_TRUE(read_texture_file((s / "srgb.dds").string()).srgb);
  const Pyramid p = pyramid_of(read_texture_file((s / "srgb.dds").string()), PyramidMode::Exact);
  EXPECT_TRUE(p.srgb);
  EXPECT_EQ(p.blocks, bc1);
  EXPECT_EQ(p.levels[0].channel_bits, 16);
  const Image codes = decode_level(TexelFormat::Bc1, bc1[0].data(), 16, 16);
  EXPECT_EQ(p.levels[0].at(5, 7)[0], srgb_decode_table()[codes.at(5, 7)[0]]);
  EXPECT_EQ(p.memory_channel_bits(), 8);
  TextureOptions srgb;
  srgb.srgb = true;
  save(s / "unorm.dds", dds("DXT1", 0, 16, 16, bc1));
  try {
    load_pyramid((s / "unorm.dds").string(), srgb);
    ADD_FAILURE() << "--srgb on a UNORM file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--srgb, but the file holds DXT1"), std::string::npos) << e.what();
  }
}

// libsquish's (BC1-BC5) and Mesa's (BC7) encodings stay close to the picture (colours along one line in RGB, which a block's
// palette can hold): the unit samples what the format gives, and BC4/BC5 take red (and green) as
// GL's RED/RG formats do.
TEST(TextureFiles, EncodersKeepThePicture) {
  Image img(64, 64, 8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) img.at(x, y) = {uint16_t(x * 4), uint16_t(x * 2 + 20), uint16_t(255 - x * 4), uint16_t(255)};
  const Pyramid rgba = build_pyramid(img);
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc2, TexelFormat::Bc3, TexelFormat::Bc4, TexelFormat::Bc5,
                        TexelFormat::Bc7}) {
    const Pyramid p = compress_pyramid(rgba, f);
    ASSERT_EQ(p.format, f);
    ASSERT_EQ(p.blocks.size(), rgba.levels.size());
    const int channels = format_info(f).channels == 4 ? 3 : format_info(f).channels;
    int worst = 0;
    double sum = 0, n = 0;
    for (size_t k = 0; k < p.levels.size(); ++k) {
      EXPECT_EQ(p.blocks[k].size(), level_bytes(f, p.levels[k].width, p.levels[k].height));
      for (size_t i = 0; i < p.levels[k].texels.size(); ++i)
        for (int c = 0; c < channels; ++c) {
          const int d = std::abs(int(p.levels[k].texels[i][size_t(c)]) - int(rgba.levels[k].texels[i][size_t(c)]));
          worst = std::max(worst, d);
          sum += d;
          ++n;
        }
    }
    // About one 5-bit step (8). Mesa's BC7 encoder is fast and rough (worst 14 on its own round
    // trip of a 16-texel ramp, measured through Mesa's decoder too): a looser bound, and the mean.
    EXPECT_LE(worst, f == TexelFormat::Bc7 ? 40 : 10) << format_info(f).name;
    EXPECT_LE(sum / n, 4.0) << format_info(f).name;
  }
}

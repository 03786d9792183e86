// Texture files (sim/workloads/texture_files.h): DDS with legacy and DX10 headers, KTX 1 and KTX2
// with every level, read back block for block, arrays and cube maps image by image; OpenImageIO
// reads the same DDS files (cube maps too) level by level and decodes them as the model does
// (within the 1 LSB of docs/numerics.md); every bad input is one error naming the file and the
// value, found before anything the file cannot hold is allocated; libsquish's BC1-BC5 keep the
// picture.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "model/astc.h"
#include "model/error.h"
#include "model/srgb.h"
#include "model/sampler.h"
#include "stimulus.h"
#include "workloads/texture_files.h"
#include "workloads/texture_io.h"

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

using Levels = std::vector<std::vector<uint8_t>>;

void set32(std::vector<uint8_t>& out, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + size_t(i)] = uint8_t(v >> (8 * i));
}

// DDS: a FourCC, or "DX10" with a DXGI format. Its images one after another, each with its whole
// chain; caps2 (0x200 | 0xFC00: a cube map of six faces), and the DX10 header's miscFlag (0x4: a
// cube) and arraySize.
std::vector<uint8_t> dds_of(const char* fourcc, uint32_t dxgi, int w, int h, const std::vector<Levels>& images,
                            uint32_t caps2 = 0, uint32_t misc = 0, uint32_t array = 1) {
  std::vector<uint8_t> out = {'D', 'D', 'S', ' '};
  const uint32_t head[31] = {124, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000, uint32_t(h), uint32_t(w), 0, 0, uint32_t(images[0].size()),
                             0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // reserved
                             32, 0x4, 0, 0, 0, 0, 0, 0,        // pixel format (FourCC below)
                             0x1000 | 0x400000 | 0x8, caps2, 0, 0, 0};
  for (uint32_t v : head) put32(out, v);
  std::memcpy(&out[84], fourcc, 4);
  if (std::string(fourcc) == "DX10")
    for (uint32_t v : {dxgi, 3u, misc, array, 0u}) put32(out, v);
  for (const Levels& image : images)
    for (const auto& l : image) out.insert(out.end(), l.begin(), l.end());
  return out;
}
std::vector<uint8_t> dds(const char* fourcc, uint32_t dxgi, int w, int h, const Levels& levels) {
  return dds_of(fourcc, dxgi, w, h, {levels});
}

// KTX 1: numberOfArrayElements `elements` (0: not an array), numberOfFaces `faces`; level after
// level, imageSize then every image. A cube map that is not an array: imageSize counts one face.
std::vector<uint8_t> ktx1_of(uint32_t internal, int w, int h, const std::vector<Levels>& images, uint32_t elements = 0,
                             uint32_t faces = 1) {
  std::vector<uint8_t> out = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
  const bool rgba8 = internal == 0x8058 || internal == 0x8C43;  // glType, glFormat: 0 when compressed
  for (uint32_t v : {0x04030201u, rgba8 ? 0x1401u : 0u, 1u, rgba8 ? 0x1908u : 0u, internal, 0x1908u, uint32_t(w),
                     uint32_t(h), 0u, elements, faces, uint32_t(images[0].size()), 0u})
    put32(out, v);
  const bool lone_cube = faces == 6 && elements == 0;
  for (size_t k = 0; k < images[0].size(); ++k) {
    put32(out, uint32_t(images[0][k].size() * (lone_cube ? 1 : images.size())));
    for (const Levels& image : images) {
      out.insert(out.end(), image[k].begin(), image[k].end());
      while (lone_cube && out.size() % 4) out.push_back(0);
    }
    while (out.size() % 4) out.push_back(0);
  }
  return out;
}
std::vector<uint8_t> ktx1(uint32_t internal, int w, int h, const Levels& levels) { return ktx1_of(internal, w, h, {levels}); }

// KTX2: layerCount `layers` (0: not an array), faceCount `faces`; each level every image in turn.
std::vector<uint8_t> ktx2_of(uint32_t vk, int w, int h, const std::vector<Levels>& images, uint32_t layers = 0,
                             uint32_t faces = 1) {
  std::vector<uint8_t> out = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  const size_t count = images[0].size();
  for (uint32_t v : {vk, 1u, uint32_t(w), uint32_t(h), 0u, layers, faces, uint32_t(count), 0u}) put32(out, v);
  for (int i = 0; i < 4; ++i) put32(out, 0);  // no DFD, no key/value data
  put64(out, 0);
  put64(out, 0);
  // Level index (level 0 first), the data smallest level first, as KTX2 writers store it.
  std::vector<uint64_t> sizes(count, 0), offsets(count);
  for (const Levels& image : images)
    for (size_t k = 0; k < count; ++k) sizes[k] += image[k].size();
  uint64_t at = out.size() + 24 * count;
  for (size_t k = count; k-- > 0;) {
    offsets[k] = at;
    at += sizes[k];
  }
  for (size_t k = 0; k < count; ++k) {
    put64(out, offsets[k]);
    put64(out, sizes[k]);
    put64(out, sizes[k]);
  }
  for (size_t k = count; k-- > 0;)
    for (const Levels& image : images) out.insert(out.end(), image[k].begin(), image[k].end());
  return out;
}
std::vector<uint8_t> ktx2(uint32_t vk, int w, int h, const Levels& levels) { return ktx2_of(vk, w, h, {levels}); }

// `count` images of distinct random levels (image i from seed + i).
std::vector<Levels> random_images(TexelFormat f, int w, int h, int levels, int count, uint64_t seed) {
  std::vector<Levels> images;
  for (int i = 0; i < count; ++i) images.push_back(random_levels(f, w, h, levels, seed + uint64_t(i)));
  return images;
}

std::string error_of(const fs::path& p) {
  try {
    read_texture_file(p.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Saves `bytes` as `path` and expects read_texture_file's error: one line naming the file and `want`.
void expect_file_error(const fs::path& path, const std::vector<uint8_t>& bytes, const std::string& want) {
  save(path, bytes);
  const std::string e = error_of(path);
  EXPECT_NE(e.find(want), std::string::npos) << path.filename() << ": " << e;
  EXPECT_NE(e.find(path.filename().string()), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// `n` random queries (u, v in -0.5..1.5, lod in -1 .. lod_top - 1) as the scratch's q.csv.
void save_queries(const Scratch& s, int n, int lod_top, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string q = "u,v,lod\n";
  for (int i = 0; i < n; ++i)
    q += std::to_string(double(rng() % 4096) / 2048 - 0.5) + "," + std::to_string(double(rng() % 4096) / 2048 - 0.5) + "," +
         std::to_string(double(rng() % uint64_t(256 * lod_top)) / 256 - 1) + "\n";
  save(s / "q.csv", std::vector<uint8_t>(q.begin(), q.end()));
}

// texsim sample of `texture` over the scratch's q.csv into its file `out`: {exit status, stderr}.
std::pair<int, std::string> texsim_sample(const Scratch& s, const std::string& texture, const std::string& args,
                                          const std::string& out) {
  const std::string cmd = std::string(TEXSIM_PATH) + " sample -t " + texture + " -q " + (s / "q.csv").string() + " -o " +
                          (s / out).string() + " " + args + " > /dev/null 2> " + (s / "err.txt").string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(s / "err.txt");
  return {WEXITSTATUS(status), std::string{std::istreambuf_iterator<char>(in), {}}};
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  return std::string{std::istreambuf_iterator<char>(in), {}};
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
    expect_file_error(s / name, bytes, want);
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

// The ETC2 encoder (workloads/etc2_encode.h, ETC1's modes: Debian packages no ETC2 encoder) keeps
// the picture within bounds a broken encoder (mean errors near 80) is far from: a colour ramp and
// the test card's sharp edges, where ETC1's one colour per half block is weakest (the T and H
// modes, which the encoder does not try, are ETC2's answer; libsquish's BC1 does 2x and 4x better
// here), and etc2a an alpha ramp within EAC's reach. Both base-colour modes and both orientations
// are chosen.
TEST(TextureFiles, Etc2EncoderKeepsThePicture) {
  Image ramp(64, 64, 8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      ramp.at(x, y) = {uint16_t(x * 4), uint16_t(x * 2 + 20), uint16_t(255 - x * 4), uint16_t(255)};
  const Image card = load_texture("testcard:128x128");
  auto mean_error = [](const Pyramid& p, const Pyramid& ref, int from, int to) {
    double sum = 0, n = 0;
    for (size_t i = 0; i < p.levels[0].texels.size(); ++i)
      for (int c = from; c < to; ++c, ++n)
        sum += std::abs(int(p.levels[0].texels[i][size_t(c)]) - int(ref.levels[0].texels[i][size_t(c)]));
    return sum / n;
  };
  int modes[2] = {}, flips[2] = {};
  for (const Image* img : std::initializer_list<const Image*>{&ramp, &card}) {
    const Pyramid rgba = build_pyramid(*img);
    const double bc1 = mean_error(compress_pyramid(rgba, TexelFormat::Bc1), rgba, 0, 3);
    const Pyramid etc2 = compress_pyramid(rgba, TexelFormat::Etc2Rgb);
    const double e = mean_error(etc2, rgba, 0, 3);
    std::printf("  %dx%d: mean error per channel etc2 %.2f, bc1 %.2f\n", img->width, img->height, e, bc1);
    EXPECT_LE(e, img == &ramp ? 3.0 : 8.0);  // (measured 2.38 and 6.49; BC1 1.19 and 1.50)
    for (const auto& level : etc2.blocks)
      for (size_t b = 0; b < level.size(); b += 8) {
        ++modes[level[b + 3] >> 1 & 1];
        ++flips[level[b + 3] & 1];
      }
  }
  EXPECT_GT(modes[0], 0);
  EXPECT_GT(modes[1], 0);
  EXPECT_GT(flips[0], 0);
  EXPECT_GT(flips[1], 0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ramp.at(x, y)[3] = uint16_t((x * 3 + y * 5) % 256);
  const Pyramid rgba = build_pyramid(ramp), etc2a = compress_pyramid(rgba, TexelFormat::Etc2Rgba);
  const double alpha = mean_error(etc2a, rgba, 3, 4), colour = mean_error(etc2a, rgba, 0, 3);
  std::printf("  alpha ramp: mean error etc2a alpha %.2f, colour %.2f\n", alpha, colour);
  EXPECT_LE(alpha, 2.0);
  EXPECT_LE(colour, 3.0);
}

namespace {

// A level as the sampler takes it: RGBA8 bytes as texels, a block format decoded.
Image decoded(TexelFormat f, const std::vector<uint8_t>& bytes, int w, int h) {
  if (is_compressed(f)) return decode_level(f, bytes.data(), w, h);
  Image img(w, h, 8);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) img.texels[i][size_t(c)] = bytes[i * 4 + size_t(c)];
  return img;
}

}  // namespace

// Arrays, cube maps and cube arrays in every container: every image's every level where the file
// put it (each image's bytes its own, so a swapped layer or face fails), one pyramid per image,
// and load_layers / load_pyramid on them.
TEST(TextureFiles, ArraysAndCubeMapsGiveBackEveryImage) {
  Scratch s;
  const struct {
    TexelFormat format;
    const char* fourcc;  // legacy DDS ("DX10": none)
    uint32_t dxgi, gl, vk;
  } formats[] = {{TexelFormat::Bc1, "DXT1", 71, 0x83F1, 133},
                 {TexelFormat::Bc7, "DX10", 98, 0x8E8C, 145},
                 {TexelFormat::Rgba8, "DX10", 28, 0x8058, 37}};
  const struct {
    int layers, faces;
    bool array;  // the header says array (an array of one is still one layer)
    int w, h, levels;
    const char* refused;  // load_pyramid's words ("": it takes the file)
  } shapes[] = {{3, 1, true, 32, 8, 6, "an array of 3 layers"},
                {1, 6, false, 16, 16, 5, "a cube map (6 faces)"},
                {2, 6, true, 8, 8, 1, "a cube-map array of 2 cubes x 6 faces"},
                {1, 1, true, 16, 16, 5, ""}};
  uint64_t seed = 100;
  for (const auto& f : formats)
    for (const auto& sh : shapes) {
      const int count = sh.layers * sh.faces;
      const auto images = random_images(f.format, sh.w, sh.h, sh.levels, count, seed += 10);
      const uint32_t caps2 = sh.faces == 6 ? 0x200 | 0xFC00 : 0;
      std::vector<std::pair<std::string, std::vector<uint8_t>>> files = {
          // DX10: a cube map's caps2 as DirectX writes it; the cube array's DX10 header alone
          {"dx10.dds", dds_of("DX10", f.dxgi, sh.w, sh.h, images, sh.layers > 1 ? 0 : caps2, sh.faces == 6 ? 4 : 0,
                              uint32_t(sh.layers))},
          {"a.ktx", ktx1_of(f.gl, sh.w, sh.h, images, sh.array ? uint32_t(sh.layers) : 0, uint32_t(sh.faces))},
          {"a.ktx2", ktx2_of(f.vk, sh.w, sh.h, images, sh.array ? uint32_t(sh.layers) : 0, uint32_t(sh.faces))}};
      if (std::string(f.fourcc) != "DX10" && sh.layers == 1)  // legacy DDS: cube maps, no arrays
        files.push_back({"legacy.dds", dds_of(f.fourcc, 0, sh.w, sh.h, images, caps2)});
      for (const auto& [name, bytes] : files) {
        const std::string what = std::string(format_info(f.format).name) + " " + name + " " +
                                 std::to_string(sh.layers) + "x" + std::to_string(sh.faces);
        const fs::path p = s / name;
        save(p, bytes);
        const TextureFile t = read_texture_file(p.string());
        EXPECT_EQ(t.layers, sh.layers) << what;
        EXPECT_EQ(t.faces, sh.faces) << what;
        EXPECT_EQ(t.width, sh.w);
        EXPECT_EQ(t.height, sh.h);
        EXPECT_EQ(t.format, f.format);
        ASSERT_EQ(t.more_images.size(), size_t(count - 1)) << what;
        for (int i = 0; i < count; ++i)
          EXPECT_EQ(i == 0 ? t.levels : t.more_images[size_t(i - 1)], images[size_t(i)]) << what << " image " << i;

        const std::vector<Pyramid> pyramids = pyramids_of(t, PyramidMode::Exact);
        ASSERT_EQ(pyramids.size(), size_t(count)) << what;
        const int full = level_count({sh.w, sh.h});
        for (int i = 0; i < count; ++i) {
          const Pyramid& pyr = pyramids[size_t(i)];
          ASSERT_EQ(pyr.levels.size(), size_t(full)) << what << " image " << i;
          EXPECT_EQ(pyr.format, f.format);
          for (int k = 0; k < sh.levels; ++k) {  // the file's levels (one level: the rest built from it)
            const Extent e = level_extent({sh.w, sh.h}, k);
            EXPECT_EQ(pyr.levels[size_t(k)].texels, decoded(f.format, images[size_t(i)][size_t(k)], e.width(), e.height()).texels)
                << what << " image " << i << " level " << k;
            if (is_compressed(f.format)) {
              EXPECT_EQ(pyr.blocks[size_t(k)], images[size_t(i)][size_t(k)]);
            }
          }
          if (sh.levels == 1 && !is_compressed(f.format)) {  // each image's chain from its own level 0
            EXPECT_EQ(pyr.levels.back().texels, build_pyramid(decoded(f.format, images[size_t(i)][0], sh.w, sh.h)).levels.back().texels)
                << what << " image " << i;
          }
        }
        EXPECT_EQ(pyramid_of(t, PyramidMode::Exact).levels[0].texels, pyramids[0].levels[0].texels);

        // load_layers: every image, with the view; load_pyramid: one image only.
        TextureOptions o;
        o.base_level = sh.levels > 1 ? 1 : 0;
        int faces = 0;
        const std::vector<Pyramid> layers = load_layers(p.string(), o, &faces);
        EXPECT_EQ(faces, sh.faces);
        ASSERT_EQ(layers.size(), size_t(count));
        for (int i = 0; i < count; ++i) {
          EXPECT_EQ(layers[size_t(i)].extent0(), level_extent({sh.w, sh.h}, o.base_level)) << what;
          EXPECT_EQ(layers[size_t(i)].levels[0].texels, pyramids[size_t(i)].levels[size_t(o.base_level)].texels) << what << " image " << i;
        }
        if (*sh.refused) {
          try {
            load_pyramid(p.string(), o);
            ADD_FAILURE() << what << ": load_pyramid took " << count << " images";
          } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(p.string() + ": " + sh.refused), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("texsim sample takes arrays"), std::string::npos) << e.what();
          }
        } else {
          EXPECT_EQ(load_pyramid(p.string(), o).levels[0].texels, layers[0].levels[0].texels) << what;
        }
      }
    }
  // An image file or pattern is one layer.
  int faces = 0;
  TextureOptions o;
  const std::vector<Pyramid> one = load_layers("checker:16x8", o, &faces);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(faces, 1);
  EXPECT_EQ(one[0].extent0(), (Extent{16, 8}));
  EXPECT_EQ(one[0].levels[0].texels, load_pyramid("checker:16x8", o).levels[0].texels);
  // A TextureFile whose images do not match its counts.
  save(s / "three.dds", dds_of("DXT1", 0, 8, 8, random_images(TexelFormat::Bc1, 8, 8, 4, 1, 5)));
  TextureFile t = read_texture_file((s / "three.dds").string());
  t.layers = 3;
  EXPECT_THROW(pyramids_of(t, PyramidMode::Exact), Error);
}

// OpenImageIO's DDS reader takes a cube map (caps2, legacy or with a DX10 header) as one image of
// its six faces stacked, +X at the top (its 1x6 layout); each face decodes as the model decodes
// that image. OpenImageIO 2.4 gives a cube map's level k >= 1 the sides of level k - 1 (its seek
// halves them once too few; 16x16 faces: levels of 16, 16, 8, 4, 2), so a level it mislabels is
// skipped: level 0 always compared (every level's place: ArraysAndCubeMapsGiveBackEveryImage).
TEST(TextureFiles, OpenImageIoReadsTheSameCubeFaces) {
  Scratch s;
  int compared = 0;
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc7}) {
    const auto images = random_images(f, 16, 16, 5, 6, 60 + uint64_t(f));
    const fs::path p = s / "cube.dds";
    save(p, f == TexelFormat::Bc7 ? dds_of("DX10", 98, 16, 16, images, 0x200 | 0xFC00, 4, 1)
                                  : dds_of("DXT1", 0, 16, 16, images, 0x200 | 0xFC00));
    const std::vector<Pyramid> faces = pyramids_of(read_texture_file(p.string()), PyramidMode::Exact);
    ASSERT_EQ(faces.size(), 6u);
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("textureformat"), "CubeFace Environment");
    for (int k = 0; k < 5; ++k) {
      ASSERT_TRUE(in->seek_subimage(0, k)) << k;
      const int w = in->spec().width, h = in->spec().height;
      const Image& level0 = faces[0].levels[size_t(k)];
      if (k > 0 && w != level0.width) continue;  // OpenImageIO 2.4's size of level k - 1 (above)
      ASSERT_EQ(w, level0.width) << "level " << k;
      ASSERT_EQ(h, 6 * level0.height) << "level " << k;
      ++compared;
      std::vector<uint8_t> px(size_t(w) * h * 4);
      ASSERT_TRUE(in->read_image(0, k, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
      for (int face = 0; face < 6; ++face) {
        const Image& mine = faces[size_t(face)].levels[size_t(k)];
        int worst = 0;
        for (int y = 0; y < mine.height; ++y)
          for (int x = 0; x < mine.width; ++x)
            for (int c = 0; c < 4; ++c)
              worst = std::max(worst, std::abs(int(mine.at(x, y)[size_t(c)]) -
                                               px[((size_t(face) * mine.height + y) * w + x) * 4 + size_t(c)]));
        EXPECT_LE(worst, f == TexelFormat::Bc7 ? 0 : 1) << format_info(f).name << " face " << face << " level " << k;
      }
    }
  }
  EXPECT_GE(compared, 2);  // level 0 of each cube map
}

TEST(TextureFiles, BadArraysAndCubeMapsNameTheProblem) {
  Scratch s;
  const auto four = random_images(TexelFormat::Bc1, 16, 16, 5, 4, 1);
  const auto six = random_images(TexelFormat::Bc1, 16, 16, 5, 6, 2);
  const auto flat = random_images(TexelFormat::Bc1, 16, 8, 5, 6, 3);  // 16x8
  auto expect_error = [&](const std::string& name, const std::vector<uint8_t>& bytes, const std::string& want) {
    expect_file_error(s / name, bytes, want);
  };
  auto cut = [](std::vector<uint8_t> b, size_t n) { return std::vector<uint8_t>(b.begin(), b.end() - std::ptrdiff_t(n)); };
  // Truncated: the error names the image and level where the file ends.
  expect_error("array.dds", cut(dds_of("DX10", 71, 16, 16, four, 0, 0, 4), 3), "truncated: layer 3 level 4 needs 8 bytes");
  expect_error("array.ktx", cut(ktx1_of(0x83F1, 16, 16, four, 4), 3), "truncated: layer 3 level 4 needs 8 bytes");
  expect_error("cube.ktx", cut(ktx1_of(0x83F1, 16, 16, six, 0, 6), 3), "truncated: face -Z level 4 needs 8 bytes");
  expect_error("cubes.ktx", cut(ktx1_of(0x83F1, 16, 16, six, 1, 6), 3), "truncated: face -Z level 4 needs 8 bytes");
  expect_error("array.ktx2", cut(ktx2_of(133, 16, 16, four, 4), 3), "truncated: level 0 needs 512 bytes");
  std::vector<uint8_t> extra = dds_of("DX10", 71, 16, 16, four, 0, 0, 4);
  extra.push_back(0);
  expect_error("extra.dds", extra, "1 bytes after the last of 5 levels of 4 images");
  // Faces: a legacy cube map without -Z, a DX10 header that contradicts caps2, face counts.
  expect_error("five.dds", dds_of("DXT1", 0, 16, 16, {six.begin(), six.end() - 1}, 0x200 | 0x7C00),
               "caps2 0x7E00: a cube map with 5 of its 6 faces (-Z missing)");
  expect_error("x.dds", dds_of("DXT1", 0, 16, 16, {six[0]}, 0x200 | 0x400), "a cube map with 1 of its 6 faces (-X, +Y, -Y, +Z, -Z missing)");
  expect_error("misc.dds", dds_of("DX10", 71, 16, 16, six, 0x200 | 0xFC00, 0, 1),
               "caps2 0xFE00 marks a cube map, the DX10 header's miscFlag 0x0 does not");
  expect_error("faces.ktx", ktx1_of(0x83F1, 16, 16, {six.begin(), six.end() - 1}, 0, 5), "numberOfFaces 5: a texture has 1 face, or 6");
  expect_error("faces.ktx2", ktx2_of(133, 16, 16, {six[0], six[1]}, 0, 2), "faceCount 2: a texture has 1 face, or 6");
  // A cube's faces are square.
  expect_error("flat.dds", dds_of("DXT1", 0, 16, 8, flat, 0x200 | 0xFC00), "width 16, height 8: a cube map's faces are square");
  expect_error("flat10.dds", dds_of("DX10", 71, 16, 8, flat, 0, 4, 1), "width 16, height 8: a cube map's faces are square");
  expect_error("flat.ktx", ktx1_of(0x83F1, 16, 8, flat, 0, 6), "width 16, height 8: a cube map's faces are square");
  expect_error("flat.ktx2", ktx2_of(133, 16, 8, flat, 0, 6), "width 16, height 8: a cube map's faces are square");
  // Layer counts: 1..256 (KTX: 0 is not an array).
  expect_error("257.dds", dds_of("DX10", 71, 16, 16, four, 0, 0, 257), "arraySize 257: an array texture has 1 to 256 layers");
  expect_error("0.dds", dds_of("DX10", 71, 16, 16, four, 0, 0, 0), "arraySize 0: an array texture has 1 to 256 layers");
  expect_error("257.ktx", ktx1_of(0x83F1, 16, 16, four, 257), "numberOfArrayElements 257: an array texture has 1 to 256 layers");
  expect_error("257.ktx2", ktx2_of(133, 16, 16, four, 257), "layerCount 257: an array texture has 1 to 256 layers");
  // Sizes the header and the layout disagree on.
  std::vector<uint8_t> size1 = ktx1_of(0x83F1, 16, 16, four, 4);
  set32(size1, 64, 128);  // level 0's imageSize: one layer's
  expect_error("size.ktx", size1, "level 0 has 128 bytes (imageSize); 4 layers of a bc1 level of that size have 512");
  std::vector<uint8_t> size2 = ktx2_of(133, 16, 16, six, 0, 6);
  set32(size2, 80 + 8, 128);  // level 0's byteLength: one face's
  expect_error("size.ktx2", size2, "level 0 has 128 bytes (byteLength); 6 faces of a bc1 level of that size have 768");
  // Volumes are still refused.
  std::vector<uint8_t> volume = ktx2_of(133, 16, 16, four, 0, 1);
  set32(volume, 28, 4);
  expect_error("volume.ktx2", volume, "pixelDepth 4 (a volume texture)");
  expect_error("volume.dds", dds_of("DXT1", 0, 16, 16, four, 0x200000), "a volume texture (caps2 0x200000");
}

// Headers that claim far more than the file holds (256 cubes of 8192x8192 RGBA8 with every level,
// about 550 GB, in a file of 1 KB) fail at once, naming where the file ends, and allocate none of
// it: while each is read the address space is held to the process's own plus 256 MB, so that an
// allocation of what the header claims would throw std::bad_alloc rather than tex::Error.
TEST(TextureFiles, HeadersClaimingMoreThanTheFileFailWithoutAllocatingIt) {
  Scratch s;
  auto padded = [](std::vector<uint8_t> b) {
    b.resize(1024, 0);
    return b;
  };
  const auto one = random_images(TexelFormat::Rgba8, 4, 4, 1, 1, 9);
  std::vector<uint8_t> dds_bytes = dds_of("DX10", 28, 4, 4, one, 0x200 | 0xFC00, 4, 256);
  set32(dds_bytes, 12, 8192);
  set32(dds_bytes, 16, 8192);
  set32(dds_bytes, 28, 14);
  // KTX 1's imageSize holds 32 bits: 256 layers of 1024x1024 RGBA8 (1 GB) in one level.
  std::vector<uint8_t> ktx_bytes = ktx1_of(0x8058, 4, 4, one, 256, 1);
  set32(ktx_bytes, 36, 1024);
  set32(ktx_bytes, 40, 1024);
  set32(ktx_bytes, 64, 1u << 30);
  // KTX2: the level index of 14 levels, each level's byteLength as 256 cubes of it have.
  std::vector<uint8_t> ktx2_bytes = ktx2_of(37, 4, 4, one, 256, 6);
  ktx2_bytes.resize(80);  // the header; the level index follows
  set32(ktx2_bytes, 20, 8192);
  set32(ktx2_bytes, 24, 8192);
  set32(ktx2_bytes, 40, 14);
  for (int k = 0; k < 14; ++k) {
    const Extent e = level_extent({8192, 8192}, k);
    const uint64_t n = level_bytes(TexelFormat::Rgba8, e.width(), e.height()) * 256 * 6;
    put64(ktx2_bytes, 512);
    put64(ktx2_bytes, n);
    put64(ktx2_bytes, n);
  }
  const std::pair<std::string, std::vector<uint8_t>> files[] = {
      {"claims.dds", padded(dds_bytes)},
      {"claims.ktx", padded(ktx_bytes)},
      {"claims.ktx2", padded(ktx2_bytes)}};
  const std::string want[] = {"truncated: layer 0 face +X level 0 needs 268435456 bytes at offset 148, the file has 1024",
                              "truncated: layer 0 level 0 needs 4194304 bytes at offset 68, the file has 1024",
                              "truncated: level 0 needs 412316860416 bytes at offset 512, the file has 1024"};
  for (size_t i = 0; i < 3; ++i) {
    save(s / files[i].first, files[i].second);
    std::ifstream statm("/proc/self/statm");
    uint64_t pages = 0;
    statm >> pages;
    rlimit old{};
    ASSERT_EQ(getrlimit(RLIMIT_AS, &old), 0);
    rlimit held = old;
    held.rlim_cur = std::min<rlim_t>(old.rlim_max, rlim_t(pages * uint64_t(sysconf(_SC_PAGESIZE)) + (256ull << 20)));
    ASSERT_EQ(setrlimit(RLIMIT_AS, &held), 0);
    const auto start = std::chrono::steady_clock::now();
    std::string e;
    bool bad_alloc = false;
    try {
      e = error_of(s / files[i].first);
    } catch (const std::bad_alloc&) {
      bad_alloc = true;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    setrlimit(RLIMIT_AS, &old);
    EXPECT_FALSE(bad_alloc) << files[i].first << ": allocated what the header claims";
    EXPECT_NE(e.find(files[i].first + ": " + want[i]), std::string::npos) << e;
    EXPECT_LT(seconds, 1.0) << files[i].first;
  }
}

// An array file and a cube file through texsim sample --texture: the CLI takes the file's layers
// (a DX10 DDS array of 3) and its faces (a KTX2 cube), and its results are the golden model's for
// the same pyramids, layer by layer and across the cube's seams (read back through load_array).
TEST(TextureFiles, ArrayAndCubeFilesSampleThroughTexsim) {
  Scratch s;
  const std::vector<Levels> layers = random_images(TexelFormat::Rgba8, 8, 8, 4, 3, 71);
  save(s / "arr.dds", dds_of("DX10", 28, 8, 8, layers, 0, 0, 3));
  const std::vector<Levels> faces = random_images(TexelFormat::Rgba8, 8, 8, 4, 6, 72);
  save(s / "cube.ktx2", ktx2_of(37, 8, 8, faces, 0, 6));
  std::mt19937_64 rng(73);
  std::string aq = "u,v,layer,lod\n", cq = "x,y,z,lod\n";
  std::vector<Request> areqs, creqs;
  for (int i = 0; i < 200; ++i) {
    Request a;
    a.u = int32_t(rng() % (3u << 24)) - (1 << 24);
    a.v = int32_t(rng() % (3u << 24)) - (1 << 24);
    a.layer = int32_t(rng() % (5u << 16)) - (1 << 16);
    a.lod = int32_t(rng() % 1024) - 256;
    areqs.push_back(a);
    aq += std::to_string(a.u / 16777216.0) + "," + std::to_string(a.v / 16777216.0) + "," +
          std::to_string(a.layer / 65536.0) + "," + std::to_string(a.lod / 256.0) + "\n";
    Request c;
    for (int32_t* d : {&c.u, &c.v, &c.w}) *d = int32_t(rng() % (2u << 24)) - (1 << 24);
    c.lod = a.lod;
    creqs.push_back(c);
    cq += std::to_string(c.u / 16777216.0) + "," + std::to_string(c.v / 16777216.0) + "," +
          std::to_string(c.w / 16777216.0) + "," + std::to_string(c.lod / 256.0) + "\n";
  }
  // (The queries as printed, read back: the model gets exactly what texsim parses.)
  auto reparse = [](std::vector<Request>& reqs, const std::string& text, bool cube) {
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    for (Request& r : reqs) {
      std::getline(in, line);
      double v[4];
      std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3]);
      EXPECT_TRUE(to_coord_fixed(v[0], r.u) && to_coord_fixed(v[1], r.v) && to_lod_fixed(v[3], r.lod));
      EXPECT_TRUE(cube ? to_coord_fixed(v[2], r.w) : to_texel_coord_fixed(v[2], r.layer));
    }
  };
  reparse(areqs, aq, false);
  reparse(creqs, cq, true);
  save(s / "aq.csv", std::vector<uint8_t>(aq.begin(), aq.end()));
  save(s / "cq.csv", std::vector<uint8_t>(cq.begin(), cq.end()));
  for (const bool cube : {false, true}) {
    const std::string file = (s / (cube ? "cube.ktx2" : "arr.dds")).string(), out = (s / "out.csv").string();
    const std::string cmd = std::string(TEXSIM_PATH) + " sample --memory cached --texture " + file + " -q " +
                            (s / (cube ? "cq.csv" : "aq.csv")).string() + " -o " + out + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    TextureKind kind = TextureKind::Texture2D;
    const std::vector<Pyramid> p = load_array({file}, TextureOptions{}, &kind);
    EXPECT_EQ(kind, cube ? TextureKind::Cube : TextureKind::Texture2D);
    std::vector<const Pyramid*> ptrs;
    for (const Pyramid& x : p) ptrs.push_back(&x);
    Sampler model(ptrs, SamplerConfig{}, SamplerPaths::Both, kind);
    std::ifstream in(out);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "r,g,b,a");
    for (const Request& r : cube ? creqs : areqs) {
      ASSERT_TRUE(std::getline(in, line));
      const Texel t = model.sample(r);
      EXPECT_EQ(line, std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) + "," +
                          std::to_string(t[3]));
    }
  }
}

// ETC2 files (KTX 1 and KTX2, each format and its sRGB form) give back their levels; texsim samples
// them in the model, cached (decoded after the cache) and on chip alike, the on-chip RTL (which holds
// the decoded levels) gives the same texels, and the cached RTL (its taps' decoders) the model's
// texels, miss stream and response clocks; RGB8A1, which has no encoder, is refused in one line as
// --format and as a file of one level (its chain would need one).
TEST(TextureFiles, Etc2FilesSampleThroughTexsim) {
  Scratch s;
  const struct {
    TexelFormat format;
    uint32_t gl, vk;
    bool srgb;
  } cases[] = {{TexelFormat::Etc2Rgb, 0x9274, 147, false},   {TexelFormat::Etc2Rgb, 0x9275, 148, true},
               {TexelFormat::Etc2RgbA1, 0x9276, 149, false}, {TexelFormat::Etc2RgbA1, 0x9277, 150, true},
               {TexelFormat::Etc2Rgba, 0x9278, 151, false},  {TexelFormat::Etc2Rgba, 0x9279, 152, true}};
  for (const auto& c : cases) {
    const auto levels = random_levels(c.format, 32, 16, 6, 80 + uint64_t(c.format) + 10 * c.srgb);
    for (const auto& [name, bytes] :
         std::vector<std::pair<std::string, std::vector<uint8_t>>>{{"e.ktx", ktx1(c.gl, 32, 16, levels)},
                                                                   {"e.ktx2", ktx2(c.vk, 32, 16, levels)}}) {
      save(s / name, bytes);
      const TextureFile t = read_texture_file((s / name).string());
      EXPECT_EQ(t.format, c.format) << name;
      EXPECT_EQ(t.srgb, c.srgb) << name;
      EXPECT_EQ(t.levels, levels) << name << " " << t.format_name;
    }
  }
  const auto levels = random_levels(TexelFormat::Etc2Rgba, 32, 16, 6, 90);
  save(s / "rgba.ktx2", ktx2(151, 32, 16, levels));
  save_queries(s, 300, 4, 91);
  auto sample = [&](const std::string& args, const std::string& out) {
    return texsim_sample(s, (s / "rgba.ktx2").string(), args, out);
  };
  auto text = [&](const std::string& name) { return text_of(s / name); };
  EXPECT_EQ(sample("", "onchip.csv").first, 0);
  EXPECT_EQ(sample("--memory cached", "cached.csv").first, 0);
  EXPECT_EQ(sample("-e rtl", "rtl.csv").first, 0);
  EXPECT_GT(text("onchip.csv").size(), 300u * 8);
  EXPECT_EQ(text("cached.csv"), text("onchip.csv"));
  EXPECT_EQ(text("rtl.csv"), text("onchip.csv"));
  // The cached RTL decodes the blocks after its caches: the model's texels, lines and clocks.
  auto in_s = [&](const std::string& name) { return (s / name).string(); };
  EXPECT_EQ(sample("--memory cached --miss-trace " + in_s("mm.txt") + " --response-clocks " + in_s("mc.txt"), "cm.csv").first, 0);
  const auto rtl =
      sample("-e rtl --memory cached --miss-trace " + in_s("rm.txt") + " --response-clocks " + in_s("rc.txt"), "cr.csv");
  EXPECT_EQ(rtl.first, 0) << rtl.second;
  EXPECT_EQ(text("cr.csv"), text("cm.csv"));
  EXPECT_EQ(text("rm.txt"), text("mm.txt"));
  EXPECT_EQ(text("rc.txt"), text("mc.txt"));
  EXPECT_GT(text("rm.txt").size(), 100u);
  // --format etc2a1 has no encoder (etc2 and etc2a have: Etc2EncoderKeepsThePicture); a file of one
  // level gets the rest of its chain encoded (etc2a), or is refused where no encoder exists (etc2a1).
  const auto enc = sample("--format etc2a1", "x.csv");
  EXPECT_NE(enc.second.find("--format etc2a1: no etc2a1 encoder is built in"), std::string::npos) << enc.second;
  save(s / "one.ktx2", ktx2(151, 32, 16, {levels[0]}));
  const Pyramid one = load_pyramid((s / "one.ktx2").string(), TextureOptions{});
  EXPECT_EQ(one.levels.size(), 6u);
  EXPECT_EQ(one.blocks[0], levels[0]);  // (level 0 as the file has it)
  save(s / "one_a1.ktx2", ktx2(149, 32, 16, {random_levels(TexelFormat::Etc2RgbA1, 32, 16, 1, 92)[0]}));
  try {
    load_pyramid((s / "one_a1.ktx2").string(), TextureOptions{});
    ADD_FAILURE() << "a one-level ETC2 RGB8A1 file was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("one_a1.ktx2: no etc2a1 encoder is built in to make the levels below level 0: "
                                         "give a file with its whole mip chain"),
              std::string::npos)
        << e.what();
  }
}

namespace {

// astcenc's .astc file of one level: the magic, the footprint, the size, then the blocks.
std::vector<uint8_t> astc_file(int bw, int bh, int bd, uint32_t w, uint32_t h, uint32_t d, const std::vector<uint8_t>& blocks) {
  std::vector<uint8_t> out = {0x13, 0xAB, 0xA1, 0x5C, uint8_t(bw), uint8_t(bh), uint8_t(bd)};
  for (uint32_t v : {w, h, d})
    for (int i = 0; i < 3; ++i) out.push_back(uint8_t(v >> (8 * i)));
  out.insert(out.end(), blocks.begin(), blocks.end());
  return out;
}

}  // namespace

// ASTC in every container: KTX 1 (GL_COMPRESSED_RGBA_ASTC_WxH_KHR and its SRGB8_ALPHA8 twin), KTX2
// (VK_FORMAT_ASTC_WxH_UNORM/SRGB_BLOCK) and astcenc's .astc (one level, no colour space: --srgb
// says sRGB), at sizes no footprint divides; bad files name the problem in one line.
TEST(TextureFiles, AstcFilesGiveBackTheirBlocks) {
  Scratch s;
  for (int i = 0; i < 14; ++i) {
    const TexelFormat f = TexelFormat(int(TexelFormat::Astc4x4) + i);
    const Pyramid p = stimulus::random_block_texture(f, {40, 22}, 100 + uint64_t(i));
    for (bool srgb : {false, true}) {
      const std::vector<std::pair<std::string, std::vector<uint8_t>>> files = {
          {"a.ktx", ktx1((srgb ? 0x93D0u : 0x93B0u) + uint32_t(i), 40, 22, p.blocks)},
          {"a.ktx2", ktx2(157u + 2 * uint32_t(i) + srgb, 40, 22, p.blocks)}};
      for (const auto& [name, bytes] : files) {
        save(s / name, bytes);
        const TextureFile t = read_texture_file((s / name).string());
        EXPECT_EQ(t.format, f) << name << " " << t.format_name;
        EXPECT_EQ(t.srgb, srgb) << name;
        EXPECT_EQ(t.levels, p.blocks) << name;
        EXPECT_NE(t.format_name.find(std::to_string(kAstcFootprints[i].w) + "x" + std::to_string(kAstcFootprints[i].h)),
                  std::string::npos) << t.format_name;
      }
    }
    const AstcFootprint fp = kAstcFootprints[i];
    save(s / "a.astc", astc_file(fp.w, fp.h, 1, 40, 22, 1, p.blocks[0]));
    ASSERT_TRUE(is_texture_file((s / "a.astc").string()));
    const TextureFile t = read_texture_file((s / "a.astc").string());
    EXPECT_EQ(t.format, f);
    EXPECT_FALSE(t.srgb);
    ASSERT_EQ(t.levels.size(), 1u);
    EXPECT_EQ(t.levels[0], p.blocks[0]);
  }
  // One level: the rest of the chain is encoded (astcenc); --srgb makes an .astc file sRGB, decoded
  // in ASTC's sRGB mode (endpoints expanded with 0x80 below the code).
  const Pyramid p = stimulus::random_block_texture(TexelFormat::Astc6x5, {40, 22}, 7);
  save(s / "one.astc", astc_file(6, 5, 1, 40, 22, 1, p.blocks[0]));
  const Pyramid linear = load_pyramid((s / "one.astc").string(), TextureOptions{});
  EXPECT_EQ(linear.levels.size(), 6u);
  EXPECT_EQ(linear.blocks[0], p.blocks[0]);
  EXPECT_EQ(linear.levels[0].at(7, 3), p.levels[0].at(7, 3));
  TextureOptions as_srgb;
  as_srgb.srgb = true;
  const Pyramid srgb = load_pyramid((s / "one.astc").string(), as_srgb);
  EXPECT_TRUE(srgb.srgb);
  const Image codes = decode_level(TexelFormat::Astc6x5, p.blocks[0].data(), 40, 22, true);
  for (int y = 0; y < 22; ++y)
    for (int x = 0; x < 40; ++x)
      ASSERT_EQ(srgb.levels[0].at(x, y)[0], srgb_decode_table()[codes.at(x, y)[0]]) << x << " " << y;
  // Bad files.
  auto expect_error = [&](const std::string& name, const std::vector<uint8_t>& bytes, const std::string& want) {
    expect_file_error(s / name, bytes, want);
  };
  std::vector<uint8_t> blocks = p.blocks[0];
  expect_error("short.astc", astc_file(6, 5, 1, 40, 22, 1, std::vector<uint8_t>(blocks.begin(), blocks.end() - 16)),
               "544 bytes of blocks; a 40x22 astc6x5 level has 560");
  expect_error("footprint.astc", astc_file(7, 7, 1, 40, 22, 1, blocks), "block footprint 7x7 is not one of ASTC's 2D footprints");
  expect_error("volume.astc", astc_file(4, 4, 4, 8, 8, 8, blocks), "a 3D ASTC texture");
  expect_error("header.astc", {0x13, 0xAB, 0xA1, 0x5C, 6, 5}, "truncated: the .astc header needs 16 bytes");
  expect_error("empty.astc", astc_file(6, 5, 1, 0, 22, 1, {}), "0x22: the unit takes sides from 1 to 8192");
  expect_error("hdr.ktx2", ktx2(1000066004, 40, 22, p.blocks), "VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK (HDR) is not supported");
}

// ASTC through texsim: the model's on-chip and cached memories, the on-chip RTL (which holds the
// texture decoded) and the cached RTL (its taps' ASTC decoders after the cache) give the same
// samples, and the cached RTL the model's miss stream and response clocks; --format astc6x6
// encodes an image with astcenc, which keeps the picture.
TEST(TextureFiles, AstcFilesSampleThroughTexsim) {
  Scratch s;
  const Pyramid p = stimulus::random_block_texture(TexelFormat::Astc10x6, {64, 48}, 11);
  save(s / "t.ktx2", ktx2(157 + 2 * 9, 64, 48, p.blocks));
  save_queries(s, 400, 6, 12);
  auto sample = [&](const std::string& texture, const std::string& args, const std::string& out) {
    return texsim_sample(s, texture, args, out);
  };
  auto text = [&](const std::string& name) { return text_of(s / name); };
  auto in_s = [&](const std::string& name) { return (s / name).string(); };
  const std::string t = (s / "t.ktx2").string();
  EXPECT_EQ(sample(t, "", "onchip.csv").first, 0);
  EXPECT_EQ(sample(t, "--memory cached --wrap repeat", "cached.csv").first, 0);
  EXPECT_EQ(sample(t, "-e rtl", "rtl.csv").first, 0);
  EXPECT_GT(text("onchip.csv").size(), 400u * 8);
  EXPECT_EQ(text("cached.csv"), text("onchip.csv"));
  EXPECT_EQ(text("rtl.csv"), text("onchip.csv"));
  EXPECT_EQ(sample(t, "--memory cached --miss-trace " + in_s("mm.txt") + " --response-clocks " + in_s("mc.txt"), "cm.csv").first, 0);
  const auto rtl = sample(t, "-e rtl --memory cached --miss-trace " + in_s("rm.txt") + " --response-clocks " + in_s("rc.txt"), "cr.csv");
  EXPECT_EQ(rtl.first, 0) << rtl.second;
  EXPECT_EQ(text("cr.csv"), text("cm.csv"));
  EXPECT_EQ(text("rm.txt"), text("mm.txt"));
  EXPECT_EQ(text("rc.txt"), text("mc.txt"));
  EXPECT_GT(text("rm.txt").size(), 100u);
  // A file with HDR blocks is sampled with a note: the unit is LDR. (The random blocks above have
  // HDR endpoint modes and void extents; astcenc's LDR encoding has none.)
  EXPECT_NE(sample(t, "", "x.csv").second.find("t.ktx2: 34 of 80 ASTC blocks are HDR"), std::string::npos);
  const Pyramid ldr = compress_pyramid(build_pyramid(stimulus::random_image(64, 48, 8, 13, 2)), TexelFormat::Astc10x6);
  save(s / "ldr.ktx2", ktx2(157 + 2 * 9, 64, 48, ldr.blocks));
  EXPECT_EQ(sample((s / "ldr.ktx2").string(), "", "ldr.csv").second, "");
  std::vector<std::vector<uint8_t>> hdr = ldr.blocks;
  for (int b = 0; b < 3; ++b) {
    uint8_t* at = &hdr[0][size_t(b) * 16];
    std::fill(at, at + 8, uint8_t(0xFF));
    at[0] = 0xFC;  // bits 8..0 = 1 1111 1100, bits 9..11 (HDR, reserved) set, no extent
  }
  save(s / "hdr.ktx2", ktx2(157 + 2 * 9, 64, 48, hdr));
  const auto noted = sample((s / "hdr.ktx2").string(), "", "hdr.csv");
  EXPECT_EQ(noted.first, 0);
  EXPECT_NE(noted.second.find("hdr.ktx2: 3 of 80 ASTC blocks are HDR; the unit decodes the LDR profile"),
            std::string::npos) << noted.second;
  // --format: astcenc's encoding of the test card (sharp edges and fine lines), within a few steps
  // of the picture at 6x6 (measured 1.2) and 4x4 (0.14); 12x12 at 0.89 bits a texel blurs it (13.6).
  const Pyramid rgba = build_pyramid(load_texture("testcard:128x128"));
  for (TexelFormat f : {TexelFormat::Astc4x4, TexelFormat::Astc6x6, TexelFormat::Astc12x12}) {
    const Pyramid a = compress_pyramid(rgba, f);
    ASSERT_EQ(a.format, f);
    double sum = 0, n = 0;
    for (size_t i = 0; i < a.levels[0].texels.size(); ++i)
      for (int c = 0; c < 3; ++c, ++n) sum += std::abs(int(a.levels[0].texels[i][size_t(c)]) - int(rgba.levels[0].texels[i][size_t(c)]));
    std::printf("  %s: mean error %.2f on the test card\n", format_info(f).name, sum / n);
    EXPECT_LE(sum / n, f == TexelFormat::Astc12x12 ? 20.0 : 4.0) << format_info(f).name;
  }
}

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

#include "model/error.h"
#include "model/srgb.h"
#include "model/sampler.h"
#include "stimulus.h"
#include "workloads/texture_files.h"
#include "texture_file_builders.h"
#include "workloads/texture_io.h"

using namespace tex;
namespace fs = std::filesystem;

using namespace tex::filetest;

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

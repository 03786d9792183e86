// PNG and JPEG through libpng and libjpeg (workloads/png_jpeg.h) against OpenImageIO, the reader
// they stand in for: the same pixels for every PNG colour type and bit depth (written here with
// libpng, palettes and tRNS, interlaced, with a gAMA chunk), for baseline and progressive JPEGs in
// gray and colour, and for every PNG and JPEG of assimp-testmodels; a 16-bit PNG and a CMYK JPEG
// are left to OpenImageIO; a broken file is reported, never read as pixels; PNGs written here
// read back the same through OpenImageIO.
#include <gtest/gtest.h>
#include <jpeglib.h>
#include <png.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "workloads/image_module.h"
#include "workloads/png_jpeg.h"

namespace fs = std::filesystem;
using tex::images::Direct;
using tex::images::Pixels;

namespace {

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("texsim_png_jpeg_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

struct PngSpec {
  int colour = PNG_COLOR_TYPE_RGB, depth = 8;
  bool trns = false, interlace = false, gamma = false;
  std::string name;
};

// A w x h PNG of random samples (palette: 2^depth random entries, a few transparent with tRNS).
void write_test_png(const fs::path& path, const PngSpec& s, int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_TRUE(f);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  ASSERT_FALSE(setjmp(png_jmpbuf(png)));
  png_init_io(png, f);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), s.depth, s.colour,
               s.interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette;
  if (s.colour == PNG_COLOR_TYPE_PALETTE) {
    for (int i = 0; i < (1 << s.depth); ++i)
      palette.push_back({png_byte(rng()), png_byte(rng()), png_byte(rng())});
    png_set_PLTE(png, info, palette.data(), int(palette.size()));
  }
  std::vector<png_byte> alpha;
  png_color_16 key{};
  if (s.trns) {
    if (s.colour == PNG_COLOR_TYPE_PALETTE) {
      for (int i = 0; i < std::min(4, 1 << s.depth); ++i) alpha.push_back(png_byte(rng()));
      png_set_tRNS(png, info, alpha.data(), int(alpha.size()), nullptr);
    } else {
      key.gray = 0;  // value 0 transparent
      key.red = key.green = key.blue = 0;
      png_set_tRNS(png, info, nullptr, 0, &key);
    }
  }
  if (s.gamma) png_set_gAMA(png, info, 1.0);  // linear: a reader that applied gamma would change the values
  png_write_info(png, info);
  const int channels = s.colour == PNG_COLOR_TYPE_RGB ? 3 : s.colour == PNG_COLOR_TYPE_RGBA ? 4
                     : s.colour == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
  const size_t row_bytes = (size_t(w) * channels * s.depth + 7) / 8;
  std::vector<std::vector<png_byte>> rows(static_cast<size_t>(h), std::vector<png_byte>(row_bytes));
  for (auto& r : rows)
    for (auto& b : r) b = png_byte(rng() % 4 == 0 ? 0 : rng());  // some zeros: the tRNS key
  std::vector<png_bytep> ptrs;
  for (auto& r : rows) ptrs.push_back(r.data());
  png_write_image(png, ptrs.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

// A w x h JPEG of smooth random colour, baseline or progressive, gray or YCbCr.
void write_test_jpeg(const fs::path& path, bool gray, bool progressive, int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  jpeg_compress_struct c;
  jpeg_error_mgr e;
  c.err = jpeg_std_error(&e);
  jpeg_create_compress(&c);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_TRUE(f);
  jpeg_stdio_dest(&c, f);
  c.image_width = JDIMENSION(w);
  c.image_height = JDIMENSION(h);
  c.input_components = gray ? 1 : 3;
  c.in_color_space = gray ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 80, TRUE);
  if (progressive) jpeg_simple_progression(&c);
  jpeg_start_compress(&c, TRUE);
  const int n = c.input_components;
  std::vector<unsigned char> row(size_t(w) * n);
  const int a = int(rng() % 7), b = int(rng() % 5);
  while (c.next_scanline < c.image_height) {
    const int y = int(c.next_scanline);
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < n; ++k) row[size_t(x * n + k)] = (unsigned char)((x * (a + k) + y * (b + 1) + int(rng() % 9)) & 255);
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&c, &r, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::fclose(f);
}

// Both readers on one file: the direct one must read it (or leave it, `expect`), and OpenImageIO
// give the same pixels.
void expect_same_as_oiio(const fs::path& path, Direct expect = Direct::Read) {
  Pixels direct, oiio;
  std::string error, oiio_error;
  const Direct d = tex::images::read_png_or_jpeg(path.string(), nullptr, 0, UINT64_MAX, direct, error);
  ASSERT_EQ(int(d), int(expect)) << path << ": " << error;
  if (d != Direct::Read) return;
  ASSERT_TRUE(tex::images::module().read(path.string(), nullptr, 0, UINT64_MAX, oiio, oiio_error)) << path << ": " << oiio_error;
  EXPECT_EQ(direct.width, oiio.width) << path;
  EXPECT_EQ(direct.height, oiio.height) << path;
  ASSERT_EQ(direct.channels, oiio.channels) << path;
  ASSERT_EQ(direct.values.size(), oiio.values.size()) << path;
  size_t differ = 0;
  for (size_t i = 0; i < direct.values.size(); ++i) differ += direct.values[i] != oiio.values[i];
  EXPECT_EQ(differ, 0u) << path << ": " << differ << " of " << direct.values.size() << " values differ";
  // From the bytes in memory too (embedded GLB textures)
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Pixels mem;
  ASSERT_EQ(int(tex::images::read_png_or_jpeg("embedded", bytes.data(), bytes.size(), UINT64_MAX, mem, error)), int(Direct::Read));
  EXPECT_EQ(mem.values, direct.values) << path;
}

}  // namespace

TEST(PngJpeg, EveryPngColourTypeAndDepthAsOpenImageIO) {
  const fs::path dir = scratch();
  std::vector<PngSpec> specs;
  for (int d : {1, 2, 4, 8}) specs.push_back({PNG_COLOR_TYPE_GRAY, d, false, false, false, "gray" + std::to_string(d)});
  for (int d : {1, 2, 4, 8}) specs.push_back({PNG_COLOR_TYPE_PALETTE, d, false, false, false, "palette" + std::to_string(d)});
  for (int d : {2, 8}) specs.push_back({PNG_COLOR_TYPE_PALETTE, d, true, false, false, "palette_trns" + std::to_string(d)});
  specs.push_back({PNG_COLOR_TYPE_GRAY, 8, true, false, false, "gray_trns"});
  specs.push_back({PNG_COLOR_TYPE_GRAY_ALPHA, 8, false, false, false, "gray_alpha"});
  specs.push_back({PNG_COLOR_TYPE_RGB, 8, false, false, false, "rgb"});
  specs.push_back({PNG_COLOR_TYPE_RGB, 8, true, false, false, "rgb_trns"});
  specs.push_back({PNG_COLOR_TYPE_RGBA, 8, false, false, false, "rgba"});
  specs.push_back({PNG_COLOR_TYPE_RGBA, 8, false, true, false, "rgba_interlaced"});
  specs.push_back({PNG_COLOR_TYPE_RGB, 8, false, false, true, "rgb_gamma1"});
  for (size_t i = 0; i < specs.size(); ++i) {
    const fs::path p = dir / (specs[i].name + ".png");
    write_test_png(p, specs[i], 37, 23, uint32_t(i));
    SCOPED_TRACE(specs[i].name);
    expect_same_as_oiio(p);
  }
  const fs::path deep = dir / "rgb16.png";
  write_test_png(deep, {PNG_COLOR_TYPE_RGB, 16, false, false, false, "rgb16"}, 8, 8, 99);
  expect_same_as_oiio(deep, Direct::NotMine);  // OpenImageIO's own 16-to-8-bit conversion
  fs::remove_all(dir);
}

TEST(PngJpeg, JpegsAsOpenImageIO) {
  const fs::path dir = scratch();
  int n = 0;
  for (bool gray : {false, true})
    for (bool progressive : {false, true})
      for (auto [w, h] : {std::pair{37, 23}, std::pair{64, 64}, std::pair{1, 17}}) {
        const fs::path p = dir / ("j" + std::to_string(n) + ".jpg");
        write_test_jpeg(p, gray, progressive, w, h, uint32_t(n++));
        SCOPED_TRACE(std::string(gray ? "gray" : "colour") + (progressive ? " progressive " : " baseline ") +
                     std::to_string(w) + "x" + std::to_string(h));
        expect_same_as_oiio(p);
      }
  fs::remove_all(dir);
}

TEST(PngJpeg, EveryImageOfTheAssimpTestModelsAsOpenImageIO) {
  int read = 0;
  for (const auto& e : fs::recursive_directory_iterator("/usr/share/assimp/models")) {
    std::string ext = e.path().extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (!e.is_regular_file() || (ext != ".png" && ext != ".jpg" && ext != ".jpeg")) continue;
    Pixels p;
    std::string error;
    const Direct d = tex::images::read_png_or_jpeg(e.path().string(), nullptr, 0, UINT64_MAX, p, error);
    if (d == Direct::NotMine) continue;  // (16-bit PNGs, CMYK JPEGs: OpenImageIO's)
    SCOPED_TRACE(e.path().string());
    expect_same_as_oiio(e.path());
    ++read;
  }
  EXPECT_GE(read, 50) << "the assimp-testmodels images (59 PNG and JPEG files) were not found";
}

TEST(PngJpeg, BrokenFilesAreReportedNotRead) {
  const fs::path dir = scratch();
  const fs::path good = dir / "good.png";
  write_test_png(good, {PNG_COLOR_TYPE_RGB, 8, false, false, false, "rgb"}, 40, 40, 5);
  std::ifstream in(good, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Pixels p;
  std::string error;
  for (size_t cut : {size_t(8), size_t(30), bytes.size() / 2}) {  // truncated: header, IHDR, data
    error.clear();
    EXPECT_EQ(int(tex::images::read_png_or_jpeg("cut.png", bytes.data(), cut, UINT64_MAX, p, error)), int(Direct::Broken)) << cut;
    EXPECT_NE(error.find("PNG"), std::string::npos) << error;
  }
  std::vector<char> flipped = bytes;
  flipped[20] ^= 0x40;  // IHDR's width: its CRC no longer matches
  EXPECT_EQ(int(tex::images::read_png_or_jpeg("bad.png", flipped.data(), flipped.size(), UINT64_MAX, p, error)), int(Direct::Broken));
  const char jpeg_head[] = "\xFF\xD8\xFF\xE0 not a JPEG";
  EXPECT_EQ(int(tex::images::read_png_or_jpeg("bad.jpg", jpeg_head, sizeof jpeg_head - 1, UINT64_MAX, p, error)), int(Direct::Broken));
  EXPECT_NE(error.find("JPEG"), std::string::npos) << error;
  EXPECT_EQ(int(tex::images::read_png_or_jpeg("x.tga", "TRUEVISION", 10, UINT64_MAX, p, error)), int(Direct::NotMine));
  fs::remove_all(dir);
}

TEST(PngJpeg, WrittenPngsReadBackThroughOpenImageIO) {
  const fs::path dir = scratch();
  Pixels p;
  p.width = 29;
  p.height = 13;
  p.channels = 4;
  std::mt19937 rng(3);
  for (int i = 0; i < p.width * p.height * 4; ++i) p.values.push_back(uint8_t(rng()));
  std::string error;
  ASSERT_TRUE(tex::images::write_png((dir / "w.png").string(), p, error)) << error;
  Pixels back;
  ASSERT_TRUE(tex::images::module().read((dir / "w.png").string(), nullptr, 0, UINT64_MAX, back, error)) << error;
  EXPECT_EQ(back.width, p.width);
  EXPECT_EQ(back.channels, 4);
  EXPECT_EQ(back.values, p.values);
  EXPECT_FALSE(tex::images::write_png((dir / "no" / "such" / "dir.png").string(), p, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  fs::remove_all(dir);
}

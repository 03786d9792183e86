// Texture files as the tests write them (tests/sim/test_texture_files.cpp and
// test_block_format_files.cpp): DDS, KTX 1 and KTX2 builders, random levels of a format, a
// scratch directory, and texsim sample runs over its query file.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "model/block_formats.h"
#include "model/error.h"
#include "model/formats.h"
#include "workloads/texture_files.h"

namespace tex::filetest {

namespace fs = std::filesystem;


struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("texture_files_" + std::to_string(getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  fs::path operator/(const std::string& name) const { return dir / name; }
};

inline void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
inline void put64(std::vector<uint8_t>& out, uint64_t v) {
  put32(out, uint32_t(v));
  put32(out, uint32_t(v >> 32));
}
inline void save(const fs::path& p, const std::vector<uint8_t>& bytes) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Random levels of a w x h texture in format f (BC7: every mode in turn).
inline std::vector<std::vector<uint8_t>> random_levels(TexelFormat f, int w, int h, int count, uint64_t seed) {
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

inline void set32(std::vector<uint8_t>& out, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + size_t(i)] = uint8_t(v >> (8 * i));
}

// DDS: a FourCC, or "DX10" with a DXGI format. Its images one after another, each with its whole
// chain; caps2 (0x200 | 0xFC00: a cube map of six faces), and the DX10 header's miscFlag (0x4: a
// cube) and arraySize.
inline std::vector<uint8_t> dds_of(const char* fourcc, uint32_t dxgi, int w, int h, const std::vector<Levels>& images,
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
inline std::vector<uint8_t> dds(const char* fourcc, uint32_t dxgi, int w, int h, const Levels& levels) {
  return dds_of(fourcc, dxgi, w, h, {levels});
}

// KTX 1: numberOfArrayElements `elements` (0: not an array), numberOfFaces `faces`; level after
// level, imageSize then every image. A cube map that is not an array: imageSize counts one face.
inline std::vector<uint8_t> ktx1_of(uint32_t internal, int w, int h, const std::vector<Levels>& images, uint32_t elements = 0,
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
inline std::vector<uint8_t> ktx1(uint32_t internal, int w, int h, const Levels& levels) { return ktx1_of(internal, w, h, {levels}); }

// KTX2: layerCount `layers` (0: not an array), faceCount `faces`; each level every image in turn.
inline std::vector<uint8_t> ktx2_of(uint32_t vk, int w, int h, const std::vector<Levels>& images, uint32_t layers = 0,
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
inline std::vector<uint8_t> ktx2(uint32_t vk, int w, int h, const Levels& levels) { return ktx2_of(vk, w, h, {levels}); }

// `count` images of distinct random levels (image i from seed + i).
inline std::vector<Levels> random_images(TexelFormat f, int w, int h, int levels, int count, uint64_t seed) {
  std::vector<Levels> images;
  for (int i = 0; i < count; ++i) images.push_back(random_levels(f, w, h, levels, seed + uint64_t(i)));
  return images;
}

inline std::string error_of(const fs::path& p) {
  try {
    read_texture_file(p.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Saves `bytes` as `path` and expects read_texture_file's error: one line naming the file and `want`.
inline void expect_file_error(const fs::path& path, const std::vector<uint8_t>& bytes, const std::string& want) {
  save(path, bytes);
  const std::string e = error_of(path);
  EXPECT_NE(e.find(want), std::string::npos) << path.filename() << ": " << e;
  EXPECT_NE(e.find(path.filename().string()), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// `n` random queries (u, v in -0.5..1.5, lod in -1 .. lod_top - 1) as the scratch's q.csv.
inline void save_queries(const Scratch& s, int n, int lod_top, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string q = "u,v,lod\n";
  for (int i = 0; i < n; ++i)
    q += std::to_string(double(rng() % 4096) / 2048 - 0.5) + "," + std::to_string(double(rng() % 4096) / 2048 - 0.5) + "," +
         std::to_string(double(rng() % uint64_t(256 * lod_top)) / 256 - 1) + "\n";
  save(s / "q.csv", std::vector<uint8_t>(q.begin(), q.end()));
}

// texsim sample of `texture` over the scratch's q.csv into its file `out`: {exit status, stderr}.
inline std::pair<int, std::string> texsim_sample(const Scratch& s, const std::string& texture, const std::string& args,
                                          const std::string& out) {
  const std::string cmd = std::string(TEXSIM_PATH) + " sample -t " + texture + " -q " + (s / "q.csv").string() + " -o " +
                          (s / out).string() + " " + args + " > /dev/null 2> " + (s / "err.txt").string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(s / "err.txt");
  return {WEXITSTATUS(status), std::string{std::istreambuf_iterator<char>(in), {}}};
}

inline std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  return std::string{std::istreambuf_iterator<char>(in), {}};
}


}  // namespace tex::filetest

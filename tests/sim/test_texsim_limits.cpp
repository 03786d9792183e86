// Bounded resources on any input (docs/robustness.md): --max-memory, the model import's memory and
// time, and the header sizes the project's own parsers check before allocating. Each refusal is
// one line naming the file and the field, quick, and leaves no output behind.
#include <sys/wait.h>
#include <zlib.h>

#include <chrono>
#include <cstring>

#include "cli_fixture.h"

namespace {

const fs::path kModels = "/usr/share/assimp/models";

void put32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(char(v >> (8 * i)));
}
void put32_be(std::string& s, uint32_t v) {
  for (int i = 3; i >= 0; --i) s.push_back(char(v >> (8 * i)));
}

// A PNG whose header claims w x h RGBA pixels, followed by an empty image data chunk: libpng reads
// the header, the pixels are never there.
std::string png_header_only(uint32_t w, uint32_t h) {
  std::string png = "\x89PNG\r\n\x1a\n";
  auto chunk = [&](const char* type, const std::string& data) {
    put32_be(png, uint32_t(data.size()));
    const std::string body = type + data;
    png += body;
    put32_be(png, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
  };
  std::string ihdr;
  put32_be(ihdr, w);
  put32_be(ihdr, h);
  ihdr += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, no filter, no interlace
  chunk("IHDR", ihdr);
  chunk("IDAT", "");
  chunk("IEND", "");
  return png;
}

// A DDS (DXT1, BC1) of w x h with its whole chain of zero blocks.
std::string dds_bc1(uint32_t w, uint32_t h) {
  std::string dds = "DDS ";
  uint32_t levels = 1;
  while ((w >> (levels - 1)) > 1 || (h >> (levels - 1)) > 1) ++levels;
  const uint32_t head[31] = {124, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000, h, w, 0, 0, levels, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                             32, 0x4, 0x31545844 /* DXT1 */, 0, 0, 0, 0, 0, 0x1000 | 0x400000 | 0x8, 0, 0, 0, 0};
  for (uint32_t v : head) put32(dds, v);
  uint64_t bytes = 0;
  for (uint32_t k = 0; k < levels; ++k) bytes += uint64_t((std::max(w >> k, 1u) + 3) / 4) * ((std::max(h >> k, 1u) + 3) / 4) * 8;
  dds.append(size_t(bytes), '\0');
  return dds;
}

// Seconds a texsim run took (the refusals below come before any work).
template <typename F>
double seconds(F run) {
  const auto t0 = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_F(TexsimCli, MaxMemoryValuesAreChecked) {
  for (const char* bad : {"12X", "0", "-1G", "G", "1e30"})
    expect_clean_failure(std::string("render --scene plane --max-memory ") + bad + " -o p.png", "p.png",
                         {"--max-memory", bad, "is not a size"});
  // Above the data limit the process may raise its own to: refused, naming both.
  const std::string cmd = "cd '" + dir.string() + "' && ulimit -d 1000000 && '" + TEXSIM_PATH +
                          "' render --scene plane --max-memory 2G -o p.png 2> err.txt";
  const int status = std::system(("bash -c \"" + cmd + "\"").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = read_text(dir / "err.txt");
  EXPECT_NE(err.find("--max-memory 2 GiB is above this process's hard data limit (977 MiB)"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "p.png"));
  // A run that needs more than the limit stops with one line naming it.
  expect_clean_failure("render --scene plane --max-memory 8M -o p.png", "p.png",
                       {"out of memory", "more than --max-memory allows (8 MiB)"});
  EXPECT_EQ(run("render --scene plane --max-memory 512M -o p.png").exit_code, 0);
}

// A PLY header claiming 3 billion vertices in 180 bytes: Assimp 5.2's PLY importer reserves them
// (36 GB). Its allocations stop at the import's budget (256 MiB plus 64 times the file) or at
// --max-memory, whichever is lower, at once.
TEST_F(TexsimCli, ModelImportsStayWithinTheirMemory) {
  write_text(dir / "big.ply",
             "ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_LT(seconds([&] {
              expect_clean_failure("render --model big.ply -o m.png", "m.png",
                                   {"big.ply", "Assimp's import needs more than 256 MiB", "64 times the 189 bytes"});
            }),
            10.0);
  expect_clean_failure("render --model big.ply --import-memory 1G -o m.png", "m.png",
                       {"big.ply", "needs more than 1 GiB (--import-memory)"});
  expect_clean_failure("render --model big.ply --max-memory 200M -o m.png", "m.png",
                       {"big.ply", "Assimp ran out of memory", "--max-memory allows: 200 MiB"});
  expect_clean_failure("render --model big.ply --import-memory 2X -o m.png", "m.png", {"--import-memory", "2X"});
  // A real model within its budget renders; one given too little memory stops.
  const std::string duck = (kModels / "Collada/duck.dae").string();
  EXPECT_EQ(run("render --model " + duck + " --width 64 --height 48 -o d.png").exit_code, 0);
  expect_clean_failure("render --model " + duck + " --import-memory 64K -o m.png", "m.png",
                       {"duck.dae", "needs more than 64 KiB"});
}

// An import past its time stops the run with one line, its staged outputs removed.
TEST_F(TexsimCli, ModelImportsStayWithinTheirTime) {
  const std::string duck = (kModels / "Collada/duck.dae").string();
  expect_clean_failure("render --model " + duck + " --import-timeout 0.000001 -o d.png --trace-queries t.csv", "d.png",
                       {"duck.dae", "Assimp's import has run 1e-06 s", "--import-timeout"});
  EXPECT_FALSE(fs::exists(dir / "t.csv"));
  expect_clean_failure("render --model " + duck + " --import-timeout -1 -o d.png", "d.png", {"--import-timeout"});
}

// Image headers are checked against the limit before any pixel is read: a PNG through libpng, a
// TGA through OpenImageIO (the image module).
TEST_F(TexsimCli, ImageHeadersBeyondTheMemoryAreRefused) {
  write_text(dir / "huge.png", png_header_only(60000, 60000));
  expect_clean_failure("render --scene plane --texture huge.png -o p.png", "p.png",
                       {"huge.png", "PNG of 60000 x 60000 pixels needs 77.1 GiB once read", "--max-memory"});
  std::string tga(18, '\0');
  tga[2] = 2;  // uncompressed true colour
  tga[12] = char(60000 & 255), tga[13] = char(60000 >> 8), tga[14] = char(60000 & 255), tga[15] = char(60000 >> 8);
  tga[16] = 32;
  tga[17] = 8;
  tga += std::string(64, '\0');
  write_text(dir / "huge.tga", tga);
  expect_clean_failure("render --scene plane --texture huge.tga -o p.png", "p.png",
                       {"huge.tga", "an image of 60000 x 60000 pixels needs", "once read, more than --max-memory"});
}

// A texture file's decoded pyramid against the limit: a 4096 x 4096 BC1 file (11 MiB) decodes to
// 179 MiB of texels.
TEST_F(TexsimCli, TextureFilesBeyondTheMemoryAreRefused) {
  write_text(dir / "big.dds", dds_bc1(4096, 4096));
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t big.dds -q q.csv -o r.csv --max-memory 160M", "r.csv",
                       {"big.dds", "1 image of 4096 x 4096, decoded, needs 171 MiB, more than --max-memory allows (160 MiB)"});
  expect_clean_failure("sample -t big.dds -q q.csv -o r.csv --max-memory 20M", "r.csv",
                       {"big.dds", "a texture file of 10.7 MiB, read, needs 21.3 MiB"});
}

// JSON files and list lines: their size against the limit, their lines against their length.
TEST_F(TexsimCli, ListsAndJsonFilesAreBounded) {
  write_text(dir / "scene.json", std::string(6 << 20, ' ') + "{}");
  expect_clean_failure("render --scene-file scene.json --max-memory 128M -o s.png", "s.png",
                       {"scene.json", "a JSON file of 6 MiB, parsed, needs 192 MiB"});
  queries("u,v,lod\n0.5,0.5,0\n");
  write_text(dir / "list.txt", "0 checker\n1 checker " + std::string(5000, 'x') + "\n");
  expect_clean_failure("sample --textures list.txt -q q.csv -o r.csv", "r.csv", {"list.txt:2", "line longer than 4096 bytes"});
  write_text(dir / "list.txt", std::string("0 checker\n1 che\0cker\n", 21));
  expect_clean_failure("sample --textures list.txt -q q.csv -o r.csv", "r.csv", {"list.txt:2", "a NUL byte"});
  write_text(dir / "list.txt", "0 testcard:6fx32\n");  // (found by fuzz_texture_list)
  expect_clean_failure("sample --textures list.txt -q q.csv -o r.csv", "r.csv", {"list.txt:1", "size must be WxH"});
}

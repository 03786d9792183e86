// Files of the block formats that came with the GLES formats (ETC2, EAC, ASTC): KTX 1, KTX2 and
// astcenc's .astc give back their blocks, texsim samples them alike in every engine (the cached
// RTL's taps decoding them after the cache: the model's texels, miss stream and response clocks),
// and the encoders (ours for ETC2 and EAC, astcenc) keep the picture.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "model/astc.h"
#include "model/etc2.h"
#include "model/sampler.h"
#include "model/srgb.h"
#include "stimulus.h"
#include "texture_file_builders.h"
#include "workloads/texture_io.h"

using namespace tex;
using namespace tex::filetest;

namespace {

// KTX 1 (glInternalFormat `gl`) and KTX2 (vkFormat `vk`) files of 6 random levels of a 32x16
// texture give them back, with their format and colour space; `more(path)` checks each further.
void expect_ktx_round_trip(const Scratch& s, TexelFormat f, uint32_t gl, uint32_t vk, bool srgb, uint64_t seed,
                           const std::function<void(const fs::path&)>& more = {}) {
  const auto levels = random_levels(f, 32, 16, 6, seed);
  for (const auto& [name, bytes] : std::vector<std::pair<std::string, std::vector<uint8_t>>>{
           {"e.ktx", ktx1(gl, 32, 16, levels)}, {"e.ktx2", ktx2(vk, 32, 16, levels)}}) {
    save(s / name, bytes);
    const TextureFile t = read_texture_file((s / name).string());
    EXPECT_EQ(t.format, f) << name;
    EXPECT_EQ(t.srgb, srgb) << name;
    EXPECT_EQ(t.levels, levels) << name << " " << t.format_name;
    if (more) more(s / name);
  }
}

}  // namespace

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
  for (const auto& c : cases) expect_ktx_round_trip(s, c.format, c.gl, c.vk, c.srgb, 80 + uint64_t(c.format) + 10 * c.srgb);
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

// EAC R11 and RG11, unsigned and signed, in KTX 1 and KTX2 give back their levels; texsim samples
// a signed RG11 file alike on chip and cached, and the cached RTL (its taps' EAC decoders, 16-bit
// channels into the 16-bit filter, offset binary) gives the model's samples, miss stream and
// response clocks. A one-level file is completed by the encoder where one exists (unsigned), and
// refused in one line where none does (signed); no depth compare reads an EAC texture.
TEST(TextureFiles, EacFilesSampleThroughTexsim) {
  Scratch s;
  const struct {
    TexelFormat format;
    uint32_t gl, vk;
  } cases[] = {{TexelFormat::EacR11, 0x9270, 153},
               {TexelFormat::EacR11Snorm, 0x9271, 154},
               {TexelFormat::EacRg11, 0x9272, 155},
               {TexelFormat::EacRg11Snorm, 0x9273, 156}};
  for (const auto& c : cases)
    expect_ktx_round_trip(s, c.format, c.gl, c.vk, false, 100 + uint64_t(c.format), [](const fs::path& path) {
      const Pyramid p = load_pyramid(path.string(), TextureOptions{});
      EXPECT_EQ(p.levels[0].channel_bits, 16) << path;
      EXPECT_EQ(p.levels[0].at(0, 0)[3], 65535) << path;  // (GL's RED and RG: A is 1)
    });
  const Pyramid signed_rg = stimulus::random_block_texture(TexelFormat::EacRg11Snorm, {64, 48}, 101);
  save(s / "rg.ktx2", ktx2(156, 64, 48, signed_rg.blocks));
  save_queries(s, 400, 6, 102);
  auto sample = [&](const std::string& args, const std::string& out) {
    return texsim_sample(s, (s / "rg.ktx2").string(), args, out);
  };
  auto text = [&](const std::string& name) { return text_of(s / name); };
  auto in_s = [&](const std::string& name) { return (s / name).string(); };
  EXPECT_EQ(sample("", "onchip.csv").first, 0);
  EXPECT_EQ(sample("--memory cached --miss-trace " + in_s("mm.txt") + " --response-clocks " + in_s("mc.txt"), "cm.csv").first, 0);
  const auto rtl =
      sample("-e rtl --memory cached --miss-trace " + in_s("rm.txt") + " --response-clocks " + in_s("rc.txt"), "cr.csv");
  EXPECT_EQ(rtl.first, 0) << rtl.second;
  const std::string onchip = text("onchip.csv");
  EXPECT_EQ(onchip.rfind("r16,g16,b16,a16\n", 0), 0u) << onchip.substr(0, 40);
  EXPECT_GT(onchip.size(), 400u * 12);
  EXPECT_EQ(text("cm.csv"), onchip);
  EXPECT_EQ(text("cr.csv"), onchip);
  EXPECT_EQ(text("rm.txt"), text("mm.txt"));
  EXPECT_EQ(text("rc.txt"), text("mc.txt"));
  EXPECT_GT(text("rm.txt").size(), 100u);
  // Every sample of a signed texture: B 0.0 (32768 in offset binary), A 1.0 (65535), R and G both
  // sides of 0.
  std::istringstream rows(onchip);
  std::string row;
  std::getline(rows, row);
  int negative = 0, positive = 0;
  while (std::getline(rows, row)) {
    int r = 0, g = 0, b = 0, a = 0;
    ASSERT_EQ(std::sscanf(row.c_str(), "%d,%d,%d,%d", &r, &g, &b, &a), 4) << row;
    EXPECT_EQ(b, 32768) << row;
    EXPECT_EQ(a, 65535) << row;
    negative += r < 32768;
    positive += r > 32768;
  }
  EXPECT_GT(negative, 50);
  EXPECT_GT(positive, 50);
  // One level: the unsigned form gets its chain from the encoder, the signed one has none.
  save(s / "one.ktx2", ktx2(155, 32, 16, {random_levels(TexelFormat::EacRg11, 32, 16, 1, 103)[0]}));
  EXPECT_EQ(load_pyramid((s / "one.ktx2").string(), TextureOptions{}).levels.size(), 6u);
  save(s / "one_snorm.ktx2", ktx2(154, 32, 16, {random_levels(TexelFormat::EacR11Snorm, 32, 16, 1, 104)[0]}));
  try {
    load_pyramid((s / "one_snorm.ktx2").string(), TextureOptions{});
    ADD_FAILURE() << "a one-level signed EAC file was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("one_snorm.ktx2: no eac_r11_snorm encoder is built in"), std::string::npos)
        << e.what();
  }
  const auto signed_format = sample("--format eac_r11_snorm", "x.csv");
  EXPECT_NE(signed_format.second.find("--format eac_r11_snorm: no eac_r11_snorm encoder is built in"), std::string::npos)
      << signed_format.second;
  // A depth compare reads depth textures only; EAC is a colour format.
  save(s / "qc.csv", std::vector<uint8_t>{'u', ',', 'v', ',', 'r', 'e', 'f', ',', 'l', 'o', 'd', '\n',
                                          '0', ',', '0', ',', '0', ',', '0', '\n'});
  const std::string compare = std::string(TEXSIM_PATH) + " sample -t " + in_s("rg.ktx2") + " -q " + in_s("qc.csv") +
                              " -o " + in_s("c.csv") + " --op compare --depth 2> " + in_s("ce.txt");
  EXPECT_NE(WEXITSTATUS(std::system(compare.c_str())), 0);
  EXPECT_NE(text("ce.txt").find("EAC is a colour format"), std::string::npos) << text("ce.txt");
}

// The EAC encoder (workloads/etc2_encode.h: every table and multiplier around each block's mean)
// keeps the picture: R (and G) of a ramp and of the test card, in 8-bit steps, well inside what a
// broken encoder (errors in the tens) gives; the decoded levels are 16-bit.
TEST(TextureFiles, EacEncoderKeepsThePicture) {
  Image ramp(64, 64, 8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ramp.at(x, y) = {uint16_t(x * 4), uint16_t(255 - y * 3), uint16_t(0), uint16_t(255)};
  const Image card = load_texture("testcard:128x128");
  for (const Image* img : std::initializer_list<const Image*>{&ramp, &card})
    for (TexelFormat f : {TexelFormat::EacR11, TexelFormat::EacRg11}) {
      const Pyramid rgba = build_pyramid(*img), eac = compress_pyramid(rgba, f);
      ASSERT_EQ(eac.levels[0].channel_bits, 16);
      double sum = 0, n = 0;
      for (size_t i = 0; i < rgba.levels[0].texels.size(); ++i)
        for (int c = 0; c < format_info(f).channels; ++c, ++n)
          sum += std::abs(eac.levels[0].texels[i][size_t(c)] / 257.0 - rgba.levels[0].texels[i][size_t(c)]);
      std::printf("  %dx%d %s: mean error %.2f (8-bit steps)\n", img->width, img->height, format_info(f).name, sum / n);
      EXPECT_LE(sum / n, img == &ramp ? 1.0 : 1.5) << format_info(f).name;  // (measured 0.41 .. 0.56)
    }
}

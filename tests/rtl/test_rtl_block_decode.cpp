// The block decoders (rtl/tex_bc_decode.sv and its parts) against the model's decode_texel
// (model/block_formats.h), bit for bit, on every texel, both as simulators take them and as
// synthesis does (-DSYNTHESIS, through rtl/synth/tex_bc_decode_top.sv): every endpoint pair and index of the
// BC4-style channel block (exhaustive), random blocks of every format (BC7 in all 8 modes and the
// reserved one), with functional coverage: every BC7 mode, every partition of the partitioned
// modes, every rotation and index selection, BC1's two colour modes and its transparent texel.
// TEX_SCALE=K (make rtl-soak) takes K times the random blocks (20: over 1 M). Also the sRGB decode
// ROM (rtl/tex_srgb_decode.sv) against the model's table, every code.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <type_traits>

#include "Vtex_astc.h"
#include "Vtex_bc_decode.h"
#include "Vtex_bc_decode_synthesis.h"
#include "Vtex_etc2.h"
#include "Vtex_srgb_decode.h"
#include "lockstep.h"
#include "model/astc.h"
#include "model/block_formats.h"
#include "model/etc2.h"
#include "model/srgb.h"

using namespace tex;

namespace {

// Both forms of the decoder: the simulator's (functions called inside `if (en)`) and the
// synthesis form (-DSYNTHESIS: continuous logic).
class Decoder {
 public:
  Decoder()
      : ctx_(std::make_unique<VerilatedContext>()),
        sim_(std::make_unique<Vtex_bc_decode>(ctx_.get())),
        synthesis_(std::make_unique<Vtex_bc_decode_synthesis>(ctx_.get())) {}
  // Texel i (x + block_w y) of a block; `srgb`: an sRGB texture (ASTC's endpoints).
  Rgba8 texel(TexelFormat f, const uint8_t* block, int i, bool synthesis, bool srgb = false) {
    const uint32_t v = word(f, block, i, synthesis, srgb);
    return {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
  }
  // The output word as it is (EAC: {G, R}, 16 bits each).
  uint32_t word(TexelFormat f, const uint8_t* block, int i, bool synthesis, bool srgb = false) {
    return synthesis ? eval(*synthesis_, f, block, i, srgb) : eval(*sim_, f, block, i, srgb);
  }

 private:
  template <class Top>
  static uint32_t eval(Top& top, TexelFormat f, const uint8_t* block, int i, bool srgb) {
    if constexpr (std::is_same_v<Top, Vtex_bc_decode>) top.en = 1;
    top.format = uint8_t(f);
    for (int w = 0; w < 4; ++w)
      top.block[w] = uint32_t(block[4 * w]) | uint32_t(block[4 * w + 1]) << 8 | uint32_t(block[4 * w + 2]) << 16 |
                     uint32_t(block[4 * w + 3]) << 24;
    const int fw = format_info(f).block_w;
    top.x = uint8_t(i % fw);
    top.y = uint8_t(i / fw);
    top.srgb = srgb;
    top.eval();
    return top.rgba;
  }
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtex_bc_decode> sim_;
  std::unique_ptr<Vtex_bc_decode_synthesis> synthesis_;
};

std::string hex(const uint8_t* b, int n) {
  std::string s;
  char buf[4];
  for (int i = n - 1; i >= 0; --i) s += (std::snprintf(buf, sizeof buf, "%02x", b[i]), buf);
  return s;
}

// Compares all 16 texels of a block; false (with a message) at the first difference.
::testing::AssertionResult same(Decoder& rtl, TexelFormat f, const uint8_t* block) {
  for (int i = 0; i < 16; ++i)
    for (bool synthesis : {false, true}) {
      const Rgba8 want = decode_texel(f, block, i), got = rtl.texel(f, block, i, synthesis);
      if (want != got)
        return ::testing::AssertionFailure()
               << format_info(f).name << " block 0x" << hex(block, format_info(f).block_bytes) << " texel " << i
               << (synthesis ? " (the synthesis form)" : "") << ": RTL (" << int(got[0]) << ", " << int(got[1])
               << ", " << int(got[2]) << ", " << int(got[3]) << "), model (" << int(want[0]) << ", "
               << int(want[1]) << ", " << int(want[2]) << ", " << int(want[3]) << ")";
    }
  return ::testing::AssertionSuccess();
}

}  // namespace

// Every (a0, a1) and every index of a BC4 block (the divisions by 7 and 5 in the RTL are
// multiplications by reciprocals: exact only if right for every numerator).
TEST(RtlBlockDecode, ChannelBlockEveryEndpointPair) {
  Decoder rtl;
  uint8_t b[8];
  for (int a0 = 0; a0 < 256; ++a0)
    for (int a1 = 0; a1 < 256; ++a1) {
      b[0] = uint8_t(a0);
      b[1] = uint8_t(a1);
      // indices 0..7, then 7..0: every index twice, in both halves of the 48 index bits
      uint64_t bits = 0;
      for (int i = 0; i < 16; ++i) bits |= uint64_t(i < 8 ? i : 15 - i) << (3 * i);
      for (int k = 0; k < 6; ++k) b[2 + k] = uint8_t(bits >> (8 * k));
      ASSERT_TRUE(same(rtl, TexelFormat::Bc4, b));
    }
}

TEST(RtlBlockDecode, RandomBlocksOfEveryFormat) {
  Decoder rtl;
  const int n = 10000 * rtltest::scale();  // 60 000 blocks; make rtl-soak (x 20): 1.2 M
  std::mt19937_64 rng(rtltest::seed_base() ^ 0xBC);
  std::map<std::string, uint64_t> bins;  // functional coverage
  for (TexelFormat f : {TexelFormat::Bc1, TexelFormat::Bc2, TexelFormat::Bc3, TexelFormat::Bc4, TexelFormat::Bc5,
                        TexelFormat::Bc7})
    for (int k = 0; k < n; ++k) {
      uint8_t b[16];
      for (uint8_t& x : b) x = uint8_t(rng());
      if (f == TexelFormat::Bc7) {
        const int mode = k % 9;  // 8 = the reserved mode
        b[0] = mode == 8 ? 0 : uint8_t((b[0] << (mode + 1)) | (1 << mode));
        const Bc7Mode m = bc7_mode_of(b);
        ++bins["bc7 mode " + std::to_string(m.mode)];
        if (m.subsets > 1) ++bins["bc7 mode " + std::to_string(m.mode) + " partition " + std::to_string(m.partition)];
        if (m.mode == 4 || m.mode == 5)
          ++bins["bc7 mode " + std::to_string(m.mode) + " rotation " + std::to_string(m.rotation) + " select " +
                 std::to_string(m.index_select)];
      }
      if (f == TexelFormat::Bc1) {
        const bool four = (b[0] | b[1] << 8) > (b[2] | b[3] << 8);
        ++bins[four ? "bc1 four colours" : "bc1 three colours"];
        for (int i = 0; i < 16; ++i)
          if (!four && (b[4 + i / 4] >> (2 * (i % 4)) & 3) == 3) ++bins["bc1 transparent texel"];
      }
      ASSERT_TRUE(same(rtl, f, b)) << "seed base " << rtltest::seed_base();
    }
  // Every bin: modes 0..8, the partitions of modes 0 (16), 1, 2, 3, 7 (64), rotation x selection
  // of mode 4 (8) and rotation of mode 5 (4), BC1's colour modes and transparent texel.
  std::vector<std::string> want = {"bc1 four colours", "bc1 three colours", "bc1 transparent texel"};
  for (int m = 0; m <= 8; ++m) want.push_back("bc7 mode " + std::to_string(m));
  for (int m : {0, 1, 2, 3, 7})
    for (int p = 0; p < (m == 0 ? 16 : 64); ++p)
      want.push_back("bc7 mode " + std::to_string(m) + " partition " + std::to_string(p));
  for (int r = 0; r < 4; ++r) {
    want.push_back("bc7 mode 4 rotation " + std::to_string(r) + " select 0");
    want.push_back("bc7 mode 4 rotation " + std::to_string(r) + " select 1");
    want.push_back("bc7 mode 5 rotation " + std::to_string(r) + " select 0");
  }
  for (const std::string& bin : want) EXPECT_GT(bins[bin], 0u) << "coverage hole: " << bin;
  EXPECT_EQ(bins.size(), want.size()) << "a bin outside the list was hit";
}

// An RGBA8 format code gives zeros: the decoder is only between a block format's cache data
// and the filter.
TEST(RtlBlockDecode, Rgba8IsNotDecoded) {
  Decoder rtl;
  uint8_t b[16];
  for (int i = 0; i < 16; ++i) b[i] = uint8_t(0x11 * i + 1);
  EXPECT_EQ(rtl.texel(TexelFormat::Rgba8, b, 3, false), (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(rtl.texel(TexelFormat::Rgba8, b, 3, true), (Rgba8{0, 0, 0, 0}));
}

// Without `en` the decoder gives zeros (what tex_tap_select passes on between block samples).
TEST(RtlBlockDecode, NothingWithoutEnable) {
  VerilatedContext ctx;
  Vtex_bc_decode top(&ctx);
  top.en = 0;
  top.format = uint8_t(TexelFormat::Bc7);
  for (int w = 0; w < 4; ++w) top.block[w] = 0x12345678u * uint32_t(w + 1) | 1u;  // mode 0
  top.x = 1;
  top.y = 1;
  top.eval();
  EXPECT_EQ(top.rgba, 0u);
  top.en = 1;
  top.eval();
  EXPECT_NE(top.rgba, 0u);
}

TEST(RtlBlockDecode, SrgbRomIsTheModelsTable) {
  VerilatedContext ctx;
  Vtex_srgb_decode rom(&ctx);
  for (int c = 0; c < 256; ++c) {
    rom.code = uint8_t(c);
    rom.eval();
    ASSERT_EQ(rom.linear, srgb_decode_table()[size_t(c)]) << "code " << c;
  }
}

// The ETC2 decoders (rtl/tex_etc2.sv, through rtl/synth/tex_etc2_top.sv) against the model's, bit
// for bit: random blocks of the three formats with their colour blocks set to each mode in turn (and
// H blocks of two equal colours, where the order bit ties), RGB8A1 half not opaque; every mode and
// the transparent texel must be seen.
TEST(RtlBlockDecode, Etc2BlocksOfEveryMode) {
  VerilatedContext ctx;
  Vtex_etc2 top(&ctx);
  std::mt19937_64 rng(rtltest::seed_base() ^ 0xE7C2);
  const int n = 3000 * rtltest::scale();
  std::map<std::string, int> seen;
  for (int k = 0; k < n; ++k) {
    const TexelFormat f = std::array{TexelFormat::Etc2Rgb, TexelFormat::Etc2RgbA1, TexelFormat::Etc2Rgba}[size_t(k % 3)];
    uint8_t block[16];
    for (uint8_t& b : block) b = uint8_t(rng());
    uint8_t* c = block + (f == TexelFormat::Etc2Rgba ? 8 : 0);
    const bool tie = k / 3 % 5 == 3 && rng() % 4 == 0;  // an H block of two equal colours
    stimulus::set_etc2_mode(rng, c, k / 3 % 5, f == TexelFormat::Etc2RgbA1, tie);  // individual .. planar in turn
    if (tie) ++seen["H with equal colours"];
    const bool punch = f == TexelFormat::Etc2RgbA1;
    ++seen[std::string(format_info(f).name) + " mode " + std::to_string(int(etc2_mode_of(c, punch)))];
    top.kind = uint8_t(k % 3);
    for (int w = 0; w < 4; ++w)
      top.block[w] = uint32_t(block[4 * w]) | uint32_t(block[4 * w + 1]) << 8 | uint32_t(block[4 * w + 2]) << 16 |
                     uint32_t(block[4 * w + 3]) << 24;
    for (int i = 0; i < 16; ++i) {
      top.texel = uint8_t(i);
      top.eval();
      const uint32_t v = top.rgba;
      const Rgba8 got{uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)}, want = decode_texel(f, block, i);
      if (punch && want[3] == 0) ++seen["transparent"];
      ASSERT_EQ(got, want) << format_info(f).name << " block 0x" << hex(block, format_info(f).block_bytes) << " texel " << i;
    }
  }
  for (const char* name : {"etc2", "etc2a", "etc2a1"})
    for (int m = std::string(name) == "etc2a1" ? 1 : 0; m < 5; ++m)
      EXPECT_GT(seen[std::string(name) + " mode " + std::to_string(m)], n / 60) << name << " mode " << m;
  EXPECT_GT(seen["H with equal colours"], 0);
  EXPECT_GT(seen["transparent"], 0);
}

// The EAC R11 decoder (rtl/tex_etc2.sv's r11, inside tex_bc_decode in both its forms) against the
// model's decode_block into Texel, bit for bit: every texel of random blocks of EAC R11, RG11 and
// their signed forms (stimulus::random_eac_block), as the 16-bit codes the filter takes ({G, R};
// R11's G 0.0). Multiplier 0, the signed base -128 and values clamped at both ends must be seen.
TEST(RtlBlockDecode, EacBlocksOfEveryFormat) {
  Decoder rtl;
  std::mt19937_64 rng(rtltest::seed_base() ^ 0xEAC);
  const int n = 1000 * rtltest::scale();  // blocks per format
  std::map<std::string, int> seen;
  for (const TexelFormat f : {TexelFormat::EacR11, TexelFormat::EacR11Snorm, TexelFormat::EacRg11, TexelFormat::EacRg11Snorm}) {
    const bool snorm = format_info(f).snorm;
    for (int k = 0; k < n; ++k) {
      uint8_t block[16] = {};
      stimulus::random_eac_block(rng, block);
      stimulus::random_eac_block(rng, block + 8);
      Texel want[16];
      decode_block(f, block, want);
      if ((block[1] >> 4) == 0) ++seen["multiplier 0"];
      if (snorm && block[0] == 0x80) ++seen["base -128"];
      for (int i = 0; i < 16; ++i) {
        const int v = eac_r11_value(block, snorm, i);
        if (v == (snorm ? -1023 : 0)) ++seen[snorm ? "signed -1023" : "unsigned 0"];
        if (v == (snorm ? 1023 : 2047)) ++seen[snorm ? "signed 1023" : "unsigned 2047"];
        for (bool synthesis : {false, true}) {
          const uint32_t got = rtl.word(f, block, i, synthesis);
          ASSERT_EQ(got, uint32_t(want[i][0]) | uint32_t(want[i][1]) << 16)
              << format_info(f).name << (synthesis ? " (synthesis)" : "") << " block 0x"
              << hex(block, format_info(f).block_bytes) << " texel " << i;
        }
      }
    }
  }
  for (const char* c : {"multiplier 0", "base -128", "signed -1023", "signed 1023", "unsigned 0", "unsigned 2047"})
    EXPECT_GT(seen[c], 0) << c;
}

// The ASTC decoder (rtl/tex_astc.sv, through rtl/synth/tex_astc_top.sv) against the model's, bit
// for bit: random blocks of every footprint (stimulus::random_astc_block: every block mode,
// partition count, endpoint mode and range, void extents, illegal blocks), every texel, linear and
// sRGB. The model's decoder is astcenc's (AstcReference.*); coverage must be complete.
TEST(RtlBlockDecode, AstcBlocksOfEveryFootprintAndMode) {
  VerilatedContext ctx;
  Vtex_astc top(&ctx);
  std::mt19937_64 rng(rtltest::seed_base() ^ 0xA57C);
  const int n = 100 * rtltest::scale();  // blocks per footprint and colour space
  std::set<int> partitions, weight_levels, colour_levels, cems, ccs;
  int void_extents = 0, errors = 0;
  // Blocks that once told the two apart, first (byte 15 first): configuration and weight bits
  // beyond 128 (3 partitions, dual plane, 32 weights of 3 bits: the remaining count went negative).
  const struct {
    int fw, fh;
    const char* hex;
  } known[] = {{6, 6, "8b206831d8569b85f41303898ae73453"}};
  const int fixed = int(std::size(known));
  for (const AstcFootprint& f : kAstcFootprints)
    for (int k = -2 * fixed; k < 2 * n; ++k) {
      const bool srgb = k & 1;
      uint8_t block[16];
      if (k < 0) {
        const auto& b = known[size_t((k + 2 * fixed) / 2)];
        if (b.fw != f.w || b.fh != f.h) continue;
        for (int i = 0; i < 16; ++i) block[i] = uint8_t(std::stoul(std::string(b.hex + 2 * (15 - i), 2), nullptr, 16));
      } else {
        stimulus::random_astc_block(rng, f.w, f.h, block);
      }
      const AstcMode m = astc_mode_of(block, f.w, f.h);
      void_extents += m.void_extent;
      errors += m.error;
      if (!m.error && !m.void_extent) {
        partitions.insert(m.partitions);
        weight_levels.insert(m.weight_levels);
        colour_levels.insert(m.colour_levels);
        if (m.dual_plane) ccs.insert(m.ccs);
        for (int p = 0; p < m.partitions; ++p) cems.insert(m.cem[size_t(p)]);
      }
      top.fw = uint8_t(f.w);
      top.fh = uint8_t(f.h);
      top.srgb = srgb;
      for (int w = 0; w < 4; ++w)
        top.block[w] = uint32_t(block[4 * w]) | uint32_t(block[4 * w + 1]) << 8 | uint32_t(block[4 * w + 2]) << 16 |
                       uint32_t(block[4 * w + 3]) << 24;
      for (int y = 0; y < f.h; ++y)
        for (int x = 0; x < f.w; ++x) {
          top.x = uint8_t(x);
          top.y = uint8_t(y);
          top.eval();
          const uint32_t v = top.rgba;
          const Rgba8 got{uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
          const Rgba8 want = astc_unorm8(astc_texel16(block, f.w, f.h, srgb, x, y));
          ASSERT_EQ(got, want) << f.w << "x" << f.h << (srgb ? " sRGB" : "") << " block 0x" << hex(block, 16) << " texel ("
                               << x << ", " << y << ")";
        }
    }
  EXPECT_EQ(partitions.size(), 4u);
  EXPECT_EQ(weight_levels.size(), 12u);
  EXPECT_EQ(cems.size(), 16u);
  // Through the taps' decoder (tex_bc_decode, as simulated and in its synthesis form): the format
  // code gives the footprint (tex_pkg::footprint) and sRGB reaches the decoder.
  Decoder dec;
  std::mt19937_64 rng2(rtltest::seed_base() ^ 0xA57D);
  for (int fi = 0; fi < 14; ++fi) {
    const TexelFormat f = TexelFormat(int(TexelFormat::Astc4x4) + fi);
    const FormatInfo& info = format_info(f);
    for (int k = 0; k < 20; ++k) {
      uint8_t block[16];
      stimulus::random_astc_block(rng2, info.block_w, info.block_h, block);
      for (int i = 0; i < info.block_w * info.block_h; ++i)
        for (bool synthesis : {false, true})
          for (bool srgb : {false, true})
            ASSERT_EQ(dec.texel(f, block, i, synthesis, srgb), decode_texel(f, block, i, srgb))
                << info.name << (srgb ? " sRGB" : "") << (synthesis ? " (synthesis form)" : "") << " texel " << i;
    }
  }
  EXPECT_EQ(ccs.size(), 4u);
  EXPECT_GE(colour_levels.size(), 16u);
  EXPECT_GT(void_extents, 0);
  EXPECT_GT(errors, 0);
}

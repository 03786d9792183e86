// The shared parameter list: rtl/tex_pkg.sv must agree with model/formats.h (and stages.h).
#include <gtest/gtest.h>

#include <bit>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "model/block_formats.h"
#include "model/formats.h"
#include "model/stages.h"

using namespace tex;

namespace {

// Value of a SystemVerilog integer literal: 24, 2'd1, 2'b10, 8'hff, 'h1f.
bool parse_sv_number(const std::string& text, int64_t& out) {
  static const std::regex sized(R"(^\s*(\d+)?\s*'\s*[sS]?([dDbBhHoO])\s*([0-9a-fA-F_]+)\s*$)");
  static const std::regex plain(R"(^\s*(\d[\d_]*)\s*$)");
  std::smatch m;
  auto strip = [](std::string s) {
    s.erase(std::remove(s.begin(), s.end(), '_'), s.end());
    return s;
  };
  if (std::regex_match(text, m, plain)) {
    out = std::stoll(strip(m[1]));
    return true;
  }
  if (std::regex_match(text, m, sized)) {
    const char base = char(std::tolower(m[2].str()[0]));
    out = std::stoll(strip(m[3]), nullptr, base == 'd' ? 10 : base == 'b' ? 2 : base == 'h' ? 16 : 8);
    return true;
  }
  return false;
}

// Every `localparam <type> NAME = value;` of the package (comments removed first).
std::map<std::string, int64_t> read_localparams(const std::string& path, std::string& problems) {
  std::ifstream f(path);
  std::map<std::string, int64_t> params;
  if (!f) {
    problems = "cannot open " + path;
    return params;
  }
  std::stringstream ss;
  ss << f.rdbuf();
  std::string text = std::regex_replace(ss.str(), std::regex(R"(//[^\n]*)"), "");
  text = std::regex_replace(text, std::regex(R"(/\*[\s\S]*?\*/)"), "");
  static const std::regex decl(R"(localparam\b[^=;]*?\b([A-Za-z_]\w*)\s*=\s*([^;]+);)");
  for (std::sregex_iterator it(text.begin(), text.end(), decl), end; it != end; ++it) {
    int64_t v = 0;
    if (parse_sv_number((*it)[2], v)) params[(*it)[1]] = v;
    else problems += "cannot read value of " + (*it)[1].str() + " = " + (*it)[2].str() + "; ";
  }
  return params;
}

}  // namespace

TEST(Params, SvLiteralParser) {
  int64_t v = 0;
  ASSERT_TRUE(parse_sv_number("24", v));
  EXPECT_EQ(v, 24);
  ASSERT_TRUE(parse_sv_number("2'd2", v));
  EXPECT_EQ(v, 2);
  ASSERT_TRUE(parse_sv_number("2'b10", v));
  EXPECT_EQ(v, 2);
  ASSERT_TRUE(parse_sv_number("8'hff", v));
  EXPECT_EQ(v, 255);
  EXPECT_FALSE(parse_sv_number("FOO + 1", v));
}

TEST(Params, RtlPackageAgreesWithModel) {
  const std::string path = std::string(SOURCE_DIR) + "/rtl/tex_pkg.sv";
  std::string problems;
  const auto p = read_localparams(path, problems);
  ASSERT_TRUE(problems.empty()) << problems;
  const std::map<std::string, int64_t> expected = {
      {"COORD_FRAC", kCoordFracBits},
      {"TEXEL_COORD_FRAC", kTexelCoordFracBits},
      {"LOD_FRAC", kLodFracBits},
      {"WEIGHT_BITS", kWeightBits},
      {"MAX_LOG2_SIZE", kMaxLog2Size},
      {"WRAP_REPEAT", int(Wrap::Repeat)},
      {"WRAP_CLAMP", int(Wrap::Clamp)},
      {"WRAP_MIRROR", int(Wrap::Mirror)},
      {"WRAP_BORDER", int(Wrap::Border)},
      {"WRAP_MIRROR_CLAMP", int(Wrap::MirrorClamp)},
      {"MIP_NONE", int(MipMode::None)},
      {"MIP_NEAREST", int(MipMode::Nearest)},
      {"MIP_LINEAR", int(MipMode::Linear)},
      {"REDUCE_AVERAGE", int(Reduction::WeightedAverage)},
      {"REDUCE_MIN", int(Reduction::Min)},
      {"REDUCE_MAX", int(Reduction::Max)},
      {"OP_SAMPLE", int(Op::Sample)},
      {"OP_FETCH", int(Op::Fetch)},
      {"OP_GATHER", int(Op::Gather)},
      {"MAX_CW", kMaxChannelBits},
      {"FMT_RGBA8", int(TexelFormat::Rgba8)},
      {"FMT_BC1", int(TexelFormat::Bc1)},
      {"FMT_BC2", int(TexelFormat::Bc2)},
      {"FMT_BC3", int(TexelFormat::Bc3)},
      {"FMT_BC4", int(TexelFormat::Bc4)},
      {"FMT_BC5", int(TexelFormat::Bc5)},
      {"FMT_BC7", int(TexelFormat::Bc7)},
      {"FMT_ASTC_4X4", int(TexelFormat::Astc4x4)},
      {"FMT_ASTC_12X12", int(TexelFormat::Astc12x12)},
      {"TEX_ID_W", std::bit_width(unsigned(kMaxTextures - 1))},
      // cfg_w, cfg_h hold every side 1..kMaxSize.
      {"SIZE_W", std::bit_width(unsigned(kMaxSize))},
  };
  for (const auto& [name, value] : expected) {
    const auto it = p.find(name);
    ASSERT_NE(it, p.end()) << path << " has no localparam " << name;
    EXPECT_EQ(it->second, value) << name << " in " << path;
  }
  // Widths that must hold the model's extreme values.
  ASSERT_TRUE(p.count("COORD_W")) << path << " lacks COORD_W";
  ASSERT_TRUE(p.count("LOD_W") && p.count("LEVEL_W")) << path << " lacks LOD_W or LEVEL_W";
  // lambda, bias and the clamps are LOD_W-bit signed on the pins: exactly the model's range.
  EXPECT_EQ(-(int64_t(1) << (p.at("LOD_W") - 1)), kLodMin) << "LOD_W";
  EXPECT_EQ((int64_t(1) << (p.at("LOD_W") - 1)) - 1, kLodMax) << "LOD_W";
  EXPECT_GE(int64_t(1) << p.at("LEVEL_W"), int64_t(kMaxLevels)) << "LEVEL_W cannot index every level";
  EXPECT_GE(int64_t(1) << p.at("COORD_W"), int64_t(1) << kMaxLog2Size) << "COORD_W cannot index 2^kMaxLog2Size texels";
  // tex_front's unwrapped index is ML + 4 bits signed (ML the unit's largest log2 size): it must
  // hold every index of a reduced coordinate, [-2n - 1, 2n] (2n + 1: the nearest filter's unused
  // second tap), at the largest size.
  int32_t lo = 0, hi = 0;
  for (int32_t u : {INT32_MIN, -(1 << 25) - 1, -1, 0, (1 << 24) - 1, (1 << 25) - 1, INT32_MAX})
    for (Wrap w : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp})
      for (TexelFilter f : {TexelFilter::Nearest, TexelFilter::Linear}) {
        const stage::AxisTaps t = stage::address(stage::scale(stage::reduce(u, w), kMaxSize), f);
        lo = std::min({lo, t.i0, t.i1});
        hi = std::max({hi, t.i0, t.i1});
      }
  const int64_t half = int64_t(1) << (kMaxLog2Size + 4 - 1);
  EXPECT_EQ(lo, -2 * kMaxSize - 1);
  EXPECT_EQ(hi, 2 * kMaxSize + 1);
  EXPECT_GE(lo, -half) << "tex_front's index (ML + 4 bits) too narrow for " << lo;
  EXPECT_LT(hi, half) << "tex_front's index (ML + 4 bits) too narrow for " << hi;
}

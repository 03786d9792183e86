// sim/engines/rtl/register_map.h, the one C++ copy of tex_axil_config's register map (the drivers
// and the AXI tests use it), read against the RTL source.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>

#include "engines/rtl/register_map.h"

using namespace tex::rtl::axil;

// The one C++ copy of the register map (sim/engines/rtl/register_map.h, used by the drivers and
// tests) against the RTL's own: every R_<name> offset of tex_axil_config.sv, the ID and VERSION
// values and the counter count, read out of the source, equal the header's, and each side has
// every register of the other.
TEST(RegisterMap, HeaderMatchesTheRtl) {
  const char* path = TEX_RTL_DIR "/tex_axil_config.sv";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::map<std::string, uint32_t> rtl;
  const std::regex reg(R"(localparam logic \[WA-1:0\] R_(\w+)\s*=\s*WA'\('h([0-9A-Fa-f]+) >> 2\);)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), reg); it != std::sregex_iterator(); ++it)
    rtl[(*it)[1]] = uint32_t(std::stoul((*it)[2], nullptr, 16));
  ASSERT_GE(rtl.size(), 10u) << "the pattern no longer finds tex_axil_config's registers";
  std::map<std::string, uint32_t> header;
  for (const Register& r : kRegisters) header[r.name] = r.offset;
  EXPECT_EQ(rtl, header);
  auto value = [&](const std::string& name) -> uint64_t {
    std::smatch m;
    const std::regex v("localparam logic \\[31:0\\] " + name + R"(\s*=\s*32'h([0-9A-Fa-f_]+);)");
    if (!std::regex_search(text, m, v)) return ~uint64_t(0);
    std::string digits = m[1];
    digits.erase(std::remove(digits.begin(), digits.end(), '_'), digits.end());
    return std::stoull(digits, nullptr, 16);
  };
  EXPECT_EQ(value("ID"), kIdValue);
  EXPECT_EQ(value("VERSION"), kVersionValue);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(localparam int NCNT = (\d+);)")));
  EXPECT_EQ(std::stoi(m[1]), kCounters);
  // Planted: a header with one offset moved is caught by the same comparison.
  header["WRAP"] += 4;
  EXPECT_NE(rtl, header);
}

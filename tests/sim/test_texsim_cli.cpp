// The texsim command line: bad input (one line on stderr, non-zero exit, no output left behind,
// before any work), --help, and what a short run loads. Runs this build's texsim (TEXSIM_PATH).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.h"
#include "engines/engine.h"
#include "model/image.h"
#include "workloads/scenes.h"

using namespace tex;
namespace fs = std::filesystem;

TEST_F(TexsimCli, MissingTextureFile) {
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t missing.png -q q.csv -o r.csv", "r.csv", {"missing.png"});
  expect_clean_failure("mip -t missing.png --dump-levels lv", "lv/level00.png", {"missing.png"});
}

TEST_F(TexsimCli, MissingQueryFile) {
  expect_clean_failure("sample -t noise:8x8 -q nothere.csv -o r.csv", "r.csv", {"nothere.csv"});
}

TEST_F(TexsimCli, CorruptImage) {
  write_text(dir / "bad.png", "this is not a PNG file at all\n");
  write_text(dir / "trunc.png", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t bad.png -q q.csv -o r.csv", "r.csv", {"bad.png"});
  expect_clean_failure("sample -t trunc.png -q q.csv -o r.csv", "r.csv", {"trunc.png"});
  expect_clean_failure("mip -t bad.png --layout lay.png", "lay.png", {"bad.png"});
}

TEST_F(TexsimCli, MalformedCsvLineGivesLineNumberAndText) {
  queries("u,v,lod\n0.1,0.2,0\n# a comment\n0.3,abc,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:4", "0.3,abc,0"});
  queries("u,v,lod\n0.1,0.2\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:2", "0.1,0.2"});
  queries("u,v,lod\n0.1,0.2,0,7\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:2", "0.1,0.2,0,7"});
}

TEST_F(TexsimCli, UnknownHeader) {
  queries("s,t,lambda\n0.1,0.2,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:1", "s,t,lambda"});
  queries("");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv"});
}

TEST_F(TexsimCli, NanInfAndOutOfRangeValues) {
  const std::pair<std::string, std::string> bad[] = {
      {"0.1,nan,0", "nan"},   {"inf,0.2,0", "inf"},        {"0.1,0.2,-inf", "inf"},
      {"200,0.2,0", "u"},     {"0.1,-128.5,0", "v"},       {"0.1,0.2,128", "lod"},
      {"1e999,0,0", "1e999"},
  };
  for (const auto& [line, word] : bad) {
    queries("u,v,lod\n0.5,0.5,0\n" + line + "\n");
    expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:3", word});
  }
  queries("u,v,dudx,dvdx,dudy,dvdy\n0.5,0.5,nan,0,0,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:2"});
  // A finite derivative of 2^15 texels or more is not an error: lambda saturates past the last
  // level, which the filter clamps to (as in GL).
  queries("u,v,dudx,dvdx,dudy,dvdy\n0.5,0.5,1e9,0,0,0\n");
  const Result big = run("sample -t noise:8x8 -q q.csv -o r.csv");
  EXPECT_EQ(big.exit_code, 0) << big.err;
}

TEST_F(TexsimCli, UnknownOptionFilterWrap) {
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --bogus-option", "r.csv", {"bogus-option"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --filter cubic", "r.csv", {"cubic"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --wrap bordered", "r.csv", {"bordered"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --wrap-v tile", "r.csv", {"tile"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --pyramid gauss", "r.csv", {"gauss"});
  expect_clean_failure("sample -t nosuchpattern:8x8 -q q.csv -o r.csv", "r.csv", {"nosuchpattern"});
  expect_clean_failure("nosuchcommand", "r.csv", {"nosuchcommand"});
  expect_clean_failure("", "r.csv", {});
}

TEST_F(TexsimCli, OutputIntoMissingDirectory) {
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o nodir/r.csv", "nodir/r.csv", {"nodir/r.csv"});
  expect_clean_failure("mip -t noise:8x8 --layout nodir/l.png", "nodir/l.png", {"nodir/l.png"});
}

TEST_F(TexsimCli, EveryCommandHasHelp) {
  const Result top = run("--help");
  ASSERT_EQ(top.exit_code, 0);
  // The subcommands as the top-level help lists them.
  std::vector<std::string> commands;
  std::istringstream in(top.out);
  std::string line;
  bool in_list = false;
  while (std::getline(in, line)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    if (in_list && line.size() > 2 && line[0] == ' ') commands.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  for (const char* required : {"sample", "mip", "render", "figures", "explore"})
    EXPECT_NE(std::find(commands.begin(), commands.end(), required), commands.end()) << required;
  for (const auto& c : commands) {
    const Result r = run(c + " --help");
    EXPECT_EQ(r.exit_code, 0) << c;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << c << ": " << r.out;
  }
}

TEST_F(TexsimCli, HelpListsEnginesStallsAndScenes) {
  const Result s = run("sample --help");
  for (const EngineInfo& e : engines()) EXPECT_NE(s.out.find(e.name), std::string::npos) << e.name << "\n" << s.out;
  for (const char* word : {"none | random | heavy", "backdoor | port"}) EXPECT_NE(s.out.find(word), std::string::npos) << word;
  const Result r = run("render --help");
  for (const std::string& scene : scene_names()) EXPECT_NE(r.out.find(scene), std::string::npos) << scene;
  EXPECT_NE(r.out.find("mesh16"), std::string::npos) << r.out;
}

TEST_F(TexsimCli, EngineOptionErrorsComeBeforeAnyWork) {
  write_text(dir / "q.csv", "u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -q q.csv -o r.csv --engine gpu", "r.csv", {"unknown engine 'gpu'", "rtl"});
  expect_clean_failure("sample -q q.csv -o r.csv --stalls sometimes", "r.csv", {"--stalls \"sometimes\""});
  expect_clean_failure("sample -q q.csv -o r.csv --load dma", "r.csv", {"--load \"dma\""});
  expect_clean_failure("sample -q q.csv -o r.csv --engine model --trace t.fst", "r.csv", {"--trace", "model"});
  EXPECT_FALSE(fs::exists(dir / "t.fst"));
  const Result f = run("figures --engine gpu --out figs");
  EXPECT_NE(f.exit_code, 0);
  EXPECT_NE(f.err.find("unknown engine 'gpu'"), std::string::npos) << f.err;
  EXPECT_FALSE(fs::exists(dir / "figs")) << "figures --engine gpu left files";
}

// Image files go through libtexsim_images.so (OpenImageIO), loaded on first use: a run without
// image files never needs it, and a module that cannot be found is a one-line error naming it,
// before any work (TEXSIM_IMAGE_MODULE points elsewhere).
// The image module (OpenImageIO) is loaded only for files other than PNG and JPEG: without it, a
// pattern, a PNG texture and a PNG picture still work, a TIFF fails naming the module.
TEST_F(TexsimCli, ImageModuleIsLoadedOnlyBeyondPngAndJpeg) {
  const auto value = [](int x, int y, int c) { return (x * 31 + y * 17 + c * 5) & 255; };
  write_image(dir / "t.png", 8, 8, 4, value);
  write_image(dir / "t.tif", 8, 8, 4, value);
  queries("u,v,lod\n0.5,0.5,0\n0.25,0.75,1\n");
  const std::string missing = (dir / "nowhere" / "libtexsim_images.so").string();
  setenv("TEXSIM_IMAGE_MODULE", missing.c_str(), 1);
  const Result pattern = run("sample -t noise:16x16 -q q.csv -o a.csv");
  const Result png = run("sample -t t.png -q q.csv -o b.csv");
  const Result picture = run("render -s plane --width 32 --height 32 -t t.png -o c.png");
  expect_clean_failure("sample -t t.tif -q q.csv -o d.csv", "d.csv", {missing, "image module"});
  expect_clean_failure("render -s plane --width 32 --height 32 -o e.tif", "e.tif", {missing});
  unsetenv("TEXSIM_IMAGE_MODULE");
  EXPECT_EQ(pattern.exit_code, 0) << pattern.err;
  EXPECT_EQ(png.exit_code, 0) << png.err;
  EXPECT_EQ(picture.exit_code, 0) << picture.err;
  const Result tif = run("sample -t t.tif -q q.csv -o d.csv");
  EXPECT_EQ(tif.exit_code, 0) << tif.err;
  std::string h;
  EXPECT_EQ(read_csv_rows(dir / "b.csv", h), read_csv_rows(dir / "d.csv", h)) << "PNG and TIFF of the same pixels";
}

// texsim's engines through the command line: every engine gives the model's texels, the cached
// RTL's miss trace and response clocks equal the model's, block formats, sRGB and memory errors.
// Runs this build's texsim (TEXSIM_PATH).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "engines/engine.h"
#include "workloads/scenes.h"

using namespace tex;
namespace fs = std::filesystem;

// The one engine-equivalence test: every engine of this build gives the golden model's texels.
// `texsim sample --engine E` writes the same bytes as `--engine model` for both query headers, a
// few filters and wrap modes, and textures of different shapes, with every --stalls profile and
// both --load methods of the cycle-accurate engines; `texsim render --verify` (the model alongside,
// failing on any differing sample) does the same for every scene. One texsim process per run: the
// SystemC engines fork their simulation; `timeout` turns a hang into a failure.
TEST_F(TexsimCli, EveryEngineGivesTheModelsTexels) {
  std::string lod_trace = "u,v,lod\n", deriv_trace = "u,v,dudx,dvdx,dudy,dvdy\n";
  uint32_t state = 12345;
  auto next = [&state] {  // small LCG: the trace is data, not a statistical sample
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (int i = 0; i < 3000; ++i) {
    const double u = next() * 6 - 3, v = next() * 6 - 3;
    lod_trace += std::to_string(u) + "," + std::to_string(v) + "," + std::to_string(next() * 9 - 2) + "\n";
    const double d = std::ldexp(next(), -int(next() * 10));
    deriv_trace += std::to_string(u) + "," + std::to_string(v) + "," + std::to_string(d) + ",0," +
                   std::to_string(d * next()) + "," + std::to_string(d * 2) + "\n";
  }
  write_text(dir / "lod.csv", lod_trace);
  write_text(dir / "deriv.csv", deriv_trace);
  const std::vector<std::string> cases = {
      "-t noise:64x32 -q lod.csv -f trilinear -w repeat",
      "-t testcard:16x16 -q deriv.csv -f mip_nearest --wrap-u clamp --wrap-v mirror",
      "-t noise:8x64 -q lod.csv -f point -w mirror --pyramid cascade",
      "-t noise:32x32 -q deriv.csv -f nearest_mipmap_linear -w clamp --lod-bias 0.5 --max-lod 3",
  };
  const char* timings[] = {"--stalls none --load port", "--stalls random --seed 3", "--stalls heavy --seed 4",
                           "--stalls random --seed 5 --load port"};
  size_t n = 0;
  for (const std::string& c : cases) {
    const Result golden = run("sample " + c + " -e model -o model.csv");
    ASSERT_EQ(golden.exit_code, 0) << c << ": " << golden.err;
    const std::string expected = read_text(dir / "model.csv");
    for (const EngineInfo& e : engines()) {
      if (e.name == "model") continue;
      const std::string timing = e.cycle_accurate ? timings[n++ % 4] : "";
      const Result r = run("sample " + c + " -e " + e.name + " " + timing + " -o " + e.name + ".csv");
      ASSERT_EQ(r.exit_code, 0) << c << " -e " << e.name << ": " << r.err;
      EXPECT_TRUE(read_text(dir / (e.name + ".csv")) == expected)
          << c << " " << timing << ": engine " << e.name << " differs from the model";
    }
  }
  for (const EngineInfo& e : engines())
    for (const std::string& scene : scene_names())
      for (const char* filter : {"point", "bilinear", "trilinear"}) {
        const Result r = run("render --scene " + scene + " --engine " + e.name + " --filter " + filter +
                             " --verify --width 24 --height 18 --out scene.png");
        EXPECT_EQ(r.exit_code, 0) << e.name << " " << scene << " " << filter << ": " << r.err;
        EXPECT_TRUE(fs::exists(dir / "scene.png")) << e.name << " " << scene << " " << filter;
        fs::remove(dir / "scene.png");
      }
}

// --memory cached: the model and the RTL write the same miss trace (every line read, in order) and
// the same samples; the cache options are refused without --memory cached.
TEST_F(TexsimCli, CachedMissTraceIsTheSameForModelAndRtl) {
  std::string q = "u,v,lod\n";
  for (int i = 0; i < 400; ++i) q += std::to_string(i * 0.013) + "," + std::to_string(i * 0.029) + "," + std::to_string(i % 7 - 1) + "\n";
  queries(q);
  const std::string common = "sample -t noise:64x8 -q q.csv --memory cached --cache-kib 1 --ways 4 --block-order morton";
  const Result m = run(common + " -o m.csv --miss-trace m.txt --stats ms.json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const Result r = run(common + " -e rtl --mem-latency 30 -o r.csv --miss-trace r.txt --stats rs.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto text = [&](const char* name) {
    std::ifstream in(dir / name);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(text("m.csv"), text("r.csv"));
  const std::string misses = text("m.txt");
  EXPECT_EQ(misses, text("r.txt"));
  // The SystemC engines read the same lines through their TLM-2.0 memory socket.
  for (const char* e : {"systemc", "systemc-model"}) {
    const Result sc = run(common + " -e " + e + " --mem-latency 30 -o s.csv --miss-trace s.txt");
    ASSERT_EQ(sc.exit_code, 0) << e << ": " << sc.err;
    EXPECT_EQ(text("s.csv"), text("m.csv")) << e;
    EXPECT_EQ(text("s.txt"), misses) << e;
  }
  ASSERT_GE(misses.size(), 11u);
  EXPECT_EQ(misses.substr(0, 2), "0x");
  EXPECT_NE(text("rs.json").find("\"fifo_max_occupancy\""), std::string::npos);
  EXPECT_NE(text("ms.json").find("\"cache_misses\""), std::string::npos);
  expect_clean_failure("sample -t noise:64x8 -q q.csv -o x.csv --cache-kib 4", "x.csv", {"--cache-kib", "--memory cached"});
  expect_clean_failure(common + " -e rtl --fifo-depth 100000 -o x.csv", "x.csv", {"100000 samples", "FIFO_DEPTH is"});
  expect_clean_failure(common + " -e rtl --fifo-depth 0 -o x.csv", "x.csv", {"--fifo-depth 0"});
}

// --response-clocks: the timing model (--engine model) and the RTL write the same clock for every
// response, on-chip and cached, under random stalls and memory jitter; the model's cycle counters
// are the RTL's.
TEST_F(TexsimCli, ResponseClocksAreTheSameForModelAndRtl) {
  std::string q = "u,v,dudx,dvdx,dudy,dvdy\n";
  for (int i = 0; i < 600; ++i)
    q += std::to_string(i * 0.0131) + "," + std::to_string(i * 0.0297) + "," + std::to_string(0.002 * (i % 13)) +
         ",0.001," + std::to_string(-0.0005 * (i % 5)) + "," + std::to_string(0.004 * (i % 3)) + "\n";
  queries(q);
  auto json_cycles = [&](const char* name) {
    const std::string j = read_text(dir / name);
    const size_t at = j.find("\"cycles\"");
    return at == std::string::npos ? std::string("none") : j.substr(at, j.find(',', at) - at);
  };
  // Every compiled configuration texsim reaches (8-bit textures; the 16-bit ones are compared in
  // the lockstep suites), under random or heavy stalls, the cached ones with memory jitter.
  const std::vector<std::string> cases = {
      "sample -t noise:16x16 -q q.csv -f anisotropic --stalls heavy",
      "sample -t noise:64x8 -q q.csv --memory cached --cache-kib 1 --ways 1 --mem-latency 60 --mem-jitter 40 "
      "--mem-bytes-per-clock 5 --fifo-depth 8 --stalls random --seed 3",
      "sample -t noise:64x8 -q q.csv -f anisotropic --max-aniso 4 --stalls random --seed 5",
      "sample -t noise:1024x1024 -q q.csv --stalls random --seed 6",
      "sample -t noise:256x256 -q q.csv --memory cached --mem-latency 150 --mem-jitter 60 --stalls random --seed 7"};
  const std::vector<std::string> configurations = {"Vtex_unit_4x4", "Vtex_cached_6x3", "Vtex_unit_6x3",
                                                   "Vtex_unit_10x10", "Vtex_cached_13x13"};
  auto json_configuration = [&](const char* name) {
    return nlohmann::json::parse(read_text(dir / name)).value("configuration", std::string("none"));
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string& c = cases[i];
    const Result m = run(c + " -o m.csv --response-clocks m.clk --stats m.json");
    ASSERT_EQ(m.exit_code, 0) << m.err;
    const Result r = run(c + " -e rtl -o r.csv --response-clocks r.clk --stats r.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json_configuration("r.json"), configurations[i]) << c;
    EXPECT_EQ(json_configuration("m.json"), configurations[i]) << c;
    const std::string clocks = read_text(dir / "m.clk");
    EXPECT_EQ(clocks, read_text(dir / "r.clk")) << c;
    EXPECT_EQ(json_cycles("m.json"), json_cycles("r.json")) << c;
    EXPECT_NE(json_cycles("m.json"), "none");
    // One line per response, in increasing clocks (at most one response per clock).
    std::istringstream in(clocks);
    uint64_t clock = 0, last = 0, lines = 0;
    while (in >> clock) {
      if (lines++ > 0) {
        EXPECT_GT(clock, last) << c << ": line " << lines;
      }
      last = clock;
    }
    EXPECT_EQ(lines, 600u) << c;
  }
  ASSERT_EQ(run(cases[0] + " -o t.csv").exit_code, 0);  // (the texels of the first case)
  const Result fast = run(cases[0] + " -o n.csv --no-timing --stats n.json");
  ASSERT_EQ(fast.exit_code, 0) << fast.err;
  EXPECT_EQ(json_cycles("n.json"), "none");
  EXPECT_EQ(read_text(dir / "n.csv"), read_text(dir / "t.csv"));
  expect_clean_failure(cases[0] + " -e rtl --no-timing -o x.csv", "x.csv", {"--no-timing", "--engine model"});
  expect_clean_failure(cases[0] + " --no-timing --response-clocks x.clk -o x.csv", "x.csv", {"--response-clocks", "--no-timing"});
  expect_clean_failure(cases[0] + " -e systemc-model --response-clocks x.clk -o x.csv", "x.csv",
                       {"--response-clocks", "systemc-model"});
  EXPECT_FALSE(fs::exists(dir / "x.clk"));
  // The SystemC engine: the RTL's clocks under its TLM-2.0 initiator's timing, one per response.
  const Result sc = run(cases[1] + " -e systemc -o s.csv --response-clocks s.clk");
  ASSERT_EQ(sc.exit_code, 0) << sc.err;
  std::istringstream sin(read_text(dir / "s.clk"));
  uint64_t clock = 0, last = 0, lines = 0;
  while (sin >> clock) {
    if (lines++ > 0) {
      EXPECT_GT(clock, last) << "systemc: line " << lines;
    }
    last = clock;
  }
  EXPECT_EQ(lines, 600u);
  ASSERT_EQ(run(cases[1] + " -o t1.csv").exit_code, 0);  // (the model's texels of that case)
  EXPECT_EQ(read_text(dir / "s.csv"), read_text(dir / "t1.csv"));
}

TEST_F(TexsimCli, TiledOrderDrawsTheSamePictureFromOtherCacheTraffic) {
  const std::string common = "render --scene plane --width 96 --height 64 --texture testcard:256x256 --memory cached";
  const Result a = run(common + " -o scan.png --miss-trace scan.txt");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const Result b = run(common + " --order tiled --tile 4 -o tiled.png --miss-trace tiled.txt");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto text = [&](const char* name) {
    std::ifstream in(dir / name, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(text("scan.png"), text("tiled.png"));
  EXPECT_NE(text("scan.txt"), text("tiled.txt"));
  EXPECT_GT(text("scan.txt").size(), 100u);
}

// --format: the texture is held compressed in memory (libsquish), the stats say so, the cached unit
// reads fewer bytes per sample than for RGBA8, the on-chip unit samples the decoded levels, and
// what cannot be done is one clean error.
TEST_F(TexsimCli, BlockFormatsThroughTheCli) {
  std::string q = "u,v,lod\n";
  for (int i = 0; i < 400; ++i) q += std::to_string((i % 20) / 20.0) + "," + std::to_string((i / 20) / 20.0) + ",1.5\n";
  queries(q);
  auto stats = [&](const std::string& args) {
    const Result r = run("sample -t testcard:256x256 -q q.csv -o r.csv --stats s.json " + args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return nlohmann::json::parse(read_text(dir / "s.json"));
  };
  const auto rgba = stats("--memory cached");
  const auto bc1 = stats("--memory cached --format bc1");
  const auto bc3 = stats("--memory cached --format bc3");
  EXPECT_EQ(rgba["format"], "rgba8");
  EXPECT_EQ(bc1["format"], "bc1");
  EXPECT_LT(bc1["bytes_per_sample"].get<double>() * 4, rgba["bytes_per_sample"].get<double>());
  EXPECT_LT(bc3["bytes_per_sample"].get<double>() * 2, rgba["bytes_per_sample"].get<double>());
  // On chip and cached sample the same decoded texels.
  const Result a = run("sample -t testcard:256x256 -q q.csv -o onchip.csv --format bc1");
  const Result b = run("sample -t testcard:256x256 -q q.csv -o cached.csv --format bc1 --memory cached");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(read_text(dir / "onchip.csv"), read_text(dir / "cached.csv"));
  EXPECT_NE(read_text(dir / "onchip.csv"), read_text(dir / "r.csv"));  // BC1 is not the RGBA8 picture
  const Result m = run("mip -t testcard:64x64 --format bc7 --memory-image m.bin");  // Mesa's encoder
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::string image = read_text(dir / "m.bin");
  ASSERT_GT(image.size(), 72u);
  EXPECT_EQ(image.substr(0, 8), "TEXMEM03");
  EXPECT_EQ(uint8_t(image[64]), 7);  // format: BC7
  EXPECT_EQ(uint8_t(image[28]), 0);  // no texel bytes: blocks
  expect_clean_failure("sample -t testcard:64x64 -q q.csv -o x.csv --format bc6", "x.csv", {"--format", "bc6", "bc7"});
  // The cached RTL decodes the blocks after its caches: the model's samples, lines and clocks.
  for (const char* f : {"bc1", "bc7"}) {
    const std::string args = std::string(" -t testcard:64x64 -q q.csv --format ") + f + " --memory cached --stalls random";
    const Result mr = run("sample" + args + " -o m.csv --response-clocks mc.txt");
    const Result rr = run("sample" + args + " -o t.csv --response-clocks tc.txt -e rtl");
    ASSERT_EQ(mr.exit_code, 0) << mr.err;
    ASSERT_EQ(rr.exit_code, 0) << rr.err;
    EXPECT_EQ(read_text(dir / "m.csv"), read_text(dir / "t.csv")) << f;
    EXPECT_EQ(read_text(dir / "mc.txt"), read_text(dir / "tc.txt")) << f;
  }
  // Behind the TLM-2.0 socket, its memory target jittering: the same samples and lines as the
  // model (the RTL decodes after its caches; the model backend decodes the lines it reads).
  for (const char* f : {"bc1", "bc7"})
    for (const char* e : {"systemc", "systemc-model"}) {
      const std::string args = std::string(" -t testcard:64x64 -q q.csv --format ") + f + " --memory cached --mem-jitter 20";
      const Result mr = run("sample" + args + " -o m.csv --miss-trace mm.txt");
      const Result sr = run("sample" + args + " -o s.csv --miss-trace sm.txt -e " + e);
      ASSERT_EQ(mr.exit_code, 0) << mr.err;
      ASSERT_EQ(sr.exit_code, 0) << sr.err;
      EXPECT_EQ(read_text(dir / "s.csv"), read_text(dir / "m.csv")) << f << " " << e;
      EXPECT_EQ(read_text(dir / "sm.txt"), read_text(dir / "mm.txt")) << f << " " << e;
    }
}

// --srgb: results are linear unorm16 under their own header, the pyramid averages in linear space
// (a checker's far levels are brighter than the codes' mean), render writes sRGB codes again,
// and what has no sRGB form is one clean error.
TEST_F(TexsimCli, SrgbTexturesThroughTheCli) {
  queries("u,v,lod\n0.5,0.5,6\n0.25,0.25,0\n");
  write_image(dir / "bw.png", 64, 64, 3, [](int x, int y, int) { return (x / 8 + y / 8) % 2 ? 255 : 0; });
  const Result r = run("sample -t bw.png --srgb -q q.csv -o s.csv --stats s.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string header;
  const auto rows = read_csv_rows(dir / "s.csv", header);
  EXPECT_EQ(header, "r16,g16,b16,a16");
  ASSERT_EQ(rows.size(), 2u);
  // The 1x1 level of a black and white checker: linear one half, code 188, decoded 32957 (averaging
  // the codes would give 128, linear 0.216).
  EXPECT_EQ(rows[0][0], 32957);
  EXPECT_EQ(nlohmann::json::parse(read_text(dir / "s.json"))["format"], "rgba8_srgb");
  const Result plain = run("sample -t bw.png -q q.csv -o p.csv");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(read_csv_rows(dir / "p.csv", header)[0][0], 128);
  EXPECT_EQ(header, "r,g,b,a");
  // On chip the RTL holds the decoded levels (a 16-bit configuration): the model's results.
  write_image(dir / "bw16.png", 16, 16, 3, [](int x, int y, int) { return (x / 2 + y / 2) % 2 ? 255 : 0; });
  std::string q2 = "u,v,lod\n";
  for (int i = 0; i < 64; ++i) q2 += std::to_string(i * 0.037) + "," + std::to_string(i * 0.051) + "," + std::to_string(i % 5 - 0.5) + "\n";
  write_text(dir / "q2.csv", q2);
  const Result m = run("sample -t bw16.png --srgb -q q2.csv -o m.csv");
  const Result t = run("sample -t bw16.png --srgb -q q2.csv -o t.csv -e rtl --stalls random");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_EQ(read_text(dir / "m.csv"), read_text(dir / "t.csv"));
  // mip --srgb: the levels as stored, sRGB codes averaged in linear space (the 1x1 level: 188).
  const Result mip = run("mip -t bw.png --srgb --dump-levels lv");
  ASSERT_EQ(mip.exit_code, 0) << mip.err;
  EXPECT_NE(mip.out.find("rgba8 sRGB texture"), std::string::npos) << mip.out;
  int lw = 0, lh = 0;
  const std::vector<uint8_t> last = read_image(dir / "lv/level06.png", lw, lh);
  ASSERT_EQ(last.size(), 4u);
  EXPECT_EQ(last[0], 188);
  const Result png = run("render --scene plane --width 64 --height 48 -t checker:64x64 --srgb -o f.png");
  ASSERT_EQ(png.exit_code, 0) << png.err;
  int w = 0, h = 0;
  EXPECT_FALSE(read_image(dir / "f.png", w, h).empty());
  expect_clean_failure("sample -t checker:64x64 --srgb --format bc5 -q q.csv -o x.csv", "x.csv", {"--srgb", "bc5"});
  // Cached, the RTL's sRGB tables after the caches: the model's results.
  const Result cm = run("sample -t bw.png --srgb --memory cached -q q2.csv -o cm.csv");
  const Result ct = run("sample -t bw.png --srgb --memory cached -q q2.csv -o ct.csv -e rtl --stats ct.json");
  ASSERT_EQ(cm.exit_code, 0) << cm.err;
  ASSERT_EQ(ct.exit_code, 0) << ct.err;
  EXPECT_EQ(read_text(dir / "cm.csv"), read_text(dir / "ct.csv"));
  EXPECT_EQ(nlohmann::json::parse(read_text(dir / "ct.json"))["configuration"], "Vtex_cached_13x13");
  // Behind the TLM-2.0 socket: the same results (RTL: its sRGB tables; model backend: the lines it
  // reads, decoded to linear).
  for (const char* e : {"systemc", "systemc-model"}) {
    const Result cs = run(std::string("sample -t bw.png --srgb --memory cached -q q2.csv -o cs.csv -e ") + e);
    ASSERT_EQ(cs.exit_code, 0) << cs.err;
    EXPECT_EQ(read_text(dir / "cs.csv"), read_text(dir / "cm.csv")) << e;
  }
}

// --mem-error-at N: the N-th line read answers SLVERR. Model, RTL and the RTL behind the TLM socket
// (its memory target answering TLM_GENERIC_ERROR_RESPONSE) flag the same samples, texsim
// names them on one line, exits non-zero and writes none of its outputs; bad values are refused
// before any work.
TEST_F(TexsimCli, MemoryErrorsNameTheFlaggedSamples) {
  std::string q = "u,v,lod\n";
  for (int i = 0; i < 400; ++i) q += std::to_string((i % 20) / 20.0) + "," + std::to_string((i / 20) / 20.0) + ",1.5\n";
  queries(q);
  const std::string args = "sample -t testcard:64x64 -q q.csv -o r.csv --memory cached --stalls random --mem-jitter 20 "
                           "--response-clocks c.txt --stats s.json --mem-error-at 9,3";
  std::string flagged[3];
  for (int e = 0; e < 3; ++e) {
    const std::string engine = e == 0 ? "model" : e == 1 ? "rtl" : "systemc";
    const std::string& a = args;
    const Result r = run(a + " -e " + engine);
    expect_clean_failure(a + " -e " + engine, "r.csv",
                         {"memory error: line reads 3, 9 answered SLVERR", "samples flagged", "engine " + engine});
    EXPECT_FALSE(fs::exists(dir / "c.txt"));
    EXPECT_FALSE(fs::exists(dir / "s.json"));
    flagged[e] = r.err.substr(0, r.err.find("; engine"));
  }
  EXPECT_EQ(flagged[0], flagged[1]);
  EXPECT_EQ(flagged[0], flagged[2]);
  EXPECT_NE(flagged[0].find("(request "), std::string::npos) << flagged[0];
  // A read the run never makes flags nothing: the results are written, with a warning.
  const Result late = run("sample -t testcard:64x64 -q q.csv -o r.csv --memory cached --mem-error-at 100000");
  EXPECT_EQ(late.exit_code, 0) << late.err;
  EXPECT_NE(late.err.find("the run read only"), std::string::npos) << late.err;
  expect_clean_failure("sample -t testcard:64x64 -q q.csv -o x.csv --memory cached --mem-error-at 0", "x.csv",
                       {"--mem-error-at 0", "counted from 1"});
  expect_clean_failure("sample -t testcard:64x64 -q q.csv -o x.csv --memory cached --mem-error-at 2,x", "x.csv",
                       {"--mem-error-at", "\"x\""});
  expect_clean_failure("sample -t testcard:64x64 -q q.csv -o x.csv --mem-error-at 2", "x.csv",
                       {"--mem-error-at", "--memory cached"});
  expect_clean_failure("sample -t testcard:64x64 -q q.csv -o x.csv --memory cached --mem-error-at 2 -e systemc-model",
                       "x.csv", {"--mem-error-at", "systemc-model"});
}

// texsim sample and mip as documented: sizes, views, unnormalized coordinates, channels, the
// results file, derivatives, sampler options, statistics, mip dumps and memory images. Runs this
// build's texsim (TEXSIM_PATH).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include <functional>

#include "cli_fixture.h"
#include "engines/engine.h"
#include "model/image.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "workloads/scenes.h"

using namespace tex;
namespace fs = std::filesystem;

// A file of any size is sampled as it is, by the model and both RTL units alike (the same
// samples); --resize resamples to powers of two.
TEST_F(TexsimCli, NonPowerOfTwoIsSampledOrNamedAndResizeWorks) {
  write_image(dir / "npot.png", 12, 5, 3, [](int x, int y, int c) { return (x * 20 + y * 7 + c * 50) & 255; });
  queries("u,v,lod\n0.5,0.5,0\n0.25,0.75,1\n");
  const Result m = run("sample -t npot.png -q q.csv -o m.csv");
  EXPECT_EQ(m.exit_code, 0) << m.err;
  std::string mh;
  EXPECT_EQ(read_csv_rows(dir / "m.csv", mh).size(), 2u);
  const Result onchip = run("sample -t npot.png -q q.csv -o o.csv -e rtl");
  EXPECT_EQ(onchip.exit_code, 0) << onchip.err;
  std::string oh;
  EXPECT_EQ(read_csv_rows(dir / "o.csv", oh), read_csv_rows(dir / "m.csv", mh));
  const Result cached = run("sample -t npot.png -q q.csv -o c.csv -e rtl --memory cached");
  EXPECT_EQ(cached.exit_code, 0) << cached.err;
  std::string ch;
  EXPECT_EQ(read_csv_rows(dir / "c.csv", ch), read_csv_rows(dir / "m.csv", mh));
  const Result r = run("sample -t npot.png --resize -q q.csv -o r.csv -e rtl");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::string header;
  EXPECT_EQ(read_csv_rows(dir / "r.csv", header).size(), 2u);
  EXPECT_EQ(header, "r,g,b,a");
}

// A view (--base-level, --max-level; a texture list's base= and max=): every engine samples the
// same bits (the on-chip unit through cfg_last_level, the cached one through its descriptor), and
// differently from the whole texture; bad levels are one line naming the option and the values.
TEST_F(TexsimCli, ViewsSampleTheSameInEveryEngine) {
  queries("u,v,lod\n0.3,0.7,0\n0.5,0.5,1.5\n0.1,0.2,3.7\n0.9,0.9,9\n-0.2,1.3,2.2\n");
  write_image(dir / "t.png", 100, 60, 3, [](int x, int y, int c) { return (x * 37 + y * 11 + c * 90) & 255; });
  const std::string view = "sample -t t.png -q q.csv --base-level 1 --max-level 3 ";
  ASSERT_EQ(run(view + "-o m.csv").exit_code, 0);
  std::string h;
  const auto model = read_csv_rows(dir / "m.csv", h);
  for (const char* e : {"-e rtl", "-e rtl --memory cached", "-e systemc", "-e systemc --memory cached"}) {
    const Result r = run(view + "-o e.csv " + e);
    EXPECT_EQ(r.exit_code, 0) << e << ": " << r.err;
    EXPECT_EQ(read_csv_rows(dir / "e.csv", h), model) << e;
  }
  ASSERT_EQ(run("sample -t t.png -q q.csv -o whole.csv").exit_code, 0);
  EXPECT_NE(read_csv_rows(dir / "whole.csv", h), model) << "the view changed nothing";
  // the same view from a texture list
  write_text(dir / "list.txt", "0 t.png base=1 max=3\n");
  ASSERT_EQ(run("sample --textures list.txt -q q.csv -o l.csv -e rtl --memory cached").exit_code, 0);
  EXPECT_EQ(read_csv_rows(dir / "l.csv", h), model);
  expect_clean_failure("sample -t testcard:100x60 -q q.csv -o x.csv --base-level 7", "x.csv",
                       {"--base-level 7", "levels 0 to 6"});
  expect_clean_failure("sample -t testcard:100x60 -q q.csv -o x.csv --base-level 3 --max-level 2", "x.csv",
                       {"--max-level 2", "--base-level 3"});
  // a built-in pattern in a list is the pattern, wherever the list is
  fs::create_directories(dir / "sub");
  write_text(dir / "sub" / "p.txt", "0 testcard:100x60 base=1 max=3\n");
  ASSERT_EQ(run("sample --textures sub/p.txt -q q.csv -o p.csv").exit_code, 0);
  ASSERT_EQ(run("sample -t testcard:100x60 --base-level 1 --max-level 3 -q q.csv -o p2.csv").exit_code, 0);
  EXPECT_EQ(read_csv_rows(dir / "p.csv", h), read_csv_rows(dir / "p2.csv", h));
  write_text(dir / "deep.txt", "0 t.png\n1 t.png base=9 max=12\n");  // 100x60: levels 0 to 6
  expect_clean_failure("sample --textures deep.txt -q q.csv -o x.csv --memory cached", "x.csv",
                       {"deep.txt:2: base=9 max=12", "levels 0 to 6"});
  write_text(dir / "bad.txt", "0 t.png base=x\n");
  expect_clean_failure("sample --textures bad.txt -q q.csv -o x.csv", "x.csv", {"bad.txt:1", "base=", "not a level"});
}

// --unnormalized (Vulkan unnormalizedCoordinates, GL rectangle textures): the trace's u, v are
// texels. On a power-of-two texture a texel coordinate x is the normalized x / w exactly, so the
// samples equal the normalized run's; an NPOT texture samples the same in every engine, and a
// texture list takes `unnormalized` per entry.
TEST_F(TexsimCli, UnnormalizedCoordinatesAreTexels) {
  queries("u,v,lod\n0.5,0.5,0\n12.25,7.75,0\n63.5,31.5,2\n-3,40,0\n70.125,-0.5,0\n31.999,16.001,0\n");
  write_text(dir / "n.csv", "u,v,lod\n0.0078125,0.015625,0\n0.19140625,0.2421875,0\n0.9921875,0.984375,2\n"
                            "-0.046875,1.25,0\n1.095703125,-0.015625,0\n");
  const std::string common = " --wrap-u clamp --wrap-v border --border-color opaque-white --filter bilinear ";
  for (const char* e : {"-e model", "-e rtl", "-e rtl --memory cached"}) {
    // the first five queries: exact in both forms (the sixth is not: 31.999 / 64 has no Q8.24 form)
    write_text(dir / "q5.csv", "u,v,lod\n0.5,0.5,0\n12.25,7.75,0\n63.5,31.5,2\n-3,40,0\n70.125,-0.5,0\n");
    ASSERT_EQ(run(std::string("sample -t noise:64x32 -q q5.csv -o u.csv --unnormalized") + common + e).exit_code, 0) << e;
    ASSERT_EQ(run(std::string("sample -t noise:64x32 -q n.csv -o n_out.csv") + common + e).exit_code, 0) << e;
    std::string h;
    EXPECT_EQ(read_csv_rows(dir / "u.csv", h), read_csv_rows(dir / "n_out.csv", h)) << e;
  }
  const std::string npot = "sample -t testcard:37x23 -q q.csv --unnormalized" + common;
  ASSERT_EQ(run(npot + "-o m.csv").exit_code, 0);
  std::string h;
  const auto model = read_csv_rows(dir / "m.csv", h);
  for (const char* e : {"-e rtl", "-e rtl --memory cached", "-e systemc", "-e systemc --memory cached"}) {
    const Result r = run(npot + "-o e.csv " + e);
    EXPECT_EQ(r.exit_code, 0) << e << ": " << r.err;
    EXPECT_EQ(read_csv_rows(dir / "e.csv", h), model) << e;
  }
  // a texture list: entry 1 unnormalized, entry 0 normalized, one trace
  write_text(dir / "list.txt", "0 noise:64x32 clamp border\n1 noise:64x32 clamp border unnormalized\n");
  write_text(dir / "t.csv", "tex,u,v,lod\n0,0.19140625,0.2421875,0\n1,12.25,7.75,0\n");
  ASSERT_EQ(run("sample --textures list.txt -q t.csv -o l.csv --filter bilinear -e rtl --memory cached").exit_code, 0);
  const auto rows = read_csv_rows(dir / "l.csv", h);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], rows[1]) << "texel (12.25, 7.75) is (0.19140625, 0.2421875) of a 64x32 texture";
  // bad input: what Vulkan forbids, named; texel coordinates beyond Q16.16
  expect_clean_failure("sample -t noise:64x32 -q q.csv -o x.csv --unnormalized --filter bilinear", "x.csv",
                       {"--unnormalized", "clamp or border", "not repeat"});
  expect_clean_failure("sample -t noise:64x32 -q q.csv -o x.csv --unnormalized --wrap clamp", "x.csv",
                       {"--unnormalized", "mipmap mode linear"});
  expect_clean_failure("sample -t noise:64x32 -q q.csv -o x.csv --unnormalized --wrap clamp --filter bilinear "
                       "--mag-filter nearest", "x.csv", {"--unnormalized", "magnification filter nearest"});
  write_text(dir / "far.csv", "u,v,lod\n1,2,0\n40000,2,0\n");
  expect_clean_failure("sample -t noise:64x32 -q far.csv -o x.csv --unnormalized --wrap clamp --filter point", "x.csv",
                       {"far.csv:3", "40000", "texels", "[-32768, 32768)"});
  // render scales the frame's coordinates to texels: the normalized frame's picture, but for the
  // coordinates' rounding (Q16.16 texels of u * 64 against Q8.24 of u: a weight 1/256 apart)
  const std::string plane = "render --scene plane --width 64 --height 48 -t noise:64x32 --wrap clamp --filter bilinear ";
  ASSERT_EQ(run(plane + "--unnormalized -e rtl --verify -o pu.png").exit_code, 0);
  ASSERT_EQ(run(plane + "-o pn.png").exit_code, 0);
  int w = 0, hh = 0;
  const std::vector<uint8_t> pu = read_image(dir / "pu.png", w, hh), pn = read_image(dir / "pn.png", w, hh);
  ASSERT_EQ(pu.size(), pn.size());
  ASSERT_FALSE(pu.empty());
  int worst = 0;
  for (size_t i = 0; i < pu.size(); ++i) worst = std::max(worst, std::abs(int(pu[i]) - int(pn[i])));
  EXPECT_LE(worst, 2);
  expect_clean_failure("render --model no.gltf --unnormalized --wrap clamp --filter bilinear -o x.png", "x.png",
                       {"--unnormalized", "normalized"});
  write_text(dir / "badlist.txt", "0 noise:64x32 repeat unnormalized\n");
  expect_clean_failure("sample --textures badlist.txt -q t.csv -o x.csv --filter bilinear --memory cached", "x.csv",
                       {"badlist.txt:1", "not repeat"});
}

// --reduction (Vulkan reductionMode): min and max bound the weighted average texel by texel, and
// differ from it; the SystemC model engine and both RTL units give the model's bytes; a texture
// list's reduction= sets its sampler's; a bad name is one line.
TEST_F(TexsimCli, ReductionMinAndMaxBoundTheAverage) {
  std::string q = "u,v,lod\n";
  for (int i = 0; i < 300; ++i)
    q += std::to_string((i * 37 % 300) / 97.0 - 1) + "," + std::to_string((i * 53 % 300) / 113.0 - 1) + "," +
         std::to_string(i % 9 * 0.5 - 1) + "\n";
  queries(q);
  const std::string base = "sample -t noise:37x23 -q q.csv -f trilinear -w mirror ";
  for (const auto& [option, out] : {std::pair{"", "avg.csv"}, {"--reduction min ", "min.csv"},
                                     {"--reduction VK_SAMPLER_REDUCTION_MODE_MAX ", "max.csv"}}) {
    const Result res = run(base + option + "-o " + out);
    ASSERT_EQ(res.exit_code, 0) << option << res.err;
  }
  std::string h;
  const auto avg = read_csv_rows(dir / "avg.csv", h), lo = read_csv_rows(dir / "min.csv", h),
             hi = read_csv_rows(dir / "max.csv", h);
  ASSERT_EQ(avg.size(), 300u);
  ASSERT_EQ(lo.size(), avg.size());
  ASSERT_EQ(hi.size(), avg.size());
  int below = 0, above = 0;
  for (size_t i = 0; i < avg.size(); ++i)
    for (size_t c = 0; c < avg[i].size(); ++c) {
      EXPECT_LE(lo[i][c], avg[i][c]) << "query " << i;
      EXPECT_LE(avg[i][c], hi[i][c]) << "query " << i;
      below += lo[i][c] < avg[i][c];
      above += avg[i][c] < hi[i][c];
    }
  EXPECT_GT(below, 300);
  EXPECT_GT(above, 300);
  ASSERT_EQ(run(base + "--reduction min -e systemc-model -o sc.csv").exit_code, 0);
  EXPECT_EQ(read_text(dir / "sc.csv"), read_text(dir / "min.csv"));
  write_text(dir / "list.txt", "0 noise:37x23 mirror reduction=max\n");
  ASSERT_EQ(run("sample --textures list.txt -q q.csv -f trilinear -o l.csv").exit_code, 0);
  EXPECT_EQ(read_text(dir / "l.csv"), read_text(dir / "max.csv"));
  ASSERT_EQ(run(base + "--reduction min -e rtl -o r.csv").exit_code, 0);
  EXPECT_EQ(read_text(dir / "r.csv"), read_text(dir / "min.csv"));
  ASSERT_EQ(run(base + "--reduction max -e rtl --memory cached -o rc.csv").exit_code, 0);
  EXPECT_EQ(read_text(dir / "rc.csv"), read_text(dir / "max.csv"));
  expect_clean_failure(base + "--reduction median -o bad.csv", "bad.csv", {"--reduction", "median"});
  write_text(dir / "bad.txt", "0 noise:37x23 reduction=avg\n");
  expect_clean_failure("sample --textures bad.txt -q q.csv -o bad.csv", "bad.csv", {"bad.txt", "reduction=", "avg"});
}

// --op fetch (texelFetch): an i,j,level trace reads level 0's texels as the image holds them, a
// level above 0 as a nearest-level point sample at that texel's centre gives it, and 0 outside the
// texture; every engine and both RTL units give the model's bytes; a trace whose header does not
// match --op, a value that is not a whole number, an unknown operation: one line, nothing written.
TEST_F(TexsimCli, TexelFetchReadsTexelsAndZeroOutside) {
  auto value = [](int x, int y, int c) { return (7 + x * 31 + y * 17 + c * 50) % 256; };
  write_image(dir / "t.png", 6, 5, 4, value);  // levels 6x5, 3x2, 1x1
  std::string q = "i,j,level\n", p = "u,v,lod\n";
  std::vector<std::vector<int>> want;
  for (int y = -1; y <= 5; ++y)
    for (int x = -1; x <= 6; ++x) {
      q += std::to_string(x) + "," + std::to_string(y) + ",0\n";
      const bool in = x >= 0 && x < 6 && y >= 0 && y < 5;
      want.push_back(in ? std::vector<int>{value(x, y, 0), value(x, y, 1), value(x, y, 2), value(x, y, 3)}
                        : std::vector<int>{0, 0, 0, 0});
    }
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {  // level 1 (3x2): against point samples at lod 1
      q += std::to_string(x) + "," + std::to_string(y) + ",1\n";
      p += std::to_string((x + 0.5) / 3) + "," + std::to_string((y + 0.5) / 2) + ",1\n";
    }
  q += "0,0,3\n-5,0,1\n0,0,-1\n";  // beyond the last level, left of level 1, below level 0
  write_text(dir / "q.csv", q);
  write_text(dir / "p.csv", p);
  const Result r = run("sample -t t.png --op fetch -q q.csv -o f.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("texel fetches"), std::string::npos) << r.out;
  std::string h;
  const auto rows = read_csv_rows(dir / "f.csv", h);
  ASSERT_EQ(rows.size(), want.size() + 6 + 3);
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(rows[i], want[i]) << "query " << i;
  ASSERT_EQ(run("sample -t t.png -f nearest_mipmap_nearest -q p.csv -o p_out.csv").exit_code, 0);
  const auto points = read_csv_rows(dir / "p_out.csv", h);
  ASSERT_EQ(points.size(), 6u);
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(rows[want.size() + i], points[i]) << "level 1 texel " << i;
  for (size_t i = want.size() + 6; i < rows.size(); ++i) EXPECT_EQ(rows[i], (std::vector<int>{0, 0, 0, 0})) << i;
  for (const char* engine : {"-e rtl", "-e rtl --memory cached", "-e systemc --memory cached", "-e systemc-model"}) {
    const Result e = run(std::string("sample -t t.png --op fetch -q q.csv -o e.csv ") + engine);
    ASSERT_EQ(e.exit_code, 0) << engine << ": " << e.err;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "f.csv")) << engine;
  }
  expect_clean_failure("sample -t t.png --op fetch -q p.csv -o bad.csv", "bad.csv", {"p.csv", "u,v,lod", "--op fetch"});
  expect_clean_failure("sample -t t.png -q q.csv -o bad.csv", "bad.csv", {"q.csv", "i,j,level", "--op fetch"});
  expect_clean_failure("sample -t t.png --op gather -q q.csv -o bad.csv", "bad.csv", {"--op", "gather"});
  write_text(dir / "half.csv", "i,j,level\n1,2,0\n1.5,2,0\n");
  expect_clean_failure("sample -t t.png --op fetch -q half.csv -o bad.csv", "bad.csv", {"half.csv:3", "i", "1.5"});
}

// --texture-layers A,B,C: an array texture. A query's layer column picks the layer, rounded to the
// nearest with a tie to the even one and clamped to the layers: each layer's rows are what sampling
// that image alone as --texture gives, for samples, gathers and fetches (a fetch outside the layers
// answers 0); every cached engine gives the model's bytes. Layers of other sizes, an array on the
// on-chip unit, a list with --texture: one line, nothing written.
TEST_F(TexsimCli, TextureLayersSampleTheLayerNamed) {
  for (int l = 0; l < 3; ++l)
    write_image(dir / ("l" + std::to_string(l) + ".png"), 7, 5, 4,
                [l](int x, int y, int c) { return (13 + x * 29 + y * 41 + c * 70 + l * 90) % 256; });
  write_image(dir / "small.png", 6, 5, 4, [](int x, int, int) { return x; });
  // Layer coordinates and the layer each reads: 0, 1, 2, 0.5 -> 0, 1.5 -> 2, 2.5 -> 2 (clamped),
  // -3 -> 0, 1.49 -> 1, 0.51 -> 1.
  const std::vector<std::pair<std::string, int>> layers = {{"0", 0},   {"1", 1},    {"2", 2},    {"0.5", 0},    {"1.5", 2},
                                                           {"2.5", 2}, {"-3", 0},   {"1.49", 1}, {"0.51", 1}};
  std::string q = "u,v,layer,lod\n", g = "u,v,layer\n", f = "i,j,layer,level\n";
  std::string single = "u,v,lod\n", single_g = "u,v\n", single_f = "i,j,level\n";
  for (const auto& [a, l] : layers) {
    q += "0.37,0.61," + a + ",0.4\n";
    g += "0.37,0.61," + a + "\n";
  }
  single += "0.37,0.61,0.4\n";
  single_g += "0.37,0.61\n";
  for (int l = -1; l <= 3; ++l) f += "3,2," + std::to_string(l) + ",0\n";
  single_f += "3,2,0\n";
  write_text(dir / "q.csv", q);
  write_text(dir / "g.csv", g);
  write_text(dir / "f.csv", f);
  write_text(dir / "single.csv", single);
  write_text(dir / "single_g.csv", single_g);
  write_text(dir / "single_f.csv", single_f);
  const std::string array = "sample --texture-layers l0.png,l1.png,l2.png --memory cached ";
  ASSERT_EQ(run(array + "-q q.csv -o a.csv").exit_code, 0);
  ASSERT_EQ(run(array + "--op gather --component g -q g.csv -o ag.csv").exit_code, 0);
  const Result fr = run(array + "--op fetch -q f.csv -o af.csv");
  ASSERT_EQ(fr.exit_code, 0) << fr.err;
  EXPECT_NE(fr.out.find("7x5 texture x 3 layers"), std::string::npos) << fr.out;
  std::string h;
  const auto rows = read_csv_rows(dir / "a.csv", h), grows = read_csv_rows(dir / "ag.csv", h),
             frows = read_csv_rows(dir / "af.csv", h);
  ASSERT_EQ(rows.size(), layers.size());
  ASSERT_EQ(grows.size(), layers.size());
  ASSERT_EQ(frows.size(), 5u);
  std::vector<std::vector<int>> alone(3), alone_g(3), alone_f(3);
  for (int l = 0; l < 3; ++l) {
    const std::string t = " -t l" + std::to_string(l) + ".png --memory cached ";
    ASSERT_EQ(run("sample" + t + "-q single.csv -o s.csv").exit_code, 0);
    alone[size_t(l)] = read_csv_rows(dir / "s.csv", h).at(0);
    ASSERT_EQ(run("sample" + t + "--op gather --component g -q single_g.csv -o s.csv").exit_code, 0);
    alone_g[size_t(l)] = read_csv_rows(dir / "s.csv", h).at(0);
    ASSERT_EQ(run("sample" + t + "--op fetch -q single_f.csv -o s.csv").exit_code, 0);
    alone_f[size_t(l)] = read_csv_rows(dir / "s.csv", h).at(0);
  }
  EXPECT_NE(alone[0], alone[1]);
  for (size_t i = 0; i < layers.size(); ++i) {
    EXPECT_EQ(rows[i], alone[size_t(layers[i].second)]) << "layer coordinate " << layers[i].first;
    EXPECT_EQ(grows[i], alone_g[size_t(layers[i].second)]) << "gather, layer coordinate " << layers[i].first;
  }
  EXPECT_EQ(frows[0], (std::vector<int>{0, 0, 0, 0})) << "fetch of layer -1";
  for (int l = 0; l < 3; ++l) EXPECT_EQ(frows[size_t(l + 1)], alone_f[size_t(l)]) << "fetch of layer " << l;
  EXPECT_EQ(frows[4], (std::vector<int>{0, 0, 0, 0})) << "fetch of layer 3";
  for (const char* engine : {"-e rtl", "-e systemc", "-e systemc-model"}) {
    ASSERT_EQ(run(array + "-q q.csv -o e.csv " + engine).exit_code, 0) << engine;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "a.csv")) << engine;
    ASSERT_EQ(run(array + "--op fetch -q f.csv -o e.csv " + engine).exit_code, 0) << engine;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "af.csv")) << engine;
  }
  expect_clean_failure("sample --texture-layers l0.png,small.png --memory cached -q q.csv -o bad.csv", "bad.csv",
                       {"small.png", "6x5", "7x5"});
  expect_clean_failure("sample --texture-layers l0.png,l1.png -q q.csv -o bad.csv", "bad.csv", {"on-chip", "--memory cached"});
  expect_clean_failure("sample --texture-layers l0.png,l1.png -t l2.png --memory cached -q q.csv -o bad.csv", "bad.csv",
                       {"--texture-layers"});
  expect_clean_failure("sample --texture-layers l0.png,,l1.png --memory cached -q q.csv -o bad.csv", "bad.csv",
                       {"empty path"});
}

// --op compare (a shadow lookup): each texel's R, its depth, tested `ref OP R` by --compare-op and
// the tests filtered. At texel centres with the point filter the result is 255 or 0 by the PNG's
// own values and the operator's words; at the corner of four texels the bilinear filter gives the
// fraction that passes; G = B = 0, A = 255. Every engine gives the model's bytes. A header
// without ref, a min/max sampler, an sRGB texture, an unknown operator: one line, nothing written.
TEST_F(TexsimCli, DepthCompareFiltersTheTests) {
  auto depth = [](int x, int y) { return (x * 37 + y * 23) % 256; };
  write_image(dir / "d.png", 8, 8, 4, [&](int x, int y, int c) { return c == 0 ? depth(x, y) : 200; });
  std::string q = "u,v,ref,lod\n";
  std::vector<std::pair<int, int>> centres;
  for (int y = 0; y < 8; y += 3)
    for (int x = 0; x < 8; x += 2) {
      centres.push_back({x, y});
      q += std::to_string((x + 0.5) / 8) + "," + std::to_string((y + 0.5) / 8) + ",0.5,0\n";
    }
  q += "0.25,0.25,0.5,0\n";  // the corner of texels (1, 1), (2, 1), (1, 2), (2, 2)
  write_text(dir / "q.csv", q);
  const int ref_code = 128;  // round(0.5 * 255)
  const std::vector<std::pair<const char*, std::function<bool(int, int)>>> ops = {
      {"less", [](int r, int d) { return r < d; }},           {"lequal", [](int r, int d) { return r <= d; }},
      {"greater", [](int r, int d) { return r > d; }},        {"gequal", [](int r, int d) { return r >= d; }},
      {"equal", [](int r, int d) { return r == d; }},         {"not-equal", [](int r, int d) { return r != d; }},
      {"never", [](int, int) { return false; }},              {"always", [](int, int) { return true; }}};
  for (const auto& [name, pass] : ops) {
    const std::string base = std::string("sample -t d.png --depth --op compare --compare-op ") + name + " -q q.csv ";
    ASSERT_EQ(run(base + "-f point -o p.csv").exit_code, 0) << name;
    std::string h;
    const auto rows = read_csv_rows(dir / "p.csv", h);
    ASSERT_EQ(rows.size(), centres.size() + 1);
    for (size_t i = 0; i < centres.size(); ++i) {
      const int d = depth(centres[i].first, centres[i].second);
      EXPECT_EQ(rows[i], (std::vector<int>{pass(ref_code, d) ? 255 : 0, 0, 0, 255})) << name << " depth " << d;
    }
    ASSERT_EQ(run(base + "-f bilinear -o b.csv").exit_code, 0) << name;
    const auto corner = read_csv_rows(dir / "b.csv", h).back();
    int passes = 0;
    for (int y : {1, 2})
      for (int x : {1, 2}) passes += pass(ref_code, depth(x, y));
    EXPECT_EQ(corner, (std::vector<int>{(passes * 255 + 2) / 4, 0, 0, 255})) << name << ": the corner's four tests";
  }
  ASSERT_EQ(run("sample -t d.png --depth --op compare --compare-op greater -q q.csv -o m.csv").exit_code, 0);
  for (const char* engine : {"-e rtl", "-e rtl --memory cached", "-e systemc --memory cached", "-e systemc-model"}) {
    ASSERT_EQ(run(std::string("sample -t d.png --depth --op compare --compare-op greater -q q.csv -o e.csv ") + engine).exit_code, 0) << engine;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "m.csv")) << engine;
  }
  write_text(dir / "plain.csv", "u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t d.png --depth --op compare -q plain.csv -o bad.csv", "bad.csv", {"plain.csv", "ref"});
  expect_clean_failure("sample -t d.png --depth --op compare --reduction max -q q.csv -o bad.csv", "bad.csv", {"q.csv:2", "min/max"});
  expect_clean_failure("sample -t d.png --srgb --depth --op compare -q q.csv -o bad.csv", "bad.csv", {"sRGB", "depth"});
  expect_clean_failure("sample -t d.png --depth --op compare --compare-op lesser -q q.csv -o bad.csv", "bad.csv", {"lesser", "less-or-equal"});
  // A colour texture (not declared a depth texture) takes no compare; a --textures line's `depth` declares one.
  expect_clean_failure("sample -t d.png --op compare -q q.csv -o bad.csv", "bad.csv", {"colour texture", "d.png", "--depth"});
  write_text(dir / "list.txt", "0 d.png clamp depth compare=greater\n");
  const Result listed = run("sample --textures list.txt --op compare -q q.csv -o l.csv");
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_EQ(read_text(dir / "l.csv"), read_text(dir / "m.csv"));
  write_text(dir / "list2.txt", "0 d.png clamp compare=greater\n");
  expect_clean_failure("sample --textures list2.txt --op compare -q q.csv -o bad.csv", "bad.csv", {"list2.txt:1", "colour texture"});
}

// --cube +X,-X,+Y,-Y,+Z,-Z: a cube map sampled by direction (x,y,z headers), seamless. Faces of
// constant R (2x2 texels): the six axis directions give each face's value; the midpoint of the
// +Z/+X edge (a tie: +Z, Vulkan's rule) weighs +Z's edge texel and +X's half and half; the corner
// (1, 1, 1) weighs +Z's corner texel, +Y's, +X's and the skirt's corner, the average of the three:
// round((30 + 97 + 250 + 10) / 4) with 97 = round((10 + 30 + 250) / 3). Faces of other sizes,
// non-square faces, five faces, the on-chip RTL, a u,v header, a texel fetch of layer 6 (no face):
// one line, nothing written. The cached RTL and SystemC sample it as the model does; a fetch of
// face f's texel reads face f.
TEST_F(TexsimCli, CubeMapsSampleAcrossTheSeams) {
  const int r[6] = {10, 80, 30, 160, 250, 200};
  std::string faces;
  for (int f = 0; f < 6; ++f) {
    const std::string name = "f" + std::to_string(f) + ".png";
    write_image(dir / name, 2, 2, 4, [&](int, int, int c) { return c == 0 ? r[f] : c == 3 ? 255 : 0; });
    faces += (f ? "," : "") + name;
  }
  write_image(dir / "big.png", 4, 4, 4, [](int, int, int) { return 9; });
  write_image(dir / "wide.png", 4, 2, 4, [](int, int, int) { return 9; });
  write_text(dir / "q.csv", "x,y,z,lod\n1,0,0,0\n-1,0,0,0\n0,1,0,0\n0,-1,0,0\n0,0,1,0\n0,0,-1,0\n1,0,1,0\n1,1,1,0\n");
  const Result res = run("sample --cube " + faces + " --memory cached -f bilinear -q q.csv -o c.csv");
  ASSERT_EQ(res.exit_code, 0) << res.err;
  EXPECT_NE(res.out.find("2x2 cube map"), std::string::npos) << res.out;
  std::string h;
  const auto rows = read_csv_rows(dir / "c.csv", h);
  ASSERT_EQ(rows.size(), 8u);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(rows[size_t(f)], (std::vector<int>{r[f], 0, 0, 255})) << "face " << f;
  EXPECT_EQ(rows[6][0], (250 + 10) / 2) << "the +Z / +X seam";
  EXPECT_EQ(rows[7][0], 97) << "the +X / +Y / +Z corner";
  const std::string rest = ",f1.png,f2.png,f3.png,f4.png,f5.png --memory cached -q q.csv -o bad.csv";
  expect_clean_failure("sample --cube big.png" + rest, "bad.csv", {"f1.png", "4x4", "2x2"});
  expect_clean_failure("sample --cube wide.png,wide.png,wide.png,wide.png,wide.png,wide.png --memory cached -q q.csv -o bad.csv",
                       "bad.csv", {"wide.png", "square"});
  expect_clean_failure("sample --cube f0.png,f1.png,f2.png,f3.png,f4.png --memory cached -q q.csv -o bad.csv", "bad.csv",
                       {"5 faces"});
  // The cached RTL (tex_cube) and SystemC give the model's samples; the on-chip unit holds no cube.
  for (const char* engine : {"-e rtl --memory cached", "-e systemc --memory cached", "-e systemc-model --memory cached"}) {
    const Result e = run("sample --cube " + faces + " -f bilinear -q q.csv -o e.csv " + engine);
    ASSERT_EQ(e.exit_code, 0) << engine << ": " << e.err;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "c.csv")) << engine;
  }
  expect_clean_failure("sample --cube " + faces + " -e rtl -q q.csv -o bad.csv", "bad.csv", {"cube map", "--memory cached"});
  // A texel fetch names the face as its layer: texel (1, 0) of each face; layer 6 is no face.
  write_text(dir / "fetch.csv", "i,j,layer,level\n1,0,0,0\n1,0,1,0\n1,0,2,0\n1,0,3,0\n1,0,4,0\n1,0,5,0\n");
  for (const char* engine : {"-e model", "-e rtl"}) {
    const Result f = run(std::string("sample --cube ") + faces + " --memory cached --op fetch -q fetch.csv -o f.csv " + engine);
    ASSERT_EQ(f.exit_code, 0) << engine << ": " << f.err;
    const auto fetched = read_csv_rows(dir / "f.csv", h);
    ASSERT_EQ(fetched.size(), 6u) << engine;
    for (int f6 = 0; f6 < 6; ++f6) EXPECT_EQ(fetched[size_t(f6)][0], r[f6]) << engine << " face " << f6;
  }
  write_text(dir / "fetch6.csv", "i,j,layer,level\n1,0,2,0\n1,0,6,0\n");
  expect_clean_failure("sample --cube " + faces + " --memory cached --op fetch -q fetch6.csv -o bad.csv", "bad.csv",
                       {"fetch6.csv", "layer 6", "not a face"});

  write_text(dir / "uv.csv", "u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample --cube " + faces + " --memory cached -q uv.csv -o bad.csv", "bad.csv", {"uv.csv", "cube map"});
}

// --op gather (textureGather) --component C: at the corner between texels (x, y) and (x+1, y+1)
// the four texels the linear filter weighs, component C of (x, y+1), (x+1, y+1), (x+1, y), (x, y)
// as R, G, B, A, read from the PNG's pixels; clamp at the texture's edge; every engine and both RTL
// units give the model's bytes; a header or option that does not fit: one line, nothing written.
TEST_F(TexsimCli, GatherReadsTheLinearFiltersFourTexels) {
  auto value = [](int x, int y, int c) { return (11 + x * 37 + y * 19 + c * 60) % 256; };
  write_image(dir / "t.png", 6, 5, 4, value);
  std::string q = "u,v\n";
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) q += std::to_string((x + 1) / 6.0) + "," + std::to_string((y + 1) / 5.0) + "\n";
  q += "0,0\n";  // the corner of the texture: every tap clamped to texel (0, 0)
  write_text(dir / "q.csv", q);
  for (int c = 0; c < 4; ++c) {
    const std::string out = "g" + std::to_string(c) + ".csv";
    const Result r = run("sample -t t.png -w clamp --op gather --component " + std::string(1, "rgBa"[c]) + " -q q.csv -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(std::string("gathers of ") + "RGBA"[c]), std::string::npos) << r.out;
    std::string h;
    const auto rows = read_csv_rows(dir / out, h);
    ASSERT_EQ(rows.size(), 21u);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x)
        EXPECT_EQ(rows[size_t(y * 5 + x)], (std::vector<int>{value(x, y + 1, c), value(x + 1, y + 1, c), value(x + 1, y, c),
                                                            value(x, y, c)}))
            << "component " << c << " corner " << x << "," << y;
    EXPECT_EQ(rows[20], (std::vector<int>(4, value(0, 0, c)))) << "component " << c;
  }
  for (const char* engine : {"-e rtl", "-e rtl --memory cached", "-e systemc --memory cached", "-e systemc-model"}) {
    const Result e = run(std::string("sample -t t.png -w clamp --op gather --component 2 -q q.csv -o e.csv ") + engine);
    ASSERT_EQ(e.exit_code, 0) << engine << ": " << e.err;
    EXPECT_EQ(read_text(dir / "e.csv"), read_text(dir / "g2.csv")) << engine;
  }
  write_text(dir / "f.csv", "i,j,level\n1,1,0\n");
  expect_clean_failure("sample -t t.png --op gather -q f.csv -o bad.csv", "bad.csv", {"f.csv", "i,j,level", "u,v"});
  expect_clean_failure("sample -t t.png -q q.csv -o bad.csv", "bad.csv", {"q.csv", "u,v", "--op gather"});
  expect_clean_failure("sample -t t.png --op gather --component 4 -q q.csv -o bad.csv", "bad.csv", {"--component", "4"});
  expect_clean_failure("sample -t t.png --component b -q f.csv -o bad.csv", "bad.csv", {"--component", "gather"});
  expect_clean_failure("sample -t t.png --op gather --unnormalized -w clamp -f point -q q.csv -o bad.csv", "bad.csv",
                       {"q.csv:2", "gather", "unnormalized"});
  // A table with an unnormalized sampler: gathers through the other one are fine, through it not.
  write_text(dir / "list.txt", "0 t.png clamp\n1 t.png clamp unnormalized min=nearest mag=nearest mip=none\n");
  write_text(dir / "ts.csv", "tex,smp,u,v\n0,0,0.5,0.5\n1,0,0.25,0.75\n");
  ASSERT_EQ(run("sample --textures list.txt --memory cached --op gather -q ts.csv -o ts_out.csv").exit_code, 0);
  write_text(dir / "ts.csv", "tex,smp,u,v\n0,0,0.5,0.5\n0,1,2,3\n");
  expect_clean_failure("sample --textures list.txt --memory cached --op gather -q ts.csv -o bad.csv", "bad.csv",
                       {"ts.csv:3", "sampler 1", "unnormalized"});
}

TEST_F(TexsimCli, GrayBecomesOpaqueRgbAndRgbGetsOpaqueAlpha) {
  auto gray = [](int x, int y, int) { return 10 + x * 30 + y * 3; };
  auto rgb = [](int x, int y, int c) { return 5 + x * 40 + y * 9 + c * 2; };
  auto rgba = [](int x, int y, int c) { return c == 3 ? 128 : 200 - x * 20 - y - c; };  // alpha 128, not premultiplied
  write_image(dir / "gray.png", 4, 2, 1, gray);
  write_image(dir / "rgb.png", 4, 2, 3, rgb);
  write_image(dir / "rgba.png", 4, 2, 4, rgba);
  write_image(dir / "rgb.tif", 4, 2, 3, rgb);
  // Point sampling at every texel centre, in row order.
  std::string q = "u,v,lod\n";
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) q += std::to_string((x + 0.5) / 4) + "," + std::to_string((y + 0.5) / 2) + ",0\n";
  queries(q);
  for (const char* file : {"gray.png", "rgb.png", "rgba.png", "rgb.tif"}) {
    const Result r = run(std::string("sample -f point -t ") + file + " -q q.csv -o r.csv");
    ASSERT_EQ(r.exit_code, 0) << file << ": " << r.err;
    std::string header;
    const auto rows = read_csv_rows(dir / "r.csv", header);
    ASSERT_EQ(rows.size(), 8u) << file;
    for (int i = 0; i < 8; ++i) {
      const int x = i % 4, y = i / 4;
      std::vector<int> want;
      if (file == std::string("gray.png")) want = {gray(x, y, 0), gray(x, y, 0), gray(x, y, 0), 255};
      else if (file == std::string("rgba.png")) want = {rgba(x, y, 0), rgba(x, y, 1), rgba(x, y, 2), 128};
      else want = {rgb(x, y, 0), rgb(x, y, 1), rgb(x, y, 2), 255};
      EXPECT_EQ(rows[i], want) << file << " texel " << x << "," << y;
    }
  }
}

TEST_F(TexsimCli, ResultCsvHasHeaderAndOneLinePerQueryInOrder) {
  // Point samples of a 16x16 noise pattern at chosen texels, with comments and blank lines between.
  const Image tex = make_pattern("noise", 16, 16);
  std::string q = "# leading comment\n\nu,v,lod\n";
  std::vector<std::pair<int, int>> texels;
  for (int i = 0; i < 40; ++i) {
    const int x = (i * 7) % 16, y = (i * 11 + 3) % 16;
    texels.push_back({x, y});
    q += std::to_string((x + 0.5) / 16) + ", " + std::to_string((y + 0.5) / 16) + " ,0\n";
    if (i % 10 == 0) q += "# comment line " + std::to_string(i) + "\n   \n";
  }
  queries(q);
  const Result r = run("sample -f point -t noise:16x16 -q q.csv -o r.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::string header;
  const auto rows = read_csv_rows(dir / "r.csv", header);
  EXPECT_EQ(header, "r,g,b,a");
  ASSERT_EQ(rows.size(), texels.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const Texel& t = tex.at(texels[i].first, texels[i].second);
    EXPECT_EQ(rows[i], (std::vector<int>{t[0], t[1], t[2], t[3]})) << "query " << i;
  }
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find("partial"), std::string::npos);
}

TEST_F(TexsimCli, DerivativeHeaderGivesTheSameAsExplicitLod) {
  // 64x64 texture: du/dx = 2/64 is 2 texels per pixel -> lambda = 1; 4/64 and 3/64 -> lambda = 2.
  queries("u,v,dudx,dvdx,dudy,dvdy\n0.3,0.6,0.03125,0,0,0.03125\n0.71,0.2,0,0.0625,0.046875,0\n0.5,0.5,0,0,0,0\n");
  Result r = run("sample -t noise:64x64 -q q.csv -o d.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  queries("u,v,lod\n0.3,0.6,1\n0.71,0.2,2\n0.5,0.5,-128\n");
  r = run("sample -t noise:64x64 -q q.csv -o l.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir / "d.csv"), read_text(dir / "l.csv"));
  std::string header;
  EXPECT_EQ(read_csv_rows(dir / "d.csv", header).size(), 3u);
}

TEST_F(TexsimCli, MipDumpLevelsWritesEveryLevel) {
  const Result r = run("mip -t noise:64x16 --dump-levels lv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 16));
  const int sizes[7][2] = {{64, 16}, {32, 8}, {16, 4}, {8, 2}, {4, 1}, {2, 1}, {1, 1}};
  for (int k = 0; k < 7; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "level%02d.png", k);
    int w = 0, h = 0;
    const auto px = read_image(dir / "lv" / name, w, h);
    ASSERT_FALSE(px.empty()) << name;
    EXPECT_EQ(w, sizes[k][0]) << name;
    EXPECT_EQ(h, sizes[k][1]) << name;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(px[(size_t(y) * w + x) * 4 + c], pyr.levels[k].at(x, y)[c]) << name << " " << x << "," << y;
  }
  EXPECT_FALSE(fs::exists(dir / "lv" / "level07.png"));
}

TEST_F(TexsimCli, MipLayoutHoldsRgbPlanesInQuadrants) {
  const Result r = run("mip -t testcard:16x16 --layout lay.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w = 0, h = 0;
  const auto px = read_image(dir / "lay.png", w, h);
  ASSERT_EQ(w, 32);
  ASSERT_EQ(h, 32);
  const Pyramid pyr = build_pyramid(make_pattern("testcard", 16, 16));
  auto at = [&](int x, int y) {
    const uint8_t* p = &px[(size_t(y) * w + x) * 4];
    return std::vector<int>{p[0], p[1], p[2], p[3]};
  };
  // Level 0: R upper right, G lower left, B lower right; level 1 the same inside the upper-left quadrant.
  for (int k = 0; k < 2; ++k) {
    const Image& lvl = pyr.levels[k];
    const int n = lvl.width;
    for (auto [x, y] : {std::pair{0, 0}, std::pair{3, 5}, std::pair{n - 1, n - 1}, std::pair{n / 2, 1}}) {
      const Texel& t = lvl.at(x, y);
      EXPECT_EQ(at(n + x, y), (std::vector<int>{t[0], 0, 0, 255})) << "R level " << k;
      EXPECT_EQ(at(x, n + y), (std::vector<int>{0, t[1], 0, 255})) << "G level " << k;
      EXPECT_EQ(at(n + x, n + y), (std::vector<int>{0, 0, t[2], 255})) << "B level " << k;
    }
  }
  // The 1x1 level sits at (1, 0), (0, 1), (1, 1); (0, 0) stays empty.
  const Texel& last = pyr.levels[4].at(0, 0);
  EXPECT_EQ(at(1, 0), (std::vector<int>{last[0], 0, 0, 255}));
  EXPECT_EQ(at(1, 1), (std::vector<int>{0, 0, last[2], 255}));
  EXPECT_EQ(at(0, 0), (std::vector<int>{0, 0, 0, 255}));
}

// --filter anisotropic: --stats counts the samples by probe count (every engine), and the RTL takes
// one clock per probe. Footprints of 1, 4 and 16 texels by 1 on a 64x64 texture: N = 1, 4, 16 by
// the definition (ceil(Pmax / Pmin)), 1 + 2*4 + 2*16 = 41 probes.
TEST_F(TexsimCli, AnisotropicStatsCountTheProbes) {
  write_text(dir / "q.csv", "u,v,dudx,dvdx,dudy,dvdy\n"
                            "0.5,0.5,0.03125,0,0,0.03125\n"      // 2 x 2 texels: N = 1
                            "0.25,0.5,0.0625,0,0,0.015625\n"     // 4 x 1 along u: N = 4
                            "0.5,0.25,0,0.015625,0,0.0625\n"     // 1 x 4, the long axis along v: N = 4
                            "0.75,0.5,0.25,0,0,0.015625\n"       // 16 x 1: N = 16
                            "0.5,0.75,0.176777,0.176777,-0.0110485,0.0110485\n");  // 16 x 1 diagonal: N = 16
  std::vector<uint64_t> expected(16, 0);
  expected[0] = 1;
  expected[3] = 2;
  expected[15] = 2;
  for (const char* engine : {"model", "rtl"}) {
    const Result r = run(std::string("sample -t noise:64x64 -q q.csv -o r.csv --filter anisotropic --stats s.json -e ") + engine);
    ASSERT_EQ(r.exit_code, 0) << engine << ": " << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir / "s.json"));
    EXPECT_EQ(stats.at("probes_per_sample").get<std::vector<uint64_t>>(), expected) << engine << ": " << stats.dump();
    EXPECT_EQ(stats.at("probes").get<uint64_t>(), 41u) << engine;
    EXPECT_DOUBLE_EQ(stats.at("mean_probes_per_sample").get<double>(), 41.0 / 5.0) << engine;
    EXPECT_NE(r.out.find("probes: 41 = 8.200 per sample (N:samples 1:1 4:2 16:2)"), std::string::npos) << r.out;
    if (std::string(engine) == "rtl") {
      EXPECT_EQ(stats.at("cycles").get<uint64_t>(), 41 + stats.at("latency_cycles").get<uint64_t>()) << stats.dump();
    }
  }
  // Other filters write no probe counts.
  const Result t = run("sample -t noise:64x64 -q q.csv -o r.csv --stats s.json");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_FALSE(nlohmann::json::parse(read_text(dir / "s.json")).contains("probes_per_sample"));
}

// A new user's first cycle-accurate run measures the design: ideal timing, backdoor load, one
// sample per clock once the pipeline has filled; the summary line says which timing ran.
TEST_F(TexsimCli, DefaultsMeasureTheDesign) {
  write_text(dir / "q.csv", "u,v,lod\n0.5,0.5,0\n0.25,0.75,2.5\n0.1,0.9,1.25\n");
  for (const char* engine : {"rtl", "systemc"}) {
    const Result r = run(std::string("sample -q q.csv -o r.csv --stats s.json --engine ") + engine);
    ASSERT_EQ(r.exit_code, 0) << engine << ": " << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir / "s.json"));
    EXPECT_GE(stats.at("samples_per_clock").get<double>(), 0.99) << engine << ": " << stats.dump();
    EXPECT_EQ(stats.at("stalls"), "none") << engine;
    EXPECT_EQ(stats.at("load"), "backdoor") << engine;
    EXPECT_EQ(stats.at("load_cycles"), 0) << engine;
    EXPECT_EQ(stats.at("output_stall_cycles"), 0) << engine;
    EXPECT_EQ(stats.at("cycles").get<uint64_t>(), 3 + stats.at("latency_cycles").get<uint64_t>()) << engine;
    EXPECT_NE(r.out.find("stalls none"), std::string::npos) << r.out;
  }
  // Random stalls are asked for, and they show.
  const Result r = run("sample -q q.csv -o r.csv --stats s.json --engine rtl --stalls heavy --load port");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = nlohmann::json::parse(read_text(dir / "s.json"));
  EXPECT_EQ(stats.at("stalls"), "heavy");
  EXPECT_GT(stats.at("load_cycles").get<uint64_t>(), 512u * 512u) << "a 512x512 pyramid through the write port";
  EXPECT_NE(r.out.find("stalls heavy"), std::string::npos) << r.out;
}

// --memory-image: the header of docs/memory.md, then the image the cached RTL reads, byte for byte
// the model's (checked against hand-computed sizes and a texel read back).
TEST_F(TexsimCli, MipMemoryImageIsTheModelsImage) {
  const Result r = run("mip -t noise:64x16 --memory-image mem.bin --block 8x2 --block-order morton --mem-base 2048");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir / "mem.bin", std::ios::binary);
  const std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Pyramid pyr = build_pyramid(make_pattern("noise", 64, 16));
  LayoutParams p;
  p.block_w = 8;
  p.block_h = 2;
  p.order = BlockOrder::Morton;
  p.base = 2048;
  const MemoryLayout layout({64, 16}, 8, p);
  EXPECT_EQ(file, memory_image_file(pyr, layout));
  // 7 levels: 8x8 + 4x4 + 2x2 + 1x1 + 1x1 + 1x1 + 1x1 blocks of 64 bytes after a 72 + 7*8 byte header.
  ASSERT_EQ(file.size(), 128u + (64u + 16u + 4u + 4u) * 64u);
  // Texel (9, 3) of level 0: block (1, 1), Morton index 3, at 2048 + 3*64, texel (1, 1) of it.
  const size_t at = 128 + 3 * 64 + (1 * 8 + 1) * 4;
  EXPECT_EQ(file[at], pyr.levels[0].at(9, 3)[0]);
  EXPECT_EQ(file[at + 3], pyr.levels[0].at(9, 3)[3]);
  EXPECT_NE(run("mip --memory-image m2.bin --mem-base 100").exit_code, 0);  // not a multiple of 64
  EXPECT_FALSE(std::filesystem::exists(dir / "m2.bin"));
}

// Sampler state on the command line (docs/numerics.md stages 1 and 3): a clamp-to-border tap takes
// the border colour (a name or R,G,B,A), mirror clamp mirrors once, the magnification filter
// applies at lambda <= 0 (in every engine, both RTL units included); GL and Vulkan names are
// accepted; bad values fail before any work, with one line naming the option and the value.
TEST_F(TexsimCli, SamplerStateOptions) {
  // 4x4: texel (x, y) = (x * 60, y * 60, 7, 255).
  write_image(dir / "ramp.png", 4, 4, 4, [](int x, int y, int c) { return c == 0 ? x * 60 : c == 1 ? y * 60 : c == 2 ? 7 : 255; });
  // Point samples of texel column -1 (outside), 0 and 5 (outside); a bilinear sample half a texel
  // left of the edge; one at lambda 0 between texels 0 and 1.
  queries("u,v,lod\n-0.125,0.375,0\n0.125,0.375,0\n1.375,0.375,0\n0,0.375,0\n0.25,0.375,0\n");
  auto rows = [&](const std::string& options) {
    fs::remove(dir / "r.csv");  // (a failed run must not leave the last one's rows to read)
    const Result r = run("sample -t ramp.png -q q.csv -o r.csv " + options);
    EXPECT_EQ(r.exit_code, 0) << options << ": " << r.err;
    std::string header;
    std::vector<std::vector<int>> out = read_csv_rows(dir / "r.csv", header);
    if (out.size() < 5) out.assign(5, std::vector<int>(4, -1));  // (failed above: rows that match nothing)
    return out;
  };
  // Point, border (opaque white by its Vulkan name): texel -1 and 5 are the border colour.
  auto p = rows("--filter point --wrap VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER --border-color VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE");
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0], (std::vector<int>{255, 255, 255, 255}));
  EXPECT_EQ(p[1], (std::vector<int>{0, 60, 7, 255}));
  EXPECT_EQ(p[2], (std::vector<int>{255, 255, 255, 255}));
  // Bilinear at u = 0, border colour (1, 0.5, 0, 0.2) = 255, 128, 0, 51: half the border, half texel 0.
  p = rows("--filter bilinear --wrap-u border --wrap-v clamp --border-color 1,0.50196,0,0.2");
  EXPECT_EQ(p[3], (std::vector<int>{128, 94, 4, 153}));  // (255+0)/2 rounded up, (128+60)/2, (0+7)/2 up, (51+255)/2
  // Mirror clamp (GL name): -1 -> 0, 5 -> 3.
  p = rows("--filter point --wrap GL_MIRROR_CLAMP_TO_EDGE");
  EXPECT_EQ(p[0][0], 0);
  EXPECT_EQ(p[2][0], 180);
  // At lambda 0, u between texels 0 and 1: the magnification filter decides.
  EXPECT_EQ(rows("--filter trilinear --mag-filter nearest")[4][0], 60);     // texel 1 (u = 0.25 is its left edge)
  EXPECT_EQ(rows("--filter trilinear --mag-filter GL_LINEAR")[4][0], 30);   // between texel 0 and 1
  EXPECT_EQ(rows("--min-filter nearest_mipmap_linear --mag-filter linear")[4][0], 30);
  EXPECT_EQ(rows("--min-filter GL_NEAREST_MIPMAP_LINEAR --mag-filter GL_LINEAR")[4][0], 30);
  // The RTL has the magnification filter (--verify: bit for bit the model's).
  EXPECT_EQ(rows("--filter trilinear --mag-filter nearest -e rtl --verify")[4][0], 60);
  EXPECT_EQ(rows("--filter point --mag-filter linear -e rtl --memory cached --cache-kib 4 --verify")[4][0], 30);
  // Bad values: one line naming the option and the value, nothing written.
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --wrap clamp_to_nowhere", "bad.csv", {"clamp_to_nowhere", "border"});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --mag-filter cubic", "bad.csv", {"--mag-filter", "cubic"});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --min-filter trilinear", "bad.csv", {"--min-filter", "trilinear"});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --mipmap-mode cubic", "bad.csv", {"--mipmap-mode", "cubic"});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --border-color 1,0,0", "bad.csv", {"--border-color", "3 values"});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --border-color 1,0,2,1", "bad.csv", {"--border-color", "\"2\""});
  expect_clean_failure("sample -t ramp.png -q q.csv -o bad.csv --border-color pink", "bad.csv", {"--border-color", "pink"});
  // Both RTL units have every address mode and the border colour (--verify: the model's bits).
  EXPECT_EQ(rows("--filter bilinear --wrap-u border --wrap-v clamp --border-color 1,0.50196,0,0.2 -e rtl --verify")[3],
            (std::vector<int>{128, 94, 4, 153}));
  EXPECT_EQ(rows("--filter point --wrap mirror-clamp -e systemc --verify")[2][0], 180);
  EXPECT_EQ(rows("--filter point --wrap mirror-clamp -e rtl --memory cached --cache-kib 4 --verify")[2][0], 180);
  EXPECT_EQ(rows("--filter bilinear --wrap-u border --wrap-v clamp --border-color 1,0.50196,0,0.2 -e rtl "
                 "--memory cached --cache-kib 4 --verify")[3],
            (std::vector<int>{128, 94, 4, 153}));
}

// A trace's `bias` column is each request's own LOD bias (GLSL texture(s, uv, bias)), added to the
// sampler's: a trace whose every request has bias 0.75 samples as the same trace without it
// through --lod-bias 0.75, on the model and the RTL; a bias outside Q8.8 is refused with its line.
TEST_F(TexsimCli, TraceBiasColumnAddsToTheSamplersBias) {
  std::string with = "u,v,dudx,dvdx,dudy,dvdy,bias\n", without = "u,v,dudx,dvdx,dudy,dvdy\n";
  for (int i = 0; i < 300; ++i) {
    const std::string row = std::to_string((i % 17) / 17.0) + "," + std::to_string((i / 17) / 18.0) + "," +
                            std::to_string(0.02 + (i % 7) * 0.015) + ",0,0," + std::to_string(0.03 + (i % 5) * 0.02);
    with += row + "," + (i % 2 ? "0.75" : "-0.5") + "\n";
    without += row + "\n";
  }
  for (const char* e : {"model", "rtl"}) {
    // Even requests carry -0.5, odd ones 0.75: each half against its own --lod-bias run.
    queries(with);
    ASSERT_EQ(run(std::string("sample -t noise:64x64 -q q.csv -o b.csv -e ") + e).exit_code, 0);
    queries(without);
    ASSERT_EQ(run(std::string("sample -t noise:64x64 -q q.csv -o p.csv --lod-bias 0.75 -e ") + e).exit_code, 0);
    ASSERT_EQ(run(std::string("sample -t noise:64x64 -q q.csv -o m.csv --lod-bias -0.5 -e ") + e).exit_code, 0);
    ASSERT_EQ(run(std::string("sample -t noise:64x64 -q q.csv -o z.csv -e ") + e).exit_code, 0);
    std::string h1, h2, h3, h4;
    const auto b = read_csv_rows(dir / "b.csv", h1), p = read_csv_rows(dir / "p.csv", h2),
               m = read_csv_rows(dir / "m.csv", h3), z = read_csv_rows(dir / "z.csv", h4);
    ASSERT_EQ(b.size(), 300u);
    size_t moved = 0;
    for (size_t i = 0; i < b.size(); ++i) {
      EXPECT_EQ(b[i], i % 2 ? p[i] : m[i]) << e << " request " << i;
      moved += b[i] != z[i];
    }
    EXPECT_GT(moved, 100u) << e << ": the bias moved too few samples to tell";
  }
  queries("u,v,dudx,dvdx,dudy,dvdy,bias\n0.5,0.5,0.01,0,0,0.01,200\n");
  expect_clean_failure("sample -t noise:64x64 -q q.csv -o r.csv", "r.csv", {"q.csv:2", "bias"});
}

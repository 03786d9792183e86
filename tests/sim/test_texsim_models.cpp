// texsim render --model / --scene-file (real frames, docs/scenes.md) and the replay of a frame's
// trace through texsim sample --textures.
#include <nlohmann/json.hpp>

#include "cli_fixture.h"

namespace {

const std::string kModels = "/usr/share/assimp/models/";
const std::string kTruck = kModels + "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf";
const std::string kBox = kModels + "glTF2/BoxTextured-glTF/BoxTextured.gltf";
const std::string kDuck = kModels + "Collada/duck.dae";
const std::string kSpider = kModels + "OBJ/spider.obj";

nlohmann::json read_json(const fs::path& p) { return nlohmann::json::parse(read_text(p)); }

class TexsimModels : public TexsimCli {
 protected:
  // An OBJ quad (two triangles facing +z) with its own texture, in `name`.obj / .mtl / .png.
  void textured_quad(const std::string& name, int texel) {
    write_image(dir / (name + ".png"), 4, 4, 3, [&](int x, int y, int c) { return (texel * 37 + x * 11 + y * 5 + c) & 255; });
    write_text(dir / (name + ".mtl"), "newmtl m\nmap_Kd " + name + ".png\n");
    write_text(dir / (name + ".obj"), "mtllib " + name +
                                          ".mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                          "usemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  }
};

}  // namespace

// Every test model renders with the golden model in cached mode, with the frame figures in the
// summary and in --stats; the spider has more than 4 textures in one frame (the descriptor table).
TEST_F(TexsimModels, TestModelsRenderWithTheirTextures) {
  struct Case {
    std::string file;
    int min_textures;
  } cases[] = {{kTruck, 1}, {kBox, 1}, {kDuck, 1}, {kSpider, 4}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    // Frame 5 of 8 of the orbit sees all of the spider's textures at this size.
    const Result r = run("render --model " + c.file + " --memory cached --width 160 --height 120 --frames 8 --frame 5 "
                         "--out f.png --stats s.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json s = read_json(dir / "s.json");
    EXPECT_GE(s.at("textures_used").get<int>(), c.min_textures);
    EXPECT_GT(s.at("quads").get<uint64_t>(), 100u);
    EXPECT_EQ(s.at("samples").get<uint64_t>(), 4 * s.at("quads").get<uint64_t>());
    EXPECT_GT(s.at("helper_samples").get<uint64_t>(), 0u);
    EXPECT_GT(s.at("texture_bytes_touched").get<uint64_t>(), 0u);
    EXPECT_LE(s.at("texture_bytes_touched").get<uint64_t>(), s.at("texture_bytes_resident").get<uint64_t>());
    EXPECT_GT(s.at("hit_rate_even_levels").get<double>(), 0.5);
    EXPECT_NE(r.out.find("texsim render: " + c.file), std::string::npos) << r.out;
    int w = 0, h = 0;
    EXPECT_FALSE(read_image(dir / "f.png", w, h).empty());
    EXPECT_EQ(w, 160);
  }
}

// The frame's trace and textures, replayed through texsim sample, give the same figures, and the
// visible lanes' results are the rendered picture's pixels.
TEST_F(TexsimModels, TraceQueriesReplayTheFrame) {
  Result r = run("render --model " + kSpider + " --memory cached --width 160 --height 120 --frames 8 --frame 4 "
                 "--out f.png --stats render.json --trace-queries trace/q.csv");
  ASSERT_NE(r.exit_code, 0);  // the directory does not exist
  fs::create_directories(dir / "trace");
  r = run("render --model " + kSpider + " --memory cached --width 160 --height 120 --frames 8 --frame 4 "
          "--out f.png --stats render.json --trace-queries trace/q.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "trace/q.textures.txt"));
  EXPECT_TRUE(fs::exists(dir / "trace/q.tex03.png"));
  r = run("sample --textures trace/q.textures.txt --queries trace/q.csv --memory cached --out r.csv --stats sample.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json a = read_json(dir / "render.json"), b = read_json(dir / "sample.json");
  for (const char* key : {"samples", "quads", "helper_samples", "textures_used", "texture_bytes_resident",
                          "texture_bytes_touched", "cache_misses", "hit_rate_even_levels", "hit_rate_odd_levels",
                          "bytes_per_sample"})
    EXPECT_EQ(a.at(key), b.at(key)) << key;

  // Pixels: each visible lane of the trace (x, y, helper) with its result (r, g, b, a).
  std::string qh, rh;
  std::istringstream trace(read_text(dir / "trace/q.csv"));
  std::string line;
  std::getline(trace, qh);
  EXPECT_EQ(qh, "tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper");
  const auto results = read_csv_rows(dir / "r.csv", rh);
  int w = 0, h = 0;
  const std::vector<uint8_t> px = read_image(dir / "f.png", w, h);
  ASSERT_EQ(w, 160);
  size_t i = 0, visible = 0;
  while (std::getline(trace, line)) {
    if (line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    ASSERT_EQ(f.size(), 11u);
    ASSERT_LT(i, results.size());
    if (f[10] == "0") {
      const int x = std::stoi(f[8]), y = std::stoi(f[9]);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(int(px[(size_t(y) * w + x) * 4 + c]), results[i][size_t(c)]) << x << "," << y;
      ++visible;
    }
    ++i;
  }
  EXPECT_EQ(i, results.size());
  EXPECT_EQ(visible, a.at("samples").get<size_t>() - a.at("helper_samples").get<size_t>());
}

// glTF 2's base colour is sRGB: decoded before the filter (the cached RTL's tables give the model's
// picture bit for bit), the trace's texture list says so, and the replay samples it as sRGB
// (linear unorm16 results). --format applies to a model's textures too.
TEST_F(TexsimModels, Gltf2BaseColourIsSrgb) {
  fs::create_directories(dir / "trace");
  const std::string common = "render --model " + kBox + " --memory cached --width 96 --height 72 --frames 8 --frame 1 ";
  Result r = run(common + "--out m.png --stats m.json --trace-queries trace/q.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The list carries the texture's glTF sampler: mirrored repeat / clamp, NEAREST_MIPMAP_LINEAR,
  // LINEAR magnification; the summary names its filter.
  EXPECT_NE(read_text(dir / "trace/q.textures.txt").find(" mirror clamp srgb min=nearest mag=linear mip=linear\n"),
            std::string::npos)
      << read_text(dir / "trace/q.textures.txt");
  EXPECT_NE(r.out.find("nearest_mipmap_linear"), std::string::npos) << r.out;
  const Result cli = run(common + "--filter trilinear --out t.png");
  EXPECT_NE(cli.out.find(", trilinear,"), std::string::npos) << cli.out;
  EXPECT_NE(read_text(dir / "t.png"), read_text(dir / "m.png")) << "--filter replaces the file's filters";
  r = run(common + "-e rtl --out r.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir / "m.png"), read_text(dir / "r.png")) << "the RTL's sRGB tables against the model";
  r = run("sample --textures trace/q.textures.txt --queries trace/q.csv --memory cached --out s.csv --stats s.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir / "s.csv").substr(0, 16), "r16,g16,b16,a16\n");
  EXPECT_EQ(read_json(dir / "m.json").at("texture_bytes_touched"), read_json(dir / "s.json").at("texture_bytes_touched"));
  r = run(common + "-e rtl --format bc1 --out b.png --stats b.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(read_json(dir / "b.json").at("texture_bytes_resident").get<uint64_t>(),
            read_json(dir / "m.json").at("texture_bytes_resident").get<uint64_t>() / 4);
  r = run(common + "--format bc4 --out x.png");  // a base colour is sRGB, BC4 has no sRGB
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("CesiumLogoFlat.png"), std::string::npos) << r.err;
}

// Several models placed by a scene file share the descriptor table: the same file twice is one
// texture; the frame samples each.
TEST_F(TexsimModels, SceneFilePlacesSeveralModels) {
  textured_quad("a", 1);
  textured_quad("b", 2);
  write_text(dir / "scene.json", R"({"models": [
    {"file": "a.obj", "translation": [-1.5, 0, 0]},
    {"file": "b.obj", "translation": [0.5, 0, 0], "rotation": [0, 0, 10], "scale": 1.2},
    {"file": "a.obj", "translation": [-0.5, -1.5, 0]}]})");
  const Result r = run("render --scene-file scene.json --memory cached --camera 0,0,6,0,0,0,40 --width 96 "
                       "--height 64 --out f.png --stats s.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = read_json(dir / "s.json");
  EXPECT_EQ(s.at("textures").get<int>(), 2);
  EXPECT_EQ(s.at("textures_used").get<int>(), 2);
  EXPECT_NE(r.out.find("3 meshes, 2 textures"), std::string::npos) << r.out;
}

// More textures than the descriptor table holds: an error with both numbers, before any work.
TEST_F(TexsimModels, TooManyTexturesForTheTable) {
  std::string models;
  for (int i = 0; i < 17; ++i) {
    textured_quad("q" + std::to_string(i), i);
    models += std::string(i ? "," : "") + R"({"file": "q)" + std::to_string(i) + R"(.obj", "translation": [)" +
              std::to_string(i) + ", 0, 0]}";
  }
  write_text(dir / "scene.json", R"({"models": [)" + models + "]}");
  expect_clean_failure("render --scene-file scene.json --memory cached --out f.png", "f.png",
                       {"17 textures", "descriptor table holds 16"});
}

TEST_F(TexsimModels, BadInputsFailCleanly) {
  textured_quad("a", 1);
  textured_quad("b", 2);
  write_text(dir / "two.json", R"({"models": [{"file": "a.obj"}, {"file": "b.obj", "translation": [2, 0, 0]}]})");
  // Several textures need the cached unit's descriptor table: chosen by default (and said so),
  // refused when --memory onchip is asked for.
  const Result chosen = run("render --scene-file two.json --out f.png");
  EXPECT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_NE(chosen.out.find("cached memory (chosen: the on-chip unit holds one texture)"), std::string::npos)
      << chosen.out;
  fs::remove(dir / "f.png");
  expect_clean_failure("render --scene-file two.json --memory onchip --out f.png", "f.png",
                       {"2 textures", "--memory cached"});
  // Through the SystemC engines' descriptor tables: the model's picture.
  ASSERT_EQ(run("render --scene-file two.json --memory cached --out m.png").exit_code, 0);
  for (const char* e : {"systemc", "systemc-model"}) {
    const Result sc = run(std::string("render --scene-file two.json --memory cached --verify --out s.png --engine ") + e);
    ASSERT_EQ(sc.exit_code, 0) << sc.err;
    EXPECT_EQ(read_text(dir / "s.png"), read_text(dir / "m.png")) << e;
    fs::remove(dir / "s.png");
  }
  // One texture no compiled on-chip unit holds (BoxTextured's 211x211 sRGB logo: 16-bit channels
  // on chip): the RTL engine takes the cached unit and says why; --memory onchip names the way out.
  const Result box = run("render --model " + kBox + " --engine rtl --verify --width 64 --height 48 --out f.png");
  EXPECT_EQ(box.exit_code, 0) << box.err;
  EXPECT_NE(box.out.find("cached memory (chosen: no compiled on-chip unit holds the texture)"), std::string::npos)
      << box.out;
  fs::remove(dir / "f.png");
  expect_clean_failure("render --model " + kBox + " --engine rtl --memory onchip --width 64 --height 48 --out f.png",
                       "f.png", {"211x211", "--memory cached"});
  expect_clean_failure("render --model missing.obj --out f.png", "f.png", {"missing.obj"});
  write_text(dir / "garbage.obj", "this is not a model\x01\x02\n");
  expect_clean_failure("render --model garbage.obj --out f.png", "f.png", {"garbage.obj"});
  expect_clean_failure("render --model a.obj --texture checker --out f.png", "f.png", {"--texture"});
  expect_clean_failure("render --model a.obj --scene plane --out f.png", "f.png", {"--scene"});
  expect_clean_failure("render --model a.obj --camera 1,2,3 --out f.png", "f.png", {"--camera", "7 values"});
  expect_clean_failure("render --scene plane --camera 0,0,1,0,0,0,45 --out f.png", "f.png", {"--camera", "--model"});
  write_text(dir / "path.json", R"({"keyframes": [{"eye": [0, 0, 1], "target": [0, 0, "x"]}]})");
  expect_clean_failure("render --model a.obj --camera-path path.json --out f.png", "f.png",
                       {"path.json", "keyframe 0", "target"});
  // Texture lists of sample.
  queries("tex,u,v,lod\n1,0.5,0.5,0\n");
  write_text(dir / "list.txt", "0 a.png\n2 b.png\n");
  expect_clean_failure("sample --textures list.txt --queries q.csv --memory cached --out r.csv", "r.csv",
                       {"list.txt:2", "expected 1"});
  write_text(dir / "list.txt", "0 a.png sideways\n");
  expect_clean_failure("sample --textures list.txt --queries q.csv --memory cached --out r.csv", "r.csv",
                       {"list.txt:1", "sideways"});
  write_text(dir / "list.txt", "0 a.png\n");
  expect_clean_failure("sample --textures list.txt --queries q.csv --memory cached --out r.csv", "r.csv",
                       {"texture 1", "holds 1"});
  queries("tex,u,v,lod\n16,0.5,0.5,0\n");
  expect_clean_failure("sample --textures list.txt --queries q.csv --memory cached --out r.csv", "r.csv",
                       {"q.csv:2", "texture", "16"});
}

// The same model through the on-chip and the cached golden model: the pictures are the same
// (only the memory differs), and the cached run adds the memory figures.
TEST_F(TexsimModels, OnChipAndCachedGiveTheSamePicture) {
  ASSERT_EQ(run("render --model " + kDuck + " --width 96 --height 72 --out a.png --stats a.json").exit_code, 0);
  ASSERT_EQ(run("render --model " + kDuck + " --width 96 --height 72 --memory cached --out b.png --stats b.json").exit_code,
            0);
  int w, h;
  EXPECT_EQ(read_image(dir / "a.png", w, h), read_image(dir / "b.png", w, h));
  EXPECT_FALSE(read_json(dir / "a.json").contains("texture_bytes_touched"));
  EXPECT_TRUE(read_json(dir / "b.json").contains("texture_bytes_touched"));
}

// An animation along a camera path: one picture per frame, per-frame figures in --stats, and the
// frames differ (the camera moves).
TEST_F(TexsimModels, CameraPathRendersEveryFrame) {
  textured_quad("a", 3);
  write_text(dir / "path.json", R"({"keyframes": [{"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "fovy": 40},
                                                 {"eye": [1.5, 0.8, 2], "target": [0.5, 0.5, 0], "fovy": 30}]})");
  const Result r = run("render --model a.obj --camera-path path.json --frames 3 --width 64 --height 48 "
                       "--out f.png --stats s.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int w, h;
  const auto first = read_image(dir / "f_000.png", w, h), last = read_image(dir / "f_002.png", w, h);
  EXPECT_FALSE(first.empty());
  EXPECT_TRUE(fs::exists(dir / "f_001.png"));
  EXPECT_NE(first, last);
  const nlohmann::json s = read_json(dir / "s.json");
  ASSERT_EQ(s.at("frames").size(), 3u);
  uint64_t sum = 0;
  for (const auto& f : s.at("frames")) sum += f.at("samples").get<uint64_t>();
  EXPECT_EQ(sum, s.at("samples").get<uint64_t>());
  EXPECT_NE(r.out.find("frame 2: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("total: "), std::string::npos) << r.out;
}

// A trace's `smp` column names the sampler of each request: texture 0 read through its own
// sampler (repeat) and through list line 1's (clamp to border, red), interleaved, by the model and
// the cached RTL, with the same results. A sampler beyond the list stops the run, nothing written.
TEST_F(TexsimModels, TraceSamplerColumnPicksTheSampler) {
  textured_quad("a", 3);
  write_text(dir / "list.txt", "0 a.png repeat repeat\n1 a.png border border\n");
  queries("tex,smp,u,v,lod\n0,0,-0.4,-0.4,0\n0,1,-0.4,-0.4,0\n0,0,-0.4,-0.4,0\n0,1,0.6,0.6,0\n");
  const std::string common = "sample --textures list.txt --queries q.csv --memory cached --cache-kib 2 --min-filter nearest "
                             "--mag-filter nearest --border-color 1,0,0,1 ";
  for (const char* engine : {"model", "rtl"}) {
    const Result r = run(common + "--engine " + engine + " --out " + engine + ".csv");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string got = read_text(dir / "model.csv");
  EXPECT_EQ(got, read_text(dir / "rtl.csv"));
  // u = v = -0.4 of a 4x4 texture at level 0: texel -1.6 -> -2 (nearest), outside the texture.
  // Repeat reads texel (2, 2); border gives the colour.
  std::vector<std::string> img;  // the header, then one line per request
  std::istringstream in(got);
  for (std::string l; std::getline(in, l);) img.push_back(l);
  ASSERT_EQ(img.size(), 5u) << got;
  const int t22 = (3 * 37 + 2 * 11 + 2 * 5) & 255;  // textured_quad's texel (2, 2), red channel
  EXPECT_EQ(img[1].substr(0, img[1].find(',')), std::to_string(t22)) << got;
  EXPECT_EQ(img[2], "255,0,0,255") << got;
  EXPECT_EQ(img[3], img[1]) << got;
  EXPECT_NE(img[4], "255,0,0,255") << got;  // (0.6, 0.6) is inside: the texel, not the border
  queries("tex,smp,u,v,lod\n0,2,0.5,0.5,0\n");
  expect_clean_failure(common + "--out r.csv", "r.csv", {"sampler 2", "holds 2"});
  queries("tex,smp,u,v,lod\n0,16,0.5,0.5,0\n");
  expect_clean_failure(common + "--out r.csv", "r.csv", {"q.csv:2", "sampler", "16"});
}

// A scene file gives each model's textures a sampler: three quads read through three samplers
// (trilinear repeat; nearest, no mips, clamp; clamp to border, opaque white) in one frame, through
// the cached RTL at full rate, bit for bit the model's (--verify); the samplers change the picture.
// A max reduction on one of them changes it again (the cached RTL: the model's picture). A bad field
// is one line naming it.
TEST_F(TexsimModels, SceneFileSetsASamplerPerModel) {
  textured_quad("a", 1);
  textured_quad("b", 2);
  textured_quad("c", 3);
  const std::string models = R"({"models": [
    {"file": "a.obj", "translation": [-1.6, -0.5, 0], "sampler": {"wrap": "repeat", "min_filter": "linear_mipmap_linear"}},
    {"file": "b.obj", "translation": [-0.5, -0.5, 0],
     "sampler": {"wrap": "clamp", "min_filter": "nearest", "mag_filter": "nearest", "mipmap_mode": "none"}},
    {"file": "c.obj", "translation": [0.6, -0.5, 0], "sampler": {"wrap_u": "border", "wrap_v": "mirror-clamp",
     "border_color": "opaque-white"}}]})";
  write_text(dir / "three.json", models);
  std::string plain = models;
  for (size_t at; (at = plain.find(R"(, "sampler")")) != std::string::npos;) plain.erase(at, plain.find("}}", at) + 1 - at);
  write_text(dir / "plain.json", plain);
  const std::string view = " --camera 0,0,3,0,0,0,45 --width 160 --height 120 ";
  const Result r = run("render --scene-file three.json -e rtl --verify --memory cached --mem-latency 20" + view +
                       "--out three.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 textures"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bit-identical"), std::string::npos) << r.out;
  const size_t spc = r.out.find(" samples/clock");
  ASSERT_NE(spc, std::string::npos) << r.out;
  const double rate = std::stod(r.out.substr(r.out.rfind(' ', spc - 1) + 1));
  EXPECT_GT(rate, 0.97) << r.out;
  std::printf("[ samplers ] three models through three samplers, cached RTL: %.4f samples/clock\n", rate);
  const Result p = run("render --scene-file plain.json" + view + "--out plain.png");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const Result m = run("render --scene-file three.json" + view + "--out model.png");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(read_text(dir / "model.png"), read_text(dir / "three.png"));
  EXPECT_NE(read_text(dir / "plain.png"), read_text(dir / "three.png")) << "the samplers changed nothing";
  write_text(dir / "bad.json", R"({"models": [{"file": "a.obj", "sampler": {"min_filter": "cubic"}}]})");
  expect_clean_failure("render --scene-file bad.json --out f.png", "f.png",
                       {"bad.json", "models[0].sampler.min_filter", "cubic"});
  write_text(dir / "bad.json", R"({"models": [{"file": "a.obj", "sampler": {"wrapS": "clamp"}}]})");
  expect_clean_failure("render --scene-file bad.json --out f.png", "f.png", {"models[0].sampler.wrapS", "unknown"});
  // A reduction per model.
  std::string reduced = models;
  reduced.replace(reduced.find(R"("border_color")"), 0, R"("reduction": "max", )");
  write_text(dir / "max.json", reduced);
  ASSERT_EQ(run("render --scene-file max.json" + view + "--out max.png").exit_code, 0);
  EXPECT_NE(read_text(dir / "max.png"), read_text(dir / "model.png")) << "a max reduction changed nothing";
  ASSERT_EQ(run("render --scene-file max.json -e rtl --memory cached --mem-latency 20" + view + "--out r.png").exit_code, 0);
  EXPECT_EQ(read_text(dir / "r.png"), read_text(dir / "max.png"));
  write_text(dir / "bad.json", R"({"models": [{"file": "a.obj", "sampler": {"reduction": "mean"}}]})");
  expect_clean_failure("render --scene-file bad.json --out f.png", "f.png", {"models[0].sampler.reduction", "mean"});
}

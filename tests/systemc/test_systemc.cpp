// The SystemC/TLM-2.0 texture unit (sim/systemc/) against the golden model: bit-exact texels over
// random requests for both backends, throughput through the socket, and the tag checks (a lost,
// duplicated, reordered or mis-tagged response must be reported). Every run_systemc call forks its
// own simulation process, so one test can run many simulations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "engine.h"
#include "model/error.h"
#include "model/image.h"
#include "systemc/systemc_engine.h"

using namespace tex;
using namespace tex::systemc;

namespace {

struct TextureSpec {
  std::string pattern;
  int width, height;
  PyramidMode mode;
};

std::vector<Filter> all_filters() {
  std::vector<Filter> f;
  for (TexelFilter t : {TexelFilter::Nearest, TexelFilter::Linear})
    for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) f.push_back({t, m});
  return f;
}

// Coordinates mostly around [0, 1) but also far outside (every wrap mode, every level);
// lod over magnification, every level and past the last.
std::vector<Request> random_requests(std::mt19937_64& rng, size_t n, int levels) {
  std::uniform_real_distribution<double> near(-0.25, 1.25), far(-3.0, 3.0);
  std::uniform_int_distribution<int> lod(-3 * 256, (levels + 2) * 256);
  std::vector<Request> r(n);
  for (size_t i = 0; i < n; ++i) {
    const bool wide = rng() % 4 == 0;
    to_coord_fixed(wide ? far(rng) : near(rng), r[i].u);
    to_coord_fixed(wide ? far(rng) : near(rng), r[i].v);
    r[i].lod = lod(rng);
    if (rng() % 8 == 0) r[i].lod = int32_t(256 * (rng() % uint64_t(levels + 1)));  // exactly on a level
    r[i].tag = uint32_t(i);
  }
  return r;
}

SamplerConfig random_config(std::mt19937_64& rng, Filter f, Wrap wu, Wrap wv) {
  SamplerConfig c;
  c.filter = f;
  c.wrap_u = wu;
  c.wrap_v = wv;
  if (rng() % 2) {  // a bias and clamps half of the time
    c.lod_bias = int32_t(rng() % 769) - 384;
    c.min_lod = int32_t(rng() % 512) - 256;
    c.max_lod = c.min_lod + int32_t(rng() % 2048);
  }
  return c;
}

std::string texel_text(const Texel& t) {
  return std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) + "," + std::to_string(t[3]);
}

// Compares with the golden model; names the seed so the case can be replayed.
void expect_bit_exact(const EngineResult& got, const Pyramid& pyr, const SamplerConfig& cfg,
                      const std::vector<Request>& reqs, const std::string& what) {
  Sampler golden(pyr, cfg);  // the reference path of the golden model
  ASSERT_EQ(got.texels.size(), reqs.size()) << what;
  size_t bad = 0;
  for (size_t i = 0; i < reqs.size() && bad < 5; ++i)
    if (const Texel want = golden.sample(reqs[i]); got.texels[i] != want) {
      ++bad;
      ADD_FAILURE() << what << ": request " << i << " (u " << reqs[i].u << ", v " << reqs[i].v << ", lod "
                    << reqs[i].lod << ") gives " << texel_text(got.texels[i]) << ", model gives "
                    << texel_text(want);
    }
}

// Every filter x every wrap pair on `tex`, one simulation each; random timing on odd cases.
void run_filter_wrap_matrix(const TextureSpec& spec, Backend backend, InitiatorStyle style, size_t per_case,
                            uint64_t seed) {
  const Pyramid pyr = build_pyramid(make_pattern(spec.pattern, spec.width, spec.height), spec.mode);
  std::mt19937_64 rng(seed);
  int n = 0;
  for (Filter f : all_filters())
    for (Wrap wu : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror})
      for (Wrap wv : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror}) {
        const SamplerConfig cfg = random_config(rng, f, wu, wv);
        const auto reqs = random_requests(rng, per_case, pyr.last_level() + 1);
        SystemcOptions o;
        o.backend = backend;
        o.initiator = style;
        o.seed = seed + uint64_t(n);
        if (n++ % 2 == 1 && style != InitiatorStyle::Lt) {
          o.gap_prob = 0.1;
          o.stall_prob = 0.1;
        }
        const std::string what = spec.pattern + " " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                 " " + filter_name(f) + " " + wrap_name(wu) + "/" + wrap_name(wv) + " seed " +
                                 std::to_string(o.seed);
        EngineResult r;
        try {
          r = run_systemc(pyr, cfg, reqs, o);
        } catch (const Error& e) {
          FAIL() << what << ": " << e.what();
        }
        expect_bit_exact(r, pyr, cfg, reqs, what);
        EXPECT_EQ(r.stats["samples"].get<uint64_t>(), per_case) << what;
      }
}

Pyramid small_pyramid() { return build_pyramid(make_pattern("testcard", 32, 16), PyramidMode::Exact); }

SystemcOptions rtl_options() {
  SystemcOptions o;
  o.backend = Backend::Rtl;
  return o;
}

// Runs with a fault and returns the error message ("" when none was reported).
std::string error_of(const SystemcOptions& o, size_t n = 200) {
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(7);
  const auto reqs = random_requests(rng, n, pyr.last_level() + 1);
  try {
    run_systemc(pyr, SamplerConfig{}, reqs, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

// ------------------------------------------------------------------ bit-exact: RTL backend (AT)

TEST(SystemcRtl, BitExactEveryFilterAndWrapNonSquare) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  run_filter_wrap_matrix({"testcard", 64, 16, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 300, 101);
}

TEST(SystemcRtl, BitExactEveryFilterAndWrapTallCascade) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  run_filter_wrap_matrix({"noise", 4, 32, PyramidMode::Cascade}, Backend::Rtl, InitiatorStyle::Auto, 300, 202);
}

TEST(SystemcRtl, BitExactEveryFilterAndWrapSquareAndOneTexel) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  run_filter_wrap_matrix({"checker", 16, 16, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 200, 303);
  run_filter_wrap_matrix({"gradient", 1, 8, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 100, 404);
}

TEST(SystemcRtl, BitExactLargestTexture) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  const Pyramid pyr = build_pyramid(make_pattern("testcard", 1024, 512), PyramidMode::Exact);
  std::mt19937_64 rng(505);
  const SamplerConfig cfg;  // trilinear, repeat
  const auto reqs = random_requests(rng, 20000, pyr.last_level() + 1);
  const EngineResult r = run_systemc(pyr, cfg, reqs, rtl_options());
  expect_bit_exact(r, pyr, cfg, reqs, "testcard 1024x512 trilinear");
  // Every texel of every level went through the write port, one per clock, after 5 reset clocks.
  size_t texels = 0;
  for (const Image& img : pyr.levels) texels += size_t(img.width) * size_t(img.height);
  EXPECT_EQ(r.stats["load_cycles"].get<uint64_t>(), texels + 5);
}

// ------------------------------------------------------------------ bit-exact: model backend (LT)

TEST(SystemcModel, BitExactEveryFilterAndWrap) {
  run_filter_wrap_matrix({"testcard", 64, 16, PyramidMode::Exact}, Backend::Model, InitiatorStyle::Auto, 300, 606);
  run_filter_wrap_matrix({"noise", 8, 128, PyramidMode::Cascade}, Backend::Model, InitiatorStyle::Auto, 200, 707);
}

TEST(SystemcModel, SixteenBitChannelsAndLargeTexture) {
  // The model backend is not limited to the RTL's 8-bit, 1024x1024 build.
  Image img = make_pattern("noise", 2048, 64);
  const Pyramid pyr = build_pyramid(img, PyramidMode::Exact);
  std::mt19937_64 rng(808);
  const SamplerConfig cfg;
  const auto reqs = random_requests(rng, 5000, pyr.last_level() + 1);
  SystemcOptions o;
  o.backend = Backend::Model;
  const EngineResult r = run_systemc(pyr, cfg, reqs, o);
  expect_bit_exact(r, pyr, cfg, reqs, "noise 2048x64 model backend");
  EXPECT_EQ(r.stats["cycles"].get<uint64_t>(), 5000u);  // one clock per sample annotated
}

// The other initiator styles go through simple_target_socket's b<->nb adapters: same texels.
TEST(SystemcAdapters, AtInitiatorOnModelAndLtInitiatorOnRtl) {
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(909);
  SamplerConfig cfg;
  cfg.wrap_u = Wrap::Mirror;
  const auto reqs = random_requests(rng, 500, pyr.last_level() + 1);
  SystemcOptions o;
  o.backend = Backend::Model;
  o.initiator = InitiatorStyle::At;
  expect_bit_exact(run_systemc(pyr, cfg, reqs, o), pyr, cfg, reqs, "AT initiator, model backend");
  if (!have_rtl_backend()) return;
  o.backend = Backend::Rtl;
  o.initiator = InitiatorStyle::Lt;
  const EngineResult r = run_systemc(pyr, cfg, reqs, o);
  expect_bit_exact(r, pyr, cfg, reqs, "LT initiator, RTL backend");
  // A blocking call waits the whole pipeline latency: far below one sample per clock.
  EXPECT_LT(r.stats["samples_per_clock"].get<double>(), 0.5);
  std::printf("LT initiator through the b->nb adapter on the RTL: %.3f samples/clock\n",
              r.stats["samples_per_clock"].get<double>());
}

// ------------------------------------------------------------------ throughput

TEST(SystemcRtl, ThroughputAtLeast099SamplesPerClock) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  const Pyramid pyr = build_pyramid(make_pattern("testcard", 256, 256), PyramidMode::Exact);
  std::mt19937_64 rng(1001);
  const SamplerConfig cfg;  // trilinear: 8 texel reads per sample
  const auto reqs = random_requests(rng, 200000, pyr.last_level() + 1);
  const EngineResult r = run_systemc(pyr, cfg, reqs, rtl_options());
  expect_bit_exact(r, pyr, cfg, reqs, "throughput stream");
  const uint64_t samples = r.stats["samples"], cycles = r.stats["cycles"];
  EXPECT_EQ(samples, reqs.size());
  // Independent of the counters' own division: samples / cycles from the raw counts.
  EXPECT_GE(double(samples) / double(cycles), 0.99) << samples << " samples in " << cycles << " clocks";
  // The socket never throttles the RTL: no clock with a request waiting and the RTL not ready, no
  // clock with a response waiting for the initiator, and the first-to-last span is the samples plus
  // one pipeline latency.
  EXPECT_EQ(r.stats["rtl_backpressure_cycles"].get<uint64_t>(), 0u);
  EXPECT_EQ(r.stats["rtl_response_stall_cycles"].get<uint64_t>(), 0u);
  EXPECT_EQ(cycles, samples + r.stats["latency_cycles"].get<uint64_t>());
  EXPECT_EQ(r.stats["latency_cycles"], r.stats["latency_max_cycles"]);
  std::printf("systemc rtl: %llu samples, %llu clocks, %.5f samples/clock, latency %llu, %.0f clocks per CPU second\n",
              (unsigned long long)samples, (unsigned long long)cycles, double(samples) / double(cycles),
              (unsigned long long)r.stats["latency_cycles"].get<uint64_t>(),
              r.stats["simulated_clocks_per_cpu_second"].get<double>());
}

TEST(SystemcRtl, RandomGapsAndStallsReachTheRtl) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(1102);
  const SamplerConfig cfg;
  const auto reqs = random_requests(rng, 30000, pyr.last_level() + 1);
  SystemcOptions o = rtl_options();
  o.gap_prob = 0.2;
  o.stall_prob = 0.3;
  o.max_stall = 12;
  o.seed = 1102;
  const EngineResult r = run_systemc(pyr, cfg, reqs, o);
  expect_bit_exact(r, pyr, cfg, reqs, "random gaps and stalls");
  EXPECT_GT(r.stats["input_gap_cycles"].get<uint64_t>(), 1000u);
  EXPECT_GT(r.stats["response_stall_cycles"].get<uint64_t>(), 1000u);
  // Held END_RESPs turn into rsp_ready low at the RTL, which then backs up to req_ready.
  EXPECT_GT(r.stats["rtl_response_stall_cycles"].get<uint64_t>(), 0u);
  EXPECT_GT(r.stats["rtl_backpressure_cycles"].get<uint64_t>(), 0u);
  EXPECT_LT(r.stats["samples_per_clock"].get<double>(), 0.9);
}

// ------------------------------------------------------------------ tag order and loss

TEST(SystemcTags, CleanRunReportsNoError) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::DropResponse;
  o.fault_index = 100000;  // beyond the stream: the fault never fires
  EXPECT_EQ(error_of(o), "");
}

TEST(SystemcTags, WrongTagOnTheRtlPinsIsReported) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::CorruptRtlTag;
  o.fault_index = 37;
  const std::string e = error_of(o);
  EXPECT_NE(e.find("has tag 38, expected tag 37 (request #37)"), std::string::npos) << e;
}

TEST(SystemcTags, LostResponseIsReported) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::DropResponse;
  o.fault_index = 50;
  const std::string e = error_of(o);
  EXPECT_NE(e.find("response with tag 51"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 50"), std::string::npos) << e;
}

TEST(SystemcTags, LostLastResponseTimesOut) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::DropResponse;
  o.fault_index = 199;
  o.timeout_cycles = 5000;
  const std::string e = error_of(o, 200);
  EXPECT_NE(e.find("time-out: no response for tag 199"), std::string::npos) << e;
}

TEST(SystemcTags, ReorderedResponsesAreReported) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::SwapResponses;
  o.fault_index = 10;
  const std::string e = error_of(o);
  EXPECT_NE(e.find("response with tag 11"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 10"), std::string::npos) << e;
}

TEST(SystemcTags, DuplicatedResponseIsReported) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemcOptions o = rtl_options();
  o.fault = Fault::DuplicateResponse;
  o.fault_index = 120;
  const std::string e = error_of(o);
  EXPECT_NE(e.find("response with tag 120"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 121"), std::string::npos) << e;
}

// ------------------------------------------------------------------ input errors

TEST(SystemcErrors, MalformedTransactionGetsBurstErrorStatus) {
  // The initiator reports the status the target set; both backends, both initiator styles.
  std::vector<std::pair<Backend, InitiatorStyle>> cases = {{Backend::Model, InitiatorStyle::Lt},
                                                           {Backend::Model, InitiatorStyle::At}};
  if (have_rtl_backend()) cases.push_back({Backend::Rtl, InitiatorStyle::At});
  for (const auto& [backend, style] : cases) {
    SystemcOptions o;
    o.backend = backend;
    o.initiator = style;
    o.fault = Fault::BadLength;
    o.fault_index = 42;
    const std::string e = error_of(o);
    EXPECT_NE(e.find("sample tag 42: response status TLM_BURST_ERROR_RESPONSE"), std::string::npos) << e;
  }
}

TEST(SystemcErrors, TooLargeTextureForTheRtlIsOneLineError) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  const Pyramid pyr = build_pyramid(make_pattern("checker", 2048, 4), PyramidMode::Exact);
  try {
    run_systemc(pyr, SamplerConfig{}, {Request{}}, rtl_options());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2048x4 does not fit"), std::string::npos) << e.what();
  }
}

TEST(SystemcErrors, LodOutsideTheRtlPortIsOneLineError) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  Request q;
  q.lod = 40000;
  try {
    run_systemc(small_pyramid(), SamplerConfig{}, {Request{}, q}, rtl_options());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("request 1: lod 40000/256"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ texsim

TEST(SystemcTexsim, SampleOutputByteIdenticalToModel) {
  const std::string dir = ::testing::TempDir();
  const std::string queries = dir + "/systemc_queries.csv";
  {
    std::ofstream q(queries);
    q << "u,v,lod\n";
    std::mt19937_64 rng(1201);
    std::uniform_real_distribution<double> c(-1.5, 2.5), l(-2, 9);
    for (int i = 0; i < 3000; ++i) q << c(rng) << "," << c(rng) << "," << l(rng) << "\n";
  }
  auto run = [&](const std::string& engine, const std::string& extra) {
    const std::string out = dir + "/systemc_out_" + engine + ".csv";
    const std::string cmd = std::string(TEXSIM_PATH) + " sample -t testcard:128x64 -f trilinear --wrap-u mirror" +
                            " --wrap-v clamp -q " + queries + " -o " + out + " -e " + engine + " " + extra +
                            " > /dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return read_file(out);
  };
  const std::string model = run("model", "");
  ASSERT_GT(model.size(), 3000u);
  EXPECT_EQ(run("systemc-model", ""), model);
  if (!have_rtl_backend()) return;
  const std::string stats = dir + "/systemc_stats.json";
  EXPECT_EQ(run("systemc", "--seed 0 --stats " + stats), model);
  const auto js = nlohmann::json::parse(read_file(stats));
  EXPECT_EQ(js["backend"], "rtl");
  EXPECT_EQ(js["samples"].get<uint64_t>(), 3000u);
  EXPECT_GE(js["samples_per_clock"].get<double>(), 0.99);
  EXPECT_EQ(js["cycles"].get<uint64_t>(), 3000u + js["latency_cycles"].get<uint64_t>());
  EXPECT_EQ(run("systemc", "--seed 5"), model);  // random gaps and stalls: same texels
}

TEST(SystemcTexsim, RenderSeveralFramesByteIdenticalToModel) {
  // Each frame is its own SystemC simulation (one forked process each).
  const std::string dir = ::testing::TempDir();
  const std::string engine = have_rtl_backend() ? "systemc" : "systemc-model";
  for (const std::string& e : {std::string("model"), engine}) {
    const std::string cmd = std::string(TEXSIM_PATH) + " render -s plane -t checker:64x64 --width 96 --height 64" +
                            " --frames 2 -o " + dir + "/systemc_render_" + e + ".png -e " + e + " > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  for (const char* f : {"_000", "_001"}) {
    const std::string a = read_file(dir + "/systemc_render_model" + f + ".png");
    const std::string b = read_file(dir + "/systemc_render_" + engine + f + ".png");
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "frame " << f << " of engine " << engine << " differs from the model's";
  }
}

TEST(SystemcTexsim, TooLargeTextureFailsWithOneLineAndNoOutput) {
  if (!have_rtl_backend()) GTEST_SKIP() << "no Verilated RTL in this build";
  const std::string dir = ::testing::TempDir();
  const std::string queries = dir + "/systemc_one.csv", out = dir + "/systemc_never.csv", err = dir + "/systemc_err.txt";
  std::ofstream(queries) << "u,v,lod\n0.5,0.5,0\n";
  std::remove(out.c_str());
  const std::string cmd = std::string(TEXSIM_PATH) + " sample -t checker:2048x2048 -q " + queries + " -o " + out +
                          " -e systemc 2> " + err;
  EXPECT_NE(std::system(cmd.c_str()), 0);
  const std::string msg = read_file(err);
  EXPECT_NE(msg.find("does not fit the SystemC RTL backend"), std::string::npos) << msg;
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
  EXPECT_FALSE(std::ifstream(out).good());
}

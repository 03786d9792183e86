// The SystemC/TLM-2.0 texture unit (sim/engines/systemc/) against the golden model: bit-exact
// texels over random requests for both backends, throughput through the socket, and the
// initiator's checks (a lost, duplicated or reordered response must be reported), shown on a
// deliberately faulty target defined here. Every simulation runs in its own forked process
// (run_systemc, run_forked), so one test can run many.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include <deque>
#include <nlohmann/json.hpp>

#include "engines/engine.h"
#include "engines/systemc/stream_initiator.h"
#include "engines/systemc/systemc_engine.h"
#include "engines/systemc/tex_unit_tlm.h"
#include "model/error.h"
#include "model/image.h"
#include "stimulus.h"

using namespace tex;
using namespace tex::systemc;

namespace {

struct TextureSpec {
  std::string pattern;
  int width, height;
  PyramidMode mode;
};

// A sampler of filter f and these wrap modes, its LOD controls and reduction at random (tests/common).
SamplerConfig random_config(std::mt19937_64& rng, Filter f, Wrap wu, Wrap wv) {
  SamplerConfig c;
  c.filter = f;
  c.wrap_u = wu;
  c.wrap_v = wv;
  stimulus::randomize_lod_controls(rng, c);
  stimulus::randomize_reduction(rng, c);
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
  for (Filter f : stimulus::all_filters())
    for (Wrap wu : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror})
      for (Wrap wv : {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror}) {
        const SamplerConfig cfg = random_config(rng, f, wu, wv);
        auto reqs = stimulus::random_requests(rng, pyr.extent0(), per_case);
        stimulus::fetches_and_gathers_among(rng, reqs, 16, [&](int) { return pyr.extent0(); });
        stimulus::compares_among(rng, reqs, 16, SamplerTable{cfg}, [](int) { return true; });
        SystemcOptions o;
        o.initiator = style;
        o.engine.seed = seed + uint64_t(n);
        if (n++ % 2 == 1 && style != InitiatorStyle::Lt) o.engine.stalls = n % 4 == 0 ? Stalls::Heavy : Stalls::Random;
        if (n % 3 == 0) o.engine.load = LoadMethod::Port;
        const std::string what = spec.pattern + " " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                 " " + filter_name(f) + " " + wrap_name(wu) + "/" + wrap_name(wv) + " seed " +
                                 std::to_string(o.engine.seed) + " stalls " + stalls_name(o.engine.stalls);
        EngineResult r;
        try {
          r = run_systemc(backend, pyr, cfg, reqs, o);
        } catch (const Error& e) {
          FAIL() << what << ": " << e.what();
        }
        expect_bit_exact(r, pyr, cfg, reqs, what);
        EXPECT_EQ(r.stats.samples, per_case) << what;
      }
}

Pyramid small_pyramid() { return build_pyramid(make_pattern("testcard", 32, 16), PyramidMode::Exact); }

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

// ------------------------------------------------------------------ bit-exact: RTL backend (AT)

TEST(SystemcRtl, BitExactEveryFilterAndWrapNonSquare) {
  run_filter_wrap_matrix({"testcard", 64, 16, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 300, 101);
}

TEST(SystemcRtl, BitExactEveryFilterAndWrapTallCascade) {
  run_filter_wrap_matrix({"noise", 4, 32, PyramidMode::Cascade}, Backend::Rtl, InitiatorStyle::Auto, 300, 202);
}

TEST(SystemcRtl, BitExactEveryFilterAndWrapSquareAndOneTexel) {
  run_filter_wrap_matrix({"checker", 16, 16, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 200, 303);
  run_filter_wrap_matrix({"gradient", 1, 8, PyramidMode::Exact}, Backend::Rtl, InitiatorStyle::Auto, 100, 404);
}

TEST(SystemcRtl, BitExactLargestTexture) {
  const Pyramid pyr = build_pyramid(make_pattern("testcard", 1024, 512), PyramidMode::Exact);
  std::mt19937_64 rng(505);
  const SamplerConfig cfg;  // trilinear, repeat
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), 20000);
  const EngineResult r = run_systemc(Backend::Rtl, pyr, cfg, reqs, SystemcOptions{});
  expect_bit_exact(r, pyr, cfg, reqs, "testcard 1024x512 trilinear");
  EXPECT_EQ(r.stats.cycle->load_cycles, 0u) << "the backdoor load takes no clock";
  EXPECT_EQ(r.stats.cycle->configuration, "Vtex_unit_10x10");
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
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), 5000);
  const EngineResult r = run_systemc(Backend::Model, pyr, cfg, reqs, SystemcOptions{});
  expect_bit_exact(r, pyr, cfg, reqs, "noise 2048x64 model backend");
  EXPECT_FALSE(r.stats.cycle) << "loosely timed: no clock counters";
}

// The other initiator styles go through simple_target_socket's b<->nb adapters: same texels.
TEST(SystemcAdapters, AtInitiatorOnModelAndLtInitiatorOnRtl) {
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(909);
  SamplerConfig cfg;
  cfg.wrap_u = Wrap::Mirror;
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), 500);
  SystemcOptions o;
  o.initiator = InitiatorStyle::At;
  expect_bit_exact(run_systemc(Backend::Model, pyr, cfg, reqs, o), pyr, cfg, reqs, "AT initiator, model backend");
  o.initiator = InitiatorStyle::Lt;
  const EngineResult r = run_systemc(Backend::Rtl, pyr, cfg, reqs, o);
  expect_bit_exact(r, pyr, cfg, reqs, "LT initiator, RTL backend");
  // A blocking call waits the whole pipeline latency: far below one sample per clock.
  EXPECT_LT(r.stats.samples_per_clock(), 0.5);
  std::printf("LT initiator through the b->nb adapter on the RTL: %.3f samples/clock\n", r.stats.samples_per_clock());
}

// ------------------------------------------------------------------ throughput

TEST(SystemcRtl, ThroughputAtLeast099SamplesPerClock) {
  const Pyramid pyr = build_pyramid(make_pattern("testcard", 256, 256), PyramidMode::Exact);
  std::mt19937_64 rng(1001);
  const SamplerConfig cfg;  // trilinear: 8 texel reads per sample
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), 200000);
  const EngineResult r = run_systemc(Backend::Rtl, pyr, cfg, reqs, SystemcOptions{});
  expect_bit_exact(r, pyr, cfg, reqs, "throughput stream");
  const CycleStats& c = *r.stats.cycle;
  const uint64_t samples = r.stats.samples, cycles = c.cycles;
  EXPECT_EQ(samples, reqs.size());
  // Independent of the counters' own division: samples / cycles from the raw counts.
  EXPECT_GE(double(samples) / double(cycles), 0.99) << samples << " samples in " << cycles << " clocks";
  // The socket never throttles the RTL: no clock with a request waiting and the RTL not ready, no
  // clock with a response waiting for the initiator, and the first-to-last span is the samples plus
  // one pipeline latency.
  EXPECT_EQ(c.backpressure_cycles, 0u);
  EXPECT_EQ(c.output_stall_cycles, 0u);
  EXPECT_EQ(cycles, samples + c.latency_cycles);
  EXPECT_EQ(c.latency_cycles, 16u);  // tex_unit's LATENCY
  EXPECT_EQ(c.latency_cycles, c.latency_max_cycles);
  std::printf("systemc rtl: %llu samples, %llu clocks, %.5f samples/clock, latency %llu\n",
              (unsigned long long)samples, (unsigned long long)cycles, double(samples) / double(cycles),
              (unsigned long long)c.latency_cycles);
}

TEST(SystemcRtl, RandomGapsAndStallsReachTheRtl) {
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(1102);
  const SamplerConfig cfg;
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), 30000);
  SystemcOptions o;
  o.engine.stalls = Stalls::Heavy;
  o.engine.seed = 1102;
  const EngineResult r = run_systemc(Backend::Rtl, pyr, cfg, reqs, o);
  expect_bit_exact(r, pyr, cfg, reqs, "random gaps and stalls");
  const CycleStats& c = *r.stats.cycle;
  EXPECT_GT(c.input_gap_cycles, 1000u);
  // Held END_RESPs turn into rsp_ready low at the RTL, which then backs up to req_ready.
  EXPECT_GT(c.output_stall_cycles, 1000u);
  EXPECT_GT(c.backpressure_cycles, 0u);
  EXPECT_LT(r.stats.samples_per_clock(), 0.9);
}

// ------------------------------------------------------------------ the initiator's checks

namespace {

// A deliberately faulty approximately-timed target (test code only): it answers every request from
// the golden model, one BEGIN_RESP per clock, and drops, swaps or duplicates response `at`.
enum class Fault { None, Drop, Swap, Duplicate };

class FaultyTarget : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<FaultyTarget> socket;
  FaultyTarget(sc_core::sc_module_name name, const Pyramid& pyr, const sc_core::sc_time& period, Fault fault,
               uint64_t at)
      : sc_module(name), socket("socket"), sampler_(pyr, SamplerConfig{}), period_(period), fault_(fault), at_(at) {
    socket.register_nb_transport_fw(this, &FaultyTarget::fw);
    SC_METHOD(clock);
  }
  SC_HAS_PROCESS(FaultyTarget);

 private:
  tlm::tlm_sync_enum fw(tlm::tlm_generic_payload& t, tlm::tlm_phase& phase, sc_core::sc_time&) {
    if (phase == tlm::END_RESP) {
      open_ = false;
      return tlm::TLM_COMPLETED;
    }
    auto* s = reinterpret_cast<SampleTransfer*>(t.get_data_ptr());
    const Texel texel = sampler_.sample(lambda_request(s->u, s->v, s->lod));
    for (int c = 0; c < 4; ++c) s->rgba[c] = texel[size_t(c)];
    t.set_response_status(tlm::TLM_OK_RESPONSE);
    const uint64_t i = count_++;
    if (!(fault_ == Fault::Drop && i == at_)) queue_.push_back({&t, fault_ == Fault::Duplicate && i == at_});
    if (fault_ == Fault::Swap && i == at_ + 1) std::swap(queue_[queue_.size() - 1], queue_[queue_.size() - 2]);
    phase = tlm::END_REQ;
    return tlm::TLM_UPDATED;
  }
  void clock() {
    next_trigger(period_);
    if (open_ || queue_.empty()) return;
    const Item item = queue_.front();
    queue_.pop_front();
    for (int copy = 0; copy < (item.twice ? 2 : 1); ++copy) {
      tlm::tlm_phase phase = tlm::BEGIN_RESP;
      sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
      if (socket->nb_transport_bw(*item.trans, phase, delay) == tlm::TLM_ACCEPTED) open_ = true;
    }
  }
  struct Item {
    tlm::tlm_generic_payload* trans;
    bool twice;
  };
  Sampler sampler_;
  sc_core::sc_time period_;
  Fault fault_;
  uint64_t at_, count_ = 0;
  std::deque<Item> queue_;
  bool open_ = false;
};

// The production initiator against the faulty target; the error message ("" when none).
std::string fault_error(Fault fault, uint64_t at, size_t n = 200) {
  const Pyramid pyr = small_pyramid();
  std::mt19937_64 rng(7);
  const auto reqs = stimulus::random_requests(rng, pyr.extent0(), n);
  try {
    run_forked([&] {
      const sc_core::sc_time period(10, sc_core::SC_NS);
      FaultyTarget target("faulty", pyr, period, fault, at);
      VectorSource source(reqs);
      VectorSink sink;
      StreamInitiator bench("testbench", source, sink, true, period, InitiatorTiming{});
      bench.socket.bind(target.socket);
      run_stream(bench, period, 5000, false, [] { return std::string(); });
      EngineResult r;
      r.texels = sink.texels;
      r.stats.engine = "faulty";
      return r;
    });
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SystemcInitiatorChecks, CleanRunReportsNoError) { EXPECT_EQ(fault_error(Fault::None, 0), ""); }

TEST(SystemcInitiatorChecks, LostResponseIsReported) {
  const std::string e = fault_error(Fault::Drop, 50);
  EXPECT_NE(e.find("response with tag 51"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 50"), std::string::npos) << e;
}

TEST(SystemcInitiatorChecks, LostLastResponseTimesOut) {
  const std::string e = fault_error(Fault::Drop, 199, 200);
  EXPECT_NE(e.find("time-out: no response for tag 199"), std::string::npos) << e;
}

TEST(SystemcInitiatorChecks, ReorderedResponsesAreReported) {
  const std::string e = fault_error(Fault::Swap, 10);
  EXPECT_NE(e.find("response with tag 11"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 10"), std::string::npos) << e;
}

TEST(SystemcInitiatorChecks, DuplicatedResponseIsReported) {
  const std::string e = fault_error(Fault::Duplicate, 120);
  EXPECT_NE(e.find("response with tag 120"), std::string::npos) << e;
  EXPECT_NE(e.find("expected tag 121"), std::string::npos) << e;
}

// ------------------------------------------------------------------ input errors

namespace {
struct OneShotInitiator : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<OneShotInitiator> socket{"socket"};
  explicit OneShotInitiator(sc_core::sc_module_name name) : sc_module(name) {}
};
}  // namespace

TEST(SystemcErrors, MalformedTransactionGetsAnErrorStatus) {
  // Transactions sent straight to the target's socket (the model's b_transport, the RTL's
  // nb_transport_fw): a wrong data length, an operation the unit has not got (4),
  // a texel fetch with derivatives, a gather of component 4. The target sets an error status at
  // once and never samples them. (The socket's b<->nb adapters need a running simulation: the
  // initiator test above.)
  struct Bad {
    const char* what;
    int shorter;  // bytes cut from the data length
    uint8_t op, component;
    uint32_t has_derivatives;
    const char* status;
  };
  const Bad bads[] = {{"short", 4, 0, 0, 0, "TLM_BURST_ERROR_RESPONSE"},
                      {"op 4", 0, 4, 0, 0, "TLM_GENERIC_ERROR_RESPONSE"},
                      {"fetch with derivatives", 0, uint8_t(Op::Fetch), 0, 1, "TLM_GENERIC_ERROR_RESPONSE"},
                      {"gather of component 4", 0, uint8_t(Op::Gather), 4, 0, "TLM_GENERIC_ERROR_RESPONSE"}};
  const std::pair<Backend, bool> cases[] = {{Backend::Model, true}, {Backend::Rtl, false}};
  for (const Bad& bad : bads)
    for (const auto& [backend, blocking] : cases) {
      const Pyramid pyr = small_pyramid();
      const EngineResult r = run_forked([&] {
        const sc_core::sc_time period(10, sc_core::SC_NS);
        TexUnitTlm unit("tex_unit_tlm", backend, pyr, SamplerConfig{}, period);
        OneShotInitiator initiator("initiator");
        auto& socket = initiator.socket;
        socket.bind(unit.socket);
        SampleTransfer data;
        data.op = bad.op;
        data.component = bad.component;
        data.has_derivatives = bad.has_derivatives;
        tlm::tlm_generic_payload t;
        t.set_command(tlm::TLM_READ_COMMAND);
        t.set_address(kSampleAddress);
        t.set_data_ptr(reinterpret_cast<unsigned char*>(&data));
        t.set_data_length(uint32_t(sizeof data) - uint32_t(bad.shorter));
        t.set_streaming_width(uint32_t(sizeof data) - uint32_t(bad.shorter));
        sc_core::sc_start(sc_core::SC_ZERO_TIME);
        sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
        if (blocking) {
          socket->b_transport(t, delay);
        } else {
          tlm::tlm_phase phase = tlm::BEGIN_REQ;
          socket->nb_transport_fw(t, phase, delay);
        }
        EngineResult out;
        out.stats.engine = t.get_response_string();
        return out;
      });
      EXPECT_EQ(r.stats.engine, bad.status) << bad.what << ", " << (backend == Backend::Rtl ? "rtl" : "model")
                                            << (blocking ? " b_transport" : " nb_transport");
    }
}

TEST(SystemcErrors, TooLargeTextureForTheRtlIsOneLineError) {
  const Pyramid pyr = build_pyramid(make_pattern("checker", 2048, 4), PyramidMode::Exact);
  try {
    run_systemc(Backend::Rtl, pyr, SamplerConfig{}, {Request{}}, SystemcOptions{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2048x4 does not fit the RTL"), std::string::npos) << e.what();
  }
}

TEST(SystemcErrors, LodOutsideTheRtlPortIsOneLineError) {
  Request q;
  q.lod = 40000;
  try {
    run_systemc(Backend::Rtl, small_pyramid(), SamplerConfig{}, {Request{}, q}, SystemcOptions{});
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
  const std::string stats = dir + "/systemc_stats.json";
  EXPECT_EQ(run("systemc", "--stats " + stats), model);
  const auto js = nlohmann::json::parse(read_file(stats));
  EXPECT_EQ(js["engine"], "systemc");
  EXPECT_EQ(js["samples"].get<uint64_t>(), 3000u);
  EXPECT_GE(js["samples_per_clock"].get<double>(), 0.99);
  EXPECT_EQ(js["cycles"].get<uint64_t>(), 3000u + js["latency_cycles"].get<uint64_t>());
  EXPECT_EQ(run("systemc", "--stalls random --seed 5"), model);  // random gaps and stalls: same texels
  EXPECT_EQ(run("systemc", "--stalls heavy --seed 6 --load port"), model);
  // The same driver as --engine rtl: an FST waveform of a window of clocks.
  const std::string fst = dir + "/systemc_trace.fst";
  std::remove(fst.c_str());
  EXPECT_EQ(run("systemc", "--trace " + fst + " --trace-window 0:200"), model);
  std::ifstream trace(fst, std::ios::binary | std::ios::ate);
  EXPECT_GT(int64_t(trace.tellg()), 1000) << fst;
}

TEST(SystemcTexsim, RenderSeveralFramesByteIdenticalToModel) {
  // Each frame is its own SystemC simulation (one forked process each).
  const std::string dir = ::testing::TempDir();
  const std::string engine = "systemc";
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
  const std::string dir = ::testing::TempDir();
  const std::string queries = dir + "/systemc_one.csv", out = dir + "/systemc_never.csv", err = dir + "/systemc_err.txt";
  std::ofstream(queries) << "u,v,lod\n0.5,0.5,0\n";
  std::remove(out.c_str());
  const std::string cmd = std::string(TEXSIM_PATH) + " sample -t checker:2048x2048 -q " + queries + " -o " + out +
                          " -e systemc 2> " + err;
  EXPECT_NE(std::system(cmd.c_str()), 0);
  const std::string msg = read_file(err);
  EXPECT_NE(msg.find("2048x2048 does not fit the RTL"), std::string::npos) << msg;
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
  EXPECT_FALSE(std::ifstream(out).good());
}

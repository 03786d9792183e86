// Timing and handshake: fixed latency, one sample per clock, no bubbles under output stalls,
// reset in the middle of traffic, the scoreboard's own checks (lost, duplicated, reordered,
// time-out) on a deliberately broken fake unit, assertion failure and FST trace windows.
#include <gtest/gtest.h>

#include <deque>
#include <filesystem>
#include <unistd.h>

#include "lockstep.h"
#include "model/error.h"
#include "model/image.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

struct Shape {
  int w, h;
};
const Shape kShapes[] = {{4, 4}, {6, 3}, {10, 10}};

Pyramid noise_pyramid(int lw, int lh) { return build_pyramid(make_pattern("noise", 1 << lw, 1 << lh)); }

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("texrtl_" + std::to_string(getpid()) + "_" + name)).string();
}

}  // namespace

TEST(RtlTiming, FixedLatencyAndOneSamplePerClock) {
  for (const Shape s : kShapes) {
    auto unit = make_unit(s.w, s.h);
    const Pyramid pyr = noise_pyramid(s.w, s.h);
    unit->load(pyr, LoadMethod::Backdoor);
    std::mt19937_64 rng(mix64(seed_base() + 11));
    for (const Filter& flt : all_filters()) {
      SamplerConfig cfg;
      cfg.filter = flt;
      const auto reqs = random_requests(rng, s.w, s.h, 3000);
      const LockstepResult r = lockstep(*unit, pyr, cfg, reqs, rtl::Timing{}, 1);
      ASSERT_TRUE(r.ok()) << r.report;
      const rtl::ProtocolCounters& pc = r.stats.protocol;
      EXPECT_EQ(pc.latency_min, kDocumentedLatency) << s.w << "x" << s.h;
      EXPECT_EQ(pc.latency_max, kDocumentedLatency) << s.w << "x" << s.h;
      // n samples take n clocks once the pipeline has filled: exactly one per clock.
      EXPECT_EQ(r.stats.cycles(), reqs.size() + kDocumentedLatency);
      EXPECT_EQ(r.stats.cycles() - kDocumentedLatency, r.stats.samples());
      EXPECT_EQ(pc.bubbles_after_fill, 0u);
      EXPECT_EQ(pc.backpressure_cycles, 0u);
    }
  }
}

// Anisotropic samples: one probe per clock. A stream of requests of N probes each (N from the
// model's tex_probe) takes exactly the sum of the probe counts plus LATENCY clocks; the first
// response comes LATENCY + N - 1 clocks after its handshake and every later one N clocks after
// the one before (N - 1 clocks with no response). tex_probe's 4 request registers take 4 requests
// before the sequencer holds req_ready low, N - 1 clocks for each later one; a request waits at
// most for the 3 ahead of it there and its own N probes.
TEST(RtlTiming, AnisotropicSampleTakesOneClockPerProbe) {
  const Shape s{10, 10};
  auto unit = make_unit(s.w, s.h);
  const Pyramid pyr = noise_pyramid(s.w, s.h);
  unit->load(pyr, LoadMethod::Backdoor);
  std::mt19937_64 rng(mix64(seed_base() + 12));
  SamplerConfig cfg;
  cfg.filter = {TexelFilter::Linear, MipMode::Linear, true};  // anisotropic, up to 16 probes
  for (int n = 1; n <= kMaxAniso; ++n) {
    std::vector<Request> reqs;
    uint64_t probes = 0;
    while (reqs.size() < 200) {  // footprints whose probe count is exactly n
      Request r = random_footprint(rng, Extent{1 << s.w, 1 << s.h}, n, int(rng() % 4));
      r.u = int32_t(rng());
      r.v = int32_t(rng());
      if (tex_probe(r, cfg, {1 << s.w, 1 << s.h}).n != n) continue;
      r.tag = uint32_t(reqs.size());
      reqs.push_back(r);
      probes += uint64_t(n);
    }
    const LockstepResult r = lockstep(*unit, pyr, cfg, reqs, rtl::Timing{}, 1);
    ASSERT_TRUE(r.ok()) << r.report;
    const rtl::ProtocolCounters& pc = r.stats.protocol;
    const uint64_t extra = uint64_t(n - 1);  // clocks per request beyond one
    EXPECT_EQ(r.stats.cycles(), probes + kDocumentedLatency) << "N = " << n;
    EXPECT_EQ(pc.latency_min, kDocumentedLatency + extra) << "N = " << n;
    EXPECT_LE(pc.latency_max, kDocumentedLatency + 4 * uint64_t(n)) << "N = " << n;
    EXPECT_EQ(pc.bubbles_after_fill, (reqs.size() - 1) * extra) << "N = " << n;
    EXPECT_EQ(pc.backpressure_cycles, (reqs.size() - 4) * extra) << "N = " << n;
  }
}

// Raw pins, independent of the driver's clock() and stream(): requests always offered, rsp_ready random with
// stalls of 1..8 and some of hundreds of clocks. After the first response, every clock with
// rsp_ready high must deliver a response until the last one: samples == ready clocks.
TEST(RtlTiming, NoBubblesUnderRandomOutputStalls) {
  for (const Shape s : kShapes) {
    auto unit = make_unit(s.w, s.h);
    const Pyramid pyr = noise_pyramid(s.w, s.h);
    unit->load(pyr, LoadMethod::Backdoor);
    SamplerConfig cfg;  // trilinear, repeat
    unit->configure(cfg, pyr);
    const uint64_t seed = mix64(seed_base() + 23 + uint64_t(s.w));
    std::mt19937_64 rng(seed);
    const auto reqs = random_requests(rng, s.w, s.h, 20000);
    Sampler model(pyr, cfg);

    size_t accepted = 0, done = 0;
    uint64_t ready_after_fill = 0, stall_left = 0, long_stalls = 0;
    bool filled = false;
    rtl::PinsIn in;
    while (done < reqs.size()) {
      ASSERT_LT(unit->cycle(), 10'000'000u) << "hang, seed " << seed;
      if (stall_left == 0) {
        if (rng() % 1000 == 0) {
          stall_left = 100 + rng() % 400;
          ++long_stalls;
        } else if (rng() % 3 == 0) {
          stall_left = 1 + rng() % 8;
        }
      }
      in.rsp_ready = stall_left == 0;
      if (stall_left) --stall_left;
      in.req_valid = accepted < reqs.size();
      if (in.req_valid) {
        rtl::set_request_pins(in, reqs[accepted]);
        in.req_tag = uint16_t(accepted);
      }
      const rtl::PinsOut out = unit->tick(in);
      if (filled && in.rsp_ready) ++ready_after_fill;
      if (out.rsp_valid && in.rsp_ready) {
        if (!filled) ready_after_fill = 1;
        filled = true;
        ASSERT_EQ(out.rsp_tag, uint16_t(done)) << "seed " << seed;
        ASSERT_EQ(out.rsp_rgba, rtl::pack_rgba(model.sample(reqs[done]), 8)) << describe(reqs[done]) << " seed " << seed;
        ++done;
      } else if (filled && in.rsp_ready) {
        FAIL() << s.w << "x" << s.h << ": bubble at clock " << unit->cycle() - 1 << " with " << (accepted - done)
               << " responses owed (seed " << seed << ")";
      }
      if (in.req_valid && out.req_ready) ++accepted;
    }
    EXPECT_EQ(done, ready_after_fill) << "samples == ready clocks after the fill";
    EXPECT_GT(long_stalls, 0u);
  }
}

TEST(RtlTiming, ResetInTheMiddleOfTraffic) {
  for (const Shape s : {kShapes[1], kShapes[2]}) {
    auto unit = make_unit(s.w, s.h);
    const Pyramid pyr = build_pyramid(make_pattern("noise", 1 << s.w, 1 << s.h), PyramidMode::Cascade);
    unit->load(pyr, LoadMethod::Backdoor);
    const uint64_t seed = mix64(seed_base() + 31 + uint64_t(s.h));
    std::mt19937_64 rng(seed);
    for (int trial = 0; trial < 8; ++trial) {
      SamplerConfig cfg;
      // trials 6, 7: anisotropic, so that the reset can hit the sequencer in the middle of a
      // request's probes (a quarter of the requests carry derivatives)
      if (trial < 6) cfg.filter = all_filters()[size_t(trial)];
      else randomize_aniso(rng, cfg);
      cfg.wrap_u = Wrap(trial % 3);
      cfg.wrap_v = Wrap((trial + 1) % 3);
      unit->configure(cfg, pyr);
      // Traffic: requests always offered, the output stalled now and then (in trial 1, 3, 5 for
      // good: the pipeline and the skid buffer are full and req_ready is low at the reset).
      const auto junk = random_requests(rng, s.w, s.h, 200);
      size_t accepted = 0;
      rtl::PinsIn in;
      const int clocks = 5 + int(rng() % 60);
      for (int c = 0; c < clocks; ++c) {
        in.req_valid = true;
        rtl::set_request_pins(in, junk[accepted % junk.size()]);
        in.req_tag = uint16_t(0xF000 + accepted);
        in.rsp_ready = (trial % 2) ? false : (rng() % 2 == 0);
        if (unit->tick(in).req_ready) ++accepted;
      }
      unit->reset(1 + int(rng() % 3));
      // Nothing from before the reset may come out.
      const rtl::PinsOut after = unit->tick(rtl::PinsIn{});
      EXPECT_FALSE(after.rsp_valid) << "stale response tag " << after.rsp_tag << " after reset";
      EXPECT_TRUE(after.req_ready);
      std::string timing_name;
      const rtl::Timing timing = random_stalls(rng, timing_name);
      const auto reqs = random_requests(rng, s.w, s.h, 5000);
      const LockstepResult r = lockstep(*unit, pyr, cfg, reqs, timing, rng());
      EXPECT_TRUE(r.ok()) << "after reset in trial " << trial << ", timing " << timing_name << ", seed " << seed
                          << "\n" << r.report;
      EXPECT_EQ(r.compared, reqs.size());
    }
  }
}

// ---------------------------------------------------------------- the scoreboard catches faults

namespace {

// A fake unit with latency 20 that can lose, duplicate, reorder or withhold responses.
enum class Fault { None, Lose, Duplicate, Swap, Silence };

class FakeUnit : public rtl::Driver {
 public:
  FakeUnit(Fault fault, uint64_t at) : Driver(rtl::RtlConfig{"fake", 4, 4}, rtl::DriverOptions{}), fault_(fault), at_(at) {}

 protected:
  rtl::PinsOut tick_pins(const rtl::PinsIn& in, bool) override {
    rtl::PinsOut out;
    out.req_ready = true;
    if (!queue_.empty() && queue_.front().ready_at <= cycle()) {
      out.rsp_valid = true;
      out.rsp_tag = queue_.front().tag;
      out.rsp_rgba = queue_.front().tag * 3u;
    }
    if (out.rsp_valid && in.rsp_ready) {
      const Item item = queue_.front();
      queue_.pop_front();
      if (fault_ == Fault::Duplicate && item.tag == at_) queue_.push_front({item.tag, cycle() + 1});
    }
    if (in.req_valid) {
      ++seen_;
      const Item item{in.req_tag, cycle() + 20};
      if (fault_ == Fault::Lose && in.req_tag == at_) return out;
      if (fault_ == Fault::Silence && seen_ > at_) return out;
      if (fault_ == Fault::Swap && in.req_tag == at_ + 1 && !queue_.empty()) {
        queue_.insert(queue_.end() - 1, item);
        return out;
      }
      queue_.push_back(item);
    }
    return out;
  }
  void apply_cfg(const rtl::CfgPins&) override {}
  void apply_cache_pins(const rtl::CachePins&) override {}
  void apply_descriptor(const rtl::DescriptorPins&, bool) override {}
  void apply_sampler(const rtl::SamplerPins&, bool) override {}
  void backdoor_write(int, int, uint32_t, uint64_t) override {}
  uint64_t backdoor_read(int, int, uint32_t) const override { return 0; }
  void close_trace_impl() override {}

 private:
  struct Item {
    uint16_t tag;
    uint64_t ready_at;
  };
  Fault fault_;
  uint64_t at_;
  uint64_t seen_ = 0;
  std::deque<Item> queue_;
};

std::string stream_error(Fault fault, uint64_t at, const rtl::Timing& timing) {
  FakeUnit unit(fault, at);
  std::vector<Request> reqs(100);
  try {
    rtl::stream(unit, reqs.data(), reqs.size(), timing, 5, [](size_t i, uint64_t rgba) {
      if (rgba != i * 3u) throw Error("data of request " + std::to_string(i) + " is wrong");
    });
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RtlScoreboard, CatchesLostDuplicatedReorderedAndMissingResponses) {
  const rtl::Timing heavy{0.6, 6, 0.6, 6, 0, 0};
  for (const rtl::Timing& t : {rtl::Timing{}, heavy}) {
    EXPECT_EQ(stream_error(Fault::None, 0, t), "");
    std::string e = stream_error(Fault::Lose, 40, t);
    EXPECT_NE(e.find("has tag 41, expected tag 40"), std::string::npos) << e;
    e = stream_error(Fault::Duplicate, 40, t);
    EXPECT_NE(e.find("has tag 40, expected tag 41"), std::string::npos) << e;
    e = stream_error(Fault::Swap, 40, t);
    EXPECT_NE(e.find("has tag 41, expected tag 40"), std::string::npos) << e;
    e = stream_error(Fault::Duplicate, 99, t);  // the extra copy comes after the last response
    EXPECT_NE(e.find("after all 100 requests were answered"), std::string::npos) << e;
    e = stream_error(Fault::Silence, 60, t);
    EXPECT_NE(e.find("time-out: no response for tag 60"), std::string::npos) << e;
    EXPECT_NE(e.find("at clock"), std::string::npos) << e;
  }
}

TEST(RtlDriver, AssertionFailureClosesTheTrace) {
  const std::string trace = temp_path("assert.fst");
  {
    auto unit = make_unit(4, 4, 3, trace);
    rtl::PinsIn in;
    in.req_valid = true;
    in.rsp_ready = false;
    // Fill the pipeline and the skid buffer until req_ready drops, then break the rule that a
    // request stays offered until taken.
    int clocks = 0;
    while (unit->tick(in).req_ready) ASSERT_LT(++clocks, 100);
    in.req_valid = false;
    try {
      unit->tick(in);
      unit->tick(in);
      FAIL() << "the RTL assertion on req_valid did not fire";
    } catch (const SimulationError& e) {  // texsim keeps the waveform of such a failure
      EXPECT_NE(std::string(e.what()).find("assertion"), std::string::npos) << e.what();
      // Closed by the failure itself, while the unit still exists: a complete file.
      ASSERT_TRUE(std::filesystem::exists(trace));
      EXPECT_GT(std::filesystem::file_size(trace), 100u);
    }
  }
  std::filesystem::remove(trace);
}

// Several units in one process (a check beside an engine, a benchmark's units): each unit's
// assertions are its own, whichever unit was made or used last (Verilator keeps one context per
// thread, not per model: the driver makes each unit's the thread's before it touches the model),
// and units go away in any order (a unit made and dropped before another used to leave the
// thread's context dangling, and a later unit's destructor hung on it at exit: make bench).
TEST(RtlDriver, EachUnitSeesItsOwnAssertionsBesideOthers) {
  auto first = make_unit(4, 4, 3);
  { auto dropped = make_unit(6, 3, 3); }
  auto later = make_unit(4, 4, 3);  // made after `first`: the thread's context was its
  rtl::PinsIn in;
  in.req_valid = true;
  in.rsp_ready = false;
  int clocks = 0;
  while (first->tick(in).req_ready) ASSERT_LT(++clocks, 100);
  later->tick(rtl::PinsIn{});  // `later` used last
  in.req_valid = false;        // `first` breaks the rule that a request stays offered until taken
  EXPECT_THROW(
      {
        first->tick(in);
        first->tick(in);
      },
      SimulationError)
      << "the assertion of the unit made first went unseen";
  EXPECT_NO_THROW(later->tick(rtl::PinsIn{})) << "the other unit's assertion stopped this one";
  first.reset();
  later.reset();
}

TEST(RtlDriver, TraceWindowIsClosedAfterItsLastClock) {
  const std::string small = temp_path("w1.fst"), large = temp_path("w2.fst");
  auto run = [](const std::string& path, uint64_t begin, uint64_t end) {
    rtl::DriverOptions o;
    o.trace_path = path;
    o.trace_begin = begin;
    o.trace_end = end;
    auto unit = rtl::Driver::create(rtl::smallest_config_for(4, 4), o);
    unit->reset();
    const Pyramid pyr = noise_pyramid(4, 4);
    unit->load(pyr, LoadMethod::Backdoor);
    SamplerConfig cfg;
    unit->configure(cfg, pyr);
    std::mt19937_64 rng(1);
    const auto reqs = random_requests(rng, 4, 4, 3000);
    rtl::stream(*unit, reqs.data(), reqs.size(), rtl::Timing{}, 1, [](size_t, uint64_t) {});
    // The window ended long ago: the file is complete before the driver goes away.
    EXPECT_TRUE(std::filesystem::exists(path));
    return std::filesystem::file_size(path);
  };
  const auto s1 = run(small, 400, 420);
  const auto s2 = run(large, 400, 3000);
  EXPECT_GT(s1, 0u);
  EXPECT_GT(s2, s1);
  std::filesystem::remove(small);
  std::filesystem::remove(large);
}

TEST(RtlDriver, PicksTheSmallestConfigurationAndRejectsTooLargeTextures) {
  EXPECT_EQ(rtl::smallest_config_for(4, 4).name, "Vtex_unit_4x4");
  EXPECT_EQ(rtl::smallest_config_for(0, 0).name, "Vtex_unit_4x4");
  EXPECT_EQ(rtl::smallest_config_for(5, 3).name, "Vtex_unit_6x3");
  EXPECT_EQ(rtl::smallest_config_for(4, 5).name, "Vtex_unit_10x10");
  EXPECT_EQ(rtl::smallest_config_for(10, 10).name, "Vtex_unit_10x10");
  EXPECT_EQ(rtl::smallest_config_for(5, 4, 16).name, "Vtex_unit_5x4_cw16");
  try {
    rtl::smallest_config_for(11, 2);
    FAIL() << "2048x4 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2048x4 does not fit the RTL"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1024x1024"), std::string::npos) << e.what();
  }
}

TEST(RtlScoreboard, DetectsOneWrongTexelInOneLevel) {
  // The RTL holds the true pyramid; the model gets a copy with one texel of level 2 off by one.
  // The lockstep comparison must see it (and only where that texel is read).
  auto unit = make_unit(4, 4);
  const Pyramid pyr = noise_pyramid(4, 4);
  unit->load(pyr, LoadMethod::Backdoor);
  Pyramid wrong = pyr;
  wrong.levels[2].at(1, 2)[1] ^= 1;
  SamplerConfig cfg;  // trilinear
  std::vector<Request> reqs;
  for (int i = 0; i < 4; ++i)  // centres of level 2 (4x4), lambda 2.0: level 2 only
    for (int j = 0; j < 4; ++j) reqs.push_back(lambda_request((2 * i + 1) << 21, (2 * j + 1) << 21, 512));
  const LockstepResult r = lockstep(*unit, wrong, cfg, reqs, rtl::Timing{}, 1);
  EXPECT_EQ(r.mismatches, 1u) << r.report;
  EXPECT_NE(r.report.find("request #6 "), std::string::npos) << r.report;
  const LockstepResult same = lockstep(*unit, pyr, cfg, reqs, rtl::Timing{}, 1);
  EXPECT_TRUE(same.ok()) << same.report;
}

// The backdoor load (texsim's default) fills the memories exactly as the write port does: in every
// configuration, both units answer the same random requests with the model's texels; the port
// takes one clock per texel plus one, the backdoor none.
TEST(RtlDriver, BackdoorAndPortLoadGiveTheSameSamples) {
  for (const rtl::RtlConfig& c : rtl::compiled_configs()) {
    if (c.cached) continue;  // the write port is the on-chip unit's (test_rtl_cached.cpp loads the cached ones)
    Pyramid pyr = build_pyramid(make_pattern("noise", 1 << c.max_log2_w, 1 << c.max_log2_h), PyramidMode::Cascade);
    for (Image& img : pyr.levels) {  // use every bit of a wider channel
      img.channel_bits = c.cw;
      for (Texel& t : img.texels)
        for (uint16_t& ch : t) ch = uint16_t((ch * 257u) >> (16 - c.cw));
    }
    size_t texels = 0;
    for (const Image& img : pyr.levels) texels += img.texels.size();
    std::mt19937_64 rng(mix64(seed_base() + 41 + uint64_t(c.max_log2_w)));
    const auto reqs = random_requests(rng, c.max_log2_w, c.max_log2_h, 4000);
    SamplerConfig cfg;
    cfg.wrap_v = Wrap::Mirror;
    for (LoadMethod method : {LoadMethod::Port, LoadMethod::Backdoor}) {
      auto unit = make_unit(c.max_log2_w, c.max_log2_h, 5, "", c.cw);
      unit->load(pyr, method);
      EXPECT_EQ(unit->load_cycles(), method == LoadMethod::Port ? texels + 1 : 0) << c.name;
      const LockstepResult r = lockstep(*unit, pyr, cfg, reqs, rtl::Timing::of(Stalls::Random), 3);
      EXPECT_TRUE(r.ok()) << c.name << " " << load_method_name(method) << "\n" << r.report;
      EXPECT_EQ(r.compared, reqs.size());
    }
  }
}

// The timing model (model/timing.h) against the Verilated RTL, clock for clock. Every lockstep
// suite compares each response's clock (lockstep(), cached_lockstep.h's run_case); these tests
// show that the comparison fires on a planted one-clock error, in each unit.
#include <gtest/gtest.h>

#include "lockstep.h"
#include "model/image.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

Pyramid noise_pyramid(int w, int h, uint64_t seed) {
  Image img(w, h, 8);
  std::mt19937_64 rng(seed);
  for (Texel& t : img.texels)
    for (uint16_t& c : t) c = uint16_t(rng() & 255);
  return build_pyramid(img, PyramidMode::Exact);
}

// The RTL's response clocks for a stream.
std::vector<uint64_t> rtl_clocks(rtl::Driver& unit, const std::vector<Request>& requests, const rtl::Timing& stim,
                                 uint64_t seed) {
  std::vector<uint64_t> clocks(requests.size());
  rtl::stream(unit, requests.data(), requests.size(), stim, seed,
              [&](size_t i, uint64_t) { clocks[i] = response_clock(unit); });
  return clocks;
}

TEST(TimingModel, OnChipCatchesAPlantedOneClockError) {
  auto unit = make_unit(4, 4);
  const Pyramid pyr = noise_pyramid(16, 16, 3);
  SamplerConfig cfg;
  cfg.filter.anisotropic = true;
  unit->configure(cfg, pyr);
  std::mt19937_64 rng(9);
  const std::vector<Request> requests = random_requests(rng, 4, 4, 3000);
  std::vector<RequestWork> work(requests.size());
  for (size_t i = 0; i < requests.size(); ++i)
    work[i].probes = uint8_t(tex_probe_count(requests[i], cfg, {16, 16}));
  const rtl::Timing stim = rtl::Timing::of(Stalls::Random);
  const std::vector<uint64_t> want = model_clocks(*unit, 0, work, stim, 21);
  const std::vector<uint64_t> got = rtl_clocks(*unit, requests, stim, 21);
  EXPECT_EQ(compare_clocks(got, want), "");
  // Planted: one single-probe request in the middle takes one probe more in the model (ideal
  // stimulus: under random stalls one clock more also moves the later draws).
  const std::vector<uint64_t> ideal = rtl_clocks(*unit, requests, {}, 1);
  size_t at = requests.size() / 2;
  while (work[at].probes != 1) ++at;
  work[at].probes = 2;
  const std::vector<uint64_t> late = model_clocks(*unit, 0, work, {}, 1);
  const std::string report = compare_clocks(ideal, late);
  EXPECT_NE(report.find("response " + std::to_string(at) + " at clock " + std::to_string(ideal[at])), std::string::npos)
      << report;
  EXPECT_EQ(late[at], ideal[at] + 1) << "one clock late, no more";
}

TEST(TimingModel, CachedCatchesAPlantedOneClockError) {
  const rtl::RtlConfig* rc = nullptr;
  for (const rtl::RtlConfig& c : rtl::compiled_configs())
    if (c.name == "Vtex_cached_6x3") rc = &c;
  ASSERT_NE(rc, nullptr);
  rtl::DriverOptions o;
  o.cache = CacheParams{2048, 2};
  o.memory.latency = 100;
  o.memory.jitter = 0;
  auto unit = rtl::Driver::create(*rc, o);
  unit->reset();
  const Pyramid pyr = noise_pyramid(64, 8, 5);
  SamplerConfig cfg;
  unit->load(pyr, LoadMethod::Backdoor);
  unit->configure(cfg, pyr);
  std::mt19937_64 rng(4);
  const std::vector<Request> requests = random_requests(rng, 6, 3, 3000);
  TextureCache cache(MemoryLayout({64, 8}, 8, o.layout), o.cache, cfg);
  std::vector<RequestWork> work;
  for (const Request& r : requests) work.push_back(cache.lookup_sample(r, nullptr));
  const rtl::Timing stim = rtl::Timing::of(Stalls::Random);
  const std::vector<uint64_t> want = model_clocks(*unit, 0, work, stim, 8);
  // Planted: the model's memory answers one clock later than the RTL's.
  MemoryTiming slow = o.memory;
  slow.latency += 1;
  const MemoryChannel late_memory(rc->line_bytes(), rc->mem_bits / 8, slow);
  TimedStream timed(rtl::unit_shape(*rc), &late_memory, stim, 8);
  for (const RequestWork& w : work) timed.push(w);
  std::vector<uint64_t> late;
  timed.finish(&late);
  const std::vector<uint64_t> got = rtl_clocks(*unit, requests, stim, 8);
  EXPECT_EQ(compare_clocks(got, want), "");
  const std::string report = compare_clocks(got, late);
  EXPECT_NE(report.find("in the timing model"), std::string::npos) << report;
  size_t first = 0;
  while (first < got.size() && got[first] == late[first]) ++first;
  ASSERT_LT(first, got.size());
  EXPECT_EQ(late[first], got[first] + 1) << "the first difference is one clock";
}

}  // namespace

// Lockstep scoreboard for the RTL tests (docs/verification.md); their stimulus is tests/common's.
#pragma once
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"
#include "engines/rtl/driver.h"
#include "stimulus.h"  // tests/common

namespace tex::rtltest {

// The documented latency of tex_unit (rtl/tex_unit.sv header: "LATENCY = 16 clocks"), in clocks
// from the request handshake edge to the response handshake edge with rsp_ready high.
constexpr uint64_t kDocumentedLatency = 16;

uint64_t mix64(uint64_t x);  // splitmix64 finalizer: independent seeds from (base, indices)

// TEX_SEED=N: replay only the case with this seed. TEX_SEED_BASE=N: another set of random cases.
// TEX_SCALE=K: K times more random requests per case (soak runs).
std::optional<uint64_t> env_u64(const char* name);
uint64_t seed_base();
int scale();

// Every request is compared with tex::Sampler::sample() of the model; the driver checks tags
// (order, loss, duplicates) and the time-out; this checks data and that every index came back once.
// It also checks each response's clock against the timing model (model/timing.h).
struct LockstepResult {
  uint64_t compared = 0;
  uint64_t mismatches = 0;
  std::string report;  // first mismatches, or the driver's error
  rtl::StreamStats stats;
  bool ok() const { return mismatches == 0 && report.empty(); }
};
LockstepResult lockstep(rtl::Driver& unit, const Pyramid& pyramid, const SamplerConfig& config,
                        const std::vector<Request>& requests, const rtl::Timing& timing, uint64_t seed);

// The timing model over the stream `unit` is about to run: the configuration's shape (fifo_depth:
// the cfg_fifo_limit in use), the driver's memory channel as it stands, the same stimulus and
// seed. The clock of each response, counted from the first offer, in response order.
std::vector<uint64_t> model_clocks(rtl::Driver& unit, uint32_t fifo_depth, const std::vector<RequestWork>& work,
                                   const rtl::Timing& stim, uint64_t seed);
// The clock of the response the driver took last, counted as model_clocks() counts.
inline uint64_t response_clock(const rtl::Driver& unit) { return unit.counters().last_response_clock(); }
// "" when equal, else the first difference and how many differ.
std::string compare_clocks(const std::vector<uint64_t>& rtl, const std::vector<uint64_t>& model);

std::string describe(const SamplerConfig& c);
std::string describe(const Request& r);
std::string describe(const Texel& t);

// The stimulus (requests, samplers, textures, stall profiles): tests/common/stimulus.h, shared
// with the AXI-top, SystemC and X-propagation suites.
using namespace tex::stimulus;
using stimulus::random_requests;  // (beside the overload below, not hidden by it)
// For a 2^lw x 2^lh texture.
inline std::vector<Request> random_requests(std::mt19937_64& rng, int lw, int lh, size_t n) {
  return random_requests(rng, Extent{1 << lw, 1 << lh}, n);
}

// The driver of the named configuration, reset.
std::unique_ptr<rtl::Driver> make_unit(int max_log2_w, int max_log2_h, uint64_t seed = 1,
                                        const std::string& trace = "", int cw = 8);

}  // namespace tex::rtltest

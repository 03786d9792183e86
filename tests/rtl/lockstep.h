// Lockstep scoreboard and constrained-random stimulus for the RTL tests (docs/verification.md).
#pragma once
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"
#include "engines/rtl/driver.h"
#include "stimulus.h"

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

// Constrained-random requests for a 2^lw x 2^lh texture: coordinates in [-100, 100), near texel
// edges and centres of every level, in [0, 1), and any 32-bit value; lambda from -2 to past the
// last level, on level and rounding boundaries, and any 16-bit value.
// A quarter of them carry derivatives instead (random_footprint: lambda from the LOD unit).
std::vector<Request> random_requests(std::mt19937_64& rng, Extent size, size_t n);
inline std::vector<Request> random_requests(std::mt19937_64& rng, int lw, int lh, size_t n) {
  return random_requests(rng, Extent{1 << lw, 1 << lh}, n);
}
// Requests of an unnormalized sampler: random_requests with u, v in Q16.16 texels of level 0 near
// texel edges and centres within a few texels of the texture, anywhere in [-2n, 3n), beyond the
// RTL's clamp (+-2^(ML+1) texels) and any 32-bit value.
std::vector<Request> random_texel_requests(std::mt19937_64& rng, Extent size, size_t n);
// A request with derivatives whose footprint takes `probes` probes (1..16) under a cap of 16, its
// major axis along u (axis 0), v (1) or diagonal (2), from magnification to past the last level;
// 1 in 16 has raw 32-bit derivatives (the format's saturating ends).
Request random_footprint(std::mt19937_64& rng, Extent size, int probes, int axis);
inline Request random_footprint(std::mt19937_64& rng, int lw, int lh, int probes, int axis) {
  return random_footprint(rng, Extent{1 << lw, 1 << lh}, probes, axis);
}
// Anisotropic filter cases: cap 16 half of the time, else 1..16; probe counts rounded to powers of
// two in a quarter of the cases.
void randomize_aniso(std::mt19937_64& rng, SamplerConfig& c);
// Random bias and clamps (half of the cases keep the full range).
// One of the five address modes.
Wrap random_wrap(std::mt19937_64& rng);
// One of the border colours (Vulkan's six or a random custom one).
void randomize_border(std::mt19937_64& rng, SamplerConfig& c);
// A third of the time, a magnification filter apart from the minification filter's texel filter.
void randomize_mag_filter(std::mt19937_64& rng, SamplerConfig& c);
void randomize_lod_controls(std::mt19937_64& rng, SamplerConfig& c);
// One of: ideal, light, heavy (about 30% of clocks without a gap), long stalls (hundreds of clocks).
rtl::Timing random_timing(std::mt19937_64& rng, std::string& name);

// A 2^lw x 2^lh texture (sides >= 4) of random blocks of a block format, every level: each BC7
// block in a random one of its 8 modes and 1 in 16 in the reserved mode (decoded to 0).
Pyramid random_block_texture(TexelFormat format, Extent size, uint64_t seed);

// The six filters (texel filter x mip mode) and three wrap modes.
std::vector<Filter> all_filters();

// The driver of the named configuration, reset.
std::unique_ptr<rtl::Driver> make_unit(int max_log2_w, int max_log2_h, uint64_t seed = 1,
                                        const std::string& trace = "", int cw = 8);

}  // namespace tex::rtltest

// The lockstep harness of tex_unit_cached's suites (test_rtl_cached.cpp, test_rtl_descriptor_tables.cpp):
// one case of requests through the Verilated unit beside the golden model (every response, every
// line read and every response clock compared), the cache-side coverage bins, and random textures,
// cache geometries, layouts and memory timings for a configuration.
#pragma once
#include <map>
#include <random>
#include <string>
#include <vector>

#include "lockstep.h"

namespace tex::rtltest {

// Cache-side coverage bins, counted from the model's lookups and the driver's counters.
struct CacheCoverage {
  std::map<std::string, uint64_t> bins;
  void hit(const std::string& name) { ++bins[name]; }
  void sample(const SampleLookup& l) {
    for (int s = 0; s < 2; ++s) {
      const SlotLookup& sl = l.slot[size_t(s)];
      if (!sl.needed) continue;
      const std::string level = s == 0 ? "level d" : "level d1";
      hit(level + ": " + std::to_string(sl.misses) + " missing lines");
      const uint8_t m = sl.block_mask;
      const int n = __builtin_popcount(m);
      hit(level + ": footprint in " +
          (n == 1 ? std::string("1 block") : n == 4 ? std::string("4 blocks")
           : (m == 0x3 || m == 0xC) ? std::string("2 blocks side by side") : std::string("2 blocks one above the other")));
    }
    if (l.slot[0].misses > 0 && l.slot[1].misses > 0) hit("both levels missing");
  }
  // Every bin the configuration can reach: level d1 (level 1 or more) straddles blocks along an
  // axis only if level 1 is more than one block long along it.
  std::vector<std::string> required(const rtl::RtlConfig& c) const {
    std::vector<std::string> r;
    for (int s = 0; s < 2; ++s) {
      const std::string level = s == 0 ? "level d" : "level d1";
      const bool across = (1 << (c.max_log2_w - s)) > c.block_w, down = (1 << (c.max_log2_h - s)) > c.block_h;
      const int most = (across ? 2 : 1) * (down ? 2 : 1);
      for (int k = 0; k <= most; ++k) r.push_back(level + ": " + std::to_string(k) + " missing lines");
      r.push_back(level + ": footprint in 1 block");
      if (across) r.push_back(level + ": footprint in 2 blocks side by side");
      if (down) r.push_back(level + ": footprint in 2 blocks one above the other");
      if (across && down) r.push_back(level + ": footprint in 4 blocks");
    }
    for (const char* b : {"both levels missing", "FIFO full", "a line evicted while the previous sample needs it",
                          "the same line read twice in flight"})
      r.push_back(b);
    return r;
  }
};

// One case: its result, or a failure description.
struct CaseResult {
  uint64_t samples = 0, clocks = 0, reads = 0;
  uint64_t flagged = 0;   // responses with rsp_error
  uint32_t fifo_max = 0;  // largest FIFO occupancy
  std::string failure;
};

// A random texture for a configuration: RGBA (channels as memory holds them) or random blocks of a
// block format; sRGB if asked and the configuration has the tables (not BC4, BC5, EAC: no sRGB).
Pyramid random_pyramid(const rtl::RtlConfig& rc, TexelFormat format, Extent size, bool srgb, uint64_t seed);

// A compiled configuration by name (throws tex::Error for another).
const rtl::RtlConfig& config_named(const std::string& name);

// One case over a descriptor table and a sampler table (requests name a texture and a sampler):
// every response against the model's sampler of that pair, every line read against the model's
// caches.
CaseResult run_case(rtl::Driver& unit, const TextureTable& table, const SamplerTable& smp, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache = nullptr, int poke_texel = -1, uint32_t fifo_depth = 0,
                    const TextureTable* model_table = nullptr, const std::vector<uint64_t>& error_reads = {},
                    const std::vector<uint64_t>* model_error_reads = nullptr,
                    const SamplerTable* model_samplers = nullptr);

// One texture and one sampler.
CaseResult run_case(rtl::Driver& unit, const Pyramid& pyr, const SamplerConfig& cfg, const LayoutParams& layout,
                    const CacheParams& cache, const rtl::MemoryTiming& timing, const std::vector<Request>& requests,
                    const rtl::Timing& stim, uint64_t seed, CacheCoverage* coverage,
                    const CacheParams* model_cache = nullptr, int poke_texel = -1, uint32_t fifo_depth = 0);

// The configuration's block shape in a random block order, at a random base.
LayoutParams random_layout(std::mt19937_64& rng, const rtl::RtlConfig& c);

// A random cache geometry the configuration holds.
CacheParams random_cache(std::mt19937_64& rng, const rtl::RtlConfig& c);

// Random memory timing for the configuration's port (latency, jitter, bandwidth, reads in flight, a
// quarter of the cases with port backpressure), and its description in `name`.
rtl::MemoryTiming random_memory(std::mt19937_64& rng, const rtl::RtlConfig& c, std::string& name);

// Case ci of a suite: in a third of the cases 1 to 3 line reads, among the first 300, answer SLVERR.
std::vector<uint64_t> random_error_reads(std::mt19937_64& rng, int ci);

}  // namespace tex::rtltest

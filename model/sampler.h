// The texture sampler: LOD, address generation, wrap, banked fetch and filter, bit-exact.
#pragma once
#include <cstdint>
#include <vector>

#include "banked_memory.h"
#include "formats.h"
#include "pyramid.h"

namespace tex {

struct SamplerConfig {
  Filter filter;
  Wrap wrap_u = Wrap::Repeat;
  Wrap wrap_v = Wrap::Repeat;
  int32_t lod_bias = 0;        // Q8.8
  int32_t min_lod = kLodMin;   // Q8.8
  int32_t max_lod = kLodMax;   // Q8.8
};

// One request in the hardware's formats (docs/numerics.md).
struct Request {
  int32_t u = 0, v = 0;  // Q8.24
  int32_t lod = 0;       // Q8.8, before bias and clamp
  uint32_t tag = 0;
};

struct SamplerStats {
  uint64_t samples = 0;
  uint64_t multiplies_per_channel = 0;  // lerps that do work: 3 per bilinear level, +1 for the blend
  BankStats memory;                     // texel words read, per level and bank
};

class Sampler {
 public:
  Sampler(const Pyramid& pyramid, const SamplerConfig& config);

  // Reference path: every stage in order, counting reads and multiplies.
  Texel sample(const Request& r);

  // Fast path for 8-bit channels: packed RGBA8 (R in the low byte), no counters.
  // Bit-identical to sample() (tests/test_sampler.cpp checks it).
  void sample_rgba8(const Request* requests, size_t n, uint32_t* out) const;

  // Replaces one texel of the pyramid the sampler reads (both paths).
  void write_texel(int level, int32_t x, int32_t y, const Texel& t);

  SamplerStats stats() const;
  void reset_stats();
  const SamplerConfig& config() const { return config_; }
  int last_level() const { return memory_.levels() - 1; }
  int channel_bits() const { return channel_bits_; }

 private:
  SamplerConfig config_;
  BankedMipMemory memory_;
  int channel_bits_;
  int log2_w0_, log2_h0_;
  uint64_t samples_ = 0, multiplies_ = 0;
  std::vector<std::vector<uint32_t>> packed_;  // per level, row-major RGBA8 (fast path only)
};

}  // namespace tex

// The timing model's speed against the Verilated cached RTL it predicts (bench_timing.cpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"

namespace bench {

// Registers, per query set, "timing_rtl/<set>" (Vtex_cached_13x13 streaming the set's first 200k
// requests, 8 KiB caches, memory latency 100) and "timing_model/<set>" (the model's caches and
// timing layer over the same requests: TextureCache::lookup_sample, then TimedStream), both in
// clocks/s (items). Before timing, checks that both give the same clock for every response (exits
// non-zero otherwise). Returns the set names.
std::vector<std::string> register_timing_benchmarks(double min_time, const tex::Pyramid& pyramid,
                                                    const std::vector<std::pair<std::string, const std::vector<tex::Request>*>>& sets);

}  // namespace bench

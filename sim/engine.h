// An engine runs a list of requests against a pyramid: the golden model, the Verilated RTL,
// or the SystemC/TLM wrapper. All engines must return identical texels.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"

namespace tex {

struct EngineOptions {
  uint64_t seed = 1;               // for engines with random timing
  bool show_progress = false;      // progress line on a terminal
  std::string trace_path;          // FST trace (RTL engines), empty = none
  uint64_t trace_begin = 0, trace_end = 0;  // cycle window of the trace
};

struct EngineResult {
  std::vector<Texel> texels;  // one per request, in request order
  nlohmann::json stats;       // engine-specific counters, at least "samples"
};

// Names accepted by --engine.
const std::vector<std::string>& engine_names();

// Throws tex::Error for an unknown engine or one this build lacks.
EngineResult run_engine(const std::string& engine, const Pyramid& pyramid, const SamplerConfig& config,
                        const std::vector<Request>& requests, const EngineOptions& options);

EngineResult run_model(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests);

}  // namespace tex

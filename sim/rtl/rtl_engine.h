// `texsim --engine rtl`: the requests through the Verilated tex_unit, smallest configuration that
// holds the texture. Texels come back in request order and must equal the model's bit for bit.
#pragma once
#include "engine.h"
#include "rtl_harness.h"

namespace tex::rtl {

// options.seed = 0: ideal timing (a request offered and a response taken every clock);
// otherwise random input gaps and output stalls (Timing::random_default) from that seed.
EngineResult run_rtl(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                     const EngineOptions& options);

// The same with an explicit timing; for benchmarks and tests.
EngineResult run_rtl(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                     const EngineOptions& options, const Timing& timing);

}  // namespace tex::rtl

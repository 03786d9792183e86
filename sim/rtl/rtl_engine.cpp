#include "rtl_engine.h"

#include <chrono>
#include <cstdio>

#include "model/error.h"

namespace tex::rtl {

EngineResult run_rtl(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                     const EngineOptions& options) {
  return run_rtl(pyramid, config, requests, options, options.seed == 0 ? Timing::ideal() : Timing::random_default());
}

EngineResult run_rtl(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                     const EngineOptions& options, const Timing& timing) {
  const int lw = pyramid.log2_w0(), lh = pyramid.log2_h0();
  if (pyramid.levels[0].channel_bits != 8)
    throw Error("--engine rtl is built for 8-bit channels; this texture has " +
                std::to_string(pyramid.levels[0].channel_bits) + "-bit channels");
  for (const Request& r : requests)
    if (r.lod < kLodMin || r.lod > kLodMax)
      throw Error("request lod " + std::to_string(r.lod) + "/256 is outside the 16-bit Q8.8 port of the RTL");
  const RtlShape& shape = smallest_shape_for(lw, lh);

  HarnessOptions ho;
  ho.seed = options.seed;
  ho.trace_path = options.trace_path;
  ho.trace_begin = options.trace_begin;
  ho.trace_end = options.trace_end;
  auto unit = Harness::create(shape, ho);

  const auto t0 = std::chrono::steady_clock::now();
  unit->reset();
  unit->load(pyramid);
  unit->configure(cfg_pins(config, lw, lh));
  const auto t1 = std::chrono::steady_clock::now();

  EngineResult r;
  r.texels.resize(requests.size());
  const bool show = options.show_progress;
  auto progress = [&](size_t done) {
    if (show)
      std::fprintf(stderr, "\rrtl: %zu / %zu samples, clock %llu", done, requests.size(),
                   (unsigned long long)unit->cycle());
  };
  const StreamStats st = unit->stream(
      requests.data(), requests.size(), timing, options.seed ^ 0x5DEECE66DULL,
      [&](size_t i, uint64_t rgba) { r.texels[i] = unpack_rgba8(rgba); }, progress);
  if (show) std::fprintf(stderr, "\r%60s\r", "");
  const auto t2 = std::chrono::steady_clock::now();
  unit->close_trace();

  const double sample_secs = std::chrono::duration<double>(t2 - t1).count();
  r.stats = {{"engine", "rtl"},
             {"rtl_configuration", shape.name},
             {"max_texture", std::to_string(1 << shape.max_log2_w) + "x" + std::to_string(1 << shape.max_log2_h)},
             {"seed", options.seed},
             {"random_timing", options.seed != 0},
             {"samples", st.samples},
             {"cycles", st.cycles},
             {"samples_per_clock", st.cycles ? double(st.samples) / double(st.cycles) : 0.0},
             {"samples_per_ready_clock", st.ready_cycles ? double(st.samples) / double(st.ready_cycles) : 0.0},
             {"latency_cycles", st.latency_min},
             {"latency_max_cycles", st.latency_max},
             {"stall_cycles", st.stall_cycles},
             {"ready_cycles", st.ready_cycles},
             {"input_gap_cycles", st.gap_cycles},
             {"backpressure_cycles", st.backpressure_cycles},
             {"bubbles_after_fill", st.bubbles_after_fill},
             {"load_cycles", unit->load_cycles()},
             {"load_seconds", std::chrono::duration<double>(t1 - t0).count()},
             {"sample_seconds", sample_secs},
             {"simulated_clocks_per_second", sample_secs > 0 ? double(st.cycles) / sample_secs : 0.0}};
  if (!options.trace_path.empty()) r.stats["trace"] = options.trace_path;
  return r;
}

}  // namespace tex::rtl

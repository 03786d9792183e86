#include "engines/rtl/rtl_engine.h"

#include <chrono>
#include <cstdio>

#include "engines/rtl/driver.h"

namespace tex::rtl {

namespace {

class RtlEngine final : public Engine {
 public:
  explicit RtlEngine(const EngineOptions& options) : options_(options) {}

  EngineResult run(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) override {
    const RtlConfig& rc = smallest_config_for(pyramid.log2_w0(), pyramid.log2_h0(), pyramid.levels[0].channel_bits);
    check_inputs(rc, pyramid, requests);

    const auto t0 = std::chrono::steady_clock::now();
    auto unit = Driver::create(rc, DriverOptions::of(options_));
    unit->reset();
    unit->load(pyramid, options_.load);
    unit->configure(config, pyramid);
    const auto t1 = std::chrono::steady_clock::now();

    EngineResult r;
    r.texels.resize(requests.size());
    const int cw = rc.cw;
    const bool show = options_.show_progress;
    auto progress = [&](size_t done) {
      if (show)
        std::fprintf(stderr, "\rrtl: %zu / %zu samples, clock %llu", done, requests.size(),
                     (unsigned long long)unit->cycle());
    };
    const StreamStats st = stream(
        *unit, requests.data(), requests.size(), Timing::of(options_.stalls), options_.seed ^ 0x5DEECE66DULL,
        [&](size_t i, uint64_t rgba) { r.texels[i] = unpack_rgba(rgba, cw); }, progress);
    if (show) std::fprintf(stderr, "\r%60s\r", "");
    const auto t2 = std::chrono::steady_clock::now();
    unit->close_trace();

    r.stats.engine = "rtl";
    r.stats.samples = st.samples();
    r.stats.load_seconds = std::chrono::duration<double>(t1 - t0).count();
    r.stats.sample_seconds = std::chrono::duration<double>(t2 - t1).count();
    CycleStats c;
    c.configuration = rc.name;
    c.cycles = st.cycles();
    c.latency_cycles = st.protocol.latency_min;
    c.latency_max_cycles = st.protocol.latency_max;
    c.output_stall_cycles = st.protocol.output_stall_cycles;
    c.input_gap_cycles = st.gap_cycles;
    c.backpressure_cycles = st.protocol.backpressure_cycles;
    c.load_cycles = unit->load_cycles();
    r.stats.cycle = c;
    return r;
  }

 private:
  EngineOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_rtl_engine(const EngineOptions& options) { return std::make_unique<RtlEngine>(options); }

}  // namespace tex::rtl

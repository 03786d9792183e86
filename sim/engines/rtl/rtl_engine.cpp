#include "engines/rtl/rtl_engine.h"

#include <chrono>
#include <cstdio>

#include "engines/rtl/driver.h"

namespace tex::rtl {

namespace {

// Checks each request against the RTL's ports as it is read.
class CheckedSource final : public RequestSource {
 public:
  explicit CheckedSource(RequestSource& inner) : inner_(inner) {}
  size_t read(Request* out, size_t max) override {
    const size_t n = inner_.read(out, max);
    for (size_t i = 0; i < n; ++i) check_request(out[i], count_ + i);
    count_ += n;
    return n;
  }

 private:
  RequestSource& inner_;
  size_t count_ = 0;
};

class RtlEngine final : public Engine {
 public:
  explicit RtlEngine(const EngineOptions& options) : options_(options) {}

  EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    const RtlConfig& rc = smallest_config_for(pyramid.log2_w0(), pyramid.log2_h0(), pyramid.levels[0].channel_bits);
    check_inputs(rc, pyramid);

    const auto t0 = std::chrono::steady_clock::now();
    auto unit = Driver::create(rc, DriverOptions::of(options_));
    unit->reset();
    unit->load(pyramid, options_.load);
    unit->configure(config, pyramid);
    const auto t1 = std::chrono::steady_clock::now();

    CheckedSource checked(source);
    TexelQueue texels(sink);
    const int cw = rc.cw;
    const bool show = options_.show_progress;
    auto progress = [&](size_t done) {
      if (show) std::fprintf(stderr, "\rrtl: %zu samples, clock %llu", done, (unsigned long long)unit->cycle());
    };
    const StreamStats st = stream(
        *unit, checked, Timing::of(options_.stalls), options_.seed ^ 0x5DEECE66DULL,
        [&](size_t, uint64_t rgba) { texels.push(unpack_rgba(rgba, cw)); }, progress);
    texels.flush();
    if (show) std::fprintf(stderr, "\r%60s\r", "");
    const auto t2 = std::chrono::steady_clock::now();
    unit->close_trace();

    EngineStats r;
    r.engine = "rtl";
    r.samples = st.samples();
    r.load_seconds = std::chrono::duration<double>(t1 - t0).count();
    r.sample_seconds = std::chrono::duration<double>(t2 - t1).count();
    CycleStats c;
    c.configuration = rc.name;
    c.cycles = st.cycles();
    c.latency_cycles = st.protocol.latency_min;
    c.latency_max_cycles = st.protocol.latency_max;
    c.output_stall_cycles = st.protocol.output_stall_cycles;
    c.input_gap_cycles = st.gap_cycles;
    c.backpressure_cycles = st.protocol.backpressure_cycles;
    c.load_cycles = unit->load_cycles();
    r.cycle = c;
    return r;
  }

 private:
  EngineOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_rtl_engine(const EngineOptions& options) { return std::make_unique<RtlEngine>(options); }

}  // namespace tex::rtl

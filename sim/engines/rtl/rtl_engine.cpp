#include "engines/rtl/rtl_engine.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "engines/rtl/driver.h"
#include "engines/rtl/miss_checker.h"

namespace tex::rtl {

namespace {

// Checks each request against the RTL's ports and the frame's tables as it is read (the on-chip
// unit has no layer pin: its fetches are of layer 0).
class CheckedSource final : public RequestSource {
 public:
  CheckedSource(RequestSource& inner, size_t textures, size_t samplers, bool cached)
      : inner_(inner), textures_(textures), samplers_(samplers), cached_(cached) {}
  size_t read(Request* out, size_t max) override {
    const size_t n = inner_.read(out, max);
    for (size_t i = 0; i < n; ++i) {
      check_request(out[i], count_ + i);
      check_request_tables(out[i], textures_, samplers_);
      if (!cached_ && out[i].op == Op::Fetch && out[i].layer != 0)
        throw Error("request " + std::to_string(count_ + i) + ": a fetch of layer " + std::to_string(out[i].layer) +
                    ": the on-chip unit holds one 2D texture (use --memory cached for arrays)");
    }
    count_ += n;
    return n;
  }

 private:
  RequestSource& inner_;
  size_t textures_, samplers_;
  bool cached_;
  size_t count_ = 0;
};

// Cached mode: the golden model's caches look every request up as it is read (MissChecker).
class PredictingSource final : public RequestSource {
 public:
  PredictingSource(RequestSource& inner, MissChecker& checker) : inner_(inner), checker_(checker) {}
  size_t read(Request* out, size_t max) override {
    const size_t n = inner_.read(out, max);
    for (size_t i = 0; i < n; ++i) checker_.predict(out[i]);
    return n;
  }

 private:
  RequestSource& inner_;
  MissChecker& checker_;
};

class RtlEngine final : public Engine {
 public:
  explicit RtlEngine(const EngineOptions& options) : options_(options) {}

  EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    return run(TextureTable{{&pyramid}}, SamplerTable{config}, source, sink);
  }

  EngineStats run(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                  TexelSink& sink) override {
    const bool cached = options_.memory == Memory::Cached;
    check_tables(textures, samplers, options_.memory);
    const Pyramid& pyramid = *textures[0].pyramid;
    const RtlConfig& rc =
        smallest_config_for(textures, options_.memory, options_.layout.block_w, options_.layout.block_h,
                            &options_.cache, options_.fifo_depth);
    for (const BoundTexture& t : textures) {
      check_inputs(rc, *t.pyramid);
      if (t.kind == TextureKind::Cube) check_cube(rc, t);
    }
    std::optional<TextureCache> cache;
    if (cached) {
      cache_pins(rc, options_.layout, options_.cache, options_.fifo_depth);  // the geometry fits the configuration
      cache.emplace(texture_descriptors(textures, options_), options_.cache, samplers);
      cache->set_error_reads(options_.mem_error_reads);
    }

    const auto t0 = std::chrono::steady_clock::now();
    auto unit = Driver::create(rc, DriverOptions::of(options_));
    unit->reset();
    if (cached && options_.load == LoadMethod::Port)
      throw Error(rc.name + " has no texture write port: a cached unit reads its texture from memory "
                  "(use --load backdoor)");
    if (cached) {
      unit->load_textures(textures);
      unit->configure(samplers);
    } else {
      unit->load(pyramid, options_.load);
      unit->configure(samplers[0], pyramid);
    }
    const auto t1 = std::chrono::steady_clock::now();

    CheckedSource checked(source, textures.size(), samplers.size(), cached);
    std::optional<MissChecker> misses;
    std::optional<PredictingSource> predicting;
    if (cached) predicting.emplace(checked, misses.emplace(*cache, options_.miss_sink));
    RequestSource& requests = cached ? static_cast<RequestSource&>(*predicting) : checked;
    TexelQueue texels(sink);
    const bool show = options_.show_progress;
    auto progress = [&](size_t done) {
      if (misses) misses->compare(unit->memory_port()->take_reads(), false);
      if (show) std::fprintf(stderr, "\rrtl: %zu samples, clock %llu", done, (unsigned long long)unit->cycle());
    };
    std::vector<uint64_t> clocks;  // --response-clocks, a chunk at a time
    ClockSink* clock_sink = options_.clock_sink;
    const StreamStats st = stream(
        *unit, requests, Timing::of(options_.stalls), options_.seed ^ 0x5DEECE66DULL,
        [&](size_t index, uint64_t rgba) {
          texels.push(unpack_rgba(rgba, rc.cw));
          if (misses) misses->check_error(index, unit->last_response_error());
          if (clock_sink) {
            clocks.push_back(unit->counters().last_response_clock());
            if (clocks.size() == 4096) {
              clock_sink->write(clocks.data(), clocks.size());
              clocks.clear();
            }
          }
        },
        progress);
    texels.flush();
    if (clock_sink && !clocks.empty()) clock_sink->write(clocks.data(), clocks.size());
    if (misses) misses->compare(unit->memory_port()->take_reads(), true);
    if (show) std::fprintf(stderr, "\r%60s\r", "");
    const auto t2 = std::chrono::steady_clock::now();
    unit->close_trace();

    EngineStats r;
    r.engine = "rtl";
    r.samples = st.samples();
    r.load_seconds = std::chrono::duration<double>(t1 - t0).count();
    r.sample_seconds = std::chrono::duration<double>(t2 - t1).count();
    r.memory_error_samples = st.error_responses;
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
    if (cache) {
      CacheCounters k = cache_counters(*cache);
      k.fifo_max_occupancy = st.memory.fifo_max;
      k.fifo_depth = options_.fifo_depth ? options_.fifo_depth : uint32_t(rc.fifo_depth);
      k.memory_stall_cycles = st.memory.head_wait_cycles;
      r.cache = k;
    }
    return r;
  }

 private:
  EngineOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_rtl_engine(const EngineOptions& options) { return std::make_unique<RtlEngine>(options); }

}  // namespace tex::rtl

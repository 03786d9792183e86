#include "engines/rtl/rtl_engine.h"

#include <chrono>
#include <cstdio>
#include <optional>

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

// Cached mode: runs the golden model's caches on every request as it is read, and compares the
// RTL's memory reads with the model's predicted misses, one for one (then hands them to the miss
// sink). Any difference is a simulation error naming the read.
class MissChecker final : public RequestSource {
 public:
  MissChecker(RequestSource& inner, TextureCache& cache, MissSink* sink) : inner_(inner), cache_(cache), sink_(sink) {}
  size_t read(Request* out, size_t max) override {
    const size_t n = inner_.read(out, max);
    for (size_t i = 0; i < n; ++i) cache_.lookup(out[i], &predicted_);
    return n;
  }
  // The RTL's reads since the last call; at the end, every predicted miss must have been read.
  void compare(const std::vector<uint32_t>& actual, bool at_end) {
    for (uint32_t a : actual) {
      if (matched_ == predicted_.size())
        throw SimulationError("the RTL read line " + hex_address(a) + " from memory (read #" + std::to_string(done_) +
                              ") that the model's caches do not miss");
      if (predicted_[matched_] != a)
        throw SimulationError("memory read #" + std::to_string(done_) + ": the RTL read line " + hex_address(a) +
                              ", the model's caches miss line " + hex_address(predicted_[matched_]));
      ++matched_;
      ++done_;
    }
    if (sink_ && matched_) sink_->write(predicted_.data(), matched_);
    predicted_.erase(predicted_.begin(), predicted_.begin() + long(matched_));
    matched_ = 0;
    if (at_end && !predicted_.empty())
      throw SimulationError("the model's caches miss " + std::to_string(predicted_.size()) +
                            " more lines than the RTL read (first: " + hex_address(predicted_.front()) + ")");
  }

 private:
  RequestSource& inner_;
  TextureCache& cache_;
  MissSink* sink_;
  std::vector<uint32_t> predicted_;
  size_t matched_ = 0;
  uint64_t done_ = 0;
};

class RtlEngine final : public Engine {
 public:
  explicit RtlEngine(const EngineOptions& options) : options_(options) {}

  EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    const bool cached = options_.memory == Memory::Cached;
    const RtlConfig& rc = smallest_config_for(pyramid.log2_w0(), pyramid.log2_h0(), pyramid.levels[0].channel_bits,
                                              options_.memory, options_.layout.block_w, options_.layout.block_h);
    check_inputs(rc, pyramid);
    std::optional<TextureCache> cache;
    if (cached) {
      cache_pins(rc, options_.layout, options_.cache, options_.fifo_depth);  // the geometry fits the configuration
      cache.emplace(MemoryLayout(pyramid.log2_w0(), pyramid.log2_h0(), rc.cw, options_.layout), options_.cache,
                    config, pyramid.log2_w0(), pyramid.log2_h0());
    }

    const auto t0 = std::chrono::steady_clock::now();
    auto unit = Driver::create(rc, DriverOptions::of(options_));
    unit->reset();
    unit->load(pyramid, options_.load);
    unit->configure(config, pyramid);
    const auto t1 = std::chrono::steady_clock::now();

    CheckedSource checked(source);
    std::optional<MissChecker> misses;
    if (cached) misses.emplace(checked, *cache, options_.miss_sink);
    RequestSource& requests = cached ? static_cast<RequestSource&>(*misses) : checked;
    TexelQueue texels(sink);
    const int cw = rc.cw;
    const bool show = options_.show_progress;
    auto progress = [&](size_t done) {
      if (misses) misses->compare(unit->memory()->take_reads(), false);
      if (show) std::fprintf(stderr, "\rrtl: %zu samples, clock %llu", done, (unsigned long long)unit->cycle());
    };
    const StreamStats st = stream(
        *unit, requests, Timing::of(options_.stalls), options_.seed ^ 0x5DEECE66DULL,
        [&](size_t, uint64_t rgba) { texels.push(unpack_rgba(rgba, cw)); }, progress);
    texels.flush();
    if (misses) misses->compare(unit->memory()->take_reads(), true);
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

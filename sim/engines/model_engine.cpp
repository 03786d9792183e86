// The golden model's engine (model_engine.h).
#include "engines/model_engine.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <optional>

#include "engines/rtl/configs.h"
#include "model/error.h"

namespace tex {

namespace {

class ModelEngine final : public Engine {
 public:
  explicit ModelEngine(const EngineOptions& options) : options_(options) {}
  EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    return run_model(pyramid, config, source, sink, options_);
  }
  EngineStats run(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                  TexelSink& sink) override {
    return run_model(textures, samplers, source, sink, options_);
  }

 private:
  EngineOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_model_engine(const EngineOptions& options) { return std::make_unique<ModelEngine>(options); }

EngineStats run_model(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source, TexelSink& sink,
                      const EngineOptions& options) {
  return run_model(TextureTable{{&pyramid}}, SamplerTable{config}, source, sink, options);
}

UnitShape model_unit_shape(const TextureTable& textures, const EngineOptions& options, std::string& name,
                           int& beat_bytes) {
  beat_bytes = 16;
  try {
    const rtl::RtlConfig& rc =
        rtl::smallest_config_for(textures, options.memory, options.layout.block_w, options.layout.block_h,
                                 &options.cache, options.fifo_depth);
    if (options.memory == Memory::Cached) {
      rtl::cache_pins(rc, options.layout, options.cache, options.fifo_depth);
      if (options.mem_bytes_per_clock > uint32_t(rc.mem_bits / 8)) throw Error("wider than the configuration's beat");
    }
    name = rc.name;
    beat_bytes = rc.mem_bits / 8;
    return rtl::unit_shape(rc, options.fifo_depth);
  } catch (const Error&) {
    // No built configuration runs this: the design's defaults.
  }
  UnitShape shape;
  shape.cached = options.memory == Memory::Cached;
  name = "model";
  if (!shape.cached) return shape;
  const int memory_bits = textures.empty() ? 8 : textures[0].pyramid->memory_channel_bits();  // (a table has one)
  const int line = options.layout.block_w * options.layout.block_h * (memory_bits > 8 ? 8 : 4);
  beat_bytes = std::min(line, std::max(16, int(std::bit_ceil(options.mem_bytes_per_clock))));
  shape.fifo_depth = 2048;
  while (shape.fifo_depth < options.fifo_depth) shape.fifo_depth *= 2;
  shape.fifo_limit = options.fifo_depth;
  shape.miss_depth = 512;
  shape.fill_depth = 4;
  shape.line_beats = uint32_t(line / beat_bytes);
  name = "model (FIFO " + std::to_string(shape.fifo_depth) + ", miss ring 512, " + std::to_string(beat_bytes) +
         "-byte beats)";
  return shape;
}

std::unique_ptr<TimedStream> model_timing(const TextureTable& textures, const EngineOptions& options, int line_bytes,
                                          std::string& configuration) {
  int beat_bytes = 16;
  const UnitShape shape = model_unit_shape(textures, options, configuration, beat_bytes);
  std::optional<MemoryChannel> memory;
  if (shape.cached) {
    MemoryTiming m;
    m.latency = options.mem_latency;
    m.jitter = options.mem_jitter;
    m.bytes_per_clock = options.mem_bytes_per_clock;
    m.max_outstanding = options.mem_outstanding;
    m.seed = options.seed ^ 0x9E3779B97F4A7C15ULL;  // (rtl::DriverOptions::of)
    memory.emplace(line_bytes, std::min(beat_bytes, line_bytes), m);
  }
  return std::make_unique<TimedStream>(shape, memory ? &*memory : nullptr, Stimulus::of(options.stalls),
                                       options.seed ^ 0x5DEECE66DULL);  // (the RTL engine's stimulus seed)
}

EngineStats run_model(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                      TexelSink& sink, const EngineOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  check_tables(textures, samplers, options.memory);
  const bool cached = options.memory == Memory::Cached;
  bool fast = !options.count_reads;  // the fast path: 8-bit textures and samplers it takes only
  for (const BoundTexture& t : textures)  // (a cube map: the reference path)
    fast = fast && t.pyramid->levels[0].channel_bits == 8 && t.kind == TextureKind::Texture2D;
  for (const SamplerConfig& s : samplers) fast = fast && Sampler::fast_path_takes(s);
  SamplerPairs pairs(textures, samplers, fast ? SamplerPaths::FastOnly : SamplerPaths::Both);
  pairs.at(Request{});  // the first pair's set-up is part of the load, as with one texture
  std::optional<TextureCache> cache;
  if (cached) {
    cache.emplace(texture_descriptors(textures, options), options.cache, samplers);
    cache->set_error_reads(options.mem_error_reads);
  }
  std::vector<uint64_t> error_samples;  // flagged by a memory error
  uint64_t done = 0;                    // requests before this chunk
  // The timing layer: the unit model_unit_shape gives, the memory and stimulus of the RTL engine.
  std::unique_ptr<TimedStream> timed;
  std::string configuration;
  if (options.timing) timed = model_timing(textures, options, cache ? cache->line_bytes() : 0, configuration);
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<Request> requests(4096);
  std::vector<Texel> texels(requests.size());
  std::vector<uint32_t> misses;
  std::vector<uint64_t> clocks;
  std::vector<uint64_t>* keep_clocks = options.clock_sink ? &clocks : nullptr;
  auto flush_clocks = [&] {
    if (options.clock_sink && !clocks.empty()) options.clock_sink->write(clocks.data(), clocks.size());
    clocks.clear();
  };
  std::vector<uint32_t> packed(fast ? requests.size() : 0);
  uint64_t fast_samples = 0;
  while (const size_t n = source.read(requests.data(), requests.size())) {
    if (fast) {
      for (size_t i = 0, j = 0; i < n; i = j) {  // a batch per run of requests of one texture and sampler
        while (j < n && requests[j].texture == requests[i].texture && requests[j].sampler == requests[i].sampler) ++j;
        pairs.at(requests[i]).sample_rgba8(&requests[i], j - i, &packed[i]);
      }
      for (size_t i = 0; i < n; ++i)
        texels[i] = {uint16_t(packed[i] & 255), uint16_t(packed[i] >> 8 & 255), uint16_t(packed[i] >> 16 & 255),
                     uint16_t(packed[i] >> 24)};
      fast_samples += n;
    } else {
      for (size_t i = 0; i < n; ++i) texels[i] = pairs.at(requests[i]).sample(requests[i]);
    }
    if (cache) {
      misses.clear();
      for (size_t i = 0; i < n; ++i) {
        const RequestWork w = cache->lookup_sample(requests[i], options.miss_sink ? &misses : nullptr);
        if (w.error) [[unlikely]] {
          texels[i] = {};  // what the unit answers with rsp_error
          error_samples.push_back(done + i);
        }
        if (timed) timed->push(w);
      }
      if (options.miss_sink && !misses.empty()) options.miss_sink->write(misses.data(), misses.size());
    } else if (timed) {
      const Pyramid& p = *textures[0].pyramid;
      for (size_t i = 0; i < n; ++i) {
        RequestWork w;
        w.probes = uint8_t(tex_probe_count(requests[i], samplers[0], p.extent0()));
        timed->push(w);
      }
    }
    sink.write(texels.data(), n);
    done += n;
    if (timed) {
      timed->run(keep_clocks);
      flush_clocks();
    }
  }
  if (timed) {
    timed->finish(keep_clocks);
    flush_clocks();
  }
  const auto t2 = std::chrono::steady_clock::now();
  EngineStats stats;
  stats.engine = "model";
  stats.samples = fast_samples;
  stats.load_seconds = std::chrono::duration<double>(t1 - t0).count();
  stats.sample_seconds = std::chrono::duration<double>(t2 - t1).count();
  for (const Sampler* sampler : pairs.built()) {
    const SamplerStats s = sampler->stats();
    stats.samples += s.samples;
    stats.texel_reads += s.memory.reads;
    stats.multiplies_per_channel += s.multiplies_per_channel;
    if (stats.bank_reads.size() < s.memory.bank_reads.size()) stats.bank_reads.resize(s.memory.bank_reads.size());
    for (size_t k = 0; k < s.memory.bank_reads.size(); ++k)
      for (size_t b = 0; b < 4; ++b) stats.bank_reads[k][b] += s.memory.bank_reads[k][b];
  }
  if (cache) stats.cache = cache_counters(*cache);
  stats.memory_error_samples = std::move(error_samples);
  if (timed) {
    const TimingCounters t = timed->counters();
    CycleStats c;
    c.configuration = configuration;
    c.cycles = t.cycles();
    c.latency_cycles = t.latency_min;
    c.latency_max_cycles = t.latency_max;
    c.output_stall_cycles = t.output_stall_cycles;
    c.input_gap_cycles = t.gap_cycles;
    c.backpressure_cycles = t.backpressure_cycles;
    stats.cycle = c;
    if (stats.cache) {
      stats.cache->fifo_depth = timed->fifo_limit();
      stats.cache->fifo_max_occupancy = t.fifo_max;
      stats.cache->memory_stall_cycles = t.head_wait_cycles;
    }
  }
  return stats;
}

EngineResult run_model(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) {
  return run_collected(requests, [&](RequestSource& s, TexelSink& t) { return run_model(pyramid, config, s, t); });
}

}  // namespace tex

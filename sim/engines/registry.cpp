// The engines of this build and the golden model's engine.
#include <chrono>

#include "engines/engine.h"
#include "engines/rtl/rtl_engine.h"
#include "engines/systemc/systemc_engine.h"
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
  EngineStats run(const TextureTable& textures, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    return run_model(textures, config, source, sink, options_);
  }

 private:
  EngineOptions options_;
};

}  // namespace

const std::vector<EngineInfo>& engines() {
  static const std::vector<EngineInfo> list = {
      {"model", "the golden model (bit-exact executable specification)", false, false,
       [](const EngineOptions& o) -> std::unique_ptr<Engine> { return std::make_unique<ModelEngine>(o); }, true},
      {"rtl", "the Verilated RTL, cycle-accurate, smallest configuration that holds the texture", true, true,
       rtl::make_rtl_engine, true},
      {"systemc", "the Verilated RTL behind a TLM-2.0 socket (approximately timed, pipelined)", true, true,
       [](const EngineOptions& o) { return systemc::make_systemc_engine(systemc::Backend::Rtl, o); }},
      {"systemc-model", "the golden model behind the same socket (loosely timed)", false, false,
       [](const EngineOptions& o) { return systemc::make_systemc_engine(systemc::Backend::Model, o); }},
  };
  return list;
}

std::string engine_list() {
  std::string s;
  for (const EngineInfo& e : engines()) s += (s.empty() ? "" : " | ") + e.name;
  return s;
}

const EngineInfo& engine_info(const std::string& name) {
  for (const EngineInfo& e : engines())
    if (e.name == name) return e;
  throw Error("unknown engine '" + name + "' (" + engine_list() + ")");
}

std::unique_ptr<Engine> make_engine(const std::string& name, const EngineOptions& options) {
  const EngineInfo& info = engine_info(name);
  if (!options.trace_path.empty() && !info.can_trace)
    throw Error("--trace: engine " + name + " cannot write waveforms (use --engine rtl)");
  return info.make(options);
}

EngineStats run_model(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source, TexelSink& sink,
                      const EngineOptions& options) {
  return run_model(TextureTable{{&pyramid, config.wrap_u, config.wrap_v}}, config, source, sink, options);
}

EngineStats run_model(const TextureTable& textures, const SamplerConfig& config, RequestSource& source,
                      TexelSink& sink, const EngineOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (textures.empty() || textures.size() > size_t(kMaxTextures))
    throw Error(std::to_string(textures.size()) + " textures: the descriptor table holds 1 to " +
                std::to_string(kMaxTextures));
  if (textures.size() > 1 && options.memory != Memory::Cached)
    throw Error(std::to_string(textures.size()) + " textures: the on-chip unit holds one texture (the paper's design); "
                "use --memory cached, whose descriptor table holds up to " + std::to_string(kMaxTextures));
  std::vector<Sampler> samplers;  // one per descriptor-table entry, with its wrap modes
  for (const BoundTexture& t : textures) {
    SamplerConfig c = config;
    c.wrap_u = t.wrap_u;
    c.wrap_v = t.wrap_v;
    samplers.emplace_back(*t.pyramid, c);
  }
  std::optional<TextureCache> cache;
  if (options.memory == Memory::Cached) cache.emplace(texture_descriptors(textures, options), options.cache, config);
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<Request> requests(4096);
  std::vector<Texel> texels(requests.size());
  std::vector<uint32_t> misses;
  while (const size_t n = source.read(requests.data(), requests.size())) {
    for (size_t i = 0; i < n; ++i) {
      if (requests[i].texture >= samplers.size())
        throw Error("request " + std::to_string(requests[i].tag) + " names texture " +
                    std::to_string(requests[i].texture) + "; the table holds " + std::to_string(samplers.size()));
      texels[i] = samplers[requests[i].texture].sample(requests[i]);
    }
    sink.write(texels.data(), n);
    if (cache) {
      misses.clear();
      for (size_t i = 0; i < n; ++i) cache->lookup_sample(requests[i], options.miss_sink ? &misses : nullptr);
      if (options.miss_sink && !misses.empty()) options.miss_sink->write(misses.data(), misses.size());
    }
  }
  const auto t2 = std::chrono::steady_clock::now();
  EngineStats stats;
  stats.engine = "model";
  stats.load_seconds = std::chrono::duration<double>(t1 - t0).count();
  stats.sample_seconds = std::chrono::duration<double>(t2 - t1).count();
  for (const Sampler& sampler : samplers) {
    const SamplerStats s = sampler.stats();
    stats.samples += s.samples;
    stats.texel_reads += s.memory.reads;
    stats.multiplies_per_channel += s.multiplies_per_channel;
    if (stats.bank_reads.size() < s.memory.bank_reads.size()) stats.bank_reads.resize(s.memory.bank_reads.size());
    for (size_t k = 0; k < s.memory.bank_reads.size(); ++k)
      for (size_t b = 0; b < 4; ++b) stats.bank_reads[k][b] += s.memory.bank_reads[k][b];
  }
  if (cache) stats.cache = cache_counters(*cache);
  return stats;
}

EngineResult run_model(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) {
  return run_collected(requests, [&](RequestSource& s, TexelSink& t) { return run_model(pyramid, config, s, t); });
}

}  // namespace tex

#include "engines/engine.h"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace tex {

namespace {

template <class E>
bool parse_named(const std::vector<std::string>& names, const std::string& name, E& out) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) {
      out = E(i);
      return true;
    }
  return false;
}

const std::vector<std::string>& load_names() {
  static const std::vector<std::string> n = {"backdoor", "port"};
  return n;
}

}  // namespace

const std::vector<std::string>& memory_names() {
  static const std::vector<std::string> n = {"onchip", "cached"};
  return n;
}
bool parse_memory(const std::string& name, Memory& out) { return parse_named(memory_names(), name, out); }
std::string memory_name(Memory m) { return memory_names()[size_t(m)]; }

const std::vector<std::string>& stalls_names() {
  static const std::vector<std::string> n = {"none", "random", "heavy"};
  return n;
}
bool parse_stalls(const std::string& name, Stalls& out) { return parse_named(stalls_names(), name, out); }
std::string stalls_name(Stalls s) { return stalls_names()[size_t(s)]; }
bool parse_load_method(const std::string& name, LoadMethod& out) { return parse_named(load_names(), name, out); }
std::string load_method_name(LoadMethod m) { return load_names()[size_t(m)]; }

CacheCounters cache_counters(const TextureCache& cache) {
  CacheCounters k;
  k.lookups = cache.stats().total_lookups();
  k.hits = cache.stats().total_hits();
  k.misses = cache.stats().total_misses();
  k.cache_lookups = cache.stats().lookups;
  k.cache_hits = cache.stats().hits;
  k.memory_read_bytes = cache.memory_read_bytes();
  return k;
}

nlohmann::json EngineStats::to_json(const EngineOptions& options) const {
  nlohmann::json j = {{"engine", engine},
                      {"samples", samples},
                      {"load_seconds", load_seconds},
                      {"sample_seconds", sample_seconds},
                      {"parse_seconds", parse_seconds},
                      {"write_seconds", write_seconds},
                      {"samples_per_second", sample_seconds > 0 ? double(samples) / sample_seconds : 0.0}};
  j["memory"] = memory_name(options.memory);
  if (!options.mem_error_reads.empty()) j["mem_error_reads"] = options.mem_error_reads;
  if (!options.mem_error_reads.empty() || !memory_error_samples.empty()) {  // (cached mode: rsp_error)
    j["memory_error_samples"] = memory_error_samples.size();
    j["memory_error_sample_indices"] = memory_error_samples;
  }
  if (!format.empty()) j["format"] = format;
  if (probes) {
    const std::vector<uint64_t> by_n(probes->begin() + 1, probes->end());  // [N - 1]: samples of N probes
    j["probes_per_sample"] = by_n;
    j["probes"] = probe_total();
    j["mean_probes_per_sample"] = samples ? double(probe_total()) / double(samples) : 0.0;
  }
  if (cache) {
    j["cache_kib"] = options.cache.size_bytes / 1024.0;
    j["ways"] = options.cache.ways;
    j["block"] = std::to_string(options.layout.block_w) + "x" + std::to_string(options.layout.block_h);
    j["block_order"] = block_order_name(options.layout.order);
    j["cache_lookups"] = cache->lookups;
    j["cache_hits"] = cache->hits;
    j["cache_lookups_per_cache"] = cache->cache_lookups;
    j["cache_hits_per_cache"] = cache->cache_hits;
    j["cache_misses"] = cache->misses;
    j["hit_rate"] = cache->lookups ? double(cache->hits) / double(cache->lookups) : 0.0;
    for (int c = 0; c < 2; ++c)
      j[c == 0 ? "hit_rate_even_levels" : "hit_rate_odd_levels"] =
          cache->cache_lookups[c] ? double(cache->cache_hits[c]) / double(cache->cache_lookups[c]) : 0.0;
    j["memory_read_bytes"] = cache->memory_read_bytes;
    j["bytes_per_sample"] = samples ? double(cache->memory_read_bytes) / double(samples) : 0.0;
    if (cycle) {
      j["mem_latency"] = options.mem_latency;
      j["mem_jitter"] = options.mem_jitter;
      j["mem_bytes_per_clock"] = options.mem_bytes_per_clock;
      j["mem_outstanding"] = options.mem_outstanding;
      j["fifo_depth"] = cache->fifo_depth;
      j["fifo_max_occupancy"] = cache->fifo_max_occupancy;
      j["memory_stall_cycles"] = cache->memory_stall_cycles;
    }
  }
  if (cycle) {
    j["configuration"] = cycle->configuration;
    j["stalls"] = stalls_name(options.stalls);
    j["seed"] = options.seed;
    j["load"] = load_method_name(options.load);
    j["cycles"] = cycle->cycles;
    j["samples_per_clock"] = samples_per_clock();
    j["latency_cycles"] = cycle->latency_cycles;
    j["latency_max_cycles"] = cycle->latency_max_cycles;
    j["output_stall_cycles"] = cycle->output_stall_cycles;
    j["input_gap_cycles"] = cycle->input_gap_cycles;
    j["backpressure_cycles"] = cycle->backpressure_cycles;
    j["load_cycles"] = cycle->load_cycles;
    j["clocks_per_second"] = sample_seconds > 0 ? double(cycle->cycles) / sample_seconds : 0.0;
    if (!options.trace_path.empty()) j["trace"] = options.trace_path;
  }
  if (!cycle || !bank_reads.empty()) {  // the golden model's counters (also beside its timing layer)
    j["texel_reads"] = texel_reads;
    j["multiplies_per_channel"] = multiplies_per_channel;
    j["bank_reads"] = bank_reads;
  }
  return j;
}

uint64_t EngineStats::probe_total() const {
  uint64_t total = 0;
  if (probes)
    for (size_t n = 1; n < probes->size(); ++n) total += n * (*probes)[n];
  return total;
}

EngineStats EngineStats::from_json(const nlohmann::json& j) {
  EngineStats s;
  s.engine = j.at("engine").get<std::string>();
  s.samples = j.at("samples").get<uint64_t>();
  s.load_seconds = j.at("load_seconds").get<double>();
  s.sample_seconds = j.at("sample_seconds").get<double>();
  if (j.contains("memory_error_sample_indices"))
    s.memory_error_samples = j.at("memory_error_sample_indices").get<std::vector<uint64_t>>();
  if (j.contains("cycles")) {
    CycleStats c;
    c.configuration = j.at("configuration").get<std::string>();
    c.cycles = j.at("cycles").get<uint64_t>();
    c.latency_cycles = j.at("latency_cycles").get<uint64_t>();
    c.latency_max_cycles = j.at("latency_max_cycles").get<uint64_t>();
    c.output_stall_cycles = j.at("output_stall_cycles").get<uint64_t>();
    c.input_gap_cycles = j.at("input_gap_cycles").get<uint64_t>();
    c.backpressure_cycles = j.at("backpressure_cycles").get<uint64_t>();
    c.load_cycles = j.at("load_cycles").get<uint64_t>();
    s.cycle = c;
    if (j.contains("cache_lookups")) {
      CacheCounters k;
      k.lookups = j.at("cache_lookups").get<uint64_t>();
      k.hits = j.at("cache_hits").get<uint64_t>();
      k.cache_lookups = j.at("cache_lookups_per_cache").get<std::array<uint64_t, 2>>();
      k.cache_hits = j.at("cache_hits_per_cache").get<std::array<uint64_t, 2>>();
      k.misses = j.at("cache_misses").get<uint64_t>();
      k.memory_read_bytes = j.at("memory_read_bytes").get<uint64_t>();
      k.fifo_depth = j.at("fifo_depth").get<uint32_t>();
      k.fifo_max_occupancy = j.at("fifo_max_occupancy").get<uint32_t>();
      k.memory_stall_cycles = j.at("memory_stall_cycles").get<uint64_t>();
      s.cache = k;
    }
  } else {
    s.texel_reads = j.at("texel_reads").get<uint64_t>();
    s.multiplies_per_channel = j.at("multiplies_per_channel").get<uint64_t>();
    s.bank_reads = j.at("bank_reads").get<std::vector<std::array<uint64_t, 4>>>();
  }
  return s;
}

size_t ProbeCounter::read(Request* out, size_t max) {
  const size_t n = source_.read(out, max);
  for (size_t i = 0; i < n; ++i) {
    check_request_tables(out[i], sizes_.size(), samplers_.size());
    ++histogram_[size_t(tex_probe(out[i], samplers_[out[i].sampler], sizes_[out[i].texture]).n)];
  }
  return n;
}

EngineResult run_collected(const std::vector<Request>& requests,
                           const std::function<EngineStats(RequestSource&, TexelSink&)>& run) {
  VectorSource source(requests);
  VectorSink sink;
  sink.texels.reserve(requests.size());
  EngineResult r;
  r.stats = run(source, sink);
  r.texels = std::move(sink.texels);
  return r;
}

void check_tables(const TextureTable& textures, const SamplerTable& samplers, Memory memory) {
  if (textures.empty() || textures.size() > size_t(kMaxTextures))
    throw Error(std::to_string(textures.size()) + " textures: the descriptor table holds 1 to " +
                std::to_string(kMaxTextures));
  if (samplers.empty() || samplers.size() > size_t(kMaxSamplers))
    throw Error(std::to_string(samplers.size()) + " samplers: the sampler table holds 1 to " +
                std::to_string(kMaxSamplers));
  if (textures.size() > 1 && memory != Memory::Cached)
    throw Error(std::to_string(textures.size()) + " textures: the on-chip unit holds one texture (the paper's design); "
                "use --memory cached, whose descriptor table holds up to " + std::to_string(kMaxTextures));
  if (samplers.size() > 1 && memory != Memory::Cached)
    throw Error(std::to_string(samplers.size()) + " samplers: the on-chip unit has one sampler; "
                "use --memory cached, whose sampler table holds up to " + std::to_string(kMaxSamplers));
  if (textures[0].layers() > 1 && memory != Memory::Cached)
    throw Error(std::string(textures[0].kind == TextureKind::Cube ? "a cube map" : "an array") + " of " +
                std::to_string(textures[0].layers()) +
                " layers: the on-chip unit holds one 2D texture (the paper's per-level memories); use --memory cached");
  for (const BoundTexture& t : textures)
    if (t.layers() > kMaxLayers)
      throw Error("an array of " + std::to_string(t.layers()) + " layers: a texture has 1 to " + std::to_string(kMaxLayers));
}

void check_request_tables(const Request& r, size_t textures, size_t samplers) {
  if (r.texture >= textures)
    throw Error("request " + std::to_string(r.tag) + " names texture " + std::to_string(r.texture) +
                "; the table holds " + std::to_string(textures));
  if (r.sampler >= samplers)
    throw Error("request " + std::to_string(r.tag) + " names sampler " + std::to_string(r.sampler) +
                "; the table holds " + std::to_string(samplers));
}

SamplerPairs::SamplerPairs(const TextureTable& textures, const SamplerTable& samplers, SamplerPaths paths)
    : textures_(textures), samplers_(samplers), paths_(paths), pairs_(textures.size() * samplers.size()) {
  check_tables(textures, samplers, Memory::Cached);
}

void SamplerPairs::write_texel(int texture, int level, int x, int y, const Texel& t, int layer) {
  for (size_t s = 0; s < samplers_.size(); ++s)
    if (Sampler* p = pairs_[size_t(texture) * samplers_.size() + s].get()) p->write_texel(level, x, y, t, layer);
}

std::vector<const Sampler*> SamplerPairs::built() const {
  std::vector<const Sampler*> out;
  for (const auto& p : pairs_)
    if (p) out.push_back(p.get());
  return out;
}

std::vector<TextureDescriptor> texture_descriptors(const TextureTable& textures, const EngineOptions& options) {
  if (textures.empty() || textures.size() > size_t(kMaxTextures))
    throw Error(std::to_string(textures.size()) + " textures: the descriptor table holds 1 to " +
                std::to_string(kMaxTextures));
  std::vector<Extent> sizes;
  std::vector<TexelFormat> formats;
  std::vector<int> levels, layers;
  std::vector<TextureKind> kinds;
  const int bits = textures[0].pyramid->memory_channel_bits();
  for (const BoundTexture& t : textures) {
    if (t.pyramid->memory_channel_bits() != bits)
      throw Error("textures of one frame must have the same channel width in memory (" + std::to_string(bits) +
                  " and " + std::to_string(t.pyramid->memory_channel_bits()) + " bits)");
    sizes.push_back(t.pyramid->extent0());
    formats.push_back(t.pyramid->format);
    levels.push_back(int(t.pyramid->levels.size()));
    layers.push_back(t.layers());
    kinds.push_back(t.kind);
  }
  const std::vector<MemoryLayout> layouts = pack_layouts(sizes, bits, options.layout, formats, levels, layers, kinds);
  std::vector<TextureDescriptor> out;
  for (size_t i = 0; i < textures.size(); ++i) out.push_back({layouts[i]});
  return out;
}

std::vector<uint8_t> frame_memory_image(const TextureTable& textures, const std::vector<TextureDescriptor>& descriptors) {
  std::vector<uint8_t> image;
  for (size_t i = 0; i < textures.size(); ++i) {
    const std::vector<uint8_t> bytes = build_memory_image(textures[i].all_layers(), descriptors[i].layout);
    image.insert(image.end(), bytes.begin(), bytes.end());  // packed: each starts where the last ended
  }
  return image;
}

EngineResult Engine::run(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) {
  return run_collected(requests, [&](RequestSource& s, TexelSink& t) { return run(pyramid, config, s, t); });
}

}  // namespace tex

#include "cli/sampling.h"

#include <bit>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <deque>
#include <optional>

namespace tex {

void ClockWriter::write(const uint64_t* clocks, size_t n) {
  std::string text(n * 21, '\0');  // 20 digits at most, and the newline
  char* p = text.data();
  for (size_t i = 0; i < n; ++i) {
    p = std::to_chars(p, p + 20, clocks[i]).ptr;
    *p++ = '\n';
  }
  std::fwrite(text.data(), 1, size_t(p - text.data()), file_);
}

namespace {

// --verify: the golden model samples every request as the engine takes it, and every texel the
// engine returns must equal the model's (0 for a sample its caches flag with a memory error).
class Verifier {
 public:
  Verifier(const TextureTable& textures, const SamplerTable& samplers, const EngineOptions& options,
           RequestSource& source, TexelSink& sink, std::string engine)
      : samplers_(textures, samplers), source_(*this, source), sink_(*this, sink), engine_(std::move(engine)) {
    if (!options.mem_error_reads.empty()) {
      cache_.emplace(texture_descriptors(textures, options), options.cache, samplers);
      cache_->set_error_reads(options.mem_error_reads);
    }
  }
  RequestSource& source() { return source_; }
  TexelSink& sink() { return sink_; }
  size_t checked() const { return checked_; }

 private:
  struct Source final : RequestSource {
    Source(Verifier& v, RequestSource& inner) : v(v), inner(inner) {}
    size_t read(Request* out, size_t max) override {
      const size_t n = inner.read(out, max);
      for (size_t i = 0; i < n; ++i) {
        const bool error = v.cache_ && v.cache_->lookup_sample(out[i], nullptr).error;
        v.expected_.push_back(error ? Texel{} : v.samplers_.at(out[i]).sample(out[i]));
      }
      return n;
    }
    Verifier& v;
    RequestSource& inner;
  };
  struct Sink final : TexelSink {
    Sink(Verifier& v, TexelSink& inner) : v(v), inner(inner) {}
    void write(const Texel* t, size_t n) override {
      for (size_t i = 0; i < n; ++i, ++v.checked_) {
        if (v.expected_.empty()) throw SimulationError("verify: engine " + v.engine_ + " returned more samples than requests");
        const Texel b = v.expected_.front();
        v.expected_.pop_front();
        if (t[i] != b)
          throw SimulationError("verify: sample " + std::to_string(v.checked_) + " differs: engine " + v.engine_ +
                                " gives " + texel_text(t[i]) + ", model gives " + texel_text(b));
      }
      inner.write(t, n);
    }
    static std::string texel_text(const Texel& t) {
      return std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) + "," + std::to_string(t[3]);
    }
    Verifier& v;
    TexelSink& inner;
  };
  SamplerPairs samplers_;  // the model's sampler of each (texture, sampler) pair
  std::optional<TextureCache> cache_;  // memory errors: the samples they flag
  Source source_;
  Sink sink_;
  std::string engine_;
  std::deque<Texel> expected_;
  size_t checked_ = 0;
};

// Time spent in a source's read() and a sink's write(), to take out of the engine's sampling time.
struct TimedSource final : RequestSource {
  explicit TimedSource(RequestSource& inner) : inner(inner) {}
  size_t read(Request* out, size_t max) override {
    const auto t0 = std::chrono::steady_clock::now();
    const size_t n = inner.read(out, max);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return n;
  }
  RequestSource& inner;
  double seconds = 0;
};
struct TimedSink final : TexelSink {
  explicit TimedSink(TexelSink& inner) : inner(inner) {}
  void write(const Texel* t, size_t n) override {
    const auto t0 = std::chrono::steady_clock::now();
    inner.write(t, n);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  TexelSink& inner;
  double seconds = 0;
};

}  // namespace

// The samples flagged by --mem-error-at, as the run's error: the reads, how many samples, the first ones.
static Error memory_error(const EngineStats& stats, const EngineOptions& eo) {
  std::string reads, samples;
  for (const uint64_t r : eo.mem_error_reads) reads += (reads.empty() ? "" : ", ") + std::to_string(r);
  const size_t n = stats.memory_error_samples.size(), shown = std::min<size_t>(n, 10);
  for (size_t i = 0; i < shown; ++i) samples += (i ? ", " : "") + std::to_string(stats.memory_error_samples[i]);
  return Error("memory error: line read" + std::string(eo.mem_error_reads.size() > 1 ? "s " : " ") + reads +
               " answered SLVERR; " + std::to_string(n) + " sample" + (n == 1 ? "" : "s") + " flagged (request " +
               samples + (n > shown ? ", ..." : "") + ", counted from 0 in request order); engine " + stats.engine +
               ", no output written");
}

EngineStats run_engine(const SamplingOptions& o, const EngineOptions& eo, OutputSet& outputs, OutputFile* trace,
                       const TextureTable& textures, const SamplerTable& samplers, RequestSource& input,
                       TexelSink& output) {
  const auto engine = make_engine(o.engine, eo);
  TimedSource source(input);
  TimedSink sink(output);
  // The anisotropic filter: count each request's probes on the way in.
  std::optional<ProbeCounter> counter;
  if (std::any_of(samplers.begin(), samplers.end(), [](const SamplerConfig& s) { return s.filter.anisotropic; })) {
    std::vector<Extent> sizes;
    for (const BoundTexture& t : textures) sizes.push_back(t.pyramid->extent0());
    counter.emplace(source, samplers, sizes);
  }
  RequestSource& requests = counter ? static_cast<RequestSource&>(*counter) : source;
  try {
    EngineStats stats;
    if (!o.verify) {
      stats = engine->run(textures, samplers, requests, sink);
    } else {
      Verifier verifier(textures, samplers, eo, requests, sink, o.engine);
      stats = engine->run(textures, samplers, verifier.source(), verifier.sink());
      std::printf("verify: %zu samples of engine %s are bit-identical to the golden model\n", verifier.checked(),
                  o.engine.c_str());
    }
    if (counter) stats.probes = counter->histogram();
    if (!stats.memory_error_samples.empty()) throw memory_error(stats, eo);
    if (!eo.mem_error_reads.empty() && stats.cache && stats.cache->misses < eo.mem_error_reads.back())
      std::fprintf(stderr, "texsim: --mem-error-at %llu: the run read only %llu lines from memory\n",
                   (unsigned long long)eo.mem_error_reads.back(), (unsigned long long)stats.cache->misses);
    std::vector<std::string> formats;  // the table's, each once, in table order
    for (const BoundTexture& t : textures) {
      const std::string name = std::string(format_info(t.pyramid->format).name) + (t.pyramid->srgb ? "_srgb" : "");
      if (std::find(formats.begin(), formats.end(), name) == formats.end()) formats.push_back(name);
    }
    stats.format.clear();
    for (const std::string& f : formats) stats.format += (stats.format.empty() ? "" : ",") + f;
    // The engine alone: without waiting for the requests and writing the results.
    stats.sample_seconds = std::max(0.0, stats.sample_seconds - source.seconds - sink.seconds);
    stats.parse_seconds = source.seconds;
    stats.write_seconds = sink.seconds;
    return stats;
  } catch (const SimulationError& e) {
    if (trace && outputs.keep(*trace)) throw Error(std::string(e.what()) + "; waveform kept: " + trace->path());
    throw;
  }
}

// Cycle counters of a cycle-accurate engine, one line (the model has none).
void print_cycle_stats(const EngineStats& stats, const EngineOptions& options) {
  if (!stats.cycle) return;
  const CycleStats& c = *stats.cycle;
  std::printf("  %s (%s): %llu samples in %llu clocks = %.4f samples/clock after the %llu-clock pipeline fill, "
              "stalls %s, %llu output-stall clocks, texture load %s (%llu clocks)\n",
              stats.engine.c_str(), c.configuration.c_str(), (unsigned long long)stats.samples,
              (unsigned long long)c.cycles, stats.samples_per_clock(), (unsigned long long)c.latency_cycles,
              stalls_name(options.stalls).c_str(), (unsigned long long)c.output_stall_cycles,
              load_method_name(options.load).c_str(), (unsigned long long)c.load_cycles);
}

// Anisotropic filter: probes per sample (mean and histogram) and, for cycle engines, per clock.
void print_probe_stats(const EngineStats& stats) {
  if (!stats.probes) return;
  const auto& h = *stats.probes;
  const uint64_t total = stats.probe_total();
  std::string histogram;
  for (size_t n = 1; n < h.size(); ++n)
    if (h[n]) histogram += " " + std::to_string(n) + ":" + std::to_string(h[n]);
  std::printf("  probes: %llu = %.3f per sample (N:samples%s)", (unsigned long long)total,
              stats.samples ? double(total) / double(stats.samples) : 0.0, histogram.c_str());
  if (stats.cycle && stats.cycle->cycles > stats.cycle->latency_cycles)
    std::printf(", %.4f probes/clock", double(total) / double(stats.cycle->cycles - stats.cycle->latency_cycles));
  std::printf("\n");
}

// Cached mode: hits, bytes and (cycle engines) the FIFO and memory stalls, one line.
void print_cache_stats(const EngineStats& stats) {
  if (!stats.cache) return;
  const CacheCounters& k = *stats.cache;
  std::printf("  caches: %llu lookups, %.2f%% hits, %llu lines read = %.2f bytes/sample",
              (unsigned long long)k.lookups, k.lookups ? 100.0 * double(k.hits) / double(k.lookups) : 0.0,
              (unsigned long long)k.misses, stats.samples ? double(k.memory_read_bytes) / double(stats.samples) : 0.0);
  if (stats.cycle)
    std::printf(", FIFO up to %u of %u samples, %llu clocks waiting for memory", k.fifo_max_occupancy, k.fifo_depth,
                (unsigned long long)k.memory_stall_cycles);
  std::printf("\n");
}

// The process's peak resident memory (VmHWM: this program's, not the parent's it was forked
// from, which getrusage's maxrss includes); 0 where /proc does not say.
static uint64_t peak_memory_bytes() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  unsigned long long kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %llu kB", &kib) == 1) break;
  std::fclose(f);
  return uint64_t(kib) * 1024;
}

void write_stats(OutputFile* out, const EngineStats& stats, const EngineOptions& options, double seconds,
                 const nlohmann::json& extra) {
  if (!out) return;
  nlohmann::json j = stats.to_json(options);
  j["wall_seconds"] = seconds;
  j["peak_memory_bytes"] = peak_memory_bytes();
  j.update(extra);
  std::fputs((j.dump(2) + "\n").c_str(), out->open());
  out->close();
}
void LineSet::write(const uint32_t* addresses, size_t n) {
  lines_.insert(addresses, addresses + n);
  if (next_) next_->write(addresses, n);
}

void FrameFigures::add(const FrameFigures& f) {
  samples += f.samples;
  quads += f.quads;
  helper_samples += f.helper_samples;
  textures_used |= f.textures_used;
  texture_bytes_resident = std::max(texture_bytes_resident, f.texture_bytes_resident);
  if (f.cache) {
    CacheCounters& k = cache ? *cache : cache.emplace();
    k.lookups += f.cache->lookups;
    k.hits += f.cache->hits;
    k.misses += f.cache->misses;
    k.memory_read_bytes += f.cache->memory_read_bytes;
    for (int c = 0; c < 2; ++c) {
      k.cache_lookups[c] += f.cache->cache_lookups[c];
      k.cache_hits[c] += f.cache->cache_hits[c];
    }
    k.memory_stall_cycles += f.cache->memory_stall_cycles;
  }
  if (f.clocks) clocks = clocks.value_or(0) + *f.clocks;
}

namespace {
double ratio(uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0.0; }
}  // namespace

nlohmann::json FrameFigures::to_json() const {
  nlohmann::json j = {{"samples", samples},
                      {"quads", quads},
                      {"helper_samples", helper_samples},
                      {"textures_used", std::popcount(textures_used)},
                      {"texture_bytes_resident", texture_bytes_resident}};
  if (cache) {
    j["texture_bytes_touched"] = texture_bytes_touched;
    j["hit_rate_even_levels"] = ratio(cache->cache_hits[0], cache->cache_lookups[0]);
    j["hit_rate_odd_levels"] = ratio(cache->cache_hits[1], cache->cache_lookups[1]);
    j["hit_rate"] = ratio(cache->hits, cache->lookups);
    j["bytes_per_sample"] = ratio(cache->memory_read_bytes, samples);
  }
  if (clocks) j["samples_per_clock"] = ratio(samples, *clocks);
  return j;
}

std::string FrameFigures::summary() const {
  char buf[512];
  int n = std::snprintf(buf, sizeof buf, "%llu samples in %llu quads (%llu helpers), %d textures of %.2f MiB",
                        (unsigned long long)samples, (unsigned long long)quads, (unsigned long long)helper_samples,
                        std::popcount(textures_used), double(texture_bytes_resident) / 1048576.0);
  if (cache)
    n += std::snprintf(buf + n, sizeof buf - size_t(n),
                       ", %.2f MiB touched, hits %.2f%% even / %.2f%% odd levels, %.2f bytes/sample",
                       double(texture_bytes_touched) / 1048576.0, 100 * ratio(cache->cache_hits[0], cache->cache_lookups[0]),
                       100 * ratio(cache->cache_hits[1], cache->cache_lookups[1]), ratio(cache->memory_read_bytes, samples));
  if (clocks) std::snprintf(buf + n, sizeof buf - size_t(n), ", %.4f samples/clock", ratio(samples, *clocks));
  return buf;
}

FrameFigures frame_figures(const QueryCounts& counts, const EngineStats& stats, uint64_t resident, uint64_t touched) {
  FrameFigures f;
  f.samples = counts.samples;
  f.quads = counts.quads;
  f.helper_samples = counts.helper_samples;
  f.textures_used = counts.textures_used;
  f.texture_bytes_resident = resident;
  f.texture_bytes_touched = touched;
  f.cache = stats.cache;
  if (stats.cycle) f.clocks = stats.cycle->cycles - std::min(stats.cycle->cycles, stats.cycle->latency_cycles);
  return f;
}

int line_bytes(const TextureTable& textures, const EngineOptions& options) {
  const int texel_bytes = textures.at(0).pyramid->memory_channel_bits() > 8 ? 8 : 4;
  return options.layout.block_w * options.layout.block_h * texel_bytes;
}

uint64_t texture_bytes_resident(const TextureTable& textures, const EngineOptions& options) {
  uint64_t bytes = 0;
  if (options.memory == Memory::Cached) {
    for (const TextureDescriptor& d : texture_descriptors(textures, options)) bytes += d.layout.image_bytes();
    return bytes;
  }
  for (const BoundTexture& t : textures)
    for (const Image& level : t.pyramid->levels)
      bytes += uint64_t(level.width) * uint64_t(level.height) * (level.channel_bits > 8 ? 8 : 4);
  return bytes;
}

}  // namespace tex

// An engine runs a list of requests against a pyramid: the golden model, the Verilated RTL, or the
// RTL / the model behind the SystemC/TLM-2.0 socket. Every engine returns the same texels, in
// request order; cycle-accurate engines also count clocks. Statistics are typed (EngineStats);
// JSON is only their output format (to_json), with the same key for the same quantity everywhere.
#pragma once
#include <nlohmann/json_fwd.hpp>  // (json.hpp where a JSON value is built or read: 2 s a file)
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/error.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"
#include "model/timing.h"
#include "engines/streams.h"

namespace tex {

// Stimulus timing of cycle-accurate engines (tex::Stalls, model/timing.h).
const std::vector<std::string>& stalls_names();
bool parse_stalls(const std::string& name, Stalls& out);
std::string stalls_name(Stalls s);

// How a cycle-accurate engine fills its texture memories: `backdoor` writes them directly (0 clocks),
// `port` simulates the write port (one texel per clock).
enum class LoadMethod { Backdoor, Port };
bool parse_load_method(const std::string& name, LoadMethod& out);
std::string load_method_name(LoadMethod m);

// Memory organisation (docs/memory.md): `onchip` per-level memories, or `cached`: the pyramid in
// external memory behind two texture caches.
enum class Memory { OnChip, Cached };
bool parse_memory(const std::string& name, Memory& out);
std::string memory_name(Memory m);

// Receives the line addresses a cached engine reads from memory, in order (--miss-trace).
class MissSink {
 public:
  virtual ~MissSink() = default;
  virtual void write(const uint32_t* addresses, size_t n) = 0;
};

// Receives the clock of every response, in order (--response-clocks): the clock of its handshake,
// counted from the clock in which the first request was offered.
class ClockSink {
 public:
  virtual ~ClockSink() = default;
  virtual void write(const uint64_t* clocks, size_t n) = 0;
};

struct EngineOptions {
  Stalls stalls = Stalls::None;
  uint64_t seed = 1;  // random stalls; the RTL's registers without reset start from it too
  LoadMethod load = LoadMethod::Backdoor;
  bool show_progress = false;  // progress line on stderr (a terminal)
  std::string trace_path;      // FST waveform, empty = none (engines with can_trace)
  uint64_t trace_begin = 0, trace_end = 0;  // clock window of the trace; end 0 = to the end
  // Memory hierarchy: organisation, layout in memory, caches, and the external memory's timing.
  Memory memory = Memory::OnChip;
  LayoutParams layout;
  CacheParams cache;
  uint32_t mem_latency = 100, mem_jitter = 0, mem_bytes_per_clock = 16, mem_outstanding = 64;
  uint32_t fifo_depth = 0;  // rtl: samples the FIFO holds at most; 0 = the configuration's FIFO_DEPTH
  // cached: line reads (1 = the first, in miss order) that memory answers with SLVERR, ascending
  // (--mem-error-at); the samples that look such a line up come out flagged, as 0.
  std::vector<uint64_t> mem_error_reads;
  MissSink* miss_sink = nullptr;  // cached: the line addresses read from memory, in order
  ClockSink* clock_sink = nullptr;  // cycle-accurate and timed engines: each response's clock
  bool timing = true;  // model: clock the timing model (model/timing.h) too: cycle counters, response clocks
  // model: count texel reads, multiplies and bank reads (the reference path); false: 8-bit textures
  // go through the fast path (Sampler::sample_rgba8, the same texels, about 3x faster).
  bool count_reads = true;
};

// Cached mode: what the caches and the memory did (every engine; timing ones from cycle engines).
struct CacheCounters {
  uint64_t lookups = 0, hits = 0, misses = 0;
  std::array<uint64_t, 2> cache_lookups{}, cache_hits{};  // per cache: 0 even levels, 1 odd levels
  uint64_t memory_read_bytes = 0;
  uint32_t fifo_depth = 0;          // cycle-accurate engines only: the FIFO depth in use
  uint32_t fifo_max_occupancy = 0;  // cycle-accurate engines only
  uint64_t memory_stall_cycles = 0; // the FIFO's head waits for memory, the output ready (cycle engines)
};
// The model caches' counters (the timing ones stay 0).
CacheCounters cache_counters(const TextureCache& cache);

// Counters of a cycle-accurate engine (the sampling phase; clocks are rising edges).
struct CycleStats {
  uint64_t cycles = 0;               // first clock a request is offered .. last response, inclusive
  uint64_t latency_cycles = 0;       // least request -> response handshake distance
  uint64_t latency_max_cycles = 0;
  uint64_t output_stall_cycles = 0;  // a response waits: rsp_valid && !rsp_ready
  uint64_t input_gap_cycles = 0;     // no request offered while some remain
  uint64_t backpressure_cycles = 0;  // a request waits: req_valid && !req_ready
  uint64_t load_cycles = 0;          // clocks spent loading the texture (0 for the backdoor)
  std::string configuration;         // the Verilated parameter configuration
};

struct EngineStats {
  std::string engine;
  std::string format;  // how memory holds the textures: rgba8, bc1, ... (several: "bc1,rgba8")
  uint64_t samples = 0;
  double load_seconds = 0;    // building the engine and loading the texture
  double sample_seconds = 0;  // the sampling phase alone (wall time; texsim takes out the two below)
  double parse_seconds = 0;   // texsim: reading and converting the requests (in parallel with the rest)
  double write_seconds = 0;   // texsim: writing the results
  std::optional<CycleStats> cycle;  // cycle-accurate engines only
  // Golden model only: texel words read, lerps that multiply.
  uint64_t texel_reads = 0, multiplies_per_channel = 0;
  std::vector<std::array<uint64_t, 4>> bank_reads;  // [level][bank]
  std::optional<CacheCounters> cache;               // cached mode only
  // cached mode: the samples that read a line memory answered with an error (rsp_error), by their
  // index in request order; their texels are 0.
  std::vector<uint64_t> memory_error_samples;
  // Anisotropic filter only (ProbeCounter): samples by probe count N, index 1..16; the RTL takes
  // N clocks for a sample of N probes.
  std::optional<std::array<uint64_t, kMaxAniso + 1>> probes;
  uint64_t probe_total() const;  // the sum of N over the samples (0 without the histogram)

  // Throughput: samples per clock once the pipeline has filled, samples / (cycles - latency), so
  // that a short run of a unit that takes one sample per clock reports 1.0 (cycles has the total).
  double samples_per_clock() const {
    if (!cycle || cycle->cycles <= cycle->latency_cycles) return 0.0;
    return double(samples) / double(cycle->cycles - cycle->latency_cycles);
  }
  nlohmann::json to_json(const EngineOptions& options) const;
  static EngineStats from_json(const nlohmann::json& j);  // what to_json wrote (SystemC child -> parent)
};

struct EngineResult {
  std::vector<Texel> texels;  // one per request, in request order
  EngineStats stats;
};

// Passes a source's requests through and counts the probes of each (tex_probe, the function the
// RTL's tex_probe implements): the probes-per-sample histogram of EngineStats.
class ProbeCounter final : public RequestSource {
 public:
  // sizes[t]: level 0 of texture t (the LOD unit takes the requested texture's, and the requested
  // sampler's anisotropy cap).
  ProbeCounter(RequestSource& source, SamplerTable samplers, std::vector<Extent> sizes)
      : source_(source), samplers_(std::move(samplers)), sizes_(std::move(sizes)) {}
  size_t read(Request* out, size_t max) override;
  const std::array<uint64_t, kMaxAniso + 1>& histogram() const { return histogram_; }

 private:
  RequestSource& source_;
  SamplerTable samplers_;
  std::vector<Extent> sizes_;
  std::array<uint64_t, kMaxAniso + 1> histogram_{};
};

// A failure inside a simulation (RTL assertion, time-out, lost or extra response, a sample that
// differs from the golden model): texsim keeps the waveform of such a run.
struct SimulationError : Error {
  using Error::Error;
};

// Runs `run` over requests in memory and collects the texels (the vector forms of the engines).
EngineResult run_collected(const std::vector<Request>& requests,
                           const std::function<EngineStats(RequestSource&, TexelSink&)>& run);

// One texture of a frame's descriptor table (real frames, docs/scenes.md): its pyramid; requests
// name an entry by Request::texture, and the sampler-table entry they read it with by
// Request::sampler (a frame's SamplerTable).
struct BoundTexture {
  BoundTexture(const Pyramid* layer0 = nullptr, std::vector<const Pyramid*> more = {},
               TextureKind k = TextureKind::Texture2D)
      : pyramid(layer0), more_layers(std::move(more)), kind(k) {}
  const Pyramid* pyramid;                   // layer 0 (a 2D texture's one layer; a cube's +X face)
  std::vector<const Pyramid*> more_layers;  // an array texture's layers 1.. (the size, format and levels of layer 0)
  TextureKind kind;                         // a cube map: 6 layers a cube
  int layers() const { return 1 + int(more_layers.size()); }
  std::vector<const Pyramid*> all_layers() const {
    std::vector<const Pyramid*> out{pyramid};
    out.insert(out.end(), more_layers.begin(), more_layers.end());
    return out;
  }
};
using TextureTable = std::vector<BoundTexture>;

// Throws tex::Error unless the frame's tables fit the cached unit's (1 to kMaxTextures textures,
// 1 to kMaxSamplers samplers).
// With on-chip memory, also one of each (the paper's unit: its texture memories and cfg pins).
void check_tables(const TextureTable& textures, const SamplerTable& samplers, Memory memory);
// A request naming a texture or sampler beyond the tables: one line with the request's tag.
void check_request_tables(const Request& r, size_t textures, size_t samplers);

// The golden model's Sampler for each (texture, sampler) pair a frame samples, built on first use.
class SamplerPairs {
 public:
  SamplerPairs(const TextureTable& textures, const SamplerTable& samplers, SamplerPaths paths = SamplerPaths::Both);
  // Throws tex::Error for a request naming a texture or sampler beyond the tables.
  Sampler& at(const Request& r) {
    if (r.texture >= textures_.size() || r.sampler >= samplers_.size()) [[unlikely]]
      check_request_tables(r, textures_.size(), samplers_.size());
    std::unique_ptr<Sampler>& s = pairs_[size_t(r.texture) * samplers_.size() + r.sampler];
    if (!s) [[unlikely]] {
      const BoundTexture& t = textures_[r.texture];
      s = std::make_unique<Sampler>(t.all_layers(), samplers_[r.sampler],
                                    t.kind == TextureKind::Cube ? SamplerPaths::Both : paths_, t.kind);
    }
    return *s;
  }
  // Every pair built so far, for counters.
  std::vector<const Sampler*> built() const;
  // A texel of a texture written into every pair of it built so far (a pair built later takes the
  // texture as it then stands).
  void write_texel(int texture, int level, int x, int y, const Texel& t, int layer = 0);

 private:
  TextureTable textures_;
  SamplerTable samplers_;
  SamplerPaths paths_;
  std::vector<std::unique_ptr<Sampler>> pairs_;  // [texture * samplers + sampler]
};

class Engine {
 public:
  virtual ~Engine() = default;
  // Streams every request of `source` through the engine into `sink`, in order. Throws
  // tex::Error for input the engine cannot take (one line), before any simulation where it can.
  virtual EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                          TexelSink& sink) = 0;
  // The same for requests in memory.
  EngineResult run(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests);
  // Several textures and samplers through the cached unit's descriptor and sampler tables (every
  // engine; on chip: one of each).
  virtual EngineStats run(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                          TexelSink& sink) = 0;
};

struct EngineInfo {
  std::string name;
  std::string description;
  bool cycle_accurate = false;
  bool can_trace = false;
  std::function<std::unique_ptr<Engine>(const EngineOptions&)> make;
};
// Every engine of this build, in the order --help lists them.
const std::vector<EngineInfo>& engines();
const EngineInfo& engine_info(const std::string& name);  // throws tex::Error naming the known ones
// "model | rtl | ..." for --help.
std::string engine_list();

// Throws tex::Error for an unknown engine or options it cannot honour (e.g. --trace on the model).
std::unique_ptr<Engine> make_engine(const std::string& name, const EngineOptions& options);

// The golden model, with its read and multiply counters; in cached mode (options.memory) also its
// caches' hits and misses, and the miss stream into options.miss_sink. With options.timing, the
// timing model's cycle counters and response clocks (model_unit_shape's unit).
EngineStats run_model(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source, TexelSink& sink,
                      const EngineOptions& options = {});
EngineResult run_model(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests);
EngineStats run_model(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                      TexelSink& sink, const EngineOptions& options = {});

// The unit the model's timing layer clocks: the RTL configuration `--engine rtl` would run for these
// textures and options where one is built (so that both engines give the same clocks), else the
// design's defaults (FIFO of 2048 samples or the depth asked for, miss ring of 512, fill FIFO of 4,
// 16-byte beats). `name`: the configuration's name, or a description of the defaults.
UnitShape model_unit_shape(const TextureTable& textures, const EngineOptions& options, std::string& name,
                           int& beat_bytes);
// The model engine's timing model for these textures and options: model_unit_shape's unit, the
// memory and stimulus of the RTL engine (the same seeds). `line_bytes`: the cache line (cached).
std::unique_ptr<TimedStream> model_timing(const TextureTable& textures, const EngineOptions& options, int line_bytes,
                                          std::string& configuration);

// The descriptor table of a texture table in cached mode: layouts packed one after another from
// options.layout.base. Throws tex::Error (too many textures, different channel widths, memory).
std::vector<TextureDescriptor> texture_descriptors(const TextureTable& textures, const EngineOptions& options);
// The memory image of a frame: each texture's (build_memory_image) at its descriptor's layout,
// packed one after another from the first descriptor's base (the image's first byte).
std::vector<uint8_t> frame_memory_image(const TextureTable& textures, const std::vector<TextureDescriptor>& descriptors);

}  // namespace tex

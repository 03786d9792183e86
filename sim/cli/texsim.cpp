// texsim: the command-line tool. Sample query traces, build and dump pyramids, render scenes.
#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <deque>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <unistd.h>

#include "engines/engine.h"
#include "model/error.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "reports/explore.h"
#include "reports/figures.h"
#include "workloads/query_trace.h"
#include "workloads/scenes.h"
#include "workloads/output_files.h"
#include "workloads/texture_io.h"

namespace {

using namespace tex;

// Unsigned decimal of an option: no sign, no wrap-around. Throws tex::Error naming the option.
uint64_t parse_unsigned(const std::string& text, const std::string& option) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw Error(option + " " + quote_clipped(text) + " is not a whole number from 0 to 18446744073709551615");
  return v;
}

// --block WxH: texels per block (= cache line), each side 2, 4 or 8.
void parse_block(const std::string& text, LayoutParams& out) {
  if (!parse_block_size(text, out))
    throw Error("--block " + quote_clipped(text) + " is not WxH with W and H each 2, 4 or 8");
}

// Options shared by every command that samples a texture.
struct SamplingOptions {
  std::string texture = "testcard";
  std::string filter = "trilinear";
  int max_aniso = kMaxAniso;
  bool aniso_pow2 = false;
  CLI::Option* max_aniso_opt = nullptr;
  std::string wrap = "repeat";
  std::string wrap_u, wrap_v;
  std::string pyramid = "exact";
  std::string engine = "model";
  double lod_bias = 0, min_lod = -128, max_lod = 127.99;
  bool resize = false;
  std::string stalls = "none";
  std::string seed = "1";
  std::string load = "backdoor";
  std::string stats_path;
  std::string trace_path;
  std::string trace_window;
  bool verify = false;
  // Memory hierarchy (docs/memory.md).
  std::string memory = "onchip";
  std::string cache_kib = "8", ways = "2", block = "4x4", block_order = "row-major";
  std::string mem_latency = "100", mem_jitter = "0", mem_bytes_per_clock = "16", mem_outstanding = "64";
  std::string fifo_depth;
  std::string miss_trace;
  CLI::Option *wrap_u_opt = nullptr, *wrap_v_opt = nullptr, *texture_opt = nullptr;
  std::vector<CLI::Option*> cached_opts;  // meaningful with --memory cached only

  void add_to(CLI::App& cmd) {
    texture_opt = cmd.add_option("--texture,-t", texture, "image file (any OpenImageIO format) or pattern NAME[:WxH]")
                      ->capture_default_str();
    cmd.add_option("--filter,-f", filter,
                   "point | bilinear | mip_nearest | trilinear | anisotropic (trilinear probes along the "
                   "footprint, for requests with derivatives), or a GL name (nearest_mipmap_linear, ...)")
        ->capture_default_str();
    max_aniso_opt = cmd.add_option("--max-aniso", max_aniso, "anisotropic: probes per sample at most, 1..16")
                        ->capture_default_str();
    cmd.add_flag("--aniso-pow2", aniso_pow2, "anisotropic: round probe counts up to a power of two");
    cmd.add_option("--wrap,-w", wrap, "repeat | clamp | mirror, both axes")->capture_default_str();
    wrap_u_opt = cmd.add_option("--wrap-u", wrap_u, "wrap mode of u only (overrides --wrap)");
    wrap_v_opt = cmd.add_option("--wrap-v", wrap_v, "wrap mode of v only (overrides --wrap)");
    cmd.add_option("--pyramid", pyramid, "exact (mean of the level-0 footprint) | cascade")->capture_default_str();
    cmd.add_option("--engine,-e", engine, engine_list())->capture_default_str();
    cmd.add_option("--lod-bias", lod_bias, "added to lambda before the clamp, in levels")->capture_default_str();
    cmd.add_option("--min-lod", min_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_option("--max-lod", max_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_flag("--resize", resize, "resample a texture whose sides are not powers of two");
    cmd.add_option("--stalls", stalls,
                   "none | random | heavy: input gaps and output stalls of cycle-accurate engines (none = ideal "
                   "timing, what the hardware sustains)")
        ->capture_default_str();
    cmd.add_option("--seed", seed, "seed of --stalls random|heavy and of the RTL's unreset registers (0 and up)")
        ->capture_default_str();
    cmd.add_option("--load", load,
                   "backdoor | port: fill the RTL's texture memories directly (0 clocks) or through the write "
                   "port (one texel per clock)")
        ->capture_default_str();
    cmd.add_option("--stats", stats_path, "write counters to this JSON file (- = standard output)");
    cmd.add_option("--trace", trace_path,
                   "write an FST waveform (engines rtl, systemc); kept when the simulation fails");
    cmd.add_option("--trace-window", trace_window, "clocks FIRST:LAST to trace (default: all)");
    cmd.add_flag("--verify", verify, "also run the golden model and fail unless every sample is bit-identical");
    cmd.add_option("--memory", memory,
                   "onchip | cached: per-level memories, or the pyramid in external memory behind two caches "
                   "(engines model, rtl; docs/memory.md)")
        ->capture_default_str();
    cached_opts.push_back(cmd.add_option("--cache-kib", cache_kib, "cached: size of each cache (even levels, odd levels) in KiB")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--ways", ways, "cached: associativity, 1 | 2 | 4")->capture_default_str());
    cached_opts.push_back(cmd.add_option("--block", block, "cached: texels per block (= cache line) WxH, each 2 | 4 | 8")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--block-order", block_order, "cached: row-major | morton order of a level's blocks")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--mem-latency", mem_latency, "cached, rtl: clocks from a memory read to its first beat")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--mem-jitter", mem_jitter, "cached, rtl: + a random 0..N clocks per read (order kept)")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--mem-bytes-per-clock", mem_bytes_per_clock, "cached, rtl: memory bandwidth")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--mem-outstanding", mem_outstanding, "cached, rtl: reads in flight at most")
        ->capture_default_str());
    cached_opts.push_back(cmd.add_option("--fifo-depth", fifo_depth,
                                         "cached, rtl: samples the FIFO holds at most, 1 to the configuration's "
                                         "FIFO_DEPTH (default: all of it)"));
    cached_opts.push_back(cmd.add_option("--miss-trace", miss_trace,
                   "cached: write the line addresses read from memory, in order, one 0x%08x per line"));
  }

  SamplerConfig config() const {
    SamplerConfig c;
    if (!parse_filter(filter, c.filter)) throw Error("unknown filter " + quote_clipped(filter));
    if (max_aniso < 1 || max_aniso > kMaxAniso)
      throw Error("--max-aniso " + std::to_string(max_aniso) + " is outside 1..16");
    if ((max_aniso_opt->count() || aniso_pow2) && !c.filter.anisotropic)
      throw Error("--max-aniso and --aniso-pow2 apply to --filter anisotropic, not " + quote_clipped(filter));
    c.max_aniso = max_aniso;
    c.aniso_pow2 = aniso_pow2;
    Wrap w;
    if (!parse_wrap(wrap, w)) throw Error("unknown wrap mode " + quote_clipped(wrap) + " (repeat, clamp, mirror)");
    c.wrap_u = c.wrap_v = w;
    if (wrap_u_opt->count() && !parse_wrap(wrap_u, c.wrap_u))
      throw Error("--wrap-u: unknown wrap mode " + quote_clipped(wrap_u) + " (repeat, clamp, mirror)");
    if (wrap_v_opt->count() && !parse_wrap(wrap_v, c.wrap_v))
      throw Error("--wrap-v: unknown wrap mode " + quote_clipped(wrap_v) + " (repeat, clamp, mirror)");
    if (!to_lod_fixed(lod_bias, c.lod_bias)) throw Error("--lod-bias " + std::to_string(lod_bias) + " is outside [-128, 128)");
    if (!to_lod_fixed(min_lod, c.min_lod)) throw Error("--min-lod " + std::to_string(min_lod) + " is outside [-128, 128)");
    if (!to_lod_fixed(max_lod, c.max_lod)) throw Error("--max-lod " + std::to_string(max_lod) + " is outside [-128, 128)");
    if (c.min_lod > c.max_lod) throw Error("--min-lod is greater than --max-lod");
    return c;
  }

  PyramidMode pyramid_mode() const {
    PyramidMode m;
    if (!parse_pyramid_mode(pyramid, m)) throw Error("unknown pyramid mode " + quote_clipped(pyramid) + " (exact, cascade)");
    return m;
  }

  // Also checks that the engine exists and can honour the options (before any work).
  EngineOptions engine_options() const {
    EngineOptions o;
    if (!parse_stalls(stalls, o.stalls)) throw Error("unknown --stalls " + quote_clipped(stalls) + " (none, random, heavy)");
    if (!parse_load_method(load, o.load)) throw Error("unknown --load " + quote_clipped(load) + " (backdoor, port)");
    o.seed = parse_unsigned(seed, "--seed");
    o.show_progress = isatty(STDERR_FILENO);
    o.trace_path = trace_path;
    if (!trace_window.empty()) {
      const auto colon = trace_window.find(':');
      if (colon == std::string::npos)
        throw Error("--trace-window " + quote_clipped(trace_window) + " is not FIRST:LAST (clocks)");
      o.trace_begin = parse_unsigned(trace_window.substr(0, colon), "--trace-window FIRST");
      o.trace_end = parse_unsigned(trace_window.substr(colon + 1), "--trace-window LAST");
      if (o.trace_end < o.trace_begin) throw Error("--trace-window " + quote_clipped(trace_window) + ": LAST < FIRST");
    }
    if (!parse_memory(memory, o.memory)) throw Error("unknown --memory " + quote_clipped(memory) + " (onchip, cached)");
    if (o.memory == Memory::Cached) {
      const uint64_t kib = parse_unsigned(cache_kib, "--cache-kib");
      if (kib == 0 || kib > 1024) throw Error("--cache-kib " + cache_kib + " is outside 1..1024");
      o.cache.size_bytes = int(kib * 1024);
      const uint64_t w = parse_unsigned(ways, "--ways");
      if (w != 1 && w != 2 && w != 4) throw Error("--ways " + quote_clipped(ways) + " is not 1, 2 or 4");
      o.cache.ways = int(w);
      parse_block(block, o.layout);
      if (!parse_block_order(block_order, o.layout.order))
        throw Error("unknown --block-order " + quote_clipped(block_order) + " (row-major, morton)");
      auto bounded = [](const std::string& text, const char* option, uint64_t lo, uint64_t hi) {
        const uint64_t v = parse_unsigned(text, option);
        if (v < lo || v > hi)
          throw Error(std::string(option) + " " + text + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
        return uint32_t(v);
      };
      o.mem_latency = bounded(mem_latency, "--mem-latency", 1, 100000);
      o.mem_jitter = bounded(mem_jitter, "--mem-jitter", 0, 100000);
      o.mem_bytes_per_clock = bounded(mem_bytes_per_clock, "--mem-bytes-per-clock", 1, 1024);
      o.mem_outstanding = bounded(mem_outstanding, "--mem-outstanding", 1, 4096);
      if (!fifo_depth.empty()) o.fifo_depth = bounded(fifo_depth, "--fifo-depth", 1, 1u << 20);
      // The geometry must be one the caches can have (the texture's channel width sets the line
      // size; 8-bit lines are checked here, the engine checks again with the real texture).
      TextureCache(MemoryLayout(0, 0, 8, o.layout), o.cache, SamplerConfig{}, 0, 0);
    } else {
      for (const CLI::Option* opt : cached_opts)
        if (opt->count()) throw Error(opt->get_name() + " needs --memory cached (the on-chip memories have no cache)");
    }
    make_engine(engine, o);  // unknown engine, --trace with an engine that cannot trace
    return o;
  }

  // The inputs of the command, for OutputSet's input-versus-output check.
  void add_inputs(OutputSet& outputs) const { outputs.add_input(texture, "--texture"); }
  // --stats and --trace, declared with the command's other outputs.
  OutputFile* stats_output(OutputSet& outputs) const {
    return stats_path.empty() ? nullptr : &outputs.declare(stats_path, "--stats");
  }
  OutputFile* trace_output(OutputSet& outputs) const {
    return trace_path.empty() ? nullptr : &outputs.declare(trace_path, "--trace", OutputSet::Kind::File);
  }
  OutputFile* miss_trace_output(OutputSet& outputs) const {
    return miss_trace.empty() ? nullptr : &outputs.declare(miss_trace, "--miss-trace");
  }
};

// --miss-trace: one line address per line, 0x%08x.
class MissTraceWriter final : public MissSink {
 public:
  explicit MissTraceWriter(OutputFile& out) : out_(out), file_(out.open()) {}
  void write(const uint32_t* a, size_t n) override {
    for (size_t i = 0; i < n; ++i) std::fprintf(file_, "0x%08x\n", a[i]);
  }
  void close() { out_.close(); }

 private:
  OutputFile& out_;
  std::FILE* file_;
};

// --verify: the golden model samples every request as the engine takes it, and every texel the
// engine returns must equal the model's.
class Verifier {
 public:
  Verifier(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source, TexelSink& sink,
           std::string engine)
      : sampler_(pyramid, config), source_(*this, source), sink_(*this, sink), engine_(std::move(engine)) {}
  RequestSource& source() { return source_; }
  TexelSink& sink() { return sink_; }
  size_t checked() const { return checked_; }

 private:
  struct Source final : RequestSource {
    Source(Verifier& v, RequestSource& inner) : v(v), inner(inner) {}
    size_t read(Request* out, size_t max) override {
      const size_t n = inner.read(out, max);
      for (size_t i = 0; i < n; ++i) v.expected_.push_back(v.sampler_.sample(out[i]));
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
  Sampler sampler_;
  Source source_;
  Sink sink_;
  std::string engine_;
  std::deque<Texel> expected_;
  size_t checked_ = 0;
};

// Runs the engine (with --verify through the golden model too). A failure inside the simulation
// keeps the waveform, the one output of a failed command: it shows what went wrong.
EngineStats run_engine(const SamplingOptions& o, const EngineOptions& eo, OutputSet& outputs, OutputFile* trace,
                       const Pyramid& pyr, const SamplerConfig& cfg, RequestSource& source, TexelSink& sink) {
  const auto engine = make_engine(o.engine, eo);
  // The anisotropic filter: count each request's probes on the way in.
  std::optional<ProbeCounter> counter;
  if (cfg.filter.anisotropic) counter.emplace(source, cfg, pyr.log2_w0(), pyr.log2_h0());
  RequestSource& requests = counter ? *counter : source;
  try {
    EngineStats stats;
    if (!o.verify) {
      stats = engine->run(pyr, cfg, requests, sink);
    } else {
      Verifier verifier(pyr, cfg, requests, sink, o.engine);
      stats = engine->run(pyr, cfg, verifier.source(), verifier.sink());
      std::printf("verify: %zu samples of engine %s are bit-identical to the golden model\n", verifier.checked(),
                  o.engine.c_str());
    }
    if (counter) stats.probes = counter->histogram();
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

void write_stats(OutputFile* out, const EngineStats& stats, const EngineOptions& options, double seconds) {
  if (!out) return;
  nlohmann::json j = stats.to_json(options);
  j["wall_seconds"] = seconds;
  std::fputs((j.dump(2) + "\n").c_str(), out->open());
  out->close();
}

int cmd_sample(const SamplingOptions& o, const std::string& queries_path, const std::string& out_path) {
  const auto t0 = std::chrono::steady_clock::now();
  // Everything is checked before the work: options, engine, outputs, texture, every query.
  const SamplerConfig cfg = o.config();
  EngineOptions eo = o.engine_options();
  OutputSet outputs;
  o.add_inputs(outputs);
  outputs.add_input(queries_path, "--queries");
  OutputFile& result = outputs.declare(out_path, "--out");
  OutputFile* stats_out = o.stats_output(outputs);
  OutputFile* trace = o.trace_output(outputs);
  OutputFile* miss_out = o.miss_trace_output(outputs);
  const Pyramid pyr = build_pyramid(load_texture(o.texture, o.resize), o.pyramid_mode());
  QueryReader reader(queries_path);
  if (reader.rewindable()) {  // a file: check every query now; a pipe is checked as it streams
    QuerySource check(reader);
    std::vector<Request> scratch(4096);
    while (check.read(scratch.data(), scratch.size())) {
    }
    reader.rewind();
  }
  if (trace) eo.trace_path = trace->write_path();

  std::optional<MissTraceWriter> misses;
  if (miss_out) eo.miss_sink = &misses.emplace(*miss_out);

  QuerySource source(reader);
  CsvTexelWriter writer(result.open());
  const EngineStats stats = run_engine(o, eo, outputs, trace, pyr, cfg, source, writer);
  if (misses) misses->close();
  if (source.count() == 0)
    std::fprintf(stderr, "texsim: %s has no queries (only a header): the result has only its header\n",
                 reader.name().c_str());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(stats_out, stats, eo, secs);
  outputs.commit();
  // The summary goes to stderr when the result itself is on standard output.
  std::FILE* report = result.path() == "-" || result.path() == "/dev/stdout" ? stderr : stdout;
  if (report == stdout) {
    print_cycle_stats(stats, eo);
    print_cache_stats(stats);
    print_probe_stats(stats);
  }
  std::fprintf(report, "texsim sample: %zu queries, %s, %s/%s, %dx%d texture, engine %s -> %s (%.2f s)\n",
               source.count(), filter_name(cfg.filter).c_str(), wrap_name(cfg.wrap_u).c_str(),
               wrap_name(cfg.wrap_v).c_str(), pyr.levels[0].width, pyr.levels[0].height, o.engine.c_str(),
               out_path.c_str(), secs);
  return 0;
}

// The memory image options of `mip` (docs/memory.md §1).
struct ImageOptions {
  std::string path, block = "4x4", order = "row-major", base = "0";
  LayoutParams layout() const {
    LayoutParams p;
    parse_block(block, p);
    if (!parse_block_order(order, p.order)) throw Error("unknown --block-order " + quote_clipped(order) + " (row-major, morton)");
    const uint64_t b = parse_unsigned(base, "--mem-base");
    if (b > 0xFFFFFFFFull) throw Error("--mem-base " + base + " is beyond the 32-bit address space");
    p.base = uint32_t(b);
    return p;
  }
};

int cmd_mip(const std::string& texture, const std::string& mode_name, bool resize, const std::string& dump_dir,
            const std::string& layout_path, const ImageOptions& image) {
  if (dump_dir.empty() && layout_path.empty() && image.path.empty())
    throw Error("mip: give --dump-levels DIR, --layout FILE and/or --memory-image FILE");
  const LayoutParams memory_layout = image.layout();
  PyramidMode mode;
  if (!parse_pyramid_mode(mode_name, mode)) throw Error("unknown pyramid mode " + quote_clipped(mode_name) + " (exact, cascade)");
  OutputSet outputs;
  outputs.add_input(texture, "--texture");
  if (!layout_path.empty()) check_image_path(layout_path);
  OutputFile* layout = layout_path.empty() ? nullptr : &outputs.declare(layout_path, "--layout", OutputSet::Kind::File);
  OutputFile* image_out = image.path.empty() ? nullptr : &outputs.declare(image.path, "--memory-image");
  const Pyramid pyr = build_pyramid(load_texture(texture, resize), mode);
  std::vector<uint8_t> image_bytes;
  if (image_out)  // (the layout checks the block, base and size before anything is written)
    image_bytes = memory_image_file(
        pyr, MemoryLayout(pyr.log2_w0(), pyr.log2_h0(), pyr.levels[0].channel_bits, memory_layout));
  if (!dump_dir.empty()) {
    outputs.make_directory(dump_dir, "--dump-levels");
    std::vector<OutputFile*> levels;
    for (size_t k = 0; k < pyr.levels.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "level%02zu.png", k);
      levels.push_back(&outputs.declare((std::filesystem::path(dump_dir) / name).string(), "--dump-levels",
                                        OutputSet::Kind::File));
    }
    for (size_t k = 0; k < pyr.levels.size(); ++k) save_image(pyr.levels[k], *levels[k]);
  }
  if (layout) save_image(mip_layout(pyr), *layout);
  if (image_out) {
    std::FILE* f = image_out->open();
    if (std::fwrite(image_bytes.data(), 1, image_bytes.size(), f) != image_bytes.size())
      throw Error("cannot write " + image_out->path());
    image_out->close();
  }
  outputs.commit();
  std::printf("texsim mip: %dx%d texture, %zu levels (%s)%s%s%s%s%s%s\n", pyr.levels[0].width, pyr.levels[0].height,
              pyr.levels.size(), mode_name.c_str(), dump_dir.empty() ? "" : ", levels in ", dump_dir.c_str(),
              layout_path.empty() ? "" : ", layout in ", layout_path.c_str(),
              image.path.empty() ? "" : ", memory image in ", image.path.c_str());
  return 0;
}

// Renders one frame of a scene, or with --frames M and no --frame every frame to OUT_000.png ...
// A scene with its own map (reflect, mesh) rejects --texture; one whose map is not periodic
// (reflect, mesh) samples with clamp-to-edge unless a --wrap option is given.
int cmd_render(const SamplingOptions& o, const std::string& scene, SceneOptions so, bool all_frames,
               bool texture_given, bool wrap_given, const std::string& out) {
  const auto t0 = std::chrono::steady_clock::now();
  SamplerConfig cfg = o.config();
  EngineOptions eo = o.engine_options();
  make_scene(scene, so);  // checks the scene name, size and frame numbers before any work
  check_image_path(out);
  const int first = all_frames ? 0 : so.frame, last = all_frames ? so.frames - 1 : so.frame;
  OutputSet outputs;
  if (texture_given) o.add_inputs(outputs);
  std::vector<OutputFile*> images;
  for (int f = first; f <= last; ++f) {
    std::string path = out;
    if (all_frames) {
      const std::filesystem::path p(out);
      char num[16];
      std::snprintf(num, sizeof num, "_%03d", f);
      path = (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
    }
    images.push_back(&outputs.declare(path, "--out", OutputSet::Kind::File));
  }
  OutputFile* stats_out = o.stats_output(outputs);
  OutputFile* trace = o.trace_output(outputs);
  if (trace) eo.trace_path = trace->write_path();
  std::optional<MissTraceWriter> misses;  // every frame's, in order
  if (OutputFile* miss_out = o.miss_trace_output(outputs)) eo.miss_sink = &misses.emplace(*miss_out);

  size_t samples = 0;
  EngineStats last_stats;
  for (int f = first; f <= last; ++f) {
    so.frame = f;
    const SceneFrame frame = make_scene(scene, so);
    const Pyramid pyr = build_pyramid(scene_texture(frame, texture_given ? o.texture : "", o.resize), o.pyramid_mode());
    if (frame.clamp_edges && !wrap_given) cfg.wrap_u = cfg.wrap_v = Wrap::Clamp;
    const auto requests = to_requests(frame.queries, "scene " + scene);
    VectorSource source(requests);
    VectorSink texels;
    last_stats = run_engine(o, eo, outputs, trace, pyr, cfg, source, texels);
    save_image(compose(frame, texels.texels, pyr.levels[0].channel_bits), *images[size_t(f - first)]);
    samples += requests.size();
  }
  if (misses) misses->close();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(stats_out, last_stats, eo, secs);  // counters of the last frame, time of them all
  outputs.commit();
  print_cycle_stats(last_stats, eo);
  print_cache_stats(last_stats);
  print_probe_stats(last_stats);
  std::printf("texsim render: scene %s, %dx%d, frame%s %d..%d of %d, %zu samples, %s, engine %s -> %s (%.2f s)\n",
              scene.c_str(), so.width, so.height, all_frames ? "s" : "", first, last, so.frames, samples,
              filter_name(cfg.filter).c_str(), o.engine.c_str(), out.c_str(), secs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"texsim: cycle-accurate mip-mapping texture unit (Williams 1983) - model, RTL and SystemC"};
  // 0..1 plus the check after parse: CLI11 reports a missing subcommand before an unexpected
  // word, so `texsim smaple ...` would not name the typo.
  app.require_subcommand(0, 1);

  SamplingOptions sample_opts;
  std::string queries, out;
  CLI::App* sample = app.add_subcommand("sample", "sample a query trace (CSV) and write one RGBA line per query");
  sample_opts.add_to(*sample);
  sample->add_option("--queries,-q", queries, "CSV: header u,v,lod or u,v,dudx,dvdx,dudy,dvdy (- = standard input)")
      ->required();
  sample->add_option("--out,-o", out, "result CSV: header r,g,b,a (- = standard output)")->required();

  std::string mip_texture = "testcard", mip_mode = "exact", dump_dir, layout;
  bool mip_resize = false;
  CLI::App* mip = app.add_subcommand("mip", "build a pyramid; dump its levels or the paper's Figure 1 layout");
  mip->add_option("--texture,-t", mip_texture, "image file or pattern NAME[:WxH]")->capture_default_str();
  mip->add_option("--pyramid", mip_mode, "exact | cascade")->capture_default_str();
  mip->add_flag("--resize", mip_resize, "resample a texture whose sides are not powers of two");
  mip->add_option("--dump-levels", dump_dir, "write DIR/level00.png, level01.png, ...");
  mip->add_option("--layout", layout, "write the packed R/G/B memory layout (paper Figure 1)");
  ImageOptions image;
  mip->add_option("--memory-image", image.path,
                  "write the pyramid as the cached unit's external memory holds it (header: docs/memory.md)");
  mip->add_option("--block", image.block, "memory image: texels per block WxH, each 2 | 4 | 8")->capture_default_str();
  mip->add_option("--block-order", image.order, "memory image: row-major | morton")->capture_default_str();
  mip->add_option("--mem-base", image.base, "memory image: byte address of level 0 (a multiple of the line)")
      ->capture_default_str();

  SamplingOptions render_opts;
  std::string scene = "plane", render_out;
  int width = 640, height = 480;
  CLI::App* render = app.add_subcommand("render", "render a scene of the paper through an engine");
  render_opts.add_to(*render);
  std::string scene_list;
  for (const std::string& n : scene_names()) scene_list += n + " | ";
  scene_list += "mesh16 (the mesh with 16-bit X, Y, Z; model engines)";
  render->add_option("--scene,-s", scene, scene_list)->capture_default_str();
  render->add_option("--width", width, "image width")->capture_default_str();
  render->add_option("--height", height, "image height")->capture_default_str();
  render->add_option("--out,-o", render_out, "output image (PNG, TIFF, EXR, ...)")->required();
  int frame = 0, frames = 1;
  CLI::Option* frame_opt = render->add_option("--frame", frame, "animation frame to render (0-based)");
  render->add_option("--frames", frames, "frames of the animation; without --frame renders all to OUT_000.png ...")
      ->capture_default_str();
  std::string order = "scanline";
  int tile = 8;
  render->add_option("--order", order, "scanline | tiled: the rasterizer's pixel walk (rows, or tiles row by row)")
      ->capture_default_str();
  CLI::Option* tile_opt =
      render->add_option("--tile", tile, "tiled order: tile side in pixels, a power of two 2 to 256")->capture_default_str();

  FiguresOptions fig;
  CLI::App* figures = app.add_subcommand("figures", "render every scene's variants, reference, errors and flicker");
  figures->add_option("--out,-o", fig.out_dir, "output directory")->capture_default_str();
  figures->add_option("--engine,-e", fig.engine, "engine of the variants: " + engine_list())->capture_default_str();
  figures->add_option("--width", fig.width, "still image width")->capture_default_str();
  figures->add_option("--height", fig.height, "still image height")->capture_default_str();
  figures->add_option("--frames", fig.frames, "animation frames (flicker)")->capture_default_str();
  figures
      ->add_option("--reference-samples", fig.reference_samples,
                   "reference sub-pixel positions per axis, at least (more where a pixel spans more texels)")
      ->capture_default_str();

  ExploreArgs ex;
  CLI::App* explore = app.add_subcommand(
      "explore", "sweep caches, memory timing and rasterization order over scenes or a query trace (cached memory): "
                 "explore.csv, plots, index.html");
  CLI::Option* ex_scene = explore->add_option("--scene,-s", ex.scenes, "scenes, comma-separated: " + scene_list)
                              ->capture_default_str();
  CLI::Option* ex_queries =
      explore->add_option("--queries,-q", ex.queries, "a query trace (CSV u,v,lod or u,v,dudx,...) instead of scenes");
  explore->add_option("--texture,-t", ex.texture, "image file or pattern NAME[:WxH] (scenes with their own map keep it)")
      ->capture_default_str();
  explore->add_option("--filter,-f", ex.filter, "point | bilinear | mip_nearest | trilinear")->capture_default_str();
  explore->add_option("--width", ex.width, "scene width")->capture_default_str();
  explore->add_option("--height", ex.height, "scene height")->capture_default_str();
  explore->add_option("--order", ex.orders, "rasterization orders: scanline,tiled")->capture_default_str();
  explore->add_option("--tile", ex.tile, "tiled order: tile side in pixels")->capture_default_str();
  explore->add_option("--cache-kib", ex.cache_kib, "sizes of each cache (even, odd levels) in KiB, 1..1024")
      ->capture_default_str();
  explore->add_option("--ways", ex.ways, "associativities: 1 | 2 | 4")->capture_default_str();
  explore->add_option("--block", ex.blocks, "block shapes WxH (= cache lines), each side 2 | 4 | 8")->capture_default_str();
  explore->add_option("--block-order", ex.block_orders, "row-major | morton")->capture_default_str();
  explore->add_option("--mem-latency", ex.latencies, "memory latencies in clocks")->capture_default_str();
  explore->add_option("--mem-bytes-per-clock", ex.bandwidths, "memory bandwidths in bytes per clock")
      ->capture_default_str();
  explore->add_option("--fifo-depth", ex.fifo_depths, "sample FIFO depths; max = the RTL configuration's FIFO_DEPTH")
      ->capture_default_str();
  explore->add_option("--timing", ex.timing,
                      "rtl | none: samples/clock through the Verilated RTL at every point a compiled configuration "
                      "holds (its block shape, cache size, FIFO), or hit rates and bytes from the model only")
      ->capture_default_str();
  explore->add_option("--out,-o", ex.out_dir, "output directory: explore.csv, *.png, index.html")->capture_default_str();
  explore->add_option("--jobs,-j", ex.jobs, "points measured in this many processes at once")->capture_default_str();
  explore->add_option("--emit-jobs", ex.emit_jobs_path,
                      "write one command line per job (GNU parallel, a Slurm array) instead of running them; each "
                      "writes OUT/points/jobNNNNNN.csv");
  explore->add_option("--collect", ex.collect_dir, "merge DIR/points/*.csv of emitted jobs into DIR/explore.csv + plots");
  explore->add_option("--rows", ex.rows_path, "measure here and write only the CSV rows to this file (what a job runs)");
  bool no_plots = false;
  explore->add_flag("--no-plots", no_plots, "write explore.csv only (no matplotlib needed)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "texsim: error: %s (see --help)\n", e.what());
    return 2;
  }
  if (app.get_subcommands().empty()) {
    std::fprintf(stderr, "texsim: error: a command is required (see --help)\n");
    return 2;
  }
  try {
    if (*sample) return cmd_sample(sample_opts, queries, out);
    if (*mip) return cmd_mip(mip_texture, mip_mode, mip_resize, dump_dir, layout, image);
    if (*render) {
      SceneOptions so;
      so.width = width;
      so.height = height;
      so.frame = frame;
      so.frames = frames;
      so.order = parse_pixel_order(order);
      so.tile = tile;
      if (tile_opt->count() && so.order != PixelOrder::Tiled) throw tex::Error("--tile applies to --order tiled");
      const bool wrap_given = render->count("--wrap") + render->count("--wrap-u") + render->count("--wrap-v") > 0;
      return cmd_render(render_opts, scene, so, frames > 1 && frame_opt->count() == 0,
                        render_opts.texture_opt->count() > 0, wrap_given, render_out);
    }
    if (*figures) return make_figures(fig);
    if (*explore) {
      if (ex_scene->count() && ex_queries->count()) throw tex::Error("explore: give --scene or --queries, not both");
      ex.plots = !no_plots;
      return run_explore(ex, std::filesystem::read_symlink("/proc/self/exe").string());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texsim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

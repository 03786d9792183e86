// Options and helpers shared by the texsim commands that sample (sample, render): the sampling
// options, the engine run with --verify, the summary lines and the --stats file.
#pragma once
#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <unistd.h>
#include <unordered_set>
#include <vector>
#include <nlohmann/json.hpp>

#include "engines/engine.h"
#include "model/error.h"
#include "model/pyramid.h"
#include "workloads/output_files.h"
#include "workloads/query_trace.h"
#include "workloads/texture_files.h"
#include "workloads/text.h"

namespace tex {

// Unsigned decimal of an option: no sign, no wrap-around. Throws tex::Error naming the option.
inline uint64_t parse_unsigned(const std::string& text, const std::string& option) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw Error(option + " " + quote_clipped(text) + " is not a whole number from 0 to 18446744073709551615");
  return v;
}

// --mem-error-at N[,N...]: line reads (1 = the first), each at least 1, returned ascending.
inline std::vector<uint64_t> parse_error_reads(const std::string& text) {
  std::vector<uint64_t> out;
  size_t at = 0;
  for (;;) {
    const size_t comma = text.find(',', at);
    const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const uint64_t n = parse_unsigned(item, "--mem-error-at");
    if (n == 0) throw Error("--mem-error-at 0: line reads are counted from 1 (the first read)");
    out.push_back(n);
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// --block WxH: texels per block (= cache line), each side 2, 4 or 8.
inline void parse_block(const std::string& text, LayoutParams& out) {
  if (!parse_block_size(text, out))
    throw Error("--block " + quote_clipped(text) + " is not WxH with W and H each 2, 4 or 8");
}


// Options shared by every command that samples a texture.
struct SamplingOptions {
  std::string texture = "testcard";
  std::string filter = "trilinear";
  int max_aniso = kMaxAniso;
  bool aniso_pow2 = false;
  bool unnormalized = false;
  CLI::Option* max_aniso_opt = nullptr;
  std::string wrap = "repeat";
  std::string wrap_u, wrap_v;
  std::string mag_filter, min_filter, mipmap_mode, border_color;
  std::string reduction = "weighted-average";
  std::string compare_op = "less-or-equal";
  std::string pyramid = "exact";
  std::string format = "rgba8";
  bool srgb = false;
  CLI::Option* format_opt = nullptr;
  std::string engine = "model";
  double lod_bias = 0, min_lod = -128, max_lod = 127.99;
  bool resize = false;
  int base_level = 0, max_level = kMaxLevels - 1;  // the texture's view
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
  std::string mem_error_at;
  std::string miss_trace;
  std::string response_clocks;
  bool no_timing = false;
  CLI::Option *wrap_u_opt = nullptr, *wrap_v_opt = nullptr, *texture_opt = nullptr, *memory_opt = nullptr;
  std::vector<CLI::Option*> cached_opts;  // meaningful with --memory cached only

  void add_to(CLI::App& cmd) {
    texture_opt = cmd.add_option("--texture,-t", texture,
                                 "image file (any OpenImageIO format), DDS/KTX/KTX2/.astc texture file, or pattern NAME[:WxH]")
                      ->capture_default_str();
    cmd.add_option("--filter,-f", filter,
                   "point | bilinear | mip_nearest | trilinear | anisotropic (trilinear probes along the "
                   "footprint, for requests with derivatives), or a GL name (nearest_mipmap_linear, ...)")
        ->capture_default_str();
    max_aniso_opt = cmd.add_option("--max-aniso", max_aniso, "anisotropic: probes per sample at most, 1..16")
                        ->capture_default_str();
    cmd.add_flag("--aniso-pow2", aniso_pow2, "anisotropic: round probe counts up to a power of two");
    cmd.add_option("--mag-filter", mag_filter,
                   "nearest | linear: the texel filter where lambda <= 0 (default: --filter's own texel filter)");
    cmd.add_option("--min-filter", min_filter,
                   "nearest | linear, or a GL minification filter (nearest_mipmap_linear, ...: sets the mipmap "
                   "mode too): overrides --filter's minification");
    cmd.add_option("--mipmap-mode", mipmap_mode, "none (base level only) | nearest | linear: overrides --filter's");
    cmd.add_option("--wrap,-w", wrap, std::string(kWrapNames) + ", both axes")->capture_default_str();
    wrap_u_opt = cmd.add_option("--wrap-u", wrap_u, "address mode of u only (overrides --wrap)");
    wrap_v_opt = cmd.add_option("--wrap-v", wrap_v, "address mode of v only (overrides --wrap)");
    cmd.add_option("--border-color", border_color,
                   "clamp to border's colour: transparent-black (default) | opaque-black | opaque-white (also "
                   "int-... and Vulkan names) | R,G,B,A in 0..1 (linear)");
    cmd.add_option("--reduction", reduction,
                   "weighted-average | min | max (or Vulkan names): how the filter combines the texels it weighs "
                   "(Vulkan reductionMode; min and max: the texels of weight above 0, both levels, every probe)")
        ->capture_default_str();
    cmd.add_option("--compare-op", compare_op,
                   std::string("a depth compare's test, `reference OP texel depth` (Vulkan compareOp; GL's LEQUAL, ... "
                               "too): ") + kCompareOpNames + "; queries with a ref column (texsim sample --op compare)")
        ->capture_default_str();
    cmd.add_flag("--unnormalized", unnormalized,
                 "u, v in texels of the base level, not texture widths (Vulkan unnormalizedCoordinates, GL "
                 "rectangle textures): with --wrap clamp | border, one texel filter (point or bilinear, or a "
                 "--max-lod of 0), no anisotropy; render scales the frame's coordinates by the texture's size");
    cmd.add_option("--pyramid", pyramid, "exact (mean of the level-0 footprint) | cascade")->capture_default_str();
    format_opt = cmd.add_option("--format", format,
                                texel_format_names() + ": how memory holds an image file or pattern (each level "
                                "compressed: libsquish, Mesa for bc7, ours for etc2 and eac, astcenc for astc); a DDS/KTX/.astc "
                                "file keeps its own (also ETC2 RGB8A1 and signed EAC R11/RG11). EAC filters 16-bit channels "
                                "(CSV r16,g16,b16,a16; signed ones in offset binary: value - 32768)")
                     ->capture_default_str();
    cmd.add_flag("--srgb", srgb,
                 "the texture's R, G, B are sRGB codes: decoded to linear (16 bits) before filtering, its pyramid "
                 "averaged in linear space, results linear (CSV r16,g16,b16,a16); DDS/KTX sRGB formats set it");
    cmd.add_option("--engine,-e", engine, engine_list())->capture_default_str();
    cmd.add_option("--lod-bias", lod_bias, "added to lambda before the clamp, in levels")->capture_default_str();
    cmd.add_option("--min-lod", min_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_option("--max-lod", max_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_option("--base-level", base_level,
                   "the view's first level (GL TEXTURE_BASE_LEVEL, Vulkan baseMipLevel): the units sample level N "
                   "as their level 0, up to the texture's last level")
        ->capture_default_str();
    cmd.add_option("--max-level", max_level,
                   "the view's last level (GL TEXTURE_MAX_LEVEL; Vulkan baseMipLevel + levelCount - 1), at least "
                   "--base-level; default: the texture's last")
        ->capture_default_str();
    cmd.add_flag("--resize", resize, "resample a texture whose sides are not powers of two to the nearest ones (no longer needed: every engine samples any size)");
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
    cmd.add_option("--response-clocks", response_clocks,
                   "write the clock of every response, one per line, counted from the first request's clock "
                   "(engines model, rtl: the same file from both; systemc: its TLM-2.0 initiator's timing)");
    cmd.add_flag("--no-timing", no_timing,
                 "engine model: skip the timing model (no cycles, samples/clock or response clocks; faster)");
    memory_opt = cmd.add_option("--memory", memory,
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
    cached_opts.push_back(cmd.add_option("--mem-error-at", mem_error_at,
                   "cached: the N-th line read from memory (1 = the first; N,M,... for several) answers SLVERR; "
                   "texsim names the samples that read it and exits with status 1, writing nothing"));
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
    if (std::optional<MipMode> mip; !min_filter.empty()) {
      if (!parse_min_filter(min_filter, c.filter.texel, mip))
        throw Error("--min-filter " + quote_clipped(min_filter) +
                    " is not nearest, linear or a GL minification filter (nearest_mipmap_nearest, ...)");
      if (mip) c.filter.mip = *mip;
    }
    if (!mipmap_mode.empty() && !parse_mip_mode(mipmap_mode, c.filter.mip))
      throw Error("--mipmap-mode " + quote_clipped(mipmap_mode) + " is not none, nearest or linear");
    if (!mag_filter.empty() && !parse_texel_filter(mag_filter, c.filter.mag))
      throw Error("--mag-filter " + quote_clipped(mag_filter) + " is not nearest or linear");
    Wrap w;
    if (!parse_wrap(wrap, w)) throw Error("unknown wrap mode " + quote_clipped(wrap) + " (" + kWrapNames + ")");
    c.wrap_u = c.wrap_v = w;
    if (wrap_u_opt->count() && !parse_wrap(wrap_u, c.wrap_u))
      throw Error("--wrap-u: unknown wrap mode " + quote_clipped(wrap_u) + " (" + kWrapNames + ")");
    if (wrap_v_opt->count() && !parse_wrap(wrap_v, c.wrap_v))
      throw Error("--wrap-v: unknown wrap mode " + quote_clipped(wrap_v) + " (" + kWrapNames + ")");
    if (!border_color.empty()) parse_border(c);
    if (!parse_reduction(reduction, c.reduction))
      throw Error("--reduction " + quote_clipped(reduction) + " is not weighted-average, min or max");
    if (!parse_compare_op(compare_op, c.compare_op))
      throw Error("--compare-op " + quote_clipped(compare_op) + " is not " + kCompareOpNames);
    if (!to_lod_fixed(lod_bias, c.lod_bias)) throw Error("--lod-bias " + std::to_string(lod_bias) + " is outside [-128, 128)");
    if (!to_lod_fixed(min_lod, c.min_lod)) throw Error("--min-lod " + std::to_string(min_lod) + " is outside [-128, 128)");
    if (!to_lod_fixed(max_lod, c.max_lod)) throw Error("--max-lod " + std::to_string(max_lod) + " is outside [-128, 128)");
    if (c.min_lod > c.max_lod) throw Error("--min-lod is greater than --max-lod");
    c.unnormalized = unnormalized;
    check_sampler(c, "--unnormalized: ");
    return c;
  }

  // --border-color: a name, or R,G,B,A (each 0..1, linear) as a custom colour in unorm16.
  void parse_border(SamplerConfig& c) const {
    if (parse_border_color(border_color, c.border)) return;
    std::vector<double> v;
    size_t at = 0;
    for (;;) {
      const size_t comma = border_color.find(',', at);
      const std::string item = border_color.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
      double x = 0;
      const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), x);
      if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !(x >= 0 && x <= 1))
        throw Error("--border-color " + quote_clipped(border_color) + ": " + quote_clipped(item) +
                    " is not a number from 0 to 1 (or use transparent-black, opaque-black, opaque-white)");
      v.push_back(x);
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    if (v.size() != 4)
      throw Error("--border-color " + quote_clipped(border_color) + " has " + std::to_string(v.size()) +
                  " values: give R,G,B,A or a name (transparent-black, opaque-black, opaque-white)");
    c.border = BorderColor::Custom;
    for (size_t i = 0; i < 4; ++i) c.border_custom[i] = uint16_t(std::lround(v[i] * 65535));
  }

  PyramidMode pyramid_mode() const {
    PyramidMode m;
    if (!parse_pyramid_mode(pyramid, m)) throw Error("unknown pyramid mode " + quote_clipped(pyramid) + " (exact, cascade)");
    return m;
  }

  TextureOptions texture_options() const {
    TextureOptions t;
    t.resize = resize;
    t.mode = pyramid_mode();
    t.format = parse_encodable_format(format);
    t.format_given = format_opt->count() > 0;
    t.srgb = srgb;
    t.base_level = base_level;
    t.max_level = max_level;
    return t;
  }

  // Also checks that the engine exists and can honour the options (before any work). `memory`:
  // the memory organisation to use instead of --memory's (a frame that needs the cached unit).
  EngineOptions engine_options(std::optional<Memory> memory_instead = {}) const {
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
    if (memory_instead) o.memory = *memory_instead;
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
      if (!mem_error_at.empty()) o.mem_error_reads = parse_error_reads(mem_error_at);
      // The geometry must be one the caches can have (the texture's channel width sets the line
      // size; 8-bit lines are checked here, the engine checks again with the real texture).
      TextureCache(MemoryLayout(Extent{}, 8, o.layout), o.cache, SamplerConfig{});
    } else {
      for (const CLI::Option* opt : cached_opts)
        if (opt->count()) throw Error(opt->get_name() + " needs --memory cached (the on-chip memories have no cache)");
    }
    make_engine(engine, o);  // unknown engine, --trace with an engine that cannot trace
    if (!o.mem_error_reads.empty() && engine != "model" && engine != "rtl" && engine != "systemc")
      throw Error("--mem-error-at: engine " + engine + " does not inject memory errors (engines model, rtl, systemc)");
    if (!fifo_depth.empty() && engine == "systemc-model")
      throw Error("--fifo-depth: engine systemc-model is loosely timed (a sample waits for its lines; no FIFO to "
                  "size; use --engine model, rtl or systemc)");
    if (no_timing && engine != "model")
      throw Error("--no-timing applies to --engine model (engine " + engine + " is clocked: its timing is the simulation)");
    o.timing = !no_timing;
    o.count_reads = !stats_path.empty();  // the model's read counters are --stats' only: else its fast path
    if (!response_clocks.empty() && no_timing) throw Error("--response-clocks needs the timing model: drop --no-timing");
    if (!response_clocks.empty() && engine == "systemc-model")
      throw Error("--response-clocks: engine systemc-model is loosely timed (the model behind the socket has no "
                  "clocks; use --engine model, rtl or systemc)");
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
  OutputFile* response_clocks_output(OutputSet& outputs) const {
    return response_clocks.empty() ? nullptr : &outputs.declare(response_clocks, "--response-clocks");
  }
};

// --response-clocks: one decimal clock per line.
class ClockWriter final : public ClockSink {
 public:
  explicit ClockWriter(OutputFile& out) : out_(out), file_(out.open()) {}
  void write(const uint64_t* clocks, size_t n) override;
  void close() { out_.close(); }

 private:
  OutputFile& out_;
  std::FILE* file_;
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

// Runs the engine (with --verify through the golden model too) over a table of textures (one for
// a query trace or a paper scene). A failure inside the simulation keeps the waveform, the one
// output of a failed command: it shows what went wrong.
// The stats' sample_seconds is the engine's alone: the time in source.read() (parse_seconds) and
// in sink.write() (write_seconds) is taken out of it (a caller whose source or sink works in a
// thread of its own sets the two to that thread's time).
EngineStats run_engine(const SamplingOptions& o, const EngineOptions& eo, OutputSet& outputs, OutputFile* trace,
                       const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                       TexelSink& sink);

// The summary lines: cycle counters of a cycle-accurate engine, caches, anisotropic probes.
void print_cycle_stats(const EngineStats& stats, const EngineOptions& options);
void print_probe_stats(const EngineStats& stats);
void print_cache_stats(const EngineStats& stats);
// --stats: the engine's counters as JSON, plus `extra` keys (the command's own).
void write_stats(OutputFile* out, const EngineStats& stats, const EngineOptions& options, double seconds,
                 const nlohmann::json& extra = nlohmann::json::object());

// The lines a cached engine reads, as a set (texture bytes touched), passed on to `next` if any.
class LineSet final : public MissSink {
 public:
  explicit LineSet(MissSink* next = nullptr) : next_(next) {}
  void write(const uint32_t* addresses, size_t n) override;
  const std::unordered_set<uint32_t>& lines() const { return lines_; }
  // The bytes of those lines, for lines of `line_bytes` (texture_bytes_touched).
  uint64_t bytes(int line_bytes) const { return uint64_t(lines_.size()) * uint64_t(line_bytes); }

 private:
  MissSink* next_;
  std::unordered_set<uint32_t> lines_;
};

// The figures of a frame of real content (docs/scenes.md), and their totals over frames.
struct FrameFigures {
  uint64_t samples = 0, quads = 0, helper_samples = 0;
  uint32_t textures_used = 0;             // bit t: texture t sampled
  uint64_t texture_bytes_resident = 0;    // every texture of the table, as memory holds it
  uint64_t texture_bytes_touched = 0;     // cached: distinct lines read x line bytes
  std::optional<CacheCounters> cache;     // cached mode
  std::optional<uint64_t> clocks;         // cycle-accurate engines: cycles - pipeline fill
  void add(const FrameFigures& f);        // totals (touched: the caller sets the union)
  nlohmann::json to_json() const;
  std::string summary() const;            // one line
};
FrameFigures frame_figures(const QueryCounts& counts, const EngineStats& stats, uint64_t resident, uint64_t touched);
// The memory's line size for the table's textures (cached mode: one block of their texels).
int line_bytes(const TextureTable& textures, const EngineOptions& options);
// Bytes of every texture of the table in memory: the cached layout's image, or the on-chip levels.
uint64_t texture_bytes_resident(const TextureTable& textures, const EngineOptions& options);

}  // namespace tex

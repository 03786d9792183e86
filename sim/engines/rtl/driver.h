// The one pin-level driver of the Verilated tex_unit (docs/rtl-interface.md): reset, texture load
// (write port or backdoor), the cfg pins, request packing with a tag, response unpacking and the
// in-order tag scoreboard, the time-out, the protocol counters and the FST trace window. The
// Verilator engine (`texsim --engine rtl`), the lockstep tests and the SystemC/TLM wrapper all
// drive the RTL through it. The configuration-specific part (one Verilated class per parameter
// set, rtl_configs.h) is a small template behind tick_pins() in verilated_tex_unit.cpp.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engines/engine.h"
#include "engines/rtl/configs.h"
#include "engines/rtl/memory_model.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"
#include "model/timing.h"

namespace tex::rtl {

constexpr int kTagBits = 16;
constexpr uint32_t kTagMask = (1u << kTagBits) - 1;
constexpr int kResetClocks = 4;

// Values on the input pins during one clock.
struct PinsIn {
  bool rst = false;
  bool wr_en = false;
  uint8_t wr_level = 0;
  uint16_t wr_x = 0, wr_y = 0;
  uint64_t wr_data = 0;  // {A, B, G, R}, CW bits each
  bool req_valid = false;
  int32_t req_u = 0, req_v = 0;  // Q8.24
  int16_t req_lod = 0;           // Q8.8
  int16_t req_bias = 0;          // Q8.8, the request's own LOD bias
  bool req_deriv = false;        // the derivatives below instead of req_lod
  int32_t req_dudx = 0, req_dvdx = 0, req_dudy = 0, req_dvdy = 0;  // Q8.24
  int32_t req_w = 0, req_dwdx = 0, req_dwdy = 0;  // tex_unit_cached: a cube's direction (u, v, w) and derivatives, Q8.24
  uint16_t req_tag = 0;
  uint8_t req_tex = 0;           // tex_unit_cached: the descriptor-table entry
  uint8_t req_sampler = 0;       // tex_unit_cached: the sampler-table entry
  uint8_t req_op = 0;            // tex_pkg::OP_*: a sample, a gather, or a texel fetch (req_u, req_v, req_lod: i, j, level)
  uint8_t req_component = 0;     // a gather's channel, 0..3
  int32_t req_layer = 0;         // tex_unit_cached: an array's layer, Q16.16 (a fetch: the integer layer)
  int32_t req_ref = 0;           // a depth compare's reference, Q8.24
  bool rsp_ready = true;
  // AXI4 read port of tex_unit_cached: driven by the driver's memory model (ignored otherwise).
  bool ar_ready = false;
  bool r_valid = false;
  const uint8_t* r_data = nullptr;  // MEM_W / 8 bytes of the beat
  uint8_t r_resp = 0;               // 0 OKAY, 2 SLVERR
  bool r_last = false;
};

// The request pins for one request (u, v and lod, or the derivatives); req_valid and req_tag are the caller's.
void set_request_pins(PinsIn& in, const Request& r);

// Output pins as seen just before the rising edge: a handshake fires at that edge when
// valid && ready.
struct PinsOut {
  bool req_ready = false;
  bool rsp_valid = false;
  uint64_t rsp_rgba = 0;  // {A, B, G, R}, CW bits each
  uint16_t rsp_tag = 0;
  bool finished = false;  // an RTL assertion ($stop) or $finish happened in this clock
  // tex_unit_cached: rsp_error, the AXI4 read port, and the statistics signals (sampled before the edge).
  bool rsp_error = false;
  bool ar_valid = false;
  uint32_t ar_addr = 0;
  uint8_t ar_len = 0, ar_size = 0, ar_burst = 0;
  bool r_ready = false;
  uint32_t fifo_count = 0;
  bool head_waits = false;
  bool desc_ready = true;  // cfg_desc_ready: the unit takes a descriptor write
};

// tex_unit_cached: one texture descriptor (the cfg_desc_* pins of a write).
struct DescriptorPins {
  uint8_t index = 0;
  uint32_t base = 0;  // byte address of level 0
  uint16_t w = 1, h = 1;  // level 0's size in texels
  uint8_t last_level = 15; // the chain's last level (a view's: docs/rtl-interface.md)
  uint8_t format = 0;  // tex_pkg::FMT_* = TexelFormat
  bool srgb = false;   // R, G, B are sRGB codes (a configuration with the formats)
  uint8_t layers_m1 = 0;  // an array's layers - 1 (0..255; a cube's: 6 a cube)
  bool cube = false;      // a cube map or cube array (CUBE_MAPS)
};

// One sampler, the cfg_smp_* pins (SamplerConfig field for field): tex_unit's static pins, or
// the data of a write of tex_unit_cached's sampler table (entry `index`).
struct SamplerPins {
  uint8_t index = 0;
  uint8_t wrap_u = 0, wrap_v = 0;
  bool min_linear = true;    // the minification filter's texel filter
  bool mag_linear = true;    // the magnification filter (where lambda' <= 0)
  uint8_t mip_mode = 2;
  int16_t lod_bias = 0, min_lod = 0, max_lod = 0;
  uint8_t max_aniso_m1 = 0;  // probes per sample at most, less one (0: trilinear)
  bool aniso_pow2 = false;
  uint64_t border_rgba = 0;  // the border colour, {A, B, G, R} unorm16
  bool unnormalized = false; // req_u, req_v are Q16.16 texels
  uint8_t reduction = 0;     // tex_pkg::REDUCE_*: the weighted average, min or max
  uint8_t compare_op = 3;    // tex_pkg::CMP_* (VkCompareOp): a depth compare's test
};
SamplerPins sampler_pins(const SamplerConfig& config, uint8_t index = 0);

// Static configuration pins: tex_unit's texture size (cfg_w, cfg_h: any size up to the
// configuration's) and its one sampler.
struct CfgPins {
  uint16_t w = 1, h = 1;
  uint8_t last_level = 15;  // cfg_last_level: the chain's last level (15: down to 1x1)
  SamplerPins sampler;
};
CfgPins cfg_pins(const SamplerConfig& config, const Pyramid& pyramid);

// Texel <-> packed {A, B, G, R} of cw bits each (R in the low bits).
uint64_t pack_rgba(const Texel& t, int cw);
Texel unpack_rgba(uint64_t p, int cw);

struct DriverOptions {
  uint64_t seed = 1;            // Verilator's random start values of registers without reset
  std::string trace_path;       // FST, empty = none
  uint64_t trace_begin = 0;     // window of clocks to dump [begin, end]; end 0 = to the end
  uint64_t trace_end = 0;
  uint64_t timeout_cycles = 10000;  // ready clocks without a response while one is owed
  // tex_unit_cached: layout of the pyramid in memory, cache geometry, memory timing.
  LayoutParams layout;
  CacheParams cache;
  MemoryTiming memory;
  uint32_t fifo_depth = 0;  // samples the FIFO holds at most; 0 = the configuration's FIFO_DEPTH
  // tex_unit_cached: drives the memory port instead of the built-in MemoryModel (not owned; the
  // memory image is then the port's business and `memory` is unused).
  MemoryPort* memory_port = nullptr;
  // tex_unit_cached, the built-in MemoryModel: the line reads (1 = the first since the texture
  // load) that answer SLVERR, ascending (--mem-error-at).
  std::vector<uint64_t> mem_error_reads;
  static DriverOptions of(const EngineOptions& o) {
    DriverOptions d;
    d.seed = o.seed;
    d.trace_path = o.trace_path;
    d.trace_begin = o.trace_begin;
    d.trace_end = o.trace_end;
    d.layout = o.layout;
    d.cache = o.cache;
    d.memory.latency = o.mem_latency;
    d.memory.jitter = o.mem_jitter;
    d.memory.bytes_per_clock = o.mem_bytes_per_clock;
    d.memory.max_outstanding = o.mem_outstanding;
    d.fifo_depth = o.fifo_depth;
    d.mem_error_reads = o.mem_error_reads;
    d.memory.seed = o.seed ^ 0x9E3779B97F4A7C15ULL;
    if (d.memory.latency + d.memory.jitter + 10000 > d.timeout_cycles)
      d.timeout_cycles = d.memory.latency + d.memory.jitter + 10000;
    return d;
  }
};

// Counters of tex_unit_cached's memory side since reset_counters().
struct MemoryCounters {
  uint64_t lines_read = 0;         // memory reads (= cache misses)
  uint32_t fifo_max = 0;           // largest sample-FIFO occupancy
  uint64_t head_wait_cycles = 0;   // the FIFO's head sample waits for memory, the output ready
};

// Protocol counters since reset_counters(), counted by clock().
struct ProtocolCounters {
  uint64_t samples = 0;
  uint64_t first_offer_cycle = 0, last_response_cycle = 0;  // valid once samples > 0
  bool any_offer = false;
  uint64_t output_stall_cycles = 0;  // rsp_valid && !rsp_ready
  uint64_t backpressure_cycles = 0;  // req_valid && !req_ready
  uint64_t ready_cycles = 0;         // rsp_ready high
  uint64_t latency_min = 0, latency_max = 0;  // accept edge -> response edge, in clocks
  uint64_t bubbles_after_fill = 0;   // rsp_ready high, no response, one owed, after the first response
  // Responses by the run of stalled clocks just before their handshake: 0, 1-9, 10-99, >= 100.
  uint64_t responses_by_stall_run[4] = {0, 0, 0, 0};
  uint64_t cycles() const { return samples ? last_response_cycle - first_offer_cycle + 1 : 0; }
  // The last response's clock, counted from the first offer (--response-clocks, the timing model's count).
  uint64_t last_response_clock() const { return last_response_cycle - first_offer_cycle; }
};

class Driver {
 public:
  virtual ~Driver();
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  // The Verilated model of `config`. Throws tex::Error.
  static std::unique_ptr<Driver> create(const RtlConfig& config, const DriverOptions& options = {});

  const RtlConfig& config() const { return config_; }
  uint64_t cycle() const { return cycle_; }
  uint64_t load_cycles() const { return load_cycles_; }

  // rst high for `clocks` clocks (no request, no response taken), then one idle clock. Forgets
  // everything in flight.
  void reset(int clocks = kResetClocks);
  // Fills the level memories with the pyramid: Backdoor writes them directly (0 clocks), Port
  // drives the write port, one texel per clock, then one idle clock. Throws tex::Error when the
  // pyramid does not fit the configuration.
  void load(const Pyramid& pyramid, LoadMethod method);
  // tex_unit: texel (x, y) of `level` as the level memories hold it now (debug reads). Throws
  // tex::Error for tex_unit_cached (its texels are in memory) or a texel outside the memories.
  Texel peek_texel(int level, int x, int y) const;
  // tex_unit_cached: several textures in memory (packed from the layout's base, as
  // texture_descriptors() does) and in the descriptor table; requests name them by
  // Request::texture. (load() of one pyramid is a table of one.) Throws tex::Error when a texture
  // does not fit the configuration or the table.
  void load_textures(const TextureTable& textures);
  // The cfg pins: tex_unit's, or tex_unit_cached's sampler table of one entry (cfg.sampler); a
  // cached unit then starts empty (a reset) and its descriptors and samplers are written again.
  void configure(const CfgPins& cfg);
  void configure(const SamplerConfig& config, const Pyramid& pyramid) {
    configure(cfg_pins(config, pyramid));
  }
  // tex_unit_cached: the sampler table (requests name an entry by Request::sampler), after a reset
  // with the descriptors. Throws tex::Error for tex_unit or more samplers than the table holds.
  void configure(const SamplerTable& samplers);

  // One clock of the request/response protocol. `offer` is presented on the request pins (nullptr:
  // req_valid low), tagged with its sequence number mod 2^16; once offered it must be offered again
  // until accepted (the RTL asserts it). rsp_ready = take_response. The scoreboard checks that each
  // response carries the tag of the oldest request in flight: a lost, duplicated, reordered or
  // spurious response, or no response for timeout_cycles ready clocks, is a tex::Error naming the
  // tag, the request number and the clock.
  struct Clock {
    bool accepted = false;   // the offered request was taken at this edge (sequence `accepted_index`)
    bool responded = false;  // a response was taken at this edge
    uint64_t accepted_index = 0;
    uint64_t response_index = 0;  // sequence number of the request it answers
    uint64_t rgba = 0;            // {A, B, G, R} CW bits each
    bool error = false;           // rsp_error: the sample read a line memory answered with an error
  };
  Clock clock(const Request* offer, bool take_response);

  // tex_unit_cached: layout, cache geometry and memory timing of the next load().
  void set_memory(const LayoutParams& layout, const CacheParams& cache, const MemoryTiming& timing,
                  uint32_t fifo_depth = 0) {
    options_.layout = layout;
    options_.cache = cache;
    options_.memory = timing;
    options_.fifo_depth = fifo_depth;
  }
  // tex_unit_cached: the line reads that answer SLVERR from the next load() on (1 = its first read).
  void set_memory_errors(std::vector<uint64_t> reads) { options_.mem_error_reads = std::move(reads); }
  // tex_unit_cached: the built-in memory model (null for tex_unit or with an external memory port),
  // the port in use (null for tex_unit), and the counters.
  MemoryModel* memory() { return memory_.get(); }
  MemoryPort* memory_port() { return port_; }
  const MemoryCounters& memory_counters() const { return memory_counters_; }

  uint64_t in_flight() const { return issued_ - answered_; }
  bool last_response_error() const { return last_error_; }  // rsp_error of the last response taken
  uint64_t issued() const { return issued_; }
  const ProtocolCounters& counters() const { return counters_; }
  void reset_counters();

  // One clock with raw pins, for tests that drive the protocol themselves; bypasses the scoreboard.
  // Closes the trace and throws tex::SimulationError when an RTL assertion fires.
  // For tex_unit_cached, the memory model drives the mem_* inputs.
  PinsOut tick(const PinsIn& in) {
    if (tracing_ || port_) return tick_full(in);  // the rare paths stay out of the per-clock code
    const PinsOut out = tick_pins(in, false);
    if (out.finished) fail_finished();
    ++cycle_;
    return out;
  }
  void close_trace();

 protected:
  Driver(const RtlConfig& config, const DriverOptions& options);
  // Configuration-specific part: set the pins, clock once, read the outputs (and whether an RTL
  // assertion or $finish happened).
  virtual PinsOut tick_pins(const PinsIn& in, bool dump_trace) = 0;
  virtual void apply_cfg(const CfgPins& cfg) = 0;
  virtual void apply_cache_pins(const CachePins& pins) = 0;  // tex_unit_cached only
  // tex_unit_cached: the cfg_desc_* pins, cfg_desc_we = `write` (set for one clock, then cleared).
  virtual void apply_descriptor(const DescriptorPins& pins, bool write) = 0;
  // tex_unit_cached: the cfg_smp_* pins, cfg_smp_we = `write` (likewise).
  virtual void apply_sampler(const SamplerPins& pins, bool write) = 0;
  // Writes one word into the bank memory of `level` holding texels of parity `bank`.
  virtual void backdoor_write(int level, int bank, uint32_t word, uint64_t data) = 0;
  virtual uint64_t backdoor_read(int level, int bank, uint32_t word) const = 0;
  virtual void close_trace_impl() = 0;

  RtlConfig config_;
  DriverOptions options_;
  bool tracing_ = false;

 private:
  PinsOut tick_full(const PinsIn& in);
  [[noreturn]] void fail_finished();
  // An AR request's burst: one INCR burst of a whole line (a tex::SimulationError otherwise).
  void check_burst(const PinsOut& out) const;
  void write_tables();  // cached: descriptors_ and samplers_ into the tables, then an idle clock

  uint64_t cycle_ = 0;
  uint64_t load_cycles_ = 0;
  // Scoreboard: requests issued and answered since reset, accept clocks of those in flight.
  uint64_t issued_ = 0, answered_ = 0;
  static constexpr size_t kRing = 4096;  // more in flight than this is an RTL error
  uint64_t accept_clock_[kRing] = {};
  uint64_t idle_ready_clocks_ = 0;
  uint64_t stall_run_ = 0;
  bool filled_ = false;
  bool last_error_ = false;
  ProtocolCounters counters_;
  PinsIn pins_;
  std::unique_ptr<MemoryModel> memory_;
  MemoryPort* port_ = nullptr;  // memory_ or options_.memory_port
  MemoryCounters memory_counters_;
  CfgPins cfg_;
  std::vector<DescriptorPins> descriptors_;  // cached: the table as loaded
  std::vector<SamplerPins> samplers_;        // cached: the sampler table as configured
};

// ---------------------------------------------------------------- stimulus

// Input gaps and output stalls (model/timing.h): the RTL harness and the timing model draw them
// from the same generator.
using Timing = tex::Stimulus;

// Counters of one stream() call: the driver's protocol counters plus the stimulus's own.
struct StreamStats {
  ProtocolCounters protocol;
  MemoryCounters memory;
  uint64_t gap_cycles = 0;          // req_valid held low by the stimulus with requests left
  uint64_t requests_after_gap = 0;  // requests accepted right after an input gap
  std::vector<uint64_t> error_responses;  // responses with rsp_error (their index in the stream)
  uint64_t samples() const { return protocol.samples; }
  uint64_t cycles() const { return protocol.cycles(); }
};

// Streams the requests through the driver with the given timing (random choices from `seed`),
// calls on_response(index, rgba) for every response in order, then idles 64 clocks: anything that
// still comes out is a duplicated response (tex::Error). progress(done) every 65536 responses.
using ResponseFn = std::function<void(size_t index, uint64_t rgba)>;
StreamStats stream(Driver& driver, RequestSource& source, const Timing& timing, uint64_t seed,
                   const ResponseFn& on_response, const std::function<void(size_t done)>& progress = {});
StreamStats stream(Driver& driver, const Request* requests, size_t n, const Timing& timing, uint64_t seed,
                   const ResponseFn& on_response, const std::function<void(size_t done)>& progress = {});

}  // namespace tex::rtl

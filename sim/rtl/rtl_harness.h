// The harness of the Verilated tex_unit (docs/rtl-interface.md): clock, reset, seed, time-out,
// FST trace of a window of cycles, texture loading, request streaming with random input gaps and
// output stalls, and an in-order tag check of every response. Used by `texsim --engine rtl` and by
// tests/rtl. One class for every compiled parameter configuration: the configuration-specific part
// is a small template (rtl_models.cpp) behind the pin-level `tick`.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"

namespace tex::rtl {

// One Verilated parameter configuration of tex_unit (TAG_W = 16).
struct RtlShape {
  std::string name;  // Verilator --prefix, e.g. "Vtex_unit_10x10"
  int max_log2_w = 0, max_log2_h = 0;
  int cw = 8;  // bits per channel
  bool fits(int log2_w, int log2_h) const { return log2_w <= max_log2_w && log2_h <= max_log2_h; }
};

// Every compiled configuration: the 8-bit ones smallest first, then the 16-bit one.
const std::vector<RtlShape>& compiled_shapes();
// The smallest 8-bit configuration that holds a 2^log2_w x 2^log2_h texture; throws tex::Error
// naming the largest one when none does.
const RtlShape& smallest_shape_for(int log2_w, int log2_h);

constexpr int kTagBits = 16;
constexpr uint32_t kTagMask = (1u << kTagBits) - 1;

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
  uint16_t req_tag = 0;
  bool rsp_ready = true;
};

// Output pins as seen just before the rising edge: a handshake fires at that edge when
// valid && ready.
struct PinsOut {
  bool req_ready = false;
  bool rsp_valid = false;
  uint64_t rsp_rgba = 0;  // {A, B, G, R}, CW bits each
  uint16_t rsp_tag = 0;
};

// Static configuration ports.
struct CfgPins {
  uint8_t log2_w = 0, log2_h = 0;
  uint8_t wrap_u = 0, wrap_v = 0;
  bool texel_linear = true;
  uint8_t mip_mode = 2;
  int16_t lod_bias = 0, min_lod = 0, max_lod = 0;
};
CfgPins cfg_pins(const SamplerConfig& config, int log2_w, int log2_h);

// Stimulus timing. All probabilities are per clock; 0 everywhere = ideal (one request offered and
// the response accepted in every clock).
struct Timing {
  double gap_prob = 0;         // start an input gap (req_valid low) in this clock
  int max_gap = 1;             // a gap lasts 1..max_gap clocks
  double stall_prob = 0;       // start an output stall (rsp_ready low) in this clock
  int max_stall = 1;           // a stall lasts 1..max_stall clocks
  double long_stall_prob = 0;  // start a long stall of long_stall clocks instead
  int long_stall = 300;
  static Timing ideal() { return {}; }
  static Timing random_default();  // moderate gaps and stalls, used by `texsim --engine rtl --seed N` (N != 0)
};

struct HarnessOptions {
  uint64_t seed = 1;            // Verilator's random reset values of non-reset registers, and timing
  std::string trace_path;       // FST, empty = none
  uint64_t trace_begin = 0;     // window of clocks to dump [begin, end]; end 0 = to the end
  uint64_t trace_end = 0;
  uint64_t timeout_cycles = 0;  // clocks without progress before a time-out; 0 = automatic
};

// Counters of one stream() call (the sampling phase only).
struct StreamStats {
  uint64_t samples = 0;
  uint64_t cycles = 0;            // first clock with a request offered .. last response, inclusive
  uint64_t stall_cycles = 0;      // rsp_valid && !rsp_ready
  uint64_t ready_cycles = 0;      // rsp_ready high (in the sampling phase)
  uint64_t gap_cycles = 0;        // req_valid held low by the driver with requests left
  uint64_t backpressure_cycles = 0;  // req_valid && !req_ready
  uint64_t latency_min = 0, latency_max = 0;  // accept edge -> response edge, in clocks
  uint64_t bubbles_after_fill = 0;  // clocks after the first response with rsp_ready high, no rsp_valid,
                                    // and responses still owed
  // Responses by the run of stalled clocks (rsp_valid && !rsp_ready) just before their handshake:
  // 0, 1-9, 10-99, >= 100 clocks (functional coverage of the output side).
  uint64_t responses_by_stall_run[4] = {0, 0, 0, 0};
  uint64_t requests_after_gap = 0;  // requests accepted right after an input gap
};

class Harness {
 public:
  virtual ~Harness();
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  // Builds the smallest (or the named) configuration. Throws tex::Error.
  static std::unique_ptr<Harness> create(const RtlShape& shape, const HarnessOptions& options = {});

  const RtlShape& shape() const { return shape_; }
  uint64_t cycle() const { return cycle_; }
  uint64_t load_cycles() const { return load_cycles_; }

  // One clock: drives `in`, returns the outputs before the rising edge. Closes the trace and
  // throws tex::Error when an RTL assertion fires; closes the trace and ends the process as
  // Ctrl-C would when SIGINT arrived.
  PinsOut tick(const PinsIn& in);

  // rst high for `cycles` clocks (requests and responses idle), then one idle clock.
  void reset(int cycles = 4);
  // Writes every level of the pyramid through the write port, one texel per clock.
  void load(const Pyramid& pyramid);
  void configure(const CfgPins& cfg);
  const CfgPins& config() const { return cfg_; }

  // Streams the requests with the given timing (random choices from `seed`). Each request gets
  // tag = index mod 2^16; responses must come back in order: a response with another tag than the
  // oldest outstanding one (lost, duplicated or reordered), a response with nothing outstanding,
  // or no progress for the time-out is a tex::Error naming tag, request index and clock.
  // on_response(index, rgba) is called for every response, in order.
  using ResponseFn = std::function<void(size_t index, uint64_t rgba)>;
  StreamStats stream(const Request* requests, size_t n, const Timing& timing, uint64_t seed,
                     const ResponseFn& on_response, const std::function<void(size_t done)>& progress = {});

  void close_trace();

 protected:
  Harness(const RtlShape& shape, const HarnessOptions& options);
  // Configuration-specific part: set the pins, clock once, read outputs.
  virtual PinsOut tick_pins(const PinsIn& in, bool dump_trace) = 0;
  virtual void apply_cfg(const CfgPins& cfg) = 0;
  virtual bool got_finish() const = 0;  // an assertion ($stop) or $finish happened
  virtual void close_trace_impl() = 0;

  RtlShape shape_;
  HarnessOptions options_;
  bool tracing_ = false;

 private:
  uint64_t cycle_ = 0;
  uint64_t load_cycles_ = 0;
  CfgPins cfg_{};
};

// Texel <-> packed {A, B, G, R} of cw bits each (R in the low bits).
uint64_t pack_rgba(const Texel& t, int cw);
Texel unpack_rgba(uint64_t p, int cw);
inline uint32_t pack_rgba8(const Texel& t) { return uint32_t(pack_rgba(t, 8)); }
inline Texel unpack_rgba8(uint64_t p) { return unpack_rgba(p, 8); }

}  // namespace tex::rtl

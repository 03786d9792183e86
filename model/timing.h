// The timing layer of the golden model (docs/timing.md): for every response, the clock at which it
// leaves the unit, exactly as the RTL gives it. The functional model (sampler, texture cache) stays
// the bit-level specification; this layer adds when. It clocks only what decides timing: the
// valid bits of every pipeline register, tex_probe's sequencer, and in the cached unit the sample
// FIFO, the miss ring, the fill FIFO and the head's fills, against the memory channel the RTL
// harness uses (model/memory_channel.h). A request's timing depends on its probe count and on how
// many lines each probe misses, which the functional model gives (RequestWork).
//
// Stage names are the RTL's (rtl/tex_unit.sv, rtl/tex_unit_cached.sv, rtl/tex_cached_fetch.sv):
//   tex_probe (request clocks 1-4, sequencer) -> probe registers -> tex_accum (2) -> tex_skid, and
//   in the cached unit: tex_probe -> front (4) -> tag stage / FIFO push -> H (head) -> R -> T ->
//   taps -> filter (3) -> tex_accum (2) -> tex_skid.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "model/formats.h"
#include "model/memory_channel.h"

namespace tex {

// Stimulus timing: `none` offers a request and takes a response in every clock (what the hardware
// does when nothing stalls it); `random` and `heavy` add input gaps and output stalls drawn from
// the seed (moderate, and in about 60% of the clocks).
enum class Stalls { None, Random, Heavy };

// Input gaps and output stalls, probabilities per clock; all 0 = ideal (a request offered and the
// response taken in every clock).
struct Stimulus {
  double gap_prob = 0;         // start an input gap (req_valid low) in this clock
  int max_gap = 1;             // a gap lasts 1..max_gap clocks
  double stall_prob = 0;       // start an output stall (rsp_ready low) in this clock
  int max_stall = 1;           // a stall lasts 1..max_stall clocks
  double long_stall_prob = 0;  // start a long stall of long_stall clocks instead
  int long_stall = 300;
  bool ideal() const { return gap_prob == 0 && stall_prob == 0 && long_stall_prob == 0; }
  static Stimulus of(Stalls stalls);  // the profiles of --stalls
};

// The stimulus's choices clock by clock, from its seed: every cycle-accurate engine (the RTL
// harness, the timing model) draws from this one generator, so they see the same gaps and stalls.
class StimulusClock {
 public:
  StimulusClock(const Stimulus& s, uint64_t seed) : s_(s), rng_(seed) {}
  // The coming clock, with `have` a request left to offer: whether it is offered, whether a
  // response is taken.
  void begin(bool have, bool& offer, bool& ready) {
    if (gap_left_ == 0 && !holding_ && s_.gap_prob > 0 && have && unit() < s_.gap_prob)
      gap_left_ = 1 + int(rng_() % uint64_t(std::max(1, s_.max_gap)));
    if (stall_left_ == 0) {
      if (s_.long_stall_prob > 0 && unit() < s_.long_stall_prob)
        stall_left_ = s_.long_stall;
      else if (s_.stall_prob > 0 && unit() < s_.stall_prob)
        stall_left_ = 1 + int(rng_() % uint64_t(std::max(1, s_.max_stall)));
    }
    offer = have && gap_left_ == 0;
    if (gap_left_ > 0) {
      --gap_left_;
      if (have) {
        ++gap_cycles;
        after_gap_ = true;
      }
    }
    ready = stall_left_ == 0;
    if (stall_left_ > 0) --stall_left_;
    offered_ = offer;
  }
  // The clock's edge: whether the offered request was taken (once offered, it is offered again
  // until taken: gaps start only between requests).
  void end(bool accepted) {
    holding_ = offered_ && !accepted;
    if (accepted) {
      requests_after_gap += after_gap_;
      after_gap_ = false;
    }
  }
  uint64_t gap_cycles = 0;          // req_valid held low with requests left
  uint64_t requests_after_gap = 0;  // requests accepted right after an input gap

 private:
  double unit() { return double(rng_() >> 11) * (1.0 / 9007199254740992.0); }
  Stimulus s_;
  std::mt19937_64 rng_;
  int gap_left_ = 0, stall_left_ = 0;
  bool holding_ = false, after_gap_ = false, offered_ = false;
};

// What one request's timing depends on: its probes (tex_probe: 1, or N of an anisotropic
// footprint) and, in the cached unit, the lines each probe misses (the tag stage's fills, 0..8).
struct RequestWork {
  uint64_t fill_bits = 0;  // probe i's fills in bits [4i, 4i + 4)
  uint8_t probes = 1;
  bool error = false;      // a line it looked up came from memory with an error (no effect on timing)
  uint32_t fills(int probe) const { return uint32_t(fill_bits >> (4 * probe)) & 15u; }
  void set_fills(int probe, uint32_t n) {
    fill_bits = (fill_bits & ~(uint64_t(15) << (4 * probe))) | uint64_t(n & 15u) << (4 * probe);
  }
};

// The unit's parameters that decide timing (the RTL's, rtl/tex_unit_cached.sv).
struct UnitShape {
  bool cached = false;
  uint32_t fifo_depth = 256;  // FIFO_DEPTH (power of two)
  uint32_t fifo_limit = 0;    // cfg_fifo_limit: samples the FIFO holds at most; 0 = fifo_depth
  uint32_t miss_depth = 64;   // MISS_DEPTH
  uint32_t fill_depth = 4;    // FILL_DEPTH
  uint32_t line_beats = 1;    // beats per line (line bytes / beat bytes)
  uint32_t cube_clocks = 0;   // CUBE_MAPS: tex_cube's clocks ahead of tex_probe (kCubeClocks; and
                              // tex_cube_seam's kSeamClocks after it), else 0
};
constexpr uint64_t kOnChipLatency = 16;  // tex_unit: request handshake -> response, one probe, no stall
constexpr uint64_t kCachedLatency = 19;  // tex_unit_cached, every line hitting (CUBE_MAPS: + kCubeClocks + kSeamClocks)
constexpr uint32_t kCubeClocks = 6;      // tex_cube: every request's line ahead of tex_probe
constexpr uint32_t kSeamClocks = 4;      // tex_cube_seam: every probe's clocks ahead of the front (CUBE_MAPS)

// Counters of a timed stream (the cycle-accurate engines' CycleStats and cache counters).
struct TimingCounters {
  uint64_t samples = 0;
  uint64_t first_offer_cycle = 0, last_response_cycle = 0;  // valid once samples > 0
  bool any_offer = false;
  uint64_t latency_min = 0, latency_max = 0;  // accept edge -> response edge
  uint64_t output_stall_cycles = 0;           // rsp_valid && !rsp_ready
  uint64_t backpressure_cycles = 0;           // req_valid && !req_ready
  uint64_t gap_cycles = 0;                    // no request offered while some remain
  uint64_t lines_read = 0;                    // cached: memory reads
  uint32_t fifo_max = 0;                      // cached: the sample FIFO's largest occupancy
  uint64_t head_wait_cycles = 0;              // cached: the FIFO's head waits for memory, the output ready
  uint64_t cycles() const { return samples ? last_response_cycle - first_offer_cycle + 1 : 0; }
};

// The unit, clock by clock, valid bits only. clock() is one rising edge with the request pins
// (offer: the request on req_valid, or null) and rsp_ready; it says what fired at that edge.
class UnitClock {
 public:
  // `memory`: the cached unit's memory channel as it stands (copied; null on-chip). `always_ready`:
  // rsp_ready is high in every clock (the ideal stimulus): the cached unit's back (H to the output
  // register) is then a fixed delay line, which the model clocks as one shift register.
  UnitClock(const UnitShape& shape, const MemoryChannel* memory, bool always_ready = false);

  // (One word of flags, not three bools: a struct of bytes returned through memory stalls the
  // caller's load of it, which cost a third of a clock's time.)
  struct Edge {
    uint32_t flags = 0;
    static constexpr uint32_t kAccepted = 1, kResponded = 2, kRspValid = 4;
    bool accepted() const { return flags & kAccepted; }    // req_valid && req_ready
    bool responded() const { return flags & kResponded; }  // rsp_valid && rsp_ready
    bool rsp_valid() const { return flags & kRspValid; }   // a response was on the output (taken or not)
  };
  Edge clock(const RequestWork* offer, bool ready) { return shape_.cached ? clock_cached(offer, ready) : clock_onchip(offer, ready); }
  // Clocks in which the unit only waits for memory (the front full, the back empty, the FIFO's head
  // waiting for its first fill) run here in a tight loop of the memory channel alone, until a line
  // has arrived: the same clocks clock() would run, with no request taken and no response. Returns
  // how many (0 when the unit is not in that state).
  uint64_t wait_for_fill();
  uint32_t fifo_limit() const { return fifo_limit_; }

  uint64_t lines_read = 0, head_wait_cycles = 0;
  uint32_t fifo_max = 0;

 private:
  Edge clock_onchip(const RequestWork* offer, bool ready);
  Edge clock_cached(const RequestWork* offer, bool ready);
  // tex_probe with enable en: accepts the offer, issues one probe per clock (valid, last, fills).
  // `ready`: tex_probe's req_ready (en and no request held for its probes).
  bool probe_stage(const RequestWork* offer, bool en, bool& probe_valid, bool& probe_last, uint8_t& probe_fills,
                   bool& ready);
  void skid_stage(bool sample_valid, bool ready);

  UnitShape shape_;
  MemoryChannel memory_;
  // tex_probe: the request registers' valid bits (bit k-1: clock k) and the requests in them,
  // oldest (clock 4) at probe_head_; the sequencer's probe index.
  uint32_t probe_valid_ = 0;
  std::array<RequestWork, 4> probe_work_{};
  uint32_t probe_head_ = 0, probe_tail_ = 0;
  uint32_t index_ = 0;
  // CUBE_MAPS: the line of cube_clocks registers ahead of tex_probe (bit k-1: clock k), advancing
  // with tex_probe's req_ready; its requests, oldest at line_head_.
  uint32_t line_valid_ = 0;
  std::array<RequestWork, 8> line_work_{};
  uint32_t line_head_ = 0, line_tail_ = 0;
  // tex_unit: the probe registers 1-9 (bit n-1) and whether each holds its sample's last probe.
  uint32_t pipe_valid_ = 0, pipe_last_ = 0;
  // tex_accum's clock 1 and 2, tex_skid's output register and skid entry.
  bool s1_valid_ = false, s1_last_ = false, sample_valid_ = false;
  bool out_valid_ = false, skid_valid_ = false;
  // tex_unit_cached: en_front; the front's clock 1-4 (bit n-1), each probe's fills and last.
  bool en_front_ = true;
  // (4 clocks, 8 with CUBE_MAPS: tex_cube_seam's 4 ahead of them; each clock's {last, fills} in 5
  // bits of front_probes_, clock n at bits 5(n-1).)
  uint32_t front_valid_ = 0, front_clocks_ = 4;
  uint64_t front_probes_ = 0;
  // The sample FIFO: each entry's fills (low 4 bits) and last (bit 4). (16-bit entries: a write
  // through a char type would alias every member and force the clock's state out of registers.)
  std::vector<uint16_t> fifo_;
  uint32_t fifo_rd_ = 0, fifo_wr_ = 0, fifo_count_ = 0, fifo_limit_ = 0;
  uint32_t ring_used_ = 0, ring_unissued_ = 0;  // the miss ring
  uint32_t fill_count_ = 0, beat_ = 0;          // the fill FIFO
  bool h_valid_ = false, h_last_ = false;       // H: the head and its fills to write
  uint32_t h_fills_ = 0;
  bool r_valid_ = false, r_last_ = false, t_valid_ = false, t_last_ = false, o_valid_ = false, o_last_ = false;
  uint32_t back_valid_ = 0, back_last_ = 0;     // the filter's clocks 1-3 (bit n-1)
  // always_ready: bit k set = a sample's last probe left H k + 1 clocks before its response clock
  // (R, T, taps, filter 1-3, tex_accum 1-2, output register: 9 registers).
  bool always_ready_ = false;
  uint32_t back_line_ = 0;
};

// A stream of requests through the unit under the stimulus: requests are queued as the functional
// model produces them (push); run() clocks while a queued request remains to be offered, finish()
// until the last response. Both append the clock of each response handshake, in response order,
// to `clocks` (if not null), counted from the clock in which the first request was offered.
class TimedStream {
 public:
  TimedStream(const UnitShape& shape, const MemoryChannel* memory, const Stimulus& stimulus, uint64_t seed);
  void push(const RequestWork& w) { queue_.push_back(w); }
  void run(std::vector<uint64_t>* clocks);
  void finish(std::vector<uint64_t>* clocks);
  TimingCounters counters() const;
  uint32_t fifo_limit() const { return unit_.fifo_limit(); }  // cached: the FIFO depth in use

 private:
  void step(const RequestWork* next, std::vector<uint64_t>* clocks);

  UnitClock unit_;
  StimulusClock stimulus_;
  bool ideal_;
  std::vector<RequestWork> queue_;
  size_t head_ = 0;
  uint64_t now_ = 0, accepted_ = 0, done_ = 0;
  std::vector<uint64_t> accept_clock_;  // accept clocks of the requests in flight (a power of two)
  TimingCounters c_;
};

}  // namespace tex

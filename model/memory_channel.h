// The external memory's timing, clock by clock (docs/memory.md §4): a fixed latency with optional
// random jitter, a bandwidth in bytes per clock, a limit on outstanding reads, optional random
// backpressure on the request port; responses in request order, one beat per clock at most. It
// knows addresses but not data: the RTL harness's memory model (engines/rtl/memory_model.h) adds
// the image, the timing model (model/timing.h) uses it as it is. One piece of code, so that both
// draw the same random numbers in the same clocks.
#pragma once
#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "model/error.h"

namespace tex {

struct MemoryTiming {
  uint32_t latency = 100;          // clocks from the request handshake to the first beat's valid
  uint32_t jitter = 0;             // + a uniform 0..jitter clocks per read (order is kept)
  uint32_t bytes_per_clock = 16;   // bandwidth: at most one beat per clock
  uint32_t max_outstanding = 64;   // reads accepted and not yet fully returned
  double request_stall_prob = 0;   // mem_req_ready low in a clock it could be high (test stress)
  double response_stall_prob = 0;  // a beat that could be sent is held back (test stress)
  uint64_t seed = 1;
};

class MemoryChannel {
 public:
  // Throws tex::Error when the bandwidth or the beat do not fit the line.
  MemoryChannel(int line_bytes, int beat_bytes, const MemoryTiming& timing);

  // Pins for the coming clock edge.
  bool request_ready() const { return request_ready_; }
  bool response_valid() const { return response_valid_; }
  // The read whose beat is offered: its line address and the beat's index.
  uint32_t response_address() const { return pending_[head_ & mask_].address; }
  int response_beat() const { return beat_; }
  // The clock edge: a read of `address` was taken and/or the offered beat was taken. Throws
  // tex::Error when the caller takes what was not offered.
  void clock(bool request_fire, uint32_t address, bool response_fire) {
    if (!request_fire && !response_fire && count_ == 0 && credit_ == uint32_t(beat_bytes_) && quiet_) {
      ++now_;  // nothing in flight, nothing drawn: the pins stay as they are
      return;
    }
    clock_slow(request_fire, address, response_fire);
  }
  // Forgets every read in flight (the unit was reset); the bandwidth credit starts full.
  void reset();

  uint64_t now() const { return now_; }
  uint64_t repeats_in_flight() const { return repeats_; }  // reads of a line already in flight
  void count_repeats(bool on) { count_repeats_ = on; }    // (a scan of the reads in flight per read)
  int line_bytes() const { return line_bytes_; }
  int beat_bytes() const { return beat_bytes_; }
  const MemoryTiming& timing() const { return timing_; }

 private:
  void clock_slow(bool request_fire, uint32_t address, bool response_fire);
  void prepare();  // the pins of the next clock
  double unit() { return double(rng_() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1) from 53 bits
  struct Read {
    uint32_t address;
    uint64_t ready_at;  // clock of the first beat
  };
  int line_bytes_, beat_bytes_;
  MemoryTiming timing_;
  std::mt19937_64 rng_;
  std::vector<Read> pending_;       // reads in flight, oldest at head_ (a ring of a power of two)
  uint32_t head_ = 0, count_ = 0, mask_ = 0;
  bool quiet_ = true;               // no random backpressure: an idle clock draws nothing
  uint64_t now_ = 0, last_ready_ = 0;
  uint32_t credit_ = 0;  // bytes the channel may send (at most one beat's worth)
  int beat_ = 0;         // beat of the oldest read being sent
  bool request_ready_ = true, response_valid_ = false;
  uint64_t repeats_ = 0;
  bool count_repeats_ = true;
};

// (Inline: in a bandwidth-bound stream the channel works in every clock.)
inline void MemoryChannel::prepare() {
  request_ready_ = count_ < timing_.max_outstanding &&
                   !(timing_.request_stall_prob > 0 && unit() < timing_.request_stall_prob);
  response_valid_ = count_ != 0 && pending_[head_ & mask_].ready_at <= now_ && credit_ >= uint32_t(beat_bytes_) &&
                    !(timing_.response_stall_prob > 0 && unit() < timing_.response_stall_prob);
}

inline void MemoryChannel::clock_slow(bool request_fire, uint32_t address, bool response_fire) {
  if (response_fire) {
    if (!response_valid_) throw Error("memory: a beat taken while none was offered");
    credit_ -= uint32_t(beat_bytes_);
    if (++beat_ * beat_bytes_ == line_bytes_) {
      beat_ = 0;
      ++head_;
      --count_;
    }
  }
  if (request_fire) {
    if (!request_ready_) throw Error("memory: a read taken while mem_req_ready was low");
    uint64_t ready = now_ + timing_.latency + (timing_.jitter ? rng_() % (uint64_t(timing_.jitter) + 1) : 0);
    ready = std::max(ready, last_ready_);  // in order
    if (count_repeats_)
      for (uint32_t i = 0; i < count_; ++i) repeats_ += pending_[(head_ + i) & mask_].address == address;
    last_ready_ = ready;
    pending_[(head_ + count_++) & mask_] = {address, ready};
  }
  ++now_;
  credit_ = std::min<uint32_t>(credit_ + timing_.bytes_per_clock, uint32_t(beat_bytes_));
  prepare();
}

}  // namespace tex

#include "model/memory_channel.h"

#include <algorithm>
#include <string>

#include "model/error.h"

namespace tex {

namespace {
inline double unit(std::mt19937_64& rng) { return double(rng() >> 11) * (1.0 / 9007199254740992.0); }
}  // namespace

MemoryChannel::MemoryChannel(int line_bytes, int beat_bytes, const MemoryTiming& timing)
    : line_bytes_(line_bytes), beat_bytes_(beat_bytes), timing_(timing), rng_(timing.seed) {
  if (beat_bytes_ <= 0 || line_bytes_ % beat_bytes_ != 0)
    throw Error("memory beat of " + std::to_string(beat_bytes_) + " bytes does not divide the " +
                std::to_string(line_bytes_) + "-byte line");
  if (timing_.bytes_per_clock == 0 || timing_.bytes_per_clock > uint32_t(beat_bytes_))
    throw Error("memory bandwidth " + std::to_string(timing_.bytes_per_clock) +
                " bytes per clock: the memory port carries 1 to " + std::to_string(beat_bytes_) +
                " bytes per clock (one beat)");
  if (timing_.max_outstanding == 0) throw Error("the memory's outstanding-read limit must be at least 1");
  credit_ = uint32_t(beat_bytes_);
  prepare();
}

void MemoryChannel::reset() {
  pending_.clear();
  beat_ = 0;
  credit_ = uint32_t(beat_bytes_);
  last_ready_ = now_;
  prepare();
}

void MemoryChannel::prepare() {
  request_ready_ = pending_.size() < timing_.max_outstanding &&
                   !(timing_.request_stall_prob > 0 && unit(rng_) < timing_.request_stall_prob);
  response_valid_ = !pending_.empty() && pending_.front().ready_at <= now_ && credit_ >= uint32_t(beat_bytes_) &&
                    !(timing_.response_stall_prob > 0 && unit(rng_) < timing_.response_stall_prob);
}

void MemoryChannel::clock(bool request_fire, uint32_t address, bool response_fire) {
  if (response_fire) {
    if (!response_valid_) throw Error("memory: a beat taken while none was offered");
    credit_ -= uint32_t(beat_bytes_);
    if (++beat_ * beat_bytes_ == line_bytes_) {
      beat_ = 0;
      pending_.pop_front();
    }
  }
  if (request_fire) {
    if (!request_ready_) throw Error("memory: a read taken while mem_req_ready was low");
    uint64_t ready = now_ + timing_.latency + (timing_.jitter ? rng_() % (uint64_t(timing_.jitter) + 1) : 0);
    ready = std::max(ready, last_ready_);  // in order
    if (count_repeats_)
      for (const Read& r : pending_) repeats_ += r.address == address;
    last_ready_ = ready;
    pending_.push_back({address, ready});
  }
  ++now_;
  credit_ = std::min<uint32_t>(credit_ + timing_.bytes_per_clock, uint32_t(beat_bytes_));
  prepare();
}

}  // namespace tex

#include "model/memory_channel.h"

#include <algorithm>
#include <string>

#include "model/error.h"

namespace tex {

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
  uint32_t ring = 1;
  while (ring < timing_.max_outstanding) ring *= 2;
  pending_.resize(ring);
  mask_ = ring - 1;
  quiet_ = !(timing_.request_stall_prob > 0) && !(timing_.response_stall_prob > 0);
  prepare();
}

void MemoryChannel::reset() {
  head_ = count_ = 0;
  beat_ = 0;
  credit_ = uint32_t(beat_bytes_);
  last_ready_ = now_;
  prepare();
}

}  // namespace tex

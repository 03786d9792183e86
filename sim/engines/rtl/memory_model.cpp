#include "engines/rtl/memory_model.h"

#include <cstdio>

#include "engines/engine.h"
#include "model/error.h"

namespace tex::rtl {

namespace {
inline double unit(std::mt19937_64& rng) { return double(rng() >> 11) * (1.0 / 9007199254740992.0); }
}  // namespace

std::string hex_address(uint32_t address) {
  char s[16];
  std::snprintf(s, sizeof s, "0x%08x", address);
  return s;
}

MemoryModel::MemoryModel(std::vector<uint8_t> image, uint32_t base, int line_bytes, int beat_bytes,
                         const MemoryTiming& timing)
    : image_(std::move(image)), base_(base), line_bytes_(line_bytes), beat_bytes_(beat_bytes), timing_(timing),
      rng_(timing.seed) {
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

void MemoryModel::reset() {
  pending_.clear();
  beat_ = 0;
  credit_ = uint32_t(beat_bytes_);
  last_ready_ = now_;
  prepare();
}

void MemoryModel::prepare() {
  request_ready_ = pending_.size() < timing_.max_outstanding &&
                   !(timing_.request_stall_prob > 0 && unit(rng_) < timing_.request_stall_prob);
  response_valid_ = !pending_.empty() && pending_.front().ready_at <= now_ && credit_ >= uint32_t(beat_bytes_) &&
                    !(timing_.response_stall_prob > 0 && unit(rng_) < timing_.response_stall_prob);
  beat_data_ = response_valid_ ? &image_[pending_.front().address - base_ + size_t(beat_) * size_t(beat_bytes_)] : nullptr;
}

void MemoryModel::clock(bool request_fire, uint32_t address, bool response_fire) {
  if (response_fire) {
    if (!response_valid_) throw SimulationError("memory model: a beat taken while none was offered");
    credit_ -= uint32_t(beat_bytes_);
    if (++beat_ * beat_bytes_ == line_bytes_) {
      beat_ = 0;
      pending_.pop_front();
    }
  }
  if (request_fire) {
    if (!request_ready_) throw SimulationError("memory model: a read taken while mem_req_ready was low");
    if (address % uint32_t(line_bytes_) != 0 || address < base_ ||
        uint64_t(address) - base_ + uint64_t(line_bytes_) > image_.size())
      throw SimulationError("RTL read of line " + hex_address(address) + " outside the texture's memory image " + hex_address(base_) +
                            ".." + hex_address(uint32_t(base_ + image_.size() - 1)) + " (or not aligned to " +
                            std::to_string(line_bytes_) + " bytes) at memory clock " + std::to_string(now_));
    uint64_t ready = now_ + timing_.latency + (timing_.jitter ? rng_() % (uint64_t(timing_.jitter) + 1) : 0);
    ready = std::max(ready, last_ready_);  // in order
    for (const Read& r : pending_) repeats_ += r.address == address;
    last_ready_ = ready;
    pending_.push_back({address, ready});
    reads_.push_back(address);
  }
  ++now_;
  credit_ = std::min<uint32_t>(credit_ + timing_.bytes_per_clock, uint32_t(beat_bytes_));
  prepare();
}

}  // namespace tex::rtl

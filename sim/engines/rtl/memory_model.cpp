#include "engines/rtl/memory_model.h"

#include <cstdio>

#include "engines/engine.h"
#include "model/error.h"

namespace tex::rtl {

std::string hex_address(uint32_t address) {
  char s[16];
  std::snprintf(s, sizeof s, "0x%08x", address);
  return s;
}

MemoryModel::MemoryModel(std::vector<uint8_t> image, uint32_t base, int line_bytes, int beat_bytes,
                         const MemoryTiming& timing)
    : image_(std::move(image)), base_(base), channel_(line_bytes, beat_bytes, timing) {}

void MemoryModel::clock(bool request_fire, uint32_t address, bool response_fire) {
  if (response_fire && !channel_.response_valid())
    throw SimulationError("memory model: a beat taken while none was offered");
  if (request_fire) {
    if (!channel_.request_ready()) throw SimulationError("memory model: a read taken while mem_req_ready was low");
    const uint32_t line = uint32_t(channel_.line_bytes());
    if (address % line != 0 || address < base_ || uint64_t(address) - base_ + uint64_t(line) > image_.size())
      throw SimulationError("RTL read of line " + hex_address(address) + " outside the texture's memory image " +
                            hex_address(base_) + ".." + hex_address(uint32_t(base_ + image_.size() - 1)) +
                            " (or not aligned to " + std::to_string(line) + " bytes) at memory clock " +
                            std::to_string(channel_.now()));
    reads_.push_back(address);
    ++read_count_;
    const bool error = next_error_ < error_reads_.size() && error_reads_[next_error_] == read_count_;
    next_error_ += error;
    in_flight_error_.push_back(error);
  }
  if (response_fire && response_last()) in_flight_error_.pop_front();
  channel_.clock(request_fire, address, response_fire);
}

}  // namespace tex::rtl

// The external memory behind tex_unit_cached's memory port (docs/memory.md, docs/rtl-interface.md):
// a byte-addressed image (the pyramid's memory image, written in 0 clocks) behind the model's
// MemoryChannel (latency, jitter, bandwidth, outstanding reads, backpressure; model/memory_channel.h),
// the same channel the timing model clocks. Every line read is recorded in order: the RTL's miss
// stream.
#pragma once
#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "model/memory_channel.h"

namespace tex::rtl {

using MemoryTiming = tex::MemoryTiming;

// "0x%08x": a line address in messages and in --miss-trace.
std::string hex_address(uint32_t address);

// What drives tex_unit_cached's AXI4 read port pins, clock by clock: the harness's MemoryModel
// below, or a TLM-2.0 initiator socket (the SystemC wrapper, engines/systemc/tlm_memory_port.h).
// request_ready is ARREADY; response_valid, response_beat, response_error and response_last are
// RVALID, RDATA, RRESP (SLVERR or OKAY) and RLAST.
class MemoryPort {
 public:
  virtual ~MemoryPort() = default;
  // Pins for the coming clock edge.
  virtual bool request_ready() const = 0;
  virtual bool response_valid() const = 0;
  virtual const uint8_t* response_beat() const = 0;
  virtual bool response_error() const = 0;
  virtual bool response_last() const = 0;
  // The clock edge: a read was taken (request_fire, its line address) and/or a beat was taken.
  virtual void clock(bool request_fire, uint32_t address, bool response_fire) = 0;
  // The unit was reset: forget every read in flight.
  virtual void reset() = 0;
  // Line addresses read since the last call, in order (the RTL's miss stream).
  virtual std::vector<uint32_t> take_reads() = 0;
};

class MemoryModel final : public MemoryPort {
 public:
  // image: the bytes at addresses base .. base + image.size() - 1. Throws tex::Error when the
  // bandwidth or the beat do not fit the line.
  MemoryModel(std::vector<uint8_t> image, uint32_t base, int line_bytes, int beat_bytes, const MemoryTiming& timing);

  // Pins for the coming clock edge.
  bool request_ready() const override { return channel_.request_ready(); }
  bool response_valid() const override { return channel_.response_valid(); }
  const uint8_t* response_beat() const override {
    return channel_.response_valid() ? &image_[channel_.response_address() - base_ +
                                               size_t(channel_.response_beat()) * size_t(channel_.beat_bytes())]
                                     : nullptr;
  }
  bool response_error() const override { return channel_.response_valid() && in_flight_error_.front(); }
  bool response_last() const override {
    return channel_.response_valid() && (channel_.response_beat() + 1) * channel_.beat_bytes() == channel_.line_bytes();
  }
  // The line reads (1 = the first since construction or reset()) that answer SLVERR on every beat,
  // ascending (--mem-error-at).
  void set_error_reads(std::vector<uint64_t> ordinals) { error_reads_ = std::move(ordinals); }
  // The clock edge: a request was taken (req_fire, address) and/or a beat was taken (rsp_fire).
  // Throws tex::SimulationError on a read outside the image, a misaligned address, or taking what
  // was not offered.
  void clock(bool request_fire, uint32_t address, bool response_fire) override;

  // Forgets every read in flight (the unit was reset); the bandwidth credit starts full.
  void reset() override {
    channel_.reset();
    read_count_ = 0;
    next_error_ = 0;
    in_flight_error_.clear();
  }

  // Line addresses read since the last take_reads(), in order (the RTL's miss stream).
  std::vector<uint32_t> take_reads() override { return std::exchange(reads_, {}); }
  uint64_t repeats_in_flight() const { return channel_.repeats_in_flight(); }  // reads of a line already in flight
  // Changes one byte of the image (tests plant a wrong texel with it).
  void poke(uint32_t address, uint8_t value) { image_.at(address - base_) = value; }
  // The channel as it stands (its clock, reads in flight and random state): a timing model started
  // from a copy of it sees the same memory from this clock on.
  const MemoryChannel& channel() const { return channel_; }

 private:
  std::vector<uint8_t> image_;
  uint32_t base_;
  MemoryChannel channel_;
  std::vector<uint32_t> reads_;
  std::vector<uint64_t> error_reads_;
  uint64_t read_count_ = 0;
  size_t next_error_ = 0;
  std::deque<bool> in_flight_error_;  // the reads in flight, oldest first: each answers SLVERR
};

}  // namespace tex::rtl

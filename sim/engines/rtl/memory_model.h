// The external memory behind tex_unit_cached's memory port (docs/memory.md, docs/rtl-interface.md):
// a byte-addressed image (the pyramid's memory image, written in 0 clocks), a fixed latency with
// optional random jitter, a bandwidth in bytes per clock, a limit on outstanding reads, and
// optional random backpressure on the request port. Responses come in request order, one beat
// (beat_bytes) per clock at most. Every line read is recorded in order: the RTL's miss stream.
#pragma once
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace tex::rtl {

struct MemoryTiming {
  uint32_t latency = 100;          // clocks from the request handshake to the first beat's valid
  uint32_t jitter = 0;             // + a uniform 0..jitter clocks per read (order is kept)
  uint32_t bytes_per_clock = 16;   // bandwidth: at most one beat per clock
  uint32_t max_outstanding = 64;   // reads accepted and not yet fully returned
  double request_stall_prob = 0;   // mem_req_ready low in a clock it could be high (test stress)
  double response_stall_prob = 0;  // a beat that could be sent is held back (test stress)
  uint64_t seed = 1;
};

// "0x%08x": a line address in messages and in --miss-trace.
std::string hex_address(uint32_t address);

// What drives tex_unit_cached's memory port pins, clock by clock: the harness's MemoryModel below,
// or a TLM-2.0 initiator socket (the SystemC wrapper, engines/systemc/tlm_memory_port.h).
class MemoryPort {
 public:
  virtual ~MemoryPort() = default;
  // Pins for the coming clock edge.
  virtual bool request_ready() const = 0;
  virtual bool response_valid() const = 0;
  virtual const uint8_t* response_beat() const = 0;
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
  bool request_ready() const override { return request_ready_; }
  bool response_valid() const override { return response_valid_; }
  const uint8_t* response_beat() const override { return beat_data_; }
  // The clock edge: a request was taken (req_fire, address) and/or a beat was taken (rsp_fire).
  // Throws tex::SimulationError on a read outside the image or a misaligned address.
  void clock(bool request_fire, uint32_t address, bool response_fire) override;

  // Forgets every read in flight (the unit was reset); the bandwidth credit starts full.
  void reset() override;

  // Line addresses read since the last take_reads(), in order (the RTL's miss stream).
  std::vector<uint32_t> take_reads() override { return std::exchange(reads_, {}); }
  uint64_t repeats_in_flight() const { return repeats_; }  // reads of a line already in flight
  // Changes one byte of the image (tests plant a wrong texel with it).
  void poke(uint32_t address, uint8_t value) { image_.at(address - base_) = value; }

 private:
  void prepare();  // the pins of the next clock
  struct Read {
    uint32_t address;
    uint64_t ready_at;  // clock of the first beat
  };
  std::vector<uint8_t> image_;
  uint32_t base_;
  int line_bytes_, beat_bytes_;
  MemoryTiming timing_;
  std::mt19937_64 rng_;
  std::deque<Read> pending_;
  uint64_t now_ = 0, last_ready_ = 0;
  uint32_t credit_ = 0;  // bytes the channel may send (at most one beat's worth)
  int beat_ = 0;         // beat of the oldest read being sent
  bool request_ready_ = true, response_valid_ = false;
  const uint8_t* beat_data_ = nullptr;
  std::vector<uint32_t> reads_;
  uint64_t repeats_ = 0;
};

}  // namespace tex::rtl

// TlmMemoryPort: tex_unit_cached's memory port pins (rtl::MemoryPort) driven through a TLM-2.0
// initiator socket, approximately timed (base protocol; docs/systemc.md). A read the RTL issues at
// a clock edge goes out as BEGIN_REQ at once; the next read waits for END_REQ (request exclusion).
// A line's beats are offered from the clock at or after its BEGIN_RESP time (the call's time plus
// the annotated delay), one beat per clock, in request order: a target may answer out of order,
// the port puts the lines back in order. Responses are taken at once (TLM_COMPLETED). A read
// answered with any status other than TLM_OK_RESPONSE gives its beats RRESP SLVERR: the samples
// that need the line come out with rsp_error.
#pragma once
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "engines/rtl/memory_model.h"

namespace tex::systemc {

class TlmMemoryPort;
using MemorySocket = tlm_utils::simple_initiator_socket_optional<TlmMemoryPort>;

class TlmMemoryPort final : public rtl::MemoryPort {
 public:
  // Registers its backward path on `socket`. line_bytes per read, beat_bytes per clock.
  TlmMemoryPort(MemorySocket& socket, int line_bytes, int beat_bytes);
  ~TlmMemoryPort() override;

  bool request_ready() const override { return end_req_owed_ == nullptr; }
  bool response_valid() const override;
  const uint8_t* response_beat() const override;
  bool response_error() const override {
    return response_valid() && lines_.front()->trans.get_response_status() != tlm::TLM_OK_RESPONSE;
  }
  bool response_last() const override { return response_valid() && (beat_ + 1) * beat_bytes_ == line_bytes_; }
  // Lines delivered so far whose read was answered with an error status.
  uint64_t error_lines() const { return error_lines_; }
  void clock(bool request_fire, uint32_t address, bool response_fire) override;
  void reset() override;
  std::vector<uint32_t> take_reads() override { return std::exchange(reads_, {}); }

  // The first protocol error of the target, empty if none.
  const std::string& error() const { return error_; }

 private:
  struct Line {
    tlm::tlm_generic_payload trans;
    std::vector<uint8_t> data;
    bool answered = false;
    sc_core::sc_time ready;  // BEGIN_RESP time: its beats may go from the first clock at or after it
  };
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& t, tlm::tlm_phase& phase, sc_core::sc_time& delay);
  void answered(Line& line, const sc_core::sc_time& delay);
  Line* find(tlm::tlm_generic_payload& t);

  MemorySocket& socket_;
  int line_bytes_, beat_bytes_;
  std::deque<std::unique_ptr<Line>> lines_;     // read, in request order, until the last beat is taken
  std::vector<std::unique_ptr<Line>> orphans_;  // read before a reset, not answered yet
  tlm::tlm_generic_payload* end_req_owed_ = nullptr;
  int beat_ = 0;
  uint64_t error_lines_ = 0;
  std::vector<uint32_t> reads_;
  std::string error_;
};

}  // namespace tex::systemc

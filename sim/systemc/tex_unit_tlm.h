// TexUnitTlm: the texture unit as a SystemC module with one TLM-2.0 target socket (docs/systemc.md).
// Each transaction carries one sample request (sample_payload.h) and returns one RGBA texel.
// Behind the socket, chosen at construction (run time):
//   Backend::Model  the golden model tex::Sampler. Loosely timed: b_transport samples at once and
//                   adds one clock period to the delay (the unit's sustained rate of one sample per
//                   clock); no clock, no latency.
//   Backend::Rtl    the Verilated tex_unit (verilator --sc), clocked by an sc_clock it owns.
//                   Approximately timed, base protocol, pipelined: BEGIN_REQ is answered with END_REQ
//                   (on the backward path) at the clock edge where the RTL accepts the request, and
//                   BEGIN_RESP is sent at the edge where the RTL's response fires, so one request
//                   per clock is accepted while earlier ones are still in flight.
// The socket is a simple_target_socket with only one of b_transport / nb_transport_fw registered:
// its built-in adapters serve the other style (at a cost, see docs/systemc.md).
// Not thread-safe; one instance per simulation is what the engine builds, but nothing stops more.
#pragma once
#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_cb_and_phase.h>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "model/pyramid.h"
#include "model/sampler.h"
#include "sample_payload.h"
#include "systemc_engine.h"

namespace tex::systemc {

// Counted by the target (RTL backend); clocks are rising edges of its sc_clock.
struct TargetCounters {
  uint64_t samples = 0;
  uint64_t load_cycles = 0;            // reset + one write per texel of every level
  uint64_t first_offer_cycle = 0;      // first edge with req_valid high
  uint64_t last_response_cycle = 0;    // edge of the last response that fired
  uint64_t backpressure_cycles = 0;    // req_valid && !req_ready
  uint64_t response_stall_cycles = 0;  // rsp_valid && !rsp_ready (the initiator had not ended a response)
};

class TexUnitTlm : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<TexUnitTlm> socket;

  // The RTL backend loads `pyramid` through the tex_unit write port (one texel per clock) after a
  // reset, then drives the configuration ports from `config`; requests wait until then.
  TexUnitTlm(sc_core::sc_module_name name, Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
             const sc_core::sc_time& clock_period, uint64_t seed = 1, Fault fault = Fault::None,
             uint64_t fault_index = 0);
  ~TexUnitTlm() override;
  SC_HAS_PROCESS(TexUnitTlm);

  Backend backend() const { return backend_; }
  const sc_core::sc_time& clock_period() const { return period_; }
  bool loaded() const { return loaded_; }
  const sc_core::sc_event& loaded_event() const { return loaded_event_; }
  uint64_t cycle() const { return cycle_; }  // rising edges so far (RTL backend)
  const TargetCounters& counters() const { return counters_; }
  size_t in_flight() const { return in_flight_.size(); }
  // The first protocol or RTL error seen (empty if none); the module stops working after one.
  const std::string& error() const { return error_; }

  static constexpr int kRtlMaxLog2W = 10, kRtlMaxLog2H = 10;  // the verilated configuration

 private:
  struct Rtl;  // the Verilated model and its signals (tex_unit_tlm.cpp)
  struct InFlight {
    tlm::tlm_generic_payload* trans;
    uint64_t sequence;  // request number; its low 16 bits are the RTL tag
  };

  // Shared: decode and check one payload; sets an error response status when it is malformed.
  SampleTransfer* decode(tlm::tlm_generic_payload& trans);
  void fail(const std::string& message);

  // Model backend.
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);

  // RTL backend.
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase, sc_core::sc_time& delay);
  void on_fw_phase(tlm::tlm_generic_payload& trans, const tlm::tlm_phase& phase);  // PEQ callback
  void on_posedge();  // sample the RTL outputs: handshakes that fired at this edge
  void on_negedge();  // drive the RTL inputs for the next edge
  void respond(tlm::tlm_generic_payload* trans);
  void send_queued_responses();

  Backend backend_;
  sc_core::sc_time period_;
  SamplerConfig config_;
  Fault fault_;
  uint64_t fault_index_;
  std::unique_ptr<Sampler> sampler_;  // model backend
  std::unique_ptr<Rtl> rtl_;          // RTL backend
  const Pyramid* pyramid_ = nullptr;  // RTL backend, until loaded
  tlm_utils::peq_with_cb_and_phase<TexUnitTlm> fw_peq_;

  bool loaded_ = false;
  sc_core::sc_event loaded_event_;
  std::string error_;
  uint64_t cycle_ = 0;
  uint64_t drive_step_ = 0;  // negedges so far in reset and load
  size_t load_level_ = 0;
  int load_x_ = 0, load_y_ = 0;

  tlm::tlm_generic_payload* pending_ = nullptr;  // between BEGIN_REQ and the RTL accepting it
  uint64_t next_sequence_ = 0;                     // of the next request the RTL accepts
  std::deque<InFlight> in_flight_;                 // accepted by the RTL, in order
  std::deque<tlm::tlm_generic_payload*> to_respond_;  // responses from the RTL not yet sent
  tlm::tlm_generic_payload* awaiting_end_resp_ = nullptr;
  uint64_t responses_from_rtl_ = 0;
  tlm::tlm_generic_payload* swap_held_ = nullptr;  // Fault::SwapResponses
  TargetCounters counters_;
};

}  // namespace tex::systemc

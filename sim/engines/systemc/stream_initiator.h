// StreamInitiator: the SystemC testbench. Streams sample requests (pulled from a RequestSource as
// it goes; texels pushed to a TexelSink in request order) through a TLM-2.0
// initiator socket, checks every response (status OK, echoed tag = the next one in request order:
// nothing lost, duplicated or reordered) and measures throughput at the socket.
//   At: base-protocol non-blocking transport, pipelined. BEGIN_REQ for request i+1 goes out as soon
//       as END_REQ of request i arrives; responses are completed at once (TLM_COMPLETED) or, with
//       random stalls, later with END_RESP. Optional random gaps before BEGIN_REQ.
//   Lt: b_transport, one request at a time, with a quantum keeper (temporal decoupling).
#pragma once
#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_cb_and_phase.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engines/systemc/sample_payload.h"
#include "engines/engine.h"
#include "model/sampler.h"

namespace tex::systemc {

struct InitiatorTiming {
  double gap_prob = 0;    // per request: wait 1..max_gap clocks before its BEGIN_REQ
  int max_gap = 4;
  double stall_prob = 0;  // per response: hold END_RESP for 1..max_stall clocks
  int max_stall = 8;
  uint64_t seed = 1;
};

struct InitiatorCounters {
  uint64_t responses = 0;
  sc_core::sc_time first_accept;           // first END_REQ (At) / start (Lt)
  sc_core::sc_time last_response;          // last BEGIN_RESP (At) / end of the last b_transport (Lt)
  uint64_t latency_min = 0, latency_max = 0;  // END_REQ -> BEGIN_RESP, clocks (At)
  uint64_t gap_cycles = 0, stall_cycles = 0;
};

class StreamInitiator : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<StreamInitiator> socket;

  // `source` and `sink` must outlive the simulation; `clock_period` is the target's clock (gaps,
  // stalls and latency are counted in it).
  StreamInitiator(sc_core::sc_module_name name, RequestSource& source, TexelSink& sink, bool approximately_timed,
                  const sc_core::sc_time& clock_period, const InitiatorTiming& timing);
  SC_HAS_PROCESS(StreamInitiator);

  bool done() const { return (all_issued_ && counters_.responses == issued_) || !error_.empty(); }
  uint64_t issued() const { return issued_; }
  void flush() { texels_.flush(); }  // hands the last texels to the sink (run_stream does)
  const InitiatorCounters& counters() const { return counters_; }
  const std::string& error() const { return error_; }
  // Responses with TLM_GENERIC_ERROR_RESPONSE (a memory error flagged the sample; its texel is 0),
  // by index.
  const std::vector<uint64_t>& flagged() const { return flagged_; }
  // Clocks from the first accepted request to the last response, inclusive (0 before any).
  uint64_t cycles() const;

 private:
  // A transaction and its data; the socket hands back the same object, so a cast finds the slot.
  struct Slot : tlm::tlm_generic_payload {
    SampleTransfer data;
    sc_core::sc_time accepted;
  };

  void run_at();
  void run_lt();
  Slot* take_slot(const Request& request, size_t index);
  void check_response(Slot& slot);
  void release(Slot& slot);
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase, sc_core::sc_time& delay);
  void on_begin_resp(Slot& slot);
  void on_request_accepted(Slot& slot);
  void send_end_resp(tlm::tlm_generic_payload& trans, const tlm::tlm_phase& phase);  // PEQ callback
  void fail(const std::string& message);
  static Slot& slot_of(tlm::tlm_generic_payload& trans) { return static_cast<Slot&>(trans); }

  RequestQueue requests_;
  TexelQueue texels_;
  uint64_t issued_ = 0;
  bool all_issued_ = false;
  bool at_;
  InitiatorTiming timing_;
  sc_core::sc_time period_;
  std::mt19937_64 rng_;
  std::vector<std::unique_ptr<Slot>> slots_;  // transactions in flight use these
  std::vector<Slot*> free_slots_;
  sc_core::sc_event slot_freed_, request_ended_;
  tlm::tlm_generic_payload* awaiting_end_req_ = nullptr;
  tlm_utils::peq_with_cb_and_phase<StreamInitiator> end_resp_peq_;
  InitiatorCounters counters_;
  std::vector<uint64_t> flagged_;
  bool any_accepted_ = false;
  std::string error_;
};

// Runs the simulation until `bench` has every response or an error: in slices of clocks, checking
// between slices `target_error` (empty = none), progress (a line on stderr) and the time-out (no
// new response for timeout_cycles clocks: a lost response). Then 64 idle clocks (a response that
// still comes out is a duplicate). Throws tex::Error with the first error.
void run_stream(StreamInitiator& bench, const sc_core::sc_time& period, uint64_t timeout_cycles,
                bool show_progress, const std::function<std::string()>& target_error);

}  // namespace tex::systemc

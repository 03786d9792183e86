// MemoryTarget: a read-only byte-addressed memory as a TLM-2.0 target (docs/systemc.md), holding
// the texture's memory image at [base, base + size). What the cached texture unit's memory socket
// reads from in the tests and the example platform; any other TLM target works the same way.
//   nb_transport_fw (approximately timed, base protocol): BEGIN_REQ is accepted at once (END_REQ on
//     the return path) while fewer than max_outstanding reads are open, else when one closes.
//     BEGIN_RESP comes `latency` (+ 0..jitter, drawn per read) clocks after acceptance, and responses, in order, are at least
//     line / bytes_per_clock clocks apart (the bandwidth). A read stays open until its data has
//     crossed the channel (BEGIN_RESP + line / bytes_per_clock clocks): the Verilator harness's
//     memory model (engines/rtl/memory_model.h) counts it until its last beat, the same clock.
//   b_transport (loosely timed): the same read, annotating latency + transfer time.
//   transport_dbg: reads bytes, no time.
// Anything but an aligned read inside the image gets an error response status; so does each good
// read whose ordinal (1 = the first) is in `error_reads` (TLM_GENERIC_ERROR_RESPONSE, its data sent
// all the same: --mem-error-at).
#pragma once
#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_cb_and_phase.h>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <deque>
#include <random>
#include <vector>

namespace tex::systemc {

struct MemoryTargetTiming {
  uint32_t latency = 100;         // clocks from accepting a read to its BEGIN_RESP
  uint32_t jitter = 0;            // plus 0..jitter clocks, uniform per read (responses stay in order)
  uint64_t seed = 1;              // of the jitter's draws
  uint32_t bytes_per_clock = 16;  // bandwidth
  uint32_t max_outstanding = 64;  // reads open at once (until their data has crossed the channel)
  std::vector<uint64_t> error_reads;  // good reads answered TLM_GENERIC_ERROR_RESPONSE, ascending
};

class MemoryTarget : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<MemoryTarget> socket;

  MemoryTarget(sc_core::sc_module_name name, std::vector<uint8_t> image, uint64_t base,
               const sc_core::sc_time& clock_period, const MemoryTargetTiming& timing);

  SC_HAS_PROCESS(MemoryTarget);

 private:
  bool check(tlm::tlm_generic_payload& t);  // sets the response status; true for a good read
  void accept(tlm::tlm_generic_payload& t);  // END_REQ given: schedule its BEGIN_RESP
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& t, tlm::tlm_phase& phase, sc_core::sc_time& delay);
  void b_transport(tlm::tlm_generic_payload& t, sc_core::sc_time& delay);
  unsigned int transport_dbg(tlm::tlm_generic_payload& t);
  void respond(tlm::tlm_generic_payload& t, const tlm::tlm_phase& phase);  // PEQ callback
  void release();    // reads whose data has crossed the channel close; waiting requests are admitted

  std::vector<uint8_t> image_;
  uint64_t base_;
  sc_core::sc_time period_;
  MemoryTargetTiming timing_;
  tlm_utils::peq_with_cb_and_phase<MemoryTarget> peq_;
  sc_core::sc_time channel_free_ = sc_core::SC_ZERO_TIME;  // the data channel's next free time
  std::deque<tlm::tlm_generic_payload*> waiting_;            // BEGIN_REQ not yet accepted
  std::deque<sc_core::sc_time> closing_;                     // when the open reads close, in order
  sc_core::sc_event release_event_;
  uint32_t open_ = 0;
  uint64_t reads_ = 0;       // good reads so far
  size_t next_error_ = 0;    // the next of timing_.error_reads
  std::mt19937_64 jitter_rng_;
  sc_core::sc_time latency();  // this read's: latency + its jitter
};

}  // namespace tex::systemc

// `texsim --engine systemc` / `--engine systemc-model`: the requests through the SystemC/TLM-2.0
// texture unit (sim/systemc/tex_unit_tlm.h) driven by the streaming testbench initiator.
// Plain C++: no SystemC header here, so the C++20 rest of the project can include it (Debian's
// SystemC 2.3.4 links only with C++17; the SystemC translation units are built as C++17).
#pragma once
#include <cstdint>
#include <vector>

#include "engine.h"

namespace tex::systemc {

enum class Backend {
  Rtl,    // the Verilated tex_unit (--sc), clocked by an sc_clock; approximately timed (nb_transport)
  Model,  // the golden model tex::Sampler; loosely timed (b_transport), one clock per sample annotated
};

// How the testbench talks to the socket. Auto = At for the RTL backend, Lt for the model.
// The other combinations go through simple_target_socket's b<->nb adapters (slower, same texels).
enum class InitiatorStyle { Auto, Lt, At };

// Deliberate faults, for the tests of the tag/order/loss checks (never used by texsim).
enum class Fault {
  None,
  CorruptRtlTag,     // the tag on the RTL request pins of request #fault_index is wrong
  DropResponse,      // response #fault_index is never delivered to the initiator
  SwapResponses,     // responses #fault_index and #fault_index+1 are delivered in swapped order
  DuplicateResponse,  // response #fault_index is delivered twice
  BadLength           // the initiator sends request #fault_index with a 20-byte data length
};

struct SystemcOptions {
  Backend backend = Backend::Rtl;
  InitiatorStyle initiator = InitiatorStyle::Auto;
  double clock_ns = 10.0;  // sc_clock period (and the model's per-sample annotation)
  // AT initiator timing, random from `seed`; all 0 = ideal (a request offered every clock, every
  // response taken at once). gap: clocks before a BEGIN_REQ; stall: clocks before END_RESP.
  double gap_prob = 0;
  int max_gap = 4;
  double stall_prob = 0;
  int max_stall = 8;
  uint64_t seed = 1;
  uint64_t timeout_cycles = 20000;  // clocks without a response while some are owed
  bool show_progress = false;
  Fault fault = Fault::None;
  uint64_t fault_index = 0;
};

// True when this build has the Verilated --sc model (rtl/ existed at configure time).
bool have_rtl_backend();

// Runs one SystemC simulation in a child process (SystemC elaborates once per process; the fork
// lets texsim render several frames and the tests run many cases). Texels come back in request
// order. Throws tex::Error with the simulation's one-line error (tag mismatch, time-out, bad input).
// stats: engine, backend, initiator, samples, cycles, samples_per_clock, latency, wall time, ...
EngineResult run_systemc(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                         const SystemcOptions& options);

// Timing options of texsim: seed 0 = ideal timing, otherwise random gaps and stalls (as --engine rtl).
SystemcOptions systemc_options_for(Backend backend, const EngineOptions& options);

}  // namespace tex::systemc

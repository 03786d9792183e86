// TexUnitTlm: the texture unit as a SystemC module with one TLM-2.0 target socket (docs/systemc.md).
// Each transaction carries one sample request (sample_payload.h) and returns one RGBA texel.
// Behind the socket, chosen at construction (run time):
// The unit samples a frame's textures and samplers: a descriptor table and a sampler table, as the
// cached RTL (a request names its entries: SampleTransfer::texture, ::sampler); the on-chip unit
// holds one of each.
//   Backend::Model  the golden model tex::Sampler. Loosely timed: b_transport samples at once and
//                   adds one clock period to the delay (the unit's sustained rate of one sample per
//                   clock); no clock, no latency.
//   Backend::Rtl    the Verilated tex_unit, clocked once per period by an SC_METHOD through the
//                   same pin-level driver as `--engine rtl` (engines/rtl/driver.h). Approximately
//                   timed, base protocol, pipelined: BEGIN_REQ is answered with END_REQ (on the
//                   backward path) at the clock edge where the RTL accepts the request, and
//                   BEGIN_RESP is sent at the edge where the RTL's response fires, so one request
//                   per clock is accepted while earlier ones are still in flight.
// The textures are loaded at construction, before simulated time starts (backdoor: 0 clocks; write
// port: load_cycles() clocks of the RTL).
// Cached memory (options.memory == Memory::Cached): the unit holds no texels; it reads cache lines
// through `memory_socket`, a TLM-2.0 initiator socket, from whatever target is bound to it (the
// frame's memory image, docs/memory.md §1, at options.layout.base: each texture's layout packed
// after the last's, as the RTL engine's memory holds them). The RTL backend drives its
// memory port through it approximately timed (tlm_memory_port.h), so memory latency and bandwidth
// are the target's; the model backend's caches read each missed line with b_transport (loosely
// timed: the sample waits for its lines) and fill the samplers' memories from the bytes read (block
// formats decoded, sRGB codes to linear, as the RTL's taps do). In
// both, the golden model's caches predict every read: the RTL's are checked against them.
// Debug transport on `socket` (transport_dbg) reads texels of the unit's memory view
// (texel_debug_address, sample_payload.h): the level memories (on-chip), or the memory behind
// `memory_socket` through its own debug transport (cached; a block format's texels: none), of
// texture 0.
// The socket is a simple_target_socket with only one of b_transport / nb_transport_fw registered:
// its built-in adapters serve the other style (at a cost, see docs/systemc.md).
#pragma once
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "engines/engine.h"
#include "engines/rtl/driver.h"
#include "engines/rtl/miss_checker.h"
#include "engines/systemc/tlm_memory_port.h"
#include "engines/systemc/systemc_engine.h"
#include "engines/systemc/sample_payload.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"

namespace tex::systemc {

class TexUnitTlm : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<TexUnitTlm> socket;
  MemorySocket memory_socket;  // cached memory only (may stay unbound otherwise)

  // Throws tex::Error for a texture, table or option the backend cannot take.
  TexUnitTlm(sc_core::sc_module_name name, Backend backend, const TextureTable& textures, const SamplerTable& samplers,
             const sc_core::sc_time& clock_period, const EngineOptions& options = {});
  // One texture, one sampler.
  TexUnitTlm(sc_core::sc_module_name name, Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
             const sc_core::sc_time& clock_period, const EngineOptions& options = {})
      : TexUnitTlm(name, backend, TextureTable{{&pyramid}}, SamplerTable{config}, clock_period, options) {}
  ~TexUnitTlm() override;
  SC_HAS_PROCESS(TexUnitTlm);

  Backend backend() const { return backend_; }
  const sc_core::sc_time& clock_period() const { return period_; }
  // RTL backend: the driver (protocol counters, clocks, load clocks); nullptr for the model.
  const rtl::Driver* driver() const { return driver_.get(); }
  size_t in_flight() const { return in_flight_.size(); }
  // The first protocol or RTL error seen (empty if none); the module stops working after one.
  const std::string& error() const { return error_; }
  // Cached memory: the golden model's caches (hits, misses), and the end-of-run check that the RTL
  // read every line they miss (sets error()).
  const TextureCache* cache() const { return cache_ ? &*cache_ : nullptr; }
  // The end of the stream: the cached RTL's last reads checked, the last response clocks passed on.
  void finish();

 private:
  // Decode and check one payload; sets an error response status when it is malformed.
  SampleTransfer* decode(tlm::tlm_generic_payload& trans);
  void fail(const std::string& message);

  // Model backend.
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);
  void read_line(uint32_t address, sc_core::sc_time& delay);  // cached: one missed line over the bus

  unsigned int transport_dbg(tlm::tlm_generic_payload& trans);

  // RTL backend.
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase, sc_core::sc_time& delay);
  void on_clock();  // one rising edge of the RTL: handshakes, END_REQ, BEGIN_RESP
  void send_queued_responses();

  Backend backend_;
  sc_core::sc_time period_;
  TextureTable textures_;
  SamplerTable samplers_;
  EngineOptions options_;
  std::vector<TextureDescriptor> descriptors_;  // cached: each texture's layout
  std::optional<TextureCache> cache_;       // cached: the golden model's caches
  std::optional<rtl::MissChecker> checker_;  // cached RTL: predicted against actual reads
  std::unique_ptr<TlmMemoryPort> memory_port_;  // cached RTL
  std::vector<uint32_t> misses_;            // cached model: lines one sample misses
  std::vector<uint64_t> clocks_;            // RTL: response clocks not yet given to options_.clock_sink
  tlm::tlm_generic_payload line_trans_;     // cached model: the read of one line
  std::vector<uint8_t> line_data_;
  // Model backend: a Sampler per (texture, sampler) pair, built at its first request; cached: from
  // the texture's memory view (views_), which the lines read fill.
  std::vector<std::vector<Pyramid>> views_;  // [texture][layer]
  std::optional<SamplerPairs> model_samplers_;
  std::unique_ptr<rtl::Driver> driver_;  // RTL backend
  std::string error_;

  tlm::tlm_generic_payload* pending_ = nullptr;       // between BEGIN_REQ and the RTL accepting it
  Request pending_request_;
  std::deque<tlm::tlm_generic_payload*> in_flight_;   // accepted by the RTL, in order
  std::deque<tlm::tlm_generic_payload*> to_respond_;  // answered by the RTL, not yet sent
  tlm::tlm_generic_payload* awaiting_end_resp_ = nullptr;
};

}  // namespace tex::systemc

#include "engines/systemc/memory_target.h"

#include <algorithm>
#include <cstring>

namespace tex::systemc {

using namespace sc_core;
using tlm::tlm_generic_payload;
using tlm::tlm_phase;
using tlm::tlm_sync_enum;

MemoryTarget::MemoryTarget(sc_module_name name, std::vector<uint8_t> image, uint64_t base, const sc_time& period,
                           const MemoryTargetTiming& timing)
    : sc_module(name), socket("socket"), image_(std::move(image)), base_(base), period_(period), timing_(timing),
      peq_(this, &MemoryTarget::respond), jitter_rng_(timing.seed) {
  socket.register_nb_transport_fw(this, &MemoryTarget::nb_transport_fw);
  socket.register_b_transport(this, &MemoryTarget::b_transport);
  socket.register_transport_dbg(this, &MemoryTarget::transport_dbg);
  SC_METHOD(release);
  sensitive << release_event_;
  dont_initialize();
}

bool MemoryTarget::check(tlm_generic_payload& t) {
  const uint64_t a = t.get_address(), n = t.get_data_length();
  if (t.get_command() != tlm::TLM_READ_COMMAND) t.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
  else if (a < base_ || a - base_ + n > image_.size() || t.get_data_ptr() == nullptr)
    t.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
  else if (t.get_byte_enable_ptr() != nullptr) t.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
  else if (t.get_streaming_width() < n) t.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
  else {
    std::memcpy(t.get_data_ptr(), &image_[a - base_], n);
    ++reads_;
    const bool error = next_error_ < timing_.error_reads.size() && timing_.error_reads[next_error_] == reads_;
    next_error_ += error;
    t.set_response_status(error ? tlm::TLM_GENERIC_ERROR_RESPONSE : tlm::TLM_OK_RESPONSE);
    return true;
  }
  return false;
}

// The read's data leaves `latency` clocks after acceptance, once the channel has sent the previous
// responses: a line of n bytes occupies it for n / bytes_per_clock clocks.
void MemoryTarget::accept(tlm_generic_payload& t) {
  ++open_;
  check(t);
  const sc_time now = sc_time_stamp();
  const sc_time at = std::max(now + latency(), channel_free_);
  const double clocks = double(t.get_data_length()) / double(timing_.bytes_per_clock);
  channel_free_ = at + clocks * period_;
  peq_.notify(t, tlm::BEGIN_RESP, at - now);
}

tlm_sync_enum MemoryTarget::nb_transport_fw(tlm_generic_payload& t, tlm_phase& phase, sc_time& delay) {
  if (phase == tlm::BEGIN_REQ) {
    if (open_ >= timing_.max_outstanding) {
      waiting_.push_back(&t);  // END_REQ when a read completes
      return tlm::TLM_ACCEPTED;
    }
    accept(t);
    phase = tlm::END_REQ;
    return tlm::TLM_UPDATED;
  }
  if (phase == tlm::END_RESP) return tlm::TLM_COMPLETED;  // the read closes on the channel's time
  (void)delay;
  return tlm::TLM_COMPLETED;
}

void MemoryTarget::respond(tlm_generic_payload& t, const tlm_phase&) {
  const sc_time transfer = (double(t.get_data_length()) / double(timing_.bytes_per_clock)) * period_;
  closing_.push_back(sc_time_stamp() + transfer);
  if (closing_.size() == 1) release_event_.notify(transfer);
  tlm_phase phase = tlm::BEGIN_RESP;
  sc_time delay = SC_ZERO_TIME;
  socket->nb_transport_bw(t, phase, delay);  // TLM_ACCEPTED: END_RESP follows on the forward path
}

void MemoryTarget::release() {
  const sc_time now = sc_time_stamp();
  while (!closing_.empty() && closing_.front() <= now) {
    closing_.pop_front();
    --open_;
    if (!waiting_.empty()) {
      tlm_generic_payload* next = waiting_.front();
      waiting_.pop_front();
      accept(*next);
      tlm_phase phase = tlm::END_REQ;
      sc_time delay = SC_ZERO_TIME;
      socket->nb_transport_bw(*next, phase, delay);
    }
  }
  if (!closing_.empty()) release_event_.notify(closing_.front() - now);
}

void MemoryTarget::b_transport(tlm_generic_payload& t, sc_time& delay) {
  if (check(t)) delay += latency() + (double(t.get_data_length()) / double(timing_.bytes_per_clock)) * period_;
}

sc_time MemoryTarget::latency() {
  const uint64_t extra = timing_.jitter ? jitter_rng_() % (uint64_t(timing_.jitter) + 1) : 0;
  return double(timing_.latency + extra) * period_;
}

unsigned int MemoryTarget::transport_dbg(tlm_generic_payload& t) {
  const uint64_t a = t.get_address();
  if (t.get_command() != tlm::TLM_READ_COMMAND || a < base_ || a - base_ >= image_.size() || !t.get_data_ptr())
    return 0;
  const size_t n = size_t(std::min<uint64_t>(t.get_data_length(), image_.size() - (a - base_)));
  std::memcpy(t.get_data_ptr(), &image_[a - base_], n);
  return unsigned(n);
}

}  // namespace tex::systemc

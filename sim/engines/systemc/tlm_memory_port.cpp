#include "engines/systemc/tlm_memory_port.h"

#include <algorithm>

namespace tex::systemc {

using namespace sc_core;
using tlm::tlm_generic_payload;
using tlm::tlm_phase;
using tlm::tlm_sync_enum;

TlmMemoryPort::TlmMemoryPort(MemorySocket& socket, int line_bytes, int beat_bytes)
    : socket_(socket), line_bytes_(line_bytes), beat_bytes_(beat_bytes) {
  socket_.register_nb_transport_bw(this, &TlmMemoryPort::nb_transport_bw);
}

TlmMemoryPort::~TlmMemoryPort() = default;

bool TlmMemoryPort::response_valid() const {
  return !lines_.empty() && lines_.front()->answered && lines_.front()->ready <= sc_time_stamp();
}

const uint8_t* TlmMemoryPort::response_beat() const {
  return response_valid() ? lines_.front()->data.data() + size_t(beat_) * size_t(beat_bytes_) : nullptr;
}

void TlmMemoryPort::clock(bool request_fire, uint32_t address, bool response_fire) {
  if (response_fire && response_valid() && ++beat_ * beat_bytes_ == line_bytes_) {
    beat_ = 0;
    error_lines_ += lines_.front()->trans.get_response_status() != tlm::TLM_OK_RESPONSE;
    lines_.pop_front();
  }
  if (!request_fire) return;
  reads_.push_back(address);
  auto line = std::make_unique<Line>();
  line->data.assign(size_t(line_bytes_), 0);
  tlm_generic_payload& t = line->trans;
  t.set_command(tlm::TLM_READ_COMMAND);
  t.set_address(address);
  t.set_data_ptr(line->data.data());
  t.set_data_length(unsigned(line_bytes_));
  t.set_streaming_width(unsigned(line_bytes_));
  t.set_byte_enable_ptr(nullptr);
  t.set_dmi_allowed(false);
  t.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  lines_.push_back(std::move(line));
  Line& l = *lines_.back();
  tlm_phase phase = tlm::BEGIN_REQ;
  sc_time delay = SC_ZERO_TIME;
  switch (socket_->nb_transport_fw(t, phase, delay)) {
    case tlm::TLM_ACCEPTED: end_req_owed_ = &t; break;
    case tlm::TLM_UPDATED:
      if (phase == tlm::BEGIN_RESP) {  // answered on the return path: END_RESP goes forward
        answered(l, delay);
        tlm_phase end = tlm::END_RESP;
        sc_time zero = SC_ZERO_TIME;
        socket_->nb_transport_fw(t, end, zero);
      } else if (phase != tlm::END_REQ) {
        error_ = "memory socket: the target returned phase " + std::string(phase.get_name()) + " for BEGIN_REQ";
      }
      break;
    case tlm::TLM_COMPLETED: answered(l, delay); break;
  }
}

void TlmMemoryPort::answered(Line& line, const sc_time& delay) {
  line.answered = true;
  line.ready = sc_time_stamp() + delay;
}

TlmMemoryPort::Line* TlmMemoryPort::find(tlm_generic_payload& t) {
  for (auto& l : lines_)
    if (&l->trans == &t) return l.get();
  for (auto& l : orphans_)
    if (&l->trans == &t) return l.get();
  return nullptr;
}

tlm_sync_enum TlmMemoryPort::nb_transport_bw(tlm_generic_payload& t, tlm_phase& phase, sc_time& delay) {
  if (phase == tlm::END_REQ || phase == tlm::BEGIN_RESP) {
    if (end_req_owed_ == &t) end_req_owed_ = nullptr;  // BEGIN_RESP also ends the request phase
    if (phase == tlm::END_REQ) return tlm::TLM_ACCEPTED;
    Line* line = find(t);
    if (!line) {
      if (error_.empty()) error_ = "memory socket: BEGIN_RESP for a transaction the unit did not send";
      return tlm::TLM_COMPLETED;
    }
    answered(*line, delay);
    orphans_.erase(std::remove_if(orphans_.begin(), orphans_.end(), [](const auto& l) { return l->answered; }),
                   orphans_.end());
    return tlm::TLM_COMPLETED;
  }
  if (error_.empty()) error_ = "memory socket: phase " + std::string(phase.get_name()) + " on the backward path";
  return tlm::TLM_COMPLETED;
}

// Reads in flight cannot be called back: their transactions live on as orphans until answered.
void TlmMemoryPort::reset() {
  for (auto& l : lines_)
    if (!l->answered) orphans_.push_back(std::move(l));
  lines_.clear();
  beat_ = 0;
}

}  // namespace tex::systemc

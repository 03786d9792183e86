#include "engines/systemc/stream_initiator.h"

#include <algorithm>
#include <cstdio>

#include "model/error.h"


namespace tex::systemc {

using namespace sc_core;
using tlm::tlm_generic_payload;
using tlm::tlm_phase;
using tlm::tlm_sync_enum;

namespace {
// More transactions than the deepest unit holds in flight (the cached unit's sample FIFO of up to
// 2048 samples plus its pipeline): the pool never throttles the stream.
constexpr size_t kSlots = 4096;

inline double unit_random(std::mt19937_64& rng) { return double(rng() >> 11) * (1.0 / 9007199254740992.0); }
}  // namespace

StreamInitiator::StreamInitiator(sc_module_name name, RequestSource& source, TexelSink& sink,
                                 bool approximately_timed, const sc_time& clock_period, const InitiatorTiming& timing)
    : sc_module(name),
      socket("socket"),
      requests_(source),
      texels_(sink),
      at_(approximately_timed),
      timing_(timing),
      period_(clock_period),
      rng_(timing.seed),
      end_resp_peq_(this, &StreamInitiator::send_end_resp) {
  socket.register_nb_transport_bw(this, &StreamInitiator::nb_transport_bw);
  for (size_t i = 0; i < kSlots; ++i) {
    slots_.push_back(std::make_unique<Slot>());
    Slot& s = *slots_.back();
    s.set_command(tlm::TLM_READ_COMMAND);
    s.set_address(kSampleAddress);
    s.set_data_ptr(reinterpret_cast<unsigned char*>(&s.data));
    s.set_data_length(sizeof(SampleTransfer));
    s.set_streaming_width(sizeof(SampleTransfer));
    s.set_byte_enable_ptr(nullptr);
    s.set_dmi_allowed(false);
    free_slots_.push_back(&s);
  }
  if (at_) {
    SC_THREAD(run_at);
  } else {
    SC_THREAD(run_lt);
  }
}

uint64_t StreamInitiator::cycles() const {
  if (counters_.responses == 0) return 0;
  return uint64_t((counters_.last_response - counters_.first_accept) / period_ + 0.5) + (at_ ? 1 : 0);
}

void StreamInitiator::fail(const std::string& message) {
  if (error_.empty()) error_ = message;
}

StreamInitiator::Slot* StreamInitiator::take_slot(const Request& q, size_t index) {
  while (free_slots_.empty()) wait(slot_freed_);
  Slot* s = free_slots_.back();
  free_slots_.pop_back();
  s->data = SampleTransfer{};
  s->data.u = q.u;
  s->data.v = q.v;
  s->data.lod = q.lod;
  s->data.tag = uint32_t(index);
  s->data.has_derivatives = q.has_derivatives;
  s->data.dudx = q.deriv.dudx;
  s->data.dvdx = q.deriv.dvdx;
  s->data.dudy = q.deriv.dudy;
  s->data.dvdy = q.deriv.dvdy;
  s->data.bias = q.bias;
  s->data.texture = q.texture;
  s->data.sampler = q.sampler;
  s->data.op = uint8_t(q.op);
  s->data.component = q.component;
  s->data.layer = q.layer;
  s->data.ref = q.ref;
  s->data.w = q.w;
  s->data.dwdx = q.dwdx;
  s->data.dwdy = q.dwdy;
  s->set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  ++issued_;
  return s;
}

void StreamInitiator::release(Slot& slot) {
  free_slots_.push_back(&slot);
  slot_freed_.notify();
}

// Every response: status OK (or a sample flagged by a memory error) and the tag of the oldest
// request not yet answered.
void StreamInitiator::check_response(Slot& slot) {
  if (!error_.empty()) return;
  const uint64_t want = counters_.responses;
  const uint32_t tag = slot.data.tag;
  if (slot.get_response_status() == tlm::TLM_GENERIC_ERROR_RESPONSE) {
    flagged_.push_back(want);
  } else if (!slot.is_response_ok()) {
    fail("sample tag " + std::to_string(tag) + ": response status " + slot.get_response_string());
    return;
  }
  if (want >= issued_) {
    fail("response with tag " + std::to_string(tag) + " after all " + std::to_string(issued_) +
         " requests were answered: duplicated response");
    return;
  }
  if (tag != want) {
    fail("response with tag " + std::to_string(tag) + " at " + sc_time_stamp().to_string() + ", expected tag " +
         std::to_string(want) + ": a response was lost, duplicated or reordered");
    return;
  }
  texels_.push({slot.data.rgba[0], slot.data.rgba[1], slot.data.rgba[2], slot.data.rgba[3]});
  ++counters_.responses;
  counters_.last_response = sc_time_stamp();
}

// ----------------------------------------------------------------------------- approximately timed

void StreamInitiator::run_at() {
  for (size_t i = 0; error_.empty(); ++i) {
    const Request* q = requests_.peek();
    if (!q) break;
    if (timing_.gap_prob > 0 && unit_random(rng_) < timing_.gap_prob) {
      const int gap = 1 + int(rng_() % uint64_t(std::max(1, timing_.max_gap)));
      counters_.gap_cycles += uint64_t(gap);
      wait(gap * period_);
    }
    Slot* s = take_slot(*q, i);
    requests_.pop();
    tlm_phase phase = tlm::BEGIN_REQ;
    sc_time delay = SC_ZERO_TIME;
    awaiting_end_req_ = s;
    const tlm_sync_enum status = socket->nb_transport_fw(*s, phase, delay);
    if (status == tlm::TLM_COMPLETED) {  // an error status, or a target that answers at once
      awaiting_end_req_ = nullptr;
      on_request_accepted(*s);
      check_response(*s);
      release(*s);
      continue;
    }
    if (status == tlm::TLM_UPDATED) {
      if (phase == tlm::END_REQ) {
        awaiting_end_req_ = nullptr;
        on_request_accepted(*s);
      } else if (phase == tlm::BEGIN_RESP) {
        awaiting_end_req_ = nullptr;
        on_request_accepted(*s);
        on_begin_resp(*s);
        phase = tlm::END_RESP;
        delay = SC_ZERO_TIME;
        socket->nb_transport_fw(*s, phase, delay);
      }
      if (delay != SC_ZERO_TIME) wait(delay);
    }
    // Request exclusion: the next BEGIN_REQ only after END_REQ (or BEGIN_RESP) of this one.
    while (awaiting_end_req_ && error_.empty()) wait(request_ended_);
  }
  all_issued_ = true;
}

void StreamInitiator::on_request_accepted(Slot& slot) {
  slot.accepted = sc_time_stamp();
  if (!any_accepted_) {
    any_accepted_ = true;
    counters_.first_accept = slot.accepted;
  }
}

void StreamInitiator::on_begin_resp(Slot& slot) {
  const uint64_t latency = uint64_t((sc_time_stamp() - slot.accepted) / period_ + 0.5);
  if (counters_.responses == 0 || latency < counters_.latency_min) counters_.latency_min = latency;
  counters_.latency_max = std::max(counters_.latency_max, latency);
  check_response(slot);
}

tlm_sync_enum StreamInitiator::nb_transport_bw(tlm_generic_payload& trans, tlm_phase& phase, sc_time& delay) {
  Slot& s = slot_of(trans);
  if (phase == tlm::END_REQ || (phase == tlm::BEGIN_RESP && awaiting_end_req_ == &s)) {
    if (awaiting_end_req_ != &s) {
      fail("TLM protocol: END_REQ for a transaction that is not the open request");
      return tlm::TLM_ACCEPTED;
    }
    awaiting_end_req_ = nullptr;
    on_request_accepted(s);
    request_ended_.notify();  // the next BEGIN_REQ goes out in this same clock
    if (phase == tlm::END_REQ) return tlm::TLM_ACCEPTED;
  }
  if (phase == tlm::BEGIN_RESP) {
    (void)delay;
    on_begin_resp(s);
    if (timing_.stall_prob > 0 && unit_random(rng_) < timing_.stall_prob) {
      // Hold the response channel: the target may not send the next BEGIN_RESP until END_RESP.
      const int stall = 1 + int(rng_() % uint64_t(std::max(1, timing_.max_stall)));
      counters_.stall_cycles += uint64_t(stall);
      end_resp_peq_.notify(trans, tlm::END_RESP, stall * period_);
      return tlm::TLM_ACCEPTED;
    }
    release(s);
    return tlm::TLM_COMPLETED;
  }
  fail("TLM protocol: the initiator got phase " + std::string(phase.get_name()) + " on the backward path");
  return tlm::TLM_COMPLETED;
}

void StreamInitiator::send_end_resp(tlm_generic_payload& trans, const tlm_phase& phase) {
  tlm_phase p = phase;
  sc_time delay = SC_ZERO_TIME;
  socket->nb_transport_fw(trans, p, delay);
  release(slot_of(trans));
}

// ----------------------------------------------------------------------------- loosely timed

void StreamInitiator::run_lt() {
  counters_.first_accept = sc_time_stamp();
  tlm_utils::tlm_quantumkeeper::set_global_quantum(1024 * period_);
  tlm_utils::tlm_quantumkeeper keeper;
  keeper.reset();
  for (size_t i = 0; error_.empty(); ++i) {
    const Request* q = requests_.peek();
    if (!q) break;
    Slot* s = take_slot(*q, i);
    requests_.pop();
    sc_time delay = keeper.get_local_time();
    socket->b_transport(*s, delay);
    keeper.set(delay);
    check_response(*s);
    counters_.last_response = keeper.get_current_time();
    release(*s);
    if (keeper.need_sync()) keeper.sync();
  }
  all_issued_ = true;
  keeper.sync();
}

// ----------------------------------------------------------------------------- the run loop

void run_stream(StreamInitiator& bench, const sc_time& period, uint64_t timeout_cycles,
                bool show_progress, const std::function<std::string()>& target_error) {
  const uint64_t slice = 4096;
  uint64_t last_done = 0, idle_clocks = 0;
  while (!bench.done() && target_error().empty()) {
    sc_start(double(slice) * period);
    const uint64_t done = bench.counters().responses;
    if (done != last_done) {
      last_done = done;
      idle_clocks = 0;
      if (show_progress) std::fprintf(stderr, "\rsystemc: %llu samples", (unsigned long long)done);
    } else if ((idle_clocks += slice) > timeout_cycles) {
      throw SimulationError("SystemC time-out: no response for tag " + std::to_string(done) + " (" +
                  std::to_string(bench.issued() - done) + " of " + std::to_string(bench.issued()) + " owed) for " +
                  std::to_string(idle_clocks) + " clocks, at " + sc_time_stamp().to_string() +
                  ": a response was lost");
    }
  }
  if (show_progress) std::fprintf(stderr, "\r%60s\r", "");
  if (bench.error().empty() && target_error().empty()) sc_start(64.0 * period);
  if (!target_error().empty()) throw SimulationError(target_error());
  if (!bench.error().empty()) throw SimulationError(bench.error());
  bench.flush();
}

}  // namespace tex::systemc

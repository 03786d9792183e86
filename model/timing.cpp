#include "model/timing.h"

#include <string>

#include "model/error.h"

namespace tex {

Stimulus Stimulus::of(Stalls stalls) {
  Stimulus t;
  switch (stalls) {
    case Stalls::None:
      break;
    case Stalls::Random:  // moderate gaps and stalls, now and then a long stall
      t.gap_prob = 0.05;
      t.max_gap = 4;
      t.stall_prob = 0.05;
      t.max_stall = 8;
      t.long_stall_prob = 0.0005;
      t.long_stall = 200;
      break;
    case Stalls::Heavy:  // a gap or stall starts in 60% of the free clocks and lasts 1..6
      t.gap_prob = 0.6;
      t.max_gap = 6;
      t.stall_prob = 0.6;
      t.max_stall = 6;
      break;
  }
  return t;
}

UnitClock::UnitClock(const UnitShape& shape, const MemoryChannel* memory, bool always_ready)
    : shape_(shape), memory_(memory ? *memory : MemoryChannel(16, 16, MemoryTiming{})), always_ready_(always_ready) {
  if (shape_.cached && !memory) throw Error("the cached unit's timing needs its memory channel");
  memory_.count_repeats(false);  // (addresses do not decide timing: the model passes none)
  if (shape_.cached) {
    const uint32_t d = shape_.fifo_depth;
    if (d < 2 || (d & (d - 1)) != 0) throw Error("FIFO depth " + std::to_string(d) + ": a power of two, at least 2");
    if (shape_.miss_depth < 16) throw Error("miss ring of " + std::to_string(shape_.miss_depth) + ": at least 16");
    if (shape_.fill_depth < 1 || shape_.line_beats < 1) throw Error("fill FIFO and beats per line: at least 1");
    fifo_.assign(d, 0);
    fifo_limit_ = shape_.fifo_limit == 0 || shape_.fifo_limit > d ? d : shape_.fifo_limit;
    if (shape_.cube_clocks != 0 && shape_.cube_clocks != kCubeClocks)
      throw Error("cube clocks " + std::to_string(shape_.cube_clocks) + ": 0 or " + std::to_string(kCubeClocks));
    front_clocks_ = 4 + (shape_.cube_clocks ? kSeamClocks : 0);
  }
}

// tex_probe (rtl/tex_probe.sv): req_ready = en && !hold; the clock-4 register holds a request
// while the sequencer issues its probes, one per clock with en.
bool UnitClock::probe_stage(const RequestWork* offer, bool en, bool& probe_valid, bool& probe_last,
                            uint8_t& probe_fills, bool& ready) {
  probe_valid = (probe_valid_ & 8u) != 0;
  const RequestWork& w = probe_work_[probe_head_ & 3];
  const bool hold = probe_valid && index_ != uint32_t(w.probes) - 1;
  const bool en_up = en && !hold;
  probe_last = !hold;
  probe_fills = probe_valid ? uint8_t(w.fills(int(index_ & (kMaxAniso - 1)))) : 0;
  const bool accepted = offer && en_up;
  ready = en_up;
  if (en_up) {
    index_ = 0;
    if (probe_valid) ++probe_head_;
    probe_valid_ = (probe_valid_ << 1 | uint32_t(accepted)) & 0xFu;
    if (accepted) probe_work_[probe_tail_++ & 3] = *offer;
  } else if (en) {
    ++index_;
  }
  return accepted;
}

// tex_skid (rtl/tex_skid.sv): the output register refills from the skid entry first, else from
// the input; the input is parked when the output is stalled.
void UnitClock::skid_stage(bool sample_valid, bool ready) {
  if (ready || !out_valid_) {
    out_valid_ = skid_valid_ || sample_valid;
    skid_valid_ = false;
  } else if (sample_valid && !skid_valid_) {
    skid_valid_ = true;
  }
}

// tex_unit: one stall-enable pipeline, en = the skid buffer has room.
UnitClock::Edge UnitClock::clock_onchip(const RequestWork* offer, bool ready) {
  const bool en = !skid_valid_;
  uint32_t flags = (out_valid_ ? Edge::kRspValid : 0) | (out_valid_ && ready ? Edge::kResponded : 0);
  const bool sample_valid = sample_valid_;
  if (en) {
    // tex_accum: clock 2 takes clock 1 (a sample leaves with its last probe); clock 1 the last
    // probe register; the probe registers shift in tex_probe's probe.
    sample_valid_ = s1_valid_ && s1_last_;
    s1_valid_ = (pipe_valid_ >> 8) & 1u;
    s1_last_ = (pipe_last_ >> 8) & 1u;
  }
  bool probe_valid = false, probe_last = false;
  uint8_t fills = 0;
  bool probe_ready = false;
  if (probe_stage(offer, en, probe_valid, probe_last, fills, probe_ready)) flags |= Edge::kAccepted;
  if (en) {
    pipe_valid_ = (pipe_valid_ << 1 | uint32_t(probe_valid)) & 0x1FFu;
    pipe_last_ = (pipe_last_ << 1 | uint32_t(probe_last)) & 0x1FFu;
  }
  skid_stage(sample_valid, ready);
  return Edge{flags};
}

// tex_unit_cached: the front (tex_probe, front clocks 1-4, the tag stage) advances with the
// registered en_front (room in the FIFO and the miss ring), the back (H, R, T, taps, filter,
// tex_accum) with en_back (room in the skid buffer); tex_cached_fetch in between.
UnitClock::Edge UnitClock::clock_cached(const RequestWork* offer, bool ready) {
  const bool en_back = !skid_valid_;
  const bool en_front = en_front_;
  uint32_t flags = (out_valid_ ? Edge::kRspValid : 0) | (out_valid_ && ready ? Edge::kResponded : 0);

  // The tag stage pushes the front's clock-4 probe and its misses.
  const uint32_t front_last = front_clocks_ - 1;
  const bool push = en_front && (front_valid_ >> front_last & 1u) != 0;
  const uint32_t push_entry = uint32_t(front_probes_ >> (5 * front_last)) & 31u;  // {last, fills}
  const uint32_t push_fills = push ? push_entry & 15u : 0;
  // Memory: a miss is issued when the channel is ready; a beat is taken when the fill FIFO has room.
  const bool issue = ring_unissued_ != 0 && memory_.request_ready();
  const bool beat_take = memory_.response_valid() && fill_count_ != shape_.fill_depth;
  const bool line_done = beat_take && beat_ == shape_.line_beats - 1;
  // H: the head writes its fills, one per clock, then leaves for R.
  const bool fill_write = en_back && h_valid_ && h_fills_ != 0 && fill_count_ != 0;
  const bool h_go = en_back && h_valid_ && (h_fills_ == 0 || (h_fills_ == 1 && fill_write));
  const bool pop = (!h_valid_ || h_go) && fifo_count_ != 0;
  fifo_max = std::max(fifo_max, fifo_count_);
  head_wait_cycles += en_back && h_valid_ && !h_go;
  lines_read += issue;

  const bool sample_valid = sample_valid_;
  if (always_ready_) {
    // rsp_ready always high: the skid entry never fills, en_back is always high, and a sample's last
    // probe leaving H is its response 9 clocks later (the same registers, clocked as one line).
    flags = (back_line_ & 1u) ? Edge::kRspValid | Edge::kResponded : 0;
    back_line_ = (back_line_ >> 1) | uint32_t(h_go && h_last_) << 8;
  } else if (en_back && (h_go || r_valid_ || t_valid_ || o_valid_ || back_valid_ != 0 || s1_valid_ || sample_valid_)) {
    sample_valid_ = s1_valid_ && s1_last_;
    s1_valid_ = (back_valid_ >> 2) & 1u;
    s1_last_ = (back_last_ >> 2) & 1u;
    back_valid_ = (back_valid_ << 1 | uint32_t(o_valid_)) & 7u;
    back_last_ = (back_last_ << 1 | uint32_t(o_last_)) & 7u;
    o_valid_ = t_valid_;
    o_last_ = t_last_;
    t_valid_ = r_valid_;
    t_last_ = r_last_;
    r_valid_ = h_go;
    r_last_ = h_last_;
  }
  if (pop) {
    const uint32_t entry = fifo_[fifo_rd_++ & (shape_.fifo_depth - 1)];
    h_valid_ = true;
    h_fills_ = entry & 15u;
    h_last_ = (entry >> 4) & 1u;
  } else {
    if (h_go) h_valid_ = false;
    if (fill_write) --h_fills_;
  }
  if (push) fifo_[fifo_wr_++ & (shape_.fifo_depth - 1)] = uint16_t(push_entry);
  fifo_count_ = fifo_count_ + uint32_t(push) - uint32_t(pop);
  ring_used_ = ring_used_ + push_fills - uint32_t(fill_write);
  ring_unissued_ = ring_unissued_ + push_fills - uint32_t(issue);
  fill_count_ = fill_count_ + uint32_t(line_done) - uint32_t(fill_write);
  if (beat_take) beat_ = line_done ? 0 : beat_ + 1;
  // Room after this clock for one more sample and its (at most 8) misses.
  en_front_ = fifo_count_ < fifo_limit_ && ring_used_ + 8 <= shape_.miss_depth;

  if (en_front) {  // (a stalled front keeps every register: nothing to do)
    bool probe_valid = false, probe_last = false;
    uint8_t fills = 0;
    bool ready = false;
    if (shape_.cube_clocks == 0) {
      if (probe_stage(offer, true, probe_valid, probe_last, fills, ready)) flags |= Edge::kAccepted;
    } else {
      // tex_cube's line: tex_probe takes its last register; it advances, taking the offer, with
      // tex_probe's req_ready (the unit's req_ready).
      const uint32_t end = 1u << (shape_.cube_clocks - 1);
      const RequestWork* head = (line_valid_ & end) ? &line_work_[line_head_ & 7] : nullptr;
      probe_stage(head, true, probe_valid, probe_last, fills, ready);
      if (ready) {
        if (head) ++line_head_;
        line_valid_ = (line_valid_ << 1 | uint32_t(offer != nullptr)) & (2 * end - 1);
        if (offer) {
          line_work_[line_tail_++ & 7] = *offer;
          flags |= Edge::kAccepted;
        }
      }
    }
    front_valid_ = (front_valid_ << 1 | uint32_t(probe_valid)) & ((1u << front_clocks_) - 1);
    front_probes_ = (front_probes_ << 5 | fills | uint64_t(probe_last) << 4) & ((uint64_t(1) << (5 * front_clocks_)) - 1);
  }
  if (!always_ready_ && (out_valid_ || skid_valid_ || sample_valid)) skid_stage(sample_valid, ready);  // (else it stays empty)
  memory_.clock(issue, 0, beat_take);
  return Edge{flags};
}

uint64_t UnitClock::wait_for_fill() {
  if (!shape_.cached || en_front_ || skid_valid_ || out_valid_ || sample_valid_ || s1_valid_ || back_valid_ != 0 ||
      o_valid_ || t_valid_ || r_valid_ || (back_line_ & 1u) || !h_valid_ || h_fills_ == 0 || fill_count_ != 0)
    return 0;
  // As clock_cached with en_front low, en_back high, nothing to fill yet: only the miss ring's
  // requests and the memory's beats move (en_front stays low: the FIFO and the ring do not change),
  // and with always_ready the samples already past H move down the back's line (no response is
  // due in these clocks: the loop stops before one is).
  fifo_max = std::max(fifo_max, fifo_count_);
  uint64_t clocks = 0;
  while (fill_count_ == 0 && !(back_line_ & 1u)) {
    back_line_ >>= 1;
    const bool issue = ring_unissued_ != 0 && memory_.request_ready();
    const bool beat_take = memory_.response_valid();
    const bool line_done = beat_take && beat_ == shape_.line_beats - 1;
    lines_read += issue;
    ring_unissued_ -= uint32_t(issue);
    fill_count_ += uint32_t(line_done);
    if (beat_take) beat_ = line_done ? 0 : beat_ + 1;
    memory_.clock(issue, 0, beat_take);
    ++clocks;
  }
  head_wait_cycles += clocks;
  return clocks;
}

TimedStream::TimedStream(const UnitShape& shape, const MemoryChannel* memory, const Stimulus& stimulus, uint64_t seed)
    : unit_(shape, memory, stimulus.ideal()), stimulus_(stimulus, seed), ideal_(stimulus.ideal()) {
  // The requests in flight: at most the FIFO's probes and the registers around it.
  size_t ring = 1024;
  while (ring < size_t(shape.fifo_depth) + 64) ring *= 2;
  accept_clock_.resize(ring);
}

void TimedStream::step(const RequestWork* next, std::vector<uint64_t>* clocks) {
  if (ideal_) {  // (with stalls the stimulus draws in every clock: clock by clock)
    const uint64_t waited = unit_.wait_for_fill();
    if (waited) {
      if (next) {
        if (!c_.any_offer) {
          c_.any_offer = true;
          c_.first_offer_cycle = now_;
        }
        c_.backpressure_cycles += waited;
      }
      now_ += waited;
    }
  }
  bool offer = next != nullptr, ready = true;
  if (!ideal_) stimulus_.begin(next != nullptr, offer, ready);  // (ideal: no draws)
  if (offer && !c_.any_offer) {
    c_.any_offer = true;
    c_.first_offer_cycle = now_;
  }
  const UnitClock::Edge e = unit_.clock(offer ? next : nullptr, ready);
  if (e.responded()) {
    const uint64_t latency = now_ - accept_clock_[done_ & (accept_clock_.size() - 1)];
    c_.latency_min = c_.samples == 0 ? latency : std::min(c_.latency_min, latency);
    c_.latency_max = std::max(c_.latency_max, latency);
    ++c_.samples;
    ++done_;
    c_.last_response_cycle = now_;
    if (clocks) clocks->push_back(now_ - c_.first_offer_cycle);
  } else if (e.rsp_valid()) {
    ++c_.output_stall_cycles;
  }
  if (offer) {
    if (e.accepted()) {
      accept_clock_[accepted_++ & (accept_clock_.size() - 1)] = now_;
      ++head_;
    } else {
      ++c_.backpressure_cycles;
    }
  }
  if (!ideal_) stimulus_.end(e.accepted());
  ++now_;
}

void TimedStream::run(std::vector<uint64_t>* clocks) {
  while (head_ < queue_.size()) step(&queue_[head_], clocks);
  queue_.clear();
  head_ = 0;
}

void TimedStream::finish(std::vector<uint64_t>* clocks) {
  run(clocks);
  while (done_ < accepted_) step(nullptr, clocks);
}

TimingCounters TimedStream::counters() const {
  TimingCounters c = c_;
  c.gap_cycles = stimulus_.gap_cycles;
  c.lines_read = unit_.lines_read;
  c.fifo_max = unit_.fifo_max;
  c.head_wait_cycles = unit_.head_wait_cycles;
  return c;
}

}  // namespace tex

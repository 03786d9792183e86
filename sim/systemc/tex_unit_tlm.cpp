#include "tex_unit_tlm.h"

#include "model/error.h"

#ifdef TEX_SYSTEMC_HAVE_RTL
#include <verilated.h>

#include "Vtex_unit_sc.h"
#endif

namespace tex::systemc {

using namespace sc_core;
using tlm::tlm_generic_payload;
using tlm::tlm_phase;
using tlm::tlm_sync_enum;

namespace {
constexpr uint32_t kRtlTagMask = 0xFFFF;  // TAG_W = 16
constexpr int kResetClocks = 4;
}  // namespace

#ifdef TEX_SYSTEMC_HAVE_RTL
// The Verilated tex_unit (MAX_LOG2_W = MAX_LOG2_H = 10, CW = 8, TAG_W = 16) and the signals on its
// pins. Verilator maps 1-bit ports to bool and 2..32-bit ports to uint32_t.
struct TexUnitTlm::Rtl {
  // Starts high, so the first edge is a falling one: inputs are driven on falling edges and
  // sampled on rising edges, and the first rising edge already sees reset.
  sc_clock clk;
  sc_signal<bool> rst{"rst", true};
  sc_signal<uint32_t> cfg_log2_w{"cfg_log2_w"}, cfg_log2_h{"cfg_log2_h"}, cfg_wrap_u{"cfg_wrap_u"},
      cfg_wrap_v{"cfg_wrap_v"}, cfg_mip_mode{"cfg_mip_mode"}, cfg_lod_bias{"cfg_lod_bias"},
      cfg_min_lod{"cfg_min_lod"}, cfg_max_lod{"cfg_max_lod"};
  sc_signal<bool> cfg_texel_linear{"cfg_texel_linear"};
  sc_signal<bool> wr_en{"wr_en"};
  sc_signal<uint32_t> wr_level{"wr_level"}, wr_x{"wr_x"}, wr_y{"wr_y"}, wr_data{"wr_data"};
  sc_signal<bool> req_valid{"req_valid"}, req_ready{"req_ready"};
  sc_signal<uint32_t> req_u{"req_u"}, req_v{"req_v"}, req_lod{"req_lod"}, req_tag{"req_tag"};
  sc_signal<bool> rsp_valid{"rsp_valid"}, rsp_ready{"rsp_ready"};
  sc_signal<uint32_t> rsp_rgba{"rsp_rgba"}, rsp_tag{"rsp_tag"};
  // The model's own Verilator context: the --sc model takes Verilated::threadContextp(), which in a
  // forked child may still point at a context of the parent (e.g. the --engine rtl harness's, freed).
  std::unique_ptr<VerilatedContext> context;
  std::unique_ptr<Vtex_unit_sc> model;

  Rtl(const sc_time& period, uint64_t seed) : clk("clk", period, 0.5, SC_ZERO_TIME, false) {
    context = std::make_unique<VerilatedContext>();
    // Registers without reset start random: the design must not depend on them. An RTL assertion
    // sets gotFinish (checked every edge) instead of aborting the process.
    context->fatalOnError(false);
    context->randReset(2);
    context->randSeed(int(seed & 0x7fffffff));
    Verilated::threadContextp(context.get());
    model = std::make_unique<Vtex_unit_sc>("tex_unit");
    Vtex_unit_sc& dut = *model;
    dut.clk(clk);
    dut.rst(rst);
    dut.cfg_log2_w(cfg_log2_w);
    dut.cfg_log2_h(cfg_log2_h);
    dut.cfg_wrap_u(cfg_wrap_u);
    dut.cfg_wrap_v(cfg_wrap_v);
    dut.cfg_texel_linear(cfg_texel_linear);
    dut.cfg_mip_mode(cfg_mip_mode);
    dut.cfg_lod_bias(cfg_lod_bias);
    dut.cfg_min_lod(cfg_min_lod);
    dut.cfg_max_lod(cfg_max_lod);
    dut.wr_en(wr_en);
    dut.wr_level(wr_level);
    dut.wr_x(wr_x);
    dut.wr_y(wr_y);
    dut.wr_data(wr_data);
    dut.req_valid(req_valid);
    dut.req_ready(req_ready);
    dut.req_u(req_u);
    dut.req_v(req_v);
    dut.req_lod(req_lod);
    dut.req_tag(req_tag);
    dut.rsp_valid(rsp_valid);
    dut.rsp_ready(rsp_ready);
    dut.rsp_rgba(rsp_rgba);
    dut.rsp_tag(rsp_tag);
  }
};
#else
struct TexUnitTlm::Rtl {};
#endif

TexUnitTlm::TexUnitTlm(sc_module_name name, Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
                       const sc_time& clock_period, uint64_t seed, Fault fault, uint64_t fault_index)
    : sc_module(name),
      socket("socket"),
      backend_(backend),
      period_(clock_period),
      config_(config),
      fault_(fault),
      fault_index_(fault_index),
      fw_peq_(this, &TexUnitTlm::on_fw_phase) {
  if (backend == Backend::Model) {
    sampler_ = std::make_unique<Sampler>(pyramid, config);
    socket.register_b_transport(this, &TexUnitTlm::b_transport);
    loaded_ = true;
    return;
  }
#ifdef TEX_SYSTEMC_HAVE_RTL
  if (pyramid.log2_w0() > kRtlMaxLog2W || pyramid.log2_h0() > kRtlMaxLog2H)
    throw Error("texture " + std::to_string(pyramid.levels[0].width) + "x" + std::to_string(pyramid.levels[0].height) +
                " does not fit the SystemC RTL backend (at most " + std::to_string(1 << kRtlMaxLog2W) + "x" +
                std::to_string(1 << kRtlMaxLog2H) + "; use --engine systemc-model)");
  if (pyramid.levels[0].channel_bits != 8)
    throw Error("the SystemC RTL backend is built for 8-bit channels; this texture has " +
                std::to_string(pyramid.levels[0].channel_bits));
  rtl_ = std::make_unique<Rtl>(clock_period, seed);
  pyramid_ = &pyramid;
  socket.register_nb_transport_fw(this, &TexUnitTlm::nb_transport_fw);
  SC_METHOD(on_posedge);
  sensitive << rtl_->clk.posedge_event();
  dont_initialize();
  SC_METHOD(on_negedge);
  sensitive << rtl_->clk.negedge_event();
  dont_initialize();
#else
  (void)seed;
  throw Error("this build has no Verilated RTL for the SystemC engine (rtl/tex_files.f was missing at configure time)");
#endif
}

TexUnitTlm::~TexUnitTlm() = default;

void TexUnitTlm::fail(const std::string& message) {
  if (error_.empty()) error_ = message;
}

SampleTransfer* TexUnitTlm::decode(tlm_generic_payload& trans) {
  trans.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  if (trans.get_command() != tlm::TLM_READ_COMMAND) {
    trans.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return nullptr;
  }
  if (trans.get_address() != kSampleAddress) {
    trans.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return nullptr;
  }
  if (trans.get_byte_enable_ptr() != nullptr) {
    trans.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return nullptr;
  }
  if (trans.get_data_length() != sizeof(SampleTransfer) || trans.get_data_ptr() == nullptr ||
      trans.get_streaming_width() != sizeof(SampleTransfer)) {
    trans.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
    return nullptr;
  }
  auto* s = reinterpret_cast<SampleTransfer*>(trans.get_data_ptr());
  if (backend_ == Backend::Rtl && (s->lod < -32768 || s->lod > 32767)) {  // the 16-bit req_lod port
    trans.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return nullptr;
  }
  return s;
}

// ------------------------------------------------------------------------------ model backend

void TexUnitTlm::b_transport(tlm_generic_payload& trans, sc_time& delay) {
  SampleTransfer* s = decode(trans);
  if (!s) return;
  Request q;
  q.u = s->u;
  q.v = s->v;
  q.lod = s->lod;
  q.tag = s->tag;
  const Texel t = sampler_->sample(q);
  for (int c = 0; c < 4; ++c) s->rgba[c] = t[c];
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
  delay += period_;  // pipelined: one sample per clock
  ++counters_.samples;
}

// ------------------------------------------------------------------------------ RTL backend

tlm_sync_enum TexUnitTlm::nb_transport_fw(tlm_generic_payload& trans, tlm_phase& phase, sc_time& delay) {
  if (phase == tlm::BEGIN_REQ) {
    // A malformed request completes at once with its error status; it never reaches the RTL.
    if (!decode(trans)) return tlm::TLM_COMPLETED;
    fw_peq_.notify(trans, phase, delay);  // takes effect at the annotated time
    return tlm::TLM_ACCEPTED;
  }
  if (phase == tlm::END_RESP) {
    fw_peq_.notify(trans, phase, delay);
    return tlm::TLM_COMPLETED;
  }
  fail("TLM protocol: the target got phase " + std::string(phase.get_name()) + " on the forward path");
  return tlm::TLM_COMPLETED;
}

void TexUnitTlm::on_fw_phase(tlm_generic_payload& trans, const tlm_phase& phase) {
  if (phase == tlm::BEGIN_REQ) {
    if (pending_)
      fail("TLM protocol: BEGIN_REQ before END_REQ of the previous request (request exclusion rule)");
    pending_ = &trans;  // driven onto the RTL request pins at the next falling edge
  } else if (phase == tlm::END_RESP) {
    if (&trans != awaiting_end_resp_) fail("TLM protocol: END_RESP for a transaction with no response open");
    awaiting_end_resp_ = nullptr;
    send_queued_responses();
  }
}

void TexUnitTlm::on_negedge() {
#ifdef TEX_SYSTEMC_HAVE_RTL
  Rtl& r = *rtl_;
  if (!error_.empty()) {  // after an error: quiet pins
    r.req_valid = false;
    r.rsp_ready = false;
    r.wr_en = false;
    return;
  }
  if (!loaded_) {
    const uint64_t step = drive_step_++;
    if (step == 0) {
      // Static configuration (docs/rtl-interface.md), from tex::SamplerConfig.
      r.cfg_log2_w = uint32_t(pyramid_->log2_w0());
      r.cfg_log2_h = uint32_t(pyramid_->log2_h0());
      r.cfg_wrap_u = uint32_t(config_.wrap_u);
      r.cfg_wrap_v = uint32_t(config_.wrap_v);
      r.cfg_texel_linear = config_.filter.texel == TexelFilter::Linear;
      r.cfg_mip_mode = uint32_t(config_.filter.mip);
      r.cfg_lod_bias = uint32_t(config_.lod_bias) & 0xFFFF;
      r.cfg_min_lod = uint32_t(config_.min_lod) & 0xFFFF;
      r.cfg_max_lod = uint32_t(config_.max_lod) & 0xFFFF;
    }
    if (step < uint64_t(kResetClocks)) {
      r.rst = true;
      return;
    }
    r.rst = false;
    if (step == uint64_t(kResetClocks)) return;  // one idle clock after reset
    if (load_level_ < pyramid_->levels.size()) {
      // The write port: one texel per clock, level by level, row by row.
      const Image& img = pyramid_->levels[load_level_];
      const Texel t = img.at(load_x_, load_y_);
      r.wr_en = true;
      r.wr_level = uint32_t(load_level_);
      r.wr_x = uint32_t(load_x_);
      r.wr_y = uint32_t(load_y_);
      r.wr_data = uint32_t(t[0] & 255) | uint32_t(t[1] & 255) << 8 | uint32_t(t[2] & 255) << 16 |
                  uint32_t(t[3] & 255) << 24;
      if (++load_x_ == img.width) {
        load_x_ = 0;
        if (++load_y_ == img.height) {
          load_y_ = 0;
          ++load_level_;
        }
      }
      return;
    }
    // The last texel was written at the edge before: requests may go from this edge on.
    r.wr_en = false;
    loaded_ = true;
    counters_.load_cycles = cycle_;  // rising edges 0 .. cycle_-1 were reset and writes
    pyramid_ = nullptr;
    loaded_event_.notify(SC_ZERO_TIME);
  }
  // Requests: the pending one stays offered until the RTL accepts it.
  r.req_valid = pending_ != nullptr;
  if (pending_) {
    const auto* s = reinterpret_cast<const SampleTransfer*>(pending_->get_data_ptr());
    uint32_t tag = uint32_t(next_sequence_) & kRtlTagMask;
    if (fault_ == Fault::CorruptRtlTag && next_sequence_ == fault_index_) tag = (tag + 1) & kRtlTagMask;
    r.req_u = uint32_t(s->u);
    r.req_v = uint32_t(s->v);
    r.req_lod = uint32_t(s->lod) & 0xFFFF;
    r.req_tag = tag;
  }
  // Responses: take one from the RTL only when it can go straight onto the socket.
  r.rsp_ready = awaiting_end_resp_ == nullptr && to_respond_.empty();
#endif
}

void TexUnitTlm::on_posedge() {
#ifdef TEX_SYSTEMC_HAVE_RTL
  Rtl& r = *rtl_;
  const uint64_t edge = cycle_++;
  if (!error_.empty()) return;
  if (r.context->gotFinish()) {
    fail("RTL assertion failed (or $finish) at clock " + std::to_string(edge) + "; see the %Error line above");
    return;
  }
  if (!loaded_) return;
  const bool req_valid = r.req_valid.read(), req_ready = r.req_ready.read();
  const bool rsp_valid = r.rsp_valid.read(), rsp_ready = r.rsp_ready.read();
  if (req_valid && counters_.first_offer_cycle == 0 && next_sequence_ == 0) counters_.first_offer_cycle = edge;
  if (req_valid && !req_ready) ++counters_.backpressure_cycles;
  if (rsp_valid && !rsp_ready) ++counters_.response_stall_cycles;

  if (rsp_valid && rsp_ready) {
    const uint32_t tag = r.rsp_tag.read();
    if (in_flight_.empty()) {
      fail("RTL response with tag " + std::to_string(tag) + " at clock " + std::to_string(edge) +
           " while no request is in flight: duplicated or spurious response");
      return;
    }
    const InFlight f = in_flight_.front();
    const uint32_t want = uint32_t(f.sequence) & kRtlTagMask;
    if (tag != want) {
      fail("RTL response at clock " + std::to_string(edge) + " has tag " + std::to_string(tag) + ", expected tag " +
           std::to_string(want) + " (request #" + std::to_string(f.sequence) +
           "): a response was lost, duplicated or reordered");
      return;
    }
    in_flight_.pop_front();
    auto* s = reinterpret_cast<SampleTransfer*>(f.trans->get_data_ptr());
    const uint32_t rgba = r.rsp_rgba.read();
    for (int c = 0; c < 4; ++c) s->rgba[c] = uint16_t((rgba >> (8 * c)) & 255);
    f.trans->set_response_status(tlm::TLM_OK_RESPONSE);
    ++counters_.samples;
    counters_.last_response_cycle = edge;
    respond(f.trans);
  }
  if (req_valid && req_ready) {
    tlm_generic_payload* t = pending_;
    pending_ = nullptr;  // free before END_REQ: the initiator may send the next BEGIN_REQ at once
    in_flight_.push_back({t, next_sequence_++});
    tlm_phase phase = tlm::END_REQ;
    sc_time delay = SC_ZERO_TIME;
    const tlm_sync_enum status = socket->nb_transport_bw(*t, phase, delay);
    if (status != tlm::TLM_ACCEPTED) fail("TLM protocol: the initiator did not return TLM_ACCEPTED for END_REQ");
  }
#endif
}

// A response from the RTL, in order; the faults reorder, drop or repeat one here on purpose.
void TexUnitTlm::respond(tlm_generic_payload* trans) {
  const uint64_t index = responses_from_rtl_++;
  if (fault_ == Fault::DropResponse && index == fault_index_) return;
  if (fault_ == Fault::SwapResponses && index == fault_index_) {
    swap_held_ = trans;
    return;
  }
  to_respond_.push_back(trans);
  if (fault_ == Fault::DuplicateResponse && index == fault_index_) to_respond_.push_back(trans);
  if (swap_held_ && index == fault_index_ + 1) {
    to_respond_.push_back(swap_held_);
    swap_held_ = nullptr;
  }
  send_queued_responses();
}

// BEGIN_RESP for queued responses while the initiator completes each at once (response exclusion:
// the next BEGIN_RESP waits for the END_RESP of the previous one).
void TexUnitTlm::send_queued_responses() {
  while (awaiting_end_resp_ == nullptr && !to_respond_.empty()) {
    tlm_generic_payload* t = to_respond_.front();
    to_respond_.pop_front();
    tlm_phase phase = tlm::BEGIN_RESP;
    sc_time delay = SC_ZERO_TIME;
    const tlm_sync_enum status = socket->nb_transport_bw(*t, phase, delay);
    if (status == tlm::TLM_ACCEPTED || (status == tlm::TLM_UPDATED && phase == tlm::BEGIN_RESP))
      awaiting_end_resp_ = t;  // END_RESP comes later on the forward path
    // TLM_COMPLETED, or TLM_UPDATED with END_RESP: this response is done.
  }
}

}  // namespace tex::systemc

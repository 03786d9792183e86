#include "engines/systemc/tex_unit_tlm.h"

#include <algorithm>

#include "model/block_formats.h"
#include "model/error.h"
#include "model/srgb.h"

namespace tex::systemc {

using namespace sc_core;
using tlm::tlm_generic_payload;
using tlm::tlm_phase;
using tlm::tlm_sync_enum;

TexUnitTlm::TexUnitTlm(sc_module_name name, Backend backend, const TextureTable& textures,
                       const SamplerTable& samplers, const sc_time& clock_period, const EngineOptions& options)
    : sc_module(name), socket("socket"), memory_socket("memory_socket"), backend_(backend), period_(clock_period),
      textures_(textures), samplers_(samplers), options_(options) {
  socket.register_transport_dbg(this, &TexUnitTlm::transport_dbg);
  check_tables(textures, samplers, options.memory);
  const bool cached = options.memory == Memory::Cached;
  if (cached) {
    descriptors_ = texture_descriptors(textures, options);
    cache_.emplace(descriptors_, options.cache, samplers);
    cache_->set_error_reads(options.mem_error_reads);  // the flags the RTL backend must give
  }
  if (backend == Backend::Model) {
    TextureTable sampled = textures;
    if (cached) {
      // The unit's memories start blank: only the lines it reads over the bus fill them. (A cube
      // map's faces are sampled as loaded: a line of one face's skirt holds texels of its
      // neighbours, which the sampler takes from their own faces.)
      views_.resize(textures.size());
      for (size_t t = 0; t < textures.size(); ++t) {
        if (textures[t].kind == TextureKind::Cube) continue;
        views_[t].assign(size_t(textures[t].layers()), *textures[t].pyramid);
        for (Pyramid& blank : views_[t])
          for (Image& level : blank.levels) std::fill(level.texels.begin(), level.texels.end(), Texel{});
        sampled[t].pyramid = &views_[t][0];
        for (size_t l = 1; l < views_[t].size(); ++l) sampled[t].more_layers[l - 1] = &views_[t][l];
      }
      line_data_.assign(size_t(descriptors_[0].layout.line_bytes()), 0);
    }
    model_samplers_.emplace(sampled, samplers);
    socket.register_b_transport(this, &TexUnitTlm::b_transport);
    return;
  }
  const rtl::RtlConfig& rc = rtl::smallest_config_for(textures, options.memory, options.layout.block_w,
                                                      options.layout.block_h, &options.cache, options.fifo_depth);
  rtl::DriverOptions d = rtl::DriverOptions::of(options);
  if (cached) {
    memory_port_ = std::make_unique<TlmMemoryPort>(memory_socket, rc.line_bytes(), rc.mem_bits / 8);
    d.memory_port = memory_port_.get();
    checker_.emplace(*cache_, options.miss_sink);
  }
  for (const BoundTexture& t : textures)
    if (t.kind == TextureKind::Cube) rtl::check_cube(rc, t);
  driver_ = rtl::Driver::create(rc, d);
  driver_->reset();
  if (cached) {
    driver_->load_textures(textures);
    driver_->configure(samplers);
  } else {
    driver_->load(*textures[0].pyramid, options.load);
    driver_->configure(samplers[0], *textures[0].pyramid);
  }
  driver_->reset_counters();
  socket.register_nb_transport_fw(this, &TexUnitTlm::nb_transport_fw);
  SC_METHOD(on_clock);  // first edge at time 0, then one per period (next_trigger)
}

void TexUnitTlm::finish() {
  if (options_.clock_sink && !clocks_.empty()) options_.clock_sink->write(clocks_.data(), clocks_.size());
  clocks_.clear();
  if (!checker_ || !error_.empty()) return;
  try {
    checker_->compare(memory_port_->take_reads(), true);
  } catch (const std::exception& e) {
    fail(e.what());
  }
}

TexUnitTlm::~TexUnitTlm() = default;

void TexUnitTlm::fail(const std::string& message) {
  if (error_.empty()) error_ = message;
}

namespace {
// The request a transfer carries, in the model's terms.
Request request_of(const SampleTransfer& s) {
  Request q = lambda_request(s.u, s.v, s.lod);
  q.has_derivatives = s.has_derivatives != 0;
  q.deriv = {s.dudx, s.dvdx, s.dudy, s.dvdy};
  q.bias = s.bias;
  q.texture = s.texture;
  q.sampler = s.sampler;
  q.op = Op(s.op);
  q.component = s.component;
  q.layer = s.layer;
  q.ref = s.ref;
  q.w = s.w;
  q.dwdx = s.dwdx;
  q.dwdy = s.dwdy;
  return q;
}
}  // namespace

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
  if (s->texture >= textures_.size() || s->sampler >= samplers_.size() ||  // beyond the tables
      s->op > uint8_t(Op::Fetch) ||
      (s->op != uint8_t(Op::Sample) && s->op != uint8_t(Op::Compare) && s->has_derivatives) ||
      s->component > 3 ||  // no such operation
      (s->op == uint8_t(Op::Compare) &&  // a compare the sampler or the texture cannot take
       (!samplers_[s->sampler].compare_problem().empty() || !textures_[s->texture].pyramid->depth_problem().empty()))) {
    trans.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return nullptr;
  }
  if (backend_ == Backend::Rtl && ((!s->has_derivatives && (s->lod < kLodMin || s->lod > kLodMax)) ||
                                   s->bias < kLodMin || s->bias > kLodMax)) {  // the 16-bit req_lod, req_bias ports
    trans.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return nullptr;
  }
  return s;
}

// ------------------------------------------------------------------------------ model backend

void TexUnitTlm::b_transport(tlm_generic_payload& trans, sc_time& delay) {
  SampleTransfer* s = decode(trans);
  if (!s) return;
  const Request q = request_of(*s);
  if (cache_) {  // the sample's missing lines come over the bus first
    misses_.clear();
    cache_->lookup_sample(q, &misses_);
    for (uint32_t a : misses_) read_line(a, delay);
    if (options_.miss_sink && !misses_.empty()) options_.miss_sink->write(misses_.data(), misses_.size());
    if (!error_.empty()) {
      trans.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
      return;
    }
  }
  const Texel t = model_samplers_->at(q).sample(q);
  for (int c = 0; c < 4; ++c) s->rgba[c] = t[size_t(c)];
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
  delay += period_;  // pipelined: one sample per clock
}

void TexUnitTlm::read_line(uint32_t address, sc_time& delay) {
  tlm_generic_payload& t = line_trans_;
  t.set_command(tlm::TLM_READ_COMMAND);
  t.set_address(address);
  t.set_data_ptr(line_data_.data());
  t.set_data_length(unsigned(line_data_.size()));
  t.set_streaming_width(unsigned(line_data_.size()));
  t.set_byte_enable_ptr(nullptr);
  t.set_dmi_allowed(false);
  t.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  memory_socket->b_transport(t, delay);
  if (t.get_response_status() != tlm::TLM_OK_RESPONSE)
    return fail("memory socket: the read of line " + rtl::hex_address(address) + " was answered with " +
                t.get_response_string());
  // The texture whose layout holds the line: its view and its samplers get the line's texels, as
  // the RTL's taps see them (blocks decoded by decode_line; sRGB codes to linear unorm16, A x 257).
  const std::array<uint16_t, 256>& srgb = srgb_decode_table();
  for (size_t t = 0; t < descriptors_.size(); ++t) {
    const bool is_srgb = textures_[t].pyramid->srgb, cube = textures_[t].kind == TextureKind::Cube;
    const bool mine = decode_line(descriptors_[t].layout, address, line_data_.data(),
                                  [&](int layer, int level, int x, int y, const Texel& code) {
      if (cube) return;  // (sampled as loaded)
      Texel texel = code;
      if (is_srgb) {
        for (size_t c = 0; c < 3; ++c) texel[c] = srgb[code[c] & 255];
        texel[3] = uint16_t(code[3] * 257);
      }
      views_[t][size_t(layer)].levels[size_t(level)].at(x, y) = texel;
      model_samplers_->write_texel(int(t), level, x, y, texel, layer);
    }, true, is_srgb);  // a repeat seam's copy as its original: the taps may read the copy's line alone
    if (mine) return;
  }
  fail("memory socket: line " + rtl::hex_address(address) + " is in no texture of the descriptor table");
}


// Texels of the memory view, 8 bytes each along a row (sample_payload.h).
unsigned int TexUnitTlm::transport_dbg(tlm_generic_payload& trans) {
  const uint64_t a = trans.get_address();
  const unsigned n = trans.get_data_length() / 8;
  if (trans.get_command() != tlm::TLM_READ_COMMAND || (a & ~((uint64_t(1) << 48) - 1)) != kTexelDebugBase ||
      !trans.get_data_ptr() || n == 0)
    return 0;
  const int level = int(a >> 40 & 0xFF);
  const uint32_t y = uint32_t(a >> 20 & 0xFFFFF), x0 = uint32_t(a & 0xFFFFF);
  const Pyramid& pyramid = *textures_[0].pyramid;
  if (level >= int(pyramid.levels.size())) return 0;
  if (!descriptors_.empty() && is_compressed(pyramid.format)) return 0;  // memory holds blocks, not texels
  const Image& shape = pyramid.levels[size_t(level)];
  if (y >= uint32_t(shape.height) || x0 + n > uint32_t(shape.width)) return 0;
  auto* out = reinterpret_cast<uint16_t*>(trans.get_data_ptr());
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t x = x0 + i;
    Texel t{};
    if (!descriptors_.empty()) {  // through the memory target's own debug transport
      const MemoryLayout& layout = descriptors_[0].layout;
      std::vector<uint8_t> bytes(size_t(layout.texel_bytes()));
      tlm_generic_payload d;
      d.set_command(tlm::TLM_READ_COMMAND);
      d.set_address(layout.line_address(level, x, y) + layout.texel_offset(x, y));
      d.set_data_ptr(bytes.data());
      d.set_data_length(unsigned(bytes.size()));
      if (memory_socket.size() == 0 || memory_socket->transport_dbg(d) != bytes.size()) return i * 8;
      for (size_t c = 0; c < 4; ++c)
        t[c] = bytes.size() == 4 ? bytes[c] : uint16_t(bytes[2 * c] | bytes[2 * c + 1] << 8);
    } else if (driver_) {
      t = driver_->peek_texel(level, int(x), int(y));
    } else {
      t = shape.at(int(x), int(y));
    }
    for (int c = 0; c < 4; ++c) out[4 * i + uint32_t(c)] = t[size_t(c)];
  }
  return n * 8;
}

// ------------------------------------------------------------------------------ RTL backend

tlm_sync_enum TexUnitTlm::nb_transport_fw(tlm_generic_payload& trans, tlm_phase& phase, sc_time& delay) {
  (void)delay;  // a request or END_RESP takes effect at the next clock edge
  if (phase == tlm::BEGIN_REQ) {
    // A malformed request completes at once with its error status; it never reaches the RTL.
    const SampleTransfer* s = decode(trans);
    if (!s) return tlm::TLM_COMPLETED;
    if (pending_) fail("TLM protocol: BEGIN_REQ before END_REQ of the previous request (request exclusion rule)");
    pending_ = &trans;
    pending_request_ = request_of(*s);  // offered on the request pins from the next edge until the RTL takes it
    if (checker_) checker_->predict(pending_request_);
    return tlm::TLM_ACCEPTED;
  }
  if (phase == tlm::END_RESP) {
    if (&trans != awaiting_end_resp_) fail("TLM protocol: END_RESP for a transaction with no response open");
    awaiting_end_resp_ = nullptr;
    send_queued_responses();
    return tlm::TLM_COMPLETED;
  }
  fail("TLM protocol: the target got phase " + std::string(phase.get_name()) + " on the forward path");
  return tlm::TLM_COMPLETED;
}

void TexUnitTlm::on_clock() {
  next_trigger(period_);
  if (!error_.empty()) return;
  // Take a response from the RTL only when it can go straight onto the socket.
  const bool take = awaiting_end_resp_ == nullptr && to_respond_.empty();
  rtl::Driver::Clock c;
  try {
    c = driver_->clock(pending_ ? &pending_request_ : nullptr, take);
    if (memory_port_) {
      if (!memory_port_->error().empty()) return fail(memory_port_->error());
      checker_->compare(memory_port_->take_reads(), false);
    }
    // rsp_error against the model: exact with a planned error (--mem-error-at) or while every
    // line came back OK; a target's own error answers cannot be predicted.
    if (c.responded && checker_ && (!options_.mem_error_reads.empty() || memory_port_->error_lines() == 0))
      checker_->check_error(c.response_index, c.error);
  } catch (const std::exception& e) {  // scoreboard, time-out, RTL assertion, a read not predicted
    fail(e.what());
    return;
  }
  if (c.responded) {
    if (options_.clock_sink) {  // --response-clocks: the handshake's clock, from the first request offered
      clocks_.push_back(driver_->counters().last_response_clock());
      if (clocks_.size() == 4096) {
        options_.clock_sink->write(clocks_.data(), clocks_.size());
        clocks_.clear();
      }
    }
    tlm_generic_payload* t = in_flight_.front();
    in_flight_.pop_front();
    auto* s = reinterpret_cast<SampleTransfer*>(t->get_data_ptr());
    const Texel texel = rtl::unpack_rgba(c.rgba, driver_->config().cw);
    for (int ch = 0; ch < 4; ++ch) s->rgba[ch] = texel[size_t(ch)];
    // rsp_error: a line the sample read came from memory with an error (its rgba is 0).
    t->set_response_status(c.error ? tlm::TLM_GENERIC_ERROR_RESPONSE : tlm::TLM_OK_RESPONSE);
    to_respond_.push_back(t);
    send_queued_responses();
  }
  if (c.accepted) {
    tlm_generic_payload* t = pending_;
    pending_ = nullptr;  // free before END_REQ: the initiator may send the next BEGIN_REQ at once
    in_flight_.push_back(t);
    tlm_phase phase = tlm::END_REQ;
    sc_time delay = SC_ZERO_TIME;
    if (socket->nb_transport_bw(*t, phase, delay) != tlm::TLM_ACCEPTED)
      fail("TLM protocol: the initiator did not return TLM_ACCEPTED for END_REQ");
  }
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

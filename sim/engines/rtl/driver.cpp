#include "engines/rtl/driver.h"

#include <algorithm>
#include <cstdio>

#include "model/error.h"
#include "model/block_formats.h"
#include "model/formats.h"

namespace tex::rtl {

void set_request_pins(PinsIn& in, const Request& r) {
  in.req_u = r.u;
  in.req_v = r.v;
  in.req_lod = int16_t(r.lod);
  in.req_bias = int16_t(r.bias);
  in.req_deriv = r.has_derivatives;
  in.req_dudx = r.deriv.dudx;
  in.req_dvdx = r.deriv.dvdx;
  in.req_dudy = r.deriv.dudy;
  in.req_dvdy = r.deriv.dvdy;
  in.req_w = r.w;
  in.req_dwdx = r.dwdx;
  in.req_dwdy = r.dwdy;
  in.req_tex = r.texture;
  in.req_sampler = r.sampler;
  in.req_op = uint8_t(r.op);
  in.req_component = r.component & 3;
  in.req_layer = r.layer;
  in.req_ref = r.ref;
}

CfgPins cfg_pins(const SamplerConfig& config, const Pyramid& pyramid) {
  CfgPins c;
  c.w = uint16_t(pyramid.extent0().w);
  c.h = uint16_t(pyramid.extent0().h);
  c.last_level = uint8_t(pyramid.last_level());
  c.sampler = sampler_pins(config);
  return c;
}

SamplerPins sampler_pins(const SamplerConfig& config, uint8_t index) {
  SamplerPins c;
  c.index = index;
  c.wrap_u = uint8_t(config.wrap_u);
  c.wrap_v = uint8_t(config.wrap_v);
  c.min_linear = config.filter.texel == TexelFilter::Linear;
  c.mag_linear = config.filter.mag == TexelFilter::Linear;
  c.mip_mode = uint8_t(config.filter.mip);
  c.lod_bias = int16_t(config.lod_bias);
  c.min_lod = int16_t(config.min_lod);
  c.max_lod = int16_t(config.max_lod);
  c.max_aniso_m1 = uint8_t(config.probe_cap() - 1);
  c.aniso_pow2 = config.aniso_pow2;
  c.unnormalized = config.unnormalized;
  c.reduction = uint8_t(config.reduction);
  c.compare_op = uint8_t(config.compare_op);
  const Texel b = config.border_unorm16();
  c.border_rgba = uint64_t(b[0]) | uint64_t(b[1]) << 16 | uint64_t(b[2]) << 32 | uint64_t(b[3]) << 48;
  return c;
}

uint64_t pack_rgba(const Texel& t, int cw) {
  const uint64_t mask = (uint64_t(1) << cw) - 1;
  uint64_t p = 0;
  for (int c = 3; c >= 0; --c) p = p << cw | (t[size_t(c)] & mask);
  return p;
}

Texel unpack_rgba(uint64_t p, int cw) {
  const uint64_t mask = (uint64_t(1) << cw) - 1;
  Texel t;
  for (size_t c = 0; c < 4; ++c) t[c] = uint16_t((p >> (int(c) * cw)) & mask);
  return t;
}

// ---------------------------------------------------------------- driver

Driver::Driver(const RtlConfig& config, const DriverOptions& options) : config_(config), options_(options) {
  tracing_ = !options_.trace_path.empty();
}

Driver::~Driver() = default;

void Driver::close_trace() {
  if (!tracing_) return;
  close_trace_impl();
  tracing_ = false;
}

PinsOut Driver::tick_full(const PinsIn& in) {
  // Past the window: close now, so the file is complete even if the run is killed later.
  if (tracing_ && options_.trace_end != 0 && cycle_ > options_.trace_end) close_trace();
  if (!port_) {
    const PinsOut out = tick_pins(in, tracing_ && cycle_ >= options_.trace_begin);
    if (out.finished) fail_finished();
    ++cycle_;
    return out;
  }
  PinsIn pins = in;
  pins.ar_ready = port_->request_ready();
  pins.r_valid = port_->response_valid();
  pins.r_data = port_->response_beat();
  pins.r_resp = port_->response_error() ? 2 : 0;  // SLVERR
  pins.r_last = port_->response_last();
  const PinsOut out = tick_pins(pins, tracing_ && cycle_ >= options_.trace_begin);
  if (out.finished) fail_finished();
  // (In reset the unit ignores its memory port, and the memory model is emptied by reset().)
  if (!pins.rst) {
    const bool request = out.ar_valid && pins.ar_ready;
    if (out.ar_valid) check_burst(out);
    port_->clock(request, out.ar_addr, pins.r_valid && out.r_ready);
    memory_counters_.lines_read += request;
    memory_counters_.fifo_max = std::max(memory_counters_.fifo_max, out.fifo_count);
    memory_counters_.head_wait_cycles += out.head_waits;
  }
  ++cycle_;
  return out;
}

void Driver::check_burst(const PinsOut& out) const {
  const int beat_bytes = config_.mem_bits / 8, beats = config_.line_bytes() / beat_bytes;
  int log2_beat = 0;
  while ((1 << log2_beat) < beat_bytes) ++log2_beat;
  if (out.ar_len != beats - 1 || out.ar_size != log2_beat || out.ar_burst != 1)
    throw SimulationError("RTL AXI read of " + hex_address(out.ar_addr) + " at clock " + std::to_string(cycle_) +
                          ": ARLEN " + std::to_string(out.ar_len) + ", ARSIZE " + std::to_string(out.ar_size) +
                          ", ARBURST " + std::to_string(out.ar_burst) + "; a line is one INCR burst (ARBURST 1) of " +
                          std::to_string(beats) + " beats (ARLEN " + std::to_string(beats - 1) + ") of " +
                          std::to_string(beat_bytes) + " bytes (ARSIZE " + std::to_string(log2_beat) + ")");
}

void Driver::fail_finished() {
  close_trace();
  throw SimulationError("RTL assertion failed (or $finish) at clock " + std::to_string(cycle_) + " of " + config_.name +
              "; see the %Error line above");
}

void Driver::reset(int clocks) {
  PinsIn in;
  in.rst = true;
  in.rsp_ready = false;
  for (int i = 0; i < clocks; ++i) tick(in);
  tick(PinsIn{});
  if (port_) port_->reset();
  issued_ = answered_ = 0;
  idle_ready_clocks_ = stall_run_ = 0;
  filled_ = false;
}

void Driver::configure(const CfgPins& cfg) {
  cfg_ = cfg;
  apply_cfg(cfg);
  if (!config_.cached) return;
  samplers_ = {cfg.sampler};
  samplers_[0].index = 0;
  reset();  // the caches start empty under the new configuration
  write_tables();
}

void Driver::configure(const SamplerTable& samplers) {
  if (!config_.cached) throw Error(config_.name + " has one sampler (the on-chip unit's cfg pins), no sampler table");
  if (samplers.empty() || samplers.size() > size_t(config_.samplers))
    throw Error(std::to_string(samplers.size()) + " samplers: " + config_.name + "'s sampler table holds 1 to " +
                std::to_string(config_.samplers));
  samplers_.clear();
  for (size_t i = 0; i < samplers.size(); ++i) samplers_.push_back(sampler_pins(samplers[i], uint8_t(i)));
  reset();
  write_tables();
}

void Driver::write_tables() {
  // A descriptor write waits for cfg_desc_ready (the unit sets each entry up, tex_desc_table).
  auto desc_ready = [&] {
    for (int i = 0; i < 64; ++i)
      if (tick(PinsIn{}).desc_ready) return;
    throw SimulationError(config_.name + ": cfg_desc_ready stayed low for 64 clocks after a descriptor write");
  };
  for (const DescriptorPins& d : descriptors_) {
    apply_descriptor(d, true);
    tick(PinsIn{});
    apply_descriptor(d, false);
    desc_ready();
  }
  for (const SamplerPins& s : samplers_) {
    apply_sampler(s, true);
    tick(PinsIn{});
    apply_sampler(s, false);
  }
  tick(PinsIn{});  // the last write lands in its table; requests may follow
}

void Driver::load_textures(const TextureTable& textures) {
  for (const BoundTexture& t : textures)
    if (t.kind == TextureKind::Cube) check_cube(config_, t);
  if (!config_.cached) {
    if (textures.size() != 1)
      throw Error(config_.name + " holds one texture (the on-chip unit); the table has " + std::to_string(textures.size()));
    load(*textures[0].pyramid, LoadMethod::Backdoor);
    return;
  }
  if (textures.size() > size_t(config_.textures))
    throw Error(std::to_string(textures.size()) + " textures: " + config_.name + "'s descriptor table holds " +
                std::to_string(config_.textures));
  for (const BoundTexture& t : textures) check_inputs(config_, *t.pyramid, {});
  const CachePins pins = cache_pins(config_, options_.layout, options_.cache, options_.fifo_depth);
  EngineOptions eo;
  eo.layout = options_.layout;
  const std::vector<TextureDescriptor> table = texture_descriptors(textures, eo);
  std::vector<uint8_t> image = frame_memory_image(textures, table);
  descriptors_.clear();
  for (size_t i = 0; i < textures.size(); ++i) {
    const MemoryLayout& layout = table[i].layout;
    descriptors_.push_back({uint8_t(i), layout.params().base, uint16_t(layout.size0().w),
                            uint16_t(layout.size0().h), uint8_t(layout.levels() - 1), uint8_t(layout.format()),
                            textures[i].pyramid->srgb, uint8_t(layout.layers() - 1),
                            layout.kind() == TextureKind::Cube});
  }
  if (options_.memory_port) {
    port_ = options_.memory_port;
  } else {
    memory_ = std::make_unique<MemoryModel>(std::move(image), options_.layout.base, config_.line_bytes(),
                                            config_.mem_bits / 8, options_.memory);
    memory_->set_error_reads(options_.mem_error_reads);
    port_ = memory_.get();
  }
  apply_cache_pins(pins);
  reset();
  write_tables();
}

void Driver::reset_counters() {
  counters_ = {};
  memory_counters_ = {};
  filled_ = false;  // a new stream fills the pipeline again
  stall_run_ = 0;
}

// The word layout of tex_level_mem (as load() writes it): bank = parity, word (y >> 1) * stride + (x >> 1).
Texel Driver::peek_texel(int level, int x, int y) const {
  if (config_.cached) throw Error(config_.name + " has no level memories: its texels are in external memory");
  const int xb = std::max(config_.max_log2_w - level, 0);
  const uint32_t stride = xb > 1 ? 1u << (xb - 1) : 1u;
  return unpack_rgba(backdoor_read(level, (y & 1) * 2 + (x & 1), uint32_t(y >> 1) * stride + uint32_t(x >> 1)),
                     config_.cw);
}

namespace {
// Every texel a level memory holds: the level's, and on a side that is not a power of two the
// repeat seam's copies of column (row) 0 at index w (h) (docs/numerics.md stage 3).
template <class Fn>
void each_stored_texel(const Image& img, Fn&& fn) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      with_seam_copies(x, y, seam_copy(img.width), seam_copy(img.height),
                       [&](int sx, int sy) { fn(sx, sy, img.at(x, y)); });
}
}  // namespace

void Driver::load(const Pyramid& pyramid, LoadMethod method) {
  check_inputs(config_, pyramid, {});
  const int cw = config_.cw;
  if (config_.cached) {
    // The pyramid's memory image goes straight into the memory model (0 clocks); the caches
    // start empty (cache pins, then a reset).
    if (method == LoadMethod::Port)
      throw Error(config_.name + " has no texture write port: a cached unit reads its texture from memory "
                  "(use --load backdoor)");
    load_textures({{&pyramid}});
    return;
  }
  if (method == LoadMethod::Backdoor) {
    // The layout of tex_level_mem: bank = parity (y & 1) * 2 + (x & 1), word (y >> 1) * stride +
    // (x >> 1) with the stride of the largest level this memory can hold.
    for (size_t k = 0; k < pyramid.levels.size(); ++k) {
      const int xb = std::max(config_.max_log2_w - int(k), 0);
      const uint32_t stride = xb > 1 ? 1u << (xb - 1) : 1u;
      each_stored_texel(pyramid.levels[k], [&](int x, int y, const Texel& t) {
        backdoor_write(int(k), (y & 1) * 2 + (x & 1), uint32_t(y >> 1) * stride + uint32_t(x >> 1), pack_rgba(t, cw));
      });
    }
    return;
  }
  PinsIn in;
  in.wr_en = true;
  in.rsp_ready = false;
  const uint64_t start = cycle_;
  for (size_t k = 0; k < pyramid.levels.size(); ++k) {
    const Image& img = pyramid.levels[k];
    in.wr_level = uint8_t(k);
    each_stored_texel(img, [&](int x, int y, const Texel& t) {
      in.wr_x = uint16_t(x);
      in.wr_y = uint16_t(y);
      in.wr_data = pack_rgba(t, cw);
      tick(in);
    });
  }
  tick(PinsIn{});  // the last write lands; requests may follow
  load_cycles_ += cycle_ - start;
}

Driver::Clock Driver::clock(const Request* offer, bool take_response) {
  PinsIn& in = pins_;
  in.req_valid = offer != nullptr;
  if (offer) {
    set_request_pins(in, *offer);
    in.req_tag = uint16_t(issued_ & kTagMask);
    if (!counters_.any_offer) {
      counters_.any_offer = true;
      counters_.first_offer_cycle = cycle_;
    }
  }
  in.rsp_ready = take_response;
  const uint64_t now = cycle_;
  const PinsOut out = tick(in);

  Clock c;
  if (out.rsp_valid && take_response) {
    if (answered_ == issued_)
      throw SimulationError("RTL response with tag " + std::to_string(out.rsp_tag) + " at clock " + std::to_string(now) +
                  " while no request is in flight (" + std::to_string(answered_) +
                  " answered): duplicated or spurious response");
    const uint32_t want = uint32_t(answered_ & kTagMask);
    if (out.rsp_tag != want)
      throw SimulationError("RTL response at clock " + std::to_string(now) + " has tag " + std::to_string(out.rsp_tag) +
                  ", expected tag " + std::to_string(want) + " (request #" + std::to_string(answered_) +
                  "): a response was lost, duplicated or reordered");
    const uint64_t latency = now - accept_clock_[answered_ % kRing];
    counters_.latency_min = counters_.samples == 0 ? latency : std::min(counters_.latency_min, latency);
    counters_.latency_max = std::max(counters_.latency_max, latency);
    ++counters_.responses_by_stall_run[stall_run_ == 0 ? 0 : stall_run_ < 10 ? 1 : stall_run_ < 100 ? 2 : 3];
    ++counters_.samples;
    counters_.last_response_cycle = now;
    stall_run_ = 0;
    filled_ = true;
    idle_ready_clocks_ = 0;
    c.responded = true;
    c.response_index = answered_++;
    c.rgba = out.rsp_rgba;
    c.error = last_error_ = out.rsp_error;
  } else if (take_response && answered_ < issued_) {
    if (filled_) ++counters_.bubbles_after_fill;
    if (++idle_ready_clocks_ > options_.timeout_cycles)
      throw SimulationError("RTL time-out: no response for tag " + std::to_string(answered_ & kTagMask) + " (request #" +
                  std::to_string(answered_) + ", accepted at clock " +
                  std::to_string(accept_clock_[answered_ % kRing]) + ") after " +
                  std::to_string(options_.timeout_cycles) + " ready clocks, at clock " + std::to_string(now));
  } else if (offer && !out.req_ready && answered_ == issued_) {
    if (++idle_ready_clocks_ > options_.timeout_cycles)
      throw SimulationError("RTL time-out: req_ready stays low with nothing in flight; request #" + std::to_string(issued_) +
                  " (tag " + std::to_string(issued_ & kTagMask) + ") not accepted by clock " + std::to_string(now));
  }
  if (offer) {
    if (out.req_ready) {
      if (issued_ - answered_ >= kRing)
        throw SimulationError("RTL accepted " + std::to_string(kRing) + " requests without answering the oldest (tag " +
                    std::to_string(answered_ & kTagMask) + ") by clock " + std::to_string(now));
      accept_clock_[issued_ % kRing] = now;
      c.accepted = true;
      c.accepted_index = issued_++;
      idle_ready_clocks_ = 0;
    } else {
      ++counters_.backpressure_cycles;
    }
  }
  if (out.rsp_valid && !take_response) {
    ++counters_.output_stall_cycles;
    ++stall_run_;
  }
  if (take_response) ++counters_.ready_cycles;
  return c;
}

// ---------------------------------------------------------------- stimulus

StreamStats stream(Driver& driver, RequestSource& source, const Timing& timing, uint64_t seed,
                   const ResponseFn& on_response, const std::function<void(size_t)>& progress) {
  StreamStats st;
  driver.reset_counters();
  const uint64_t base = driver.issued();  // sequence numbers continue across streams until a reset
  RequestQueue queue(source);
  size_t accepted = 0, done = 0;
  StimulusClock stimulus(timing, seed);
  for (;;) {
    const Request* next = queue.peek();
    if (!next && done == accepted) break;
    bool offer = next != nullptr, ready = true;
    if (!timing.ideal()) stimulus.begin(next != nullptr, offer, ready);  // (ideal: no draws)
    const Driver::Clock c = driver.clock(offer ? next : nullptr, ready);
    if (c.responded) {
      on_response(size_t(c.response_index - base), c.rgba);
      if (c.error) st.error_responses.push_back(c.response_index - base);
      if ((++done & 0xFFFF) == 0 && progress) progress(done);
    }
    if (!timing.ideal()) stimulus.end(c.accepted);
    if (c.accepted) {
      queue.pop();
      ++accepted;
    }
  }
  st.gap_cycles = stimulus.gap_cycles;
  st.requests_after_gap = stimulus.requests_after_gap;
  st.protocol = driver.counters();
  st.memory = driver.memory_counters();

  // A few idle clocks: anything that still comes out is a duplicate.
  for (int i = 0; i < 64; ++i) {
    const uint64_t now = driver.cycle();
    const PinsOut out = driver.tick(PinsIn{});
    if (out.rsp_valid)
      throw SimulationError("RTL response with tag " + std::to_string(out.rsp_tag) + " at clock " + std::to_string(now) +
                  " after all " + std::to_string(done) + " requests were answered: duplicated or spurious response");
  }
  return st;
}

StreamStats stream(Driver& driver, const Request* requests, size_t n, const Timing& timing, uint64_t seed,
                   const ResponseFn& on_response, const std::function<void(size_t)>& progress) {
  VectorSource source(requests, n);
  return stream(driver, source, timing, seed, on_response, progress);
}

}  // namespace tex::rtl

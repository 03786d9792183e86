#include "rtl_harness.h"

#include <algorithm>
#include <csignal>
#include <cstdio>

#include "model/error.h"

namespace tex::rtl {

namespace {

// Ctrl-C while a trace is open: the next clock closes the trace, then the process ends as Ctrl-C
// would. Only a flag is set in the handler (async-signal-safe).
volatile std::sig_atomic_t g_sigint = 0;
int g_handlers_installed = 0;
struct sigaction g_previous_sigint;

void on_sigint(int) { g_sigint = 1; }

void install_sigint_handler() {
  if (g_handlers_installed++ > 0) return;
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_previous_sigint);
}

void remove_sigint_handler() {
  if (--g_handlers_installed == 0) sigaction(SIGINT, &g_previous_sigint, nullptr);
}

// Uniform double in [0, 1) from 53 random bits.
inline double unit(std::mt19937_64& rng) { return double(rng() >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace

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

const RtlShape& smallest_shape_for(int log2_w, int log2_h) {
  const RtlShape* big = nullptr;
  for (const RtlShape& s : compiled_shapes()) {  // smallest first
    if (s.cw != 8) continue;
    if (s.fits(log2_w, log2_h)) return s;
    big = &s;
  }
  throw Error("texture " + std::to_string(1 << log2_w) + "x" + std::to_string(1 << log2_h) +
              " does not fit the RTL: the largest compiled tex_unit takes " + std::to_string(1 << big->max_log2_w) +
              "x" + std::to_string(1 << big->max_log2_h) + " (use --engine model for larger textures)");
}

CfgPins cfg_pins(const SamplerConfig& config, int log2_w, int log2_h) {
  CfgPins c;
  c.log2_w = uint8_t(log2_w);
  c.log2_h = uint8_t(log2_h);
  c.wrap_u = uint8_t(config.wrap_u);
  c.wrap_v = uint8_t(config.wrap_v);
  c.texel_linear = config.filter.texel == TexelFilter::Linear;
  c.mip_mode = uint8_t(config.filter.mip);
  c.lod_bias = int16_t(config.lod_bias);
  c.min_lod = int16_t(config.min_lod);
  c.max_lod = int16_t(config.max_lod);
  return c;
}

Timing Timing::random_default() {
  Timing t;
  t.gap_prob = 0.05;
  t.max_gap = 4;
  t.stall_prob = 0.05;
  t.max_stall = 8;
  t.long_stall_prob = 0.0005;
  t.long_stall = 200;
  return t;
}

Harness::Harness(const RtlShape& shape, const HarnessOptions& options) : shape_(shape), options_(options) {
  tracing_ = !options_.trace_path.empty();
  if (tracing_) install_sigint_handler();
}

Harness::~Harness() {
  if (tracing_) remove_sigint_handler();
}

void Harness::close_trace() {
  if (!tracing_) return;
  close_trace_impl();
  remove_sigint_handler();
  tracing_ = false;
}

PinsOut Harness::tick(const PinsIn& in) {
  if (tracing_) {
    if (g_sigint) {
      close_trace();
      std::fprintf(stderr, "\ninterrupted at clock %llu; FST trace closed: %s\n", (unsigned long long)cycle_,
                   options_.trace_path.c_str());
      std::signal(SIGINT, SIG_DFL);
      std::raise(SIGINT);
    }
    // Past the window: close now, so the file is complete even if the run is killed later.
    if (options_.trace_end != 0 && cycle_ > options_.trace_end) close_trace();
  }
  const bool dump = tracing_ && cycle_ >= options_.trace_begin;
  const PinsOut out = tick_pins(in, dump);
  if (got_finish()) {
    close_trace();
    throw Error("RTL assertion failed (or $finish) at clock " + std::to_string(cycle_) +
                " of " + shape_.name + "; see the %Error line above" +
                (options_.trace_path.empty() ? std::string() : "; FST trace closed: " + options_.trace_path));
  }
  ++cycle_;
  return out;
}

void Harness::reset(int cycles) {
  PinsIn in;
  in.rst = true;
  for (int i = 0; i < cycles; ++i) tick(in);
  in.rst = false;
  tick(in);
}

void Harness::configure(const CfgPins& cfg) {
  cfg_ = cfg;
  apply_cfg(cfg);
}

void Harness::load(const Pyramid& pyramid) {
  const int lw = pyramid.log2_w0(), lh = pyramid.log2_h0();
  if (!shape_.fits(lw, lh))
    throw Error("texture " + std::to_string(1 << lw) + "x" + std::to_string(1 << lh) + " does not fit " + shape_.name);
  if (pyramid.levels[0].channel_bits != shape_.cw)
    throw Error(shape_.name + " is built for " + std::to_string(shape_.cw) + "-bit channels; this texture has " +
                std::to_string(pyramid.levels[0].channel_bits));
  PinsIn in;
  in.wr_en = true;
  const uint64_t start = cycle_;
  for (size_t k = 0; k < pyramid.levels.size(); ++k) {
    const Image& img = pyramid.levels[k];
    in.wr_level = uint8_t(k);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        in.wr_x = uint16_t(x);
        in.wr_y = uint16_t(y);
        in.wr_data = pack_rgba(img.at(x, y), shape_.cw);
        tick(in);
      }
  }
  load_cycles_ += cycle_ - start;
}

StreamStats Harness::stream(const Request* requests, size_t n, const Timing& timing, uint64_t seed,
                            const ResponseFn& on_response, const std::function<void(size_t)>& progress) {
  StreamStats st;
  std::mt19937_64 rng(seed);
  std::vector<uint64_t> accept_clock(n);
  size_t accepted = 0, done = 0;
  int gap_left = 0, stall_left = 0;
  // Clocks with rsp_ready high and no response while one is owed; long stalls do not count.
  const uint64_t timeout = options_.timeout_cycles ? options_.timeout_cycles : 10000;
  uint64_t idle_ready_clocks = 0;
  const uint64_t start = cycle_;
  bool filled = false;
  bool holding = false;  // a request was offered and not taken in the previous clock
  uint64_t stall_run = 0;   // clocks the oldest response has waited with rsp_ready low
  bool after_gap = false;   // the next request follows an input gap
  PinsIn in;
  while (done < n) {
    // A request once offered stays offered until accepted (the RTL asserts this): gaps start
    // only between requests.
    if (gap_left == 0 && !holding && timing.gap_prob > 0 && accepted < n && unit(rng) < timing.gap_prob)
      gap_left = 1 + int(rng() % uint64_t(std::max(1, timing.max_gap)));
    if (stall_left == 0) {
      if (timing.long_stall_prob > 0 && unit(rng) < timing.long_stall_prob)
        stall_left = timing.long_stall;
      else if (timing.stall_prob > 0 && unit(rng) < timing.stall_prob)
        stall_left = 1 + int(rng() % uint64_t(std::max(1, timing.max_stall)));
    }
    const bool offer = accepted < n && gap_left == 0;
    if (gap_left > 0) {
      --gap_left;
      if (accepted < n) {
        ++st.gap_cycles;
        after_gap = true;
      }
    }
    in.rsp_ready = stall_left == 0;
    if (stall_left > 0) --stall_left;
    in.req_valid = offer;
    if (offer) {
      const Request& r = requests[accepted];
      in.req_u = r.u;
      in.req_v = r.v;
      in.req_lod = int16_t(r.lod);
      in.req_tag = uint16_t(accepted & kTagMask);
    }

    const uint64_t now = cycle_;
    const PinsOut out = tick(in);
    const size_t owed_before = accepted - done;  // responses that may legally fire at this edge

    if (out.rsp_valid && in.rsp_ready) {
      if (owed_before == 0)
        throw Error("RTL response with tag " + std::to_string(out.rsp_tag) + " at clock " + std::to_string(now) +
                    " while no request is outstanding (" + std::to_string(done) + " of " + std::to_string(n) +
                    " answered): duplicated or spurious response");
      const uint32_t want = uint32_t(done & kTagMask);
      if (out.rsp_tag != want)
        throw Error("RTL response at clock " + std::to_string(now) + " has tag " + std::to_string(out.rsp_tag) +
                    ", expected tag " + std::to_string(want) + " (request #" + std::to_string(done) +
                    "): a response was lost, duplicated or reordered");
      const uint64_t lat = now - accept_clock[done];
      st.latency_min = st.samples == 0 ? lat : std::min(st.latency_min, lat);
      st.latency_max = std::max(st.latency_max, lat);
      ++st.responses_by_stall_run[stall_run == 0 ? 0 : stall_run < 10 ? 1 : stall_run < 100 ? 2 : 3];
      stall_run = 0;
      on_response(done, out.rsp_rgba);
      ++done;
      ++st.samples;
      filled = true;
      idle_ready_clocks = 0;
      if (progress && (done & 0xFFFF) == 0) progress(done);
    } else if (in.rsp_ready && accepted > done) {
      if (filled) ++st.bubbles_after_fill;
      if (++idle_ready_clocks > timeout)
        throw Error("RTL time-out: no response for tag " + std::to_string(done & kTagMask) + " (request #" +
                    std::to_string(done) + ", accepted at clock " + std::to_string(accept_clock[done]) + ") after " +
                    std::to_string(timeout) + " ready clocks, at clock " + std::to_string(now));
    } else if (offer && !out.req_ready && accepted == done) {
      // Nothing in flight and the unit refuses requests.
      if (++idle_ready_clocks > timeout)
        throw Error("RTL time-out: req_ready stays low with nothing in flight; request #" + std::to_string(accepted) +
                    " (tag " + std::to_string(accepted & kTagMask) + ") not accepted by clock " + std::to_string(now));
    }
    holding = offer && !out.req_ready;
    if (offer && out.req_ready) {
      if (after_gap) ++st.requests_after_gap;
      after_gap = false;
      accept_clock[accepted] = now;
      ++accepted;
      idle_ready_clocks = 0;
    }
    if (offer && !out.req_ready) ++st.backpressure_cycles;
    if (out.rsp_valid && !in.rsp_ready) {
      ++st.stall_cycles;
      ++stall_run;
    }
    if (in.rsp_ready) ++st.ready_cycles;
  }
  st.cycles = cycle_ - start;

  // A few idle clocks: anything that still comes out is a duplicate.
  PinsIn idle;
  for (int i = 0; i < 64; ++i) {
    const uint64_t now = cycle_;
    const PinsOut out = tick(idle);
    if (out.rsp_valid)
      throw Error("RTL response with tag " + std::to_string(out.rsp_tag) + " at clock " + std::to_string(now) +
                  " after all " + std::to_string(n) + " requests were answered: duplicated or spurious response");
  }
  return st;
}

}  // namespace tex::rtl

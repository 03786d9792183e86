// The harness of tex_unit_axi's end-to-end suite (test_rtl_axi_top.cpp): one Verilated
// tex_unit_axi, Verilated with the parameters below (tests/rtl/CMakeLists.txt), and everything at
// its pins, no rtl::Driver: an AXI4-Lite master, the request stream (its gaps and stalls a
// tex::Stimulus, tests/common/stimulus.h), the AXI4 slave memory and the record of every clock's
// events for the counters.
#pragma once
#include <verilated.h>
#include <verilated_syms.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vtex_unit_axi.h"
#include "engines/rtl/register_map.h"
#include "model/sampler.h"
#include "model/timing.h"

namespace tex::axitest {

// ---- the Verilated build's parameters (tests/rtl/CMakeLists.txt)
constexpr int kMaxLog2W = 6, kMaxLog2H = 3, kBlockW = 4, kBlockH = 4, kLines = 64, kMaxWays = 4;
constexpr int kFifoDepth = 32, kMemW = 128, kTextures = 4, kSamplers = 8;
constexpr int kLineBytes = kBlockW * kBlockH * 4, kBeatBytes = kMemW / 8, kBeats = kLineBytes / kBeatBytes;

// ---- the register map: sim/engines/rtl/register_map.h (checked against the RTL)
using namespace tex::rtl::axil;
// The counters the test sees at the pins (the others: against the model).
inline bool pin_visible(int i) { return i != kLookups && i != kMisses; }
constexpr uint32_t kDecerr = 3;

inline int log2i(int v) {
  int k = 0;
  while ((1 << k) < v) ++k;
  return k;
}

inline std::string hex(uint64_t v) {
  char s[24];
  std::snprintf(s, sizeof s, "0x%llx", (unsigned long long)v);
  return s;
}

inline std::string describe(const Texel& t) {
  return "(" + std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) + "," +
         std::to_string(t[3]) + ")";
}

inline std::string describe(const Request& r) {
  std::string s = "texture " + std::to_string(r.texture) + " u=" + std::to_string(r.u) + " v=" + std::to_string(r.v);
  if (r.has_derivatives)
    s += " d=(" + std::to_string(r.deriv.dudx) + "," + std::to_string(r.deriv.dvdx) + "," +
         std::to_string(r.deriv.dudy) + "," + std::to_string(r.deriv.dvdy) + ")";
  else
    s += " lod=" + std::to_string(r.lod);
  if (r.op != Op::Sample) s += " op " + std::to_string(int(r.op)) + " component " + std::to_string(r.component);
  if (r.layer) s += " layer=" + std::to_string(r.layer);
  return s;
}

inline uint32_t pack_rgba8(const Texel& t) {
  return uint32_t(t[0] & 255) | uint32_t(t[1] & 255) << 8 | uint32_t(t[2] & 255) << 16 | uint32_t(t[3] & 255) << 24;
}
inline Texel unpack_rgba8(uint32_t p) {
  return Texel{uint16_t(p & 255), uint16_t(p >> 8 & 255), uint16_t(p >> 16 & 255), uint16_t(p >> 24)};
}

// The memory's behaviour in a case.
struct MemorySetup {
  uint32_t latency = 20, jitter = 0;  // clocks from the AR edge to the first beat (+ 0..jitter)
  double arready_p = 1.0;             // ARREADY high in a clock with this probability
  double rgap_p = 0.0;                // before a beat, a gap of 1..3 clocks with this probability
  uint32_t max_outstanding = 64;      // ARREADY low while this many bursts are open
  std::vector<uint64_t> error_reads;  // line reads (from 1, in AR order) answered with an error
};


// ---------------------------------------------------------------- the harness
// One Verilated tex_unit_axi and everything at its pins: an AXI4-Lite master (a write and a read
// queue, both channels at once, AW/W in random order, random BREADY/RREADY), the request stream,
// the AXI4 slave memory, and the record of every clock's events for the counters.
class AxiTop {
 public:
  using WriteDone = std::function<void(uint32_t bresp, uint64_t edge)>;  // edge: the write's
  using ReadDone = std::function<void(uint32_t data, uint32_t resp, uint64_t edge)>;  // edge: the AR's
  using ResponseFn = std::function<void(size_t index, uint32_t rgba, bool error)>;
  using Totals = std::array<uint64_t, kCounters>;

  explicit AxiTop(uint64_t seed) : ctx_(std::make_unique<VerilatedContext>()), rng_(seed) {
    ctx_->fatalOnError(false);  // an RTL assertion sets gotFinish: failure() reports it
    ctx_->randReset(2);         // registers without reset start random
    ctx_->randSeed(int(seed % 100000) + 1);
    top_ = std::make_unique<Vtex_unit_axi>(ctx_.get(), "tex_unit_axi");
    for (const auto& entry : *ctx_->scopeNameMap())
      if (const VerilatedVar* v = entry.second->varFind("head_waits"))
        head_waits_ = static_cast<const uint8_t*>(v->datap());
    cum_.push_back(Totals{});
    hardware_reset();
  }
  ~AxiTop() { top_->final(); }

  // rst for 4 clocks: the slave resets and holds the unit in reset. The unit's rst is the slave's
  // CONTROL.unit_reset, a register: at the first edge of rst after power-up it still holds its
  // random initial value, and so do cfg_desc_we and the staged descriptor, which tex_unit_cached's
  // simulation checks then see (cfg_desc_index beyond TEXTURES, a format it lacks, ...). Its
  // assertions are off for that one edge only; from the next one the unit is in reset.
  void hardware_reset() {
    rst_ = true;
    ctx_->assertOn(false);
    clock();
    ctx_->assertOn(true);
    for (int i = 0; i < 3; ++i) clock();
    rst_ = false;
  }

  // ---- AXI4-Lite
  double bready_p = 0.7, rready_p = 0.7;  // BREADY / RREADY high in a clock with this probability
  void queue_write(uint32_t addr, uint32_t data, WriteDone done) { wq_.push_back({addr, data, std::move(done)}); }
  void queue_read(uint32_t addr, ReadDone done) { rq_.push_back({addr, std::move(done)}); }
  bool lite_idle() const { return wq_.empty() && rq_.empty(); }
  // A write or a read alone, run to its response (~0u if none came).
  uint32_t write(uint32_t addr, uint32_t data, uint64_t* edge = nullptr) {
    bool done = false;
    uint32_t resp = ~0u;
    queue_write(addr, data, [&](uint32_t r, uint64_t e) {
      done = true;
      resp = r;
      if (edge) *edge = e;
    });
    run_until([&] { return done; }, 1000);
    return resp;
  }
  std::pair<uint32_t, uint32_t> read(uint32_t addr, uint64_t* edge = nullptr) {
    bool done = false;
    std::pair<uint32_t, uint32_t> out{~0u, ~0u};
    queue_read(addr, [&](uint32_t d, uint32_t r, uint64_t e) {
      done = true;
      out = {d, r};
      if (edge) *edge = e;
    });
    run_until([&] { return done; }, 1000);
    return out;
  }

  // ---- the memory: a new image from `base` and a new setup (the read count starts again).
  void set_memory(uint32_t base, std::vector<uint8_t> image, const MemorySetup& setup) {
    if (!bursts_.empty()) fail("set_memory with " + std::to_string(bursts_.size()) + " bursts open");
    mem_base_ = base;
    image_ = std::move(image);
    mem_ = setup;
    reads_ = 0;
    ar_log_.clear();
  }
  const std::vector<uint32_t>& ar_log() const { return ar_log_; }
  bool memory_idle() const { return bursts_.empty(); }

  // ---- the request stream: starts offering `requests` (tags = index), answers through `fn`.
  void start_stream(const std::vector<Request>& requests, const Stimulus& stim, ResponseFn fn) {
    reqs_ = &requests;
    stim_ = stim;
    on_rsp_ = std::move(fn);
    next_req_ = answered_ = 0;
    gap_ = stall_ = 0;
  }
  uint64_t first_request_edge() const { return first_req_edge_; }  // its handshake's edge
  bool stream_done() const { return !reqs_ || answered_ == reqs_->size(); }
  void end_stream() { reqs_ = nullptr; }

  // ---- clocks
  uint64_t edge() const { return edge_; }  // the index of the next clock edge
  // The sums of the events the pins showed at edges e < k (cum_[k]); index kCycles: k.
  const Totals& sums_before(uint64_t k) const { return cum_.at(size_t(k)); }
  bool head_waits_visible() const { return head_waits_ != nullptr; }
  const std::string& failure() const { return failure_; }
  void fail(const std::string& what) {
    if (failure_.empty()) failure_ = what + " (clock " + std::to_string(edge_) + ")";
  }

  void run_until(const std::function<bool()>& done, uint64_t limit) {
    for (uint64_t i = 0; !done(); ++i) {
      if (!failure_.empty()) return;
      if (i >= limit) {
        fail("time-out after " + std::to_string(limit) + " clocks");
        return;
      }
      clock();
    }
  }
  void idle(int clocks) {
    for (int i = 0; i < clocks && failure_.empty(); ++i) clock();
  }

  // One clock: every master and slave drives its pins, the handshakes are taken before the edge,
  // the state moves after it.
  void clock() {
    Vtex_unit_axi& t = *top_;
    t.rst = rst_;

    // ---- AXI4-Lite master: valids held until taken; junk payload while low
    if (!w_on_ && !wq_.empty() && !rst_) {
      w_on_ = true;
      aw_done_ = w_done_ = b_seen_ = false;
      w_order_ = int(rng_() % 3);  // 0 together, 1 AW first, 2 W first
    }
    if (!r_on_lite_ && !rq_.empty() && !rst_) {
      r_on_lite_ = true;
      ar_done_ = false;
    }
    const bool awvalid = w_on_ && !aw_done_ && (w_order_ != 2 || w_done_);
    const bool wvalid = w_on_ && !w_done_ && (w_order_ != 1 || aw_done_);
    const bool arvalid = r_on_lite_ && !ar_done_;
    t.s_axi_awvalid = awvalid;
    t.s_axi_awaddr = awvalid ? wq_.front().addr : junk() & 0xFFF;
    t.s_axi_awprot = junk() & 7;
    t.s_axi_wvalid = wvalid;
    t.s_axi_wdata = wvalid ? wq_.front().data : junk();
    t.s_axi_wstrb = wvalid ? 0xF : junk() & 15;
    t.s_axi_bready = coin(bready_p);
    t.s_axi_arvalid = arvalid;
    t.s_axi_araddr = arvalid ? rq_.front().addr : junk() & 0xFFF;
    t.s_axi_arprot = junk() & 7;
    t.s_axi_rready = coin(rready_p);

    // ---- requests: gaps between them, junk while req_valid is low
    bool req_valid = false;
    if (reqs_ && next_req_ < reqs_->size() && !rst_) {
      if (gap_ > 0) --gap_;
      else req_valid = true;
    }
    if (req_valid) {
      const Request& q = (*reqs_)[next_req_];
      t.req_u = uint32_t(q.u);
      t.req_v = uint32_t(q.v);
      t.req_lod = uint16_t(q.lod);
      t.req_bias = uint16_t(q.bias);
      t.req_deriv = q.has_derivatives;
      t.req_dudx = uint32_t(q.deriv.dudx);
      t.req_dvdx = uint32_t(q.deriv.dvdx);
      t.req_dudy = uint32_t(q.deriv.dudy);
      t.req_dvdy = uint32_t(q.deriv.dvdy);
      t.req_tex = q.texture;
      t.req_sampler = q.sampler;
      t.req_op = uint8_t(q.op);
      t.req_component = q.component;
      t.req_layer = uint32_t(q.layer);
      t.req_ref = uint32_t(q.ref);
      t.req_w = uint32_t(q.w);
      t.req_dwdx = uint32_t(q.dwdx);
      t.req_dwdy = uint32_t(q.dwdy);
      t.req_tag = uint16_t(next_req_);
    } else {
      t.req_u = junk();
      t.req_v = junk();
      t.req_lod = uint16_t(junk());
      t.req_bias = uint16_t(junk());
      t.req_deriv = junk() & 1;
      t.req_dudx = junk();
      t.req_dvdx = junk();
      t.req_dudy = junk();
      t.req_dvdy = junk();
      t.req_tex = junk() & 15;
      t.req_sampler = junk() & 15;
      t.req_op = junk() & 3;
      t.req_component = junk() & 3;
      t.req_layer = junk();
      t.req_ref = junk();
      t.req_w = junk();
      t.req_dwdx = junk();
      t.req_dwdy = junk();
      t.req_tag = uint16_t(junk());
    }
    t.req_valid = req_valid;
    // rsp_ready: stalls of 1..max_stall clocks, now and then a long one
    bool rsp_ready = !rst_;
    if (reqs_) {
      if (stall_ == 0 && coin(stim_.long_stall_prob)) stall_ = stim_.long_stall;
      if (stall_ == 0 && coin(stim_.stall_prob)) stall_ = 1 + int(rng_() % uint64_t(stim_.max_stall));
      if (stall_ > 0) {
        --stall_;
        rsp_ready = false;
      }
    }
    t.rsp_ready = rsp_ready;

    // ---- the AXI4 slave memory
    t.m_axi_arready = !rst_ && bursts_.size() < mem_.max_outstanding && coin(mem_.arready_p);
    if (!beat_on_ && !bursts_.empty() && bursts_.front().ready <= edge_) {
      if (beat_gap_ > 0) --beat_gap_;
      else if (coin(mem_.rgap_p)) beat_gap_ = int(rng_() % 3);
      else beat_on_ = true;
    }
    if (beat_on_) {
      const Burst& b = bursts_.front();
      const uint32_t at = b.addr - mem_base_ + uint32_t(b.beat * kBeatBytes);
      for (int w = 0; w < kBeatBytes / 4; ++w) {
        uint32_t word = 0;
        for (int k = 3; k >= 0; --k) {
          const size_t i = size_t(at) + size_t(4 * w + k);
          word = word << 8 | (i < image_.size() ? image_[i] : 0);
        }
        t.m_axi_rdata[size_t(w)] = word;
      }
      t.m_axi_rresp = b.resp[size_t(b.beat)];
      t.m_axi_rlast = b.beat == kBeats - 1;
      t.m_axi_rid = 0;
    } else {
      for (int w = 0; w < kBeatBytes / 4; ++w) t.m_axi_rdata[size_t(w)] = junk();
      t.m_axi_rresp = junk() & 3;
      t.m_axi_rlast = junk() & 1;
      t.m_axi_rid = junk() & 1;
    }
    t.m_axi_rvalid = beat_on_;

    t.clk = 0;
    t.eval();

    // ---- before the edge: the handshakes of this edge and the events the counters see
    const bool aw_take = awvalid && t.s_axi_awready, w_take = wvalid && t.s_axi_wready;
    const bool b_take = t.s_axi_bvalid && t.s_axi_bready;
    const bool ar_take = arvalid && t.s_axi_arready, r_take = t.s_axi_rvalid && t.s_axi_rready;
    const bool req_take = req_valid && t.req_ready, rsp_take = t.rsp_valid && rsp_ready;
    const bool mar_take = t.m_axi_arvalid && t.m_axi_arready;
    const bool beat_take = beat_on_ && t.m_axi_rready;
    if (!rst_) {
      if (t.s_axi_bvalid && !(w_on_ && (aw_done_ || aw_take) && (w_done_ || w_take)))
        fail("AXI4-Lite: BVALID without a write taken");
      if (t.s_axi_rvalid && !(r_on_lite_ && ar_done_)) fail("AXI4-Lite: RVALID without a read taken");
      if (t.rsp_valid && (!reqs_ || answered_ >= next_req_)) fail("rsp_valid with no request in flight");
    }
    if (w_on_ && t.s_axi_bvalid && !b_seen_) {  // BVALID rose at the write's edge, the last one
      b_seen_ = true;
      w_edge_ = edge_ - 1;
    }
    Totals ev{};
    ev[kCycles] = 1;
    ev[kSamples] = rsp_take;
    ev[kSampleErrors] = rsp_take && t.rsp_error;
    ev[kMemBytes] = beat_take ? kBeatBytes : 0;
    ev[kOutStall] = t.rsp_valid && !rsp_ready;
    ev[kMemWait] = head_waits_ ? *head_waits_ : 0;
    ev[kReqStall] = req_valid && !t.req_ready;
    Totals next = cum_.back();
    for (int i = 0; i < kCounters; ++i) next[size_t(i)] += ev[size_t(i)];
    cum_.push_back(next);

    if (mar_take) take_ar(t);
    const uint32_t bresp = t.s_axi_bresp, rdata = t.s_axi_rdata, rresp = t.s_axi_rresp;
    const uint32_t rgba = t.rsp_rgba, tag = t.rsp_tag;
    const bool rsp_error = t.rsp_error;

    // ---- the edge
    t.clk = 1;
    t.eval();
    const uint64_t this_edge = edge_++;
    if (ctx_->gotFinish()) fail("an RTL assertion fired (its message is on stderr)");

    // ---- after it
    if (aw_take) aw_done_ = true;
    if (w_take) w_done_ = true;
    if (ar_take) {
      ar_done_ = true;
      ar_edge_ = this_edge;
    }
    if (b_take && w_on_) {
      const WriteDone done = std::move(wq_.front().done);
      wq_.pop_front();
      w_on_ = false;
      if (done) done(bresp, w_edge_);
    }
    if (r_take && r_on_lite_) {
      const ReadDone done = std::move(rq_.front().done);
      rq_.pop_front();
      r_on_lite_ = false;
      if (done) done(rdata, rresp, ar_edge_);
    }
    if (req_take) {
      if (next_req_ == 0) first_req_edge_ = this_edge;
      ++next_req_;
      if (coin(stim_.gap_prob)) gap_ = 1 + int(rng_() % uint64_t(stim_.max_gap));
    }
    if (rsp_take && reqs_) {
      const size_t i = answered_++;
      if (tag != (i & 0xFFFF)) fail("response " + std::to_string(i) + " has tag " + std::to_string(tag));
      if (on_rsp_) on_rsp_(i, rgba, rsp_error);
    }
    if (beat_take) {
      beat_on_ = false;
      if (++bursts_.front().beat == kBeats) bursts_.pop_front();
    }
  }

 private:
  struct LiteWrite {
    uint32_t addr, data;
    WriteDone done;
  };
  struct LiteRead {
    uint32_t addr;
    ReadDone done;
  };
  struct Burst {
    uint32_t addr = 0;
    uint64_t ready = 0;  // the first clock its first beat may come
    int beat = 0;        // beats taken
    std::array<uint8_t, kBeats> resp{};
  };

  bool coin(double p) { return p > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  uint32_t junk() { return uint32_t(rng_()); }

  // An AR taken at this edge: its fields, its place in the image, its beats' responses.
  void take_ar(const Vtex_unit_axi& t) {
    const uint32_t addr = t.m_axi_araddr;
    if (t.m_axi_arlen != kBeats - 1 || t.m_axi_arsize != log2i(kBeatBytes) || t.m_axi_arburst != 1)
      fail("AR " + hex(addr) + ": ARLEN " + std::to_string(t.m_axi_arlen) + " ARSIZE " +
           std::to_string(t.m_axi_arsize) + " ARBURST " + std::to_string(t.m_axi_arburst) + ", want " +
           std::to_string(kBeats - 1) + ", " + std::to_string(log2i(kBeatBytes)) + ", 1 (INCR)");
    if (t.m_axi_arid != 0 || t.m_axi_arcache != 3 || t.m_axi_arprot != 0)
      fail("AR " + hex(addr) + ": ARID " + std::to_string(t.m_axi_arid) + " ARCACHE " +
           std::to_string(t.m_axi_arcache) + " ARPROT " + std::to_string(t.m_axi_arprot));
    if (addr % kLineBytes != 0 || addr < mem_base_ || uint64_t(addr) + kLineBytes > mem_base_ + image_.size())
      fail("AR " + hex(addr) + ": not a line of the memory image");
    ar_log_.push_back(addr);
    Burst b;
    b.addr = addr;
    b.ready = edge_ + mem_.latency + (mem_.jitter ? rng_() % (mem_.jitter + 1) : 0);
    ++reads_;
    if (std::binary_search(mem_.error_reads.begin(), mem_.error_reads.end(), reads_)) {
      switch (rng_() % 3) {  // SLVERR on every beat, SLVERR on one, DECERR on one: the line is in error
        case 0: b.resp.fill(uint8_t(kSlverr)); break;
        case 1: b.resp[rng_() % kBeats] = uint8_t(kSlverr); break;
        default: b.resp[rng_() % kBeats] = uint8_t(kDecerr); break;
      }
    }
    bursts_.push_back(b);
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtex_unit_axi> top_;
  std::mt19937_64 rng_;
  const uint8_t* head_waits_ = nullptr;
  bool rst_ = false;
  uint64_t edge_ = 0;
  std::vector<Totals> cum_;
  std::string failure_;
  // AXI4-Lite master
  std::deque<LiteWrite> wq_;
  std::deque<LiteRead> rq_;
  bool w_on_ = false, aw_done_ = false, w_done_ = false, b_seen_ = false, r_on_lite_ = false, ar_done_ = false;
  int w_order_ = 0;
  uint64_t w_edge_ = 0, ar_edge_ = 0;
  // requests
  const std::vector<Request>* reqs_ = nullptr;
  Stimulus stim_;
  ResponseFn on_rsp_;
  size_t next_req_ = 0, answered_ = 0;
  uint64_t first_req_edge_ = 0;
  int gap_ = 0, stall_ = 0;
  // memory
  MemorySetup mem_;
  uint32_t mem_base_ = 0;
  std::vector<uint8_t> image_;
  std::deque<Burst> bursts_;
  bool beat_on_ = false;
  int beat_gap_ = 0;
  uint64_t reads_ = 0;
  std::vector<uint32_t> ar_log_;
};

}  // namespace tex::axitest

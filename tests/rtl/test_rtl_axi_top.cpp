// tex_unit_axi (rtl/tex_unit_axi.sv) end to end, Verilated with the parameters below
// (tests/rtl/CMakeLists.txt): the test drives every pin itself, no rtl::Driver.
//
// - Programming over AXI4-Lite only (docs/rtl-interface.md, "AXI4-Lite configuration
//   (tex_unit_axi)"): the ID, VERSION and CAPS registers against the build's parameters; with the
//   unit in reset (CONTROL.unit_reset) the cache geometry, FIFO limit, filter and LOD registers;
//   then the unit released, 2 to 4 descriptors staged and committed (RGBA8 pyramids packed in
//   memory by texture_descriptors / build_memory_image), the counters cleared. Refused writes on
//   the way: DESC_COMMIT while the unit is in reset, CACHE while it runs, DESC_COMMIT of an entry
//   beyond TEXTURES, of a base off the line, of a size beyond MAX_LOG2_W (each SLVERR, the
//   register unchanged). CACHE and the release come as close as the slave allows (BREADY high at
//   once). The first case starts from the hardware reset, the others use the documented way to
//   change the geometry (unit_reset 1, CACHE, unit_reset 0, every descriptor again).
// - The test's AXI4 slave memory serves the image: random ARREADY, a latency (and jitter), random
//   gaps between beats, RLAST on each burst's last beat, SLVERR / DECERR on chosen line reads (on
//   every beat of the line or on one beat), junk on R while RVALID is low; every AR's ARLEN,
//   ARSIZE, ARBURST, ARID, ARCACHE, ARPROT and alignment checked, and the addresses against the
//   model's miss stream, in order.
// - Random requests (lambda and derivatives; textures interleaved), random req_valid gaps and
//   rsp_ready stalls, junk on the request payload while req_valid is low: every response against
//   tex::Sampler of its texture (with that texture's wrap modes) bit for bit, and its rsp_error
//   against tex::TextureCache::set_error_reads (a flagged sample answers 0).
// - The counters: read (LO then HI) while the stream runs and after a freeze at the end, each
//   against what the test saw at the pins in the exact window the register map defines (events of
//   a clock counted one clock later, from the clear's edge): CYCLES, SAMPLES, SAMPLE_ERRORS,
//   MEM_BYTES, OUT_STALL, REQ_STALL, MEM_WAIT (tex_cached_fetch's head_waits, public for the
//   harness); LOOKUPS and MISSES against the model's cache statistics, MEM_BYTES = MISSES x line.
// - Planted bugs: a descriptor committed with other wrap modes than the model's table, and a
//   model that expects the memory error one read late, are caught.
// - A descriptor rewritten and requests naming it right after the commit's B handshake.
#include <gtest/gtest.h>
#include <verilated.h>
#include <verilated_syms.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vtex_unit_axi.h"
#include "engines/engine.h"
#include "engines/rtl/register_map.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"
#include "stimulus.h"

using namespace tex;

namespace {

// ---- the Verilated build's parameters (tests/rtl/CMakeLists.txt)
constexpr int kMaxLog2W = 6, kMaxLog2H = 3, kBlockW = 4, kBlockH = 4, kLines = 64, kMaxWays = 4;
constexpr int kFifoDepth = 32, kMemW = 128, kTextures = 4, kSamplers = 8;
constexpr int kLineBytes = kBlockW * kBlockH * 4, kBeatBytes = kMemW / 8, kBeats = kLineBytes / kBeatBytes;

// ---- the register map: sim/engines/rtl/register_map.h (checked against the RTL)
using namespace tex::rtl::axil;
// The counters the test sees at the pins (the others: against the model).
bool pin_visible(int i) { return i != kLookups && i != kMisses; }
constexpr uint32_t kDecerr = 3;

int log2i(int v) {
  int k = 0;
  while ((1 << k) < v) ++k;
  return k;
}

std::string hex(uint64_t v) {
  char s[24];
  std::snprintf(s, sizeof s, "0x%llx", (unsigned long long)v);
  return s;
}

std::string describe(const Texel& t) {
  return "(" + std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) + "," +
         std::to_string(t[3]) + ")";
}

std::string describe(const Request& r) {
  std::string s = "texture " + std::to_string(r.texture) + " u=" + std::to_string(r.u) + " v=" + std::to_string(r.v);
  if (r.has_derivatives)
    s += " d=(" + std::to_string(r.deriv.dudx) + "," + std::to_string(r.deriv.dvdx) + "," +
         std::to_string(r.deriv.dudy) + "," + std::to_string(r.deriv.dvdy) + ")";
  else
    s += " lod=" + std::to_string(r.lod);
  return s;
}

uint32_t pack_rgba8(const Texel& t) {
  return uint32_t(t[0] & 255) | uint32_t(t[1] & 255) << 8 | uint32_t(t[2] & 255) << 16 | uint32_t(t[3] & 255) << 24;
}
Texel unpack_rgba8(uint32_t p) {
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

// The request and response sides' behaviour in a case.
struct StreamTiming {
  double gap_p = 0, stall_p = 0;  // after a request / in a clock: a req_valid gap / rsp_ready stall starts
  int max_gap = 4, max_stall = 6;
  double long_stall_p = 0;        // a stall of long_stall clocks (the FIFO fills: req_ready drops)
  int long_stall = 0;
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
  void start_stream(const std::vector<Request>& requests, const StreamTiming& stim, ResponseFn fn) {
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
      t.req_tag = uint16_t(junk());
    }
    t.req_valid = req_valid;
    // rsp_ready: stalls of 1..max_stall clocks, now and then a long one
    bool rsp_ready = !rst_;
    if (reqs_) {
      if (stall_ == 0 && coin(stim_.long_stall_p)) stall_ = stim_.long_stall;
      if (stall_ == 0 && coin(stim_.stall_p)) stall_ = 1 + int(rng_() % uint64_t(stim_.max_stall));
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
      if (coin(stim_.gap_p)) gap_ = 1 + int(rng_() % uint64_t(stim_.max_gap));
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
  StreamTiming stim_;
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

// ---------------------------------------------------------------- cases

// One case: textures (the RTL's descriptor table), samplers (its sampler table), the cache
// configuration, the memory, the stimulus, the requests.
struct Case {
  Case() = default;
  Case(Case&&) = default;  // (moves keep the pyramids where the table points)
  Case(const Case&) = delete;
  std::vector<Pyramid> pyramids;
  TextureTable table;
  SamplerTable samplers;
  LayoutParams layout;
  int log2_sets = 4, log2_ways = 1;
  uint32_t fifo_limit = 0;
  MemorySetup memory;
  StreamTiming stim;
  std::vector<Request> requests;
};

struct CaseResult {
  std::string first_mismatch;         // the first response unlike the model's (value or rsp_error)
  std::vector<std::string> failures;  // anything else: protocol, registers, miss stream, counters
  uint64_t samples = 0, flagged = 0, reads = 0, clocks = 0;
  uint64_t counter_reads = 0;         // counters read (LO, HI) while the stream ran
  AxiTop::Totals counters{};          // read back after the freeze
};

int32_t coordinate(std::mt19937_64& rng, int log2_size, int last_level) {
  const int64_t one = int64_t(1) << kCoordFracBits;
  const int kind = int(rng() % 100);
  if (kind < 30) return int32_t(int64_t(rng() % uint64_t(8 * one)) - 4 * one);  // [-4, 4)
  if (kind < 65) {  // near a texel edge or centre of some level, a few units off
    const int lk = std::max(log2_size - int(rng() % uint64_t(last_level + 1)), 0);
    const int64_t texel = one >> lk, j = int64_t(rng() % uint64_t((int64_t(1) << lk) + 4)) - 2;
    return int32_t(j * texel + (rng() % 2 ? texel / 2 : 0) + (rng() % 3 ? int64_t(rng() % 65) - 32 : 0));
  }
  if (kind < 90) return int32_t(rng() % uint64_t(one));  // [0, 1)
  if (kind < 97) return int32_t(uint32_t(rng()));        // any
  const int32_t edges[] = {0, 1, -1, int32_t(one - 1), int32_t(one), INT32_MIN, INT32_MAX};
  return edges[rng() % 7];
}

int32_t lod_value(std::mt19937_64& rng, int last_level) {
  const int kind = int(rng() % 100);
  if (kind < 60) return int32_t(int64_t(rng() % uint64_t((last_level + 4) * 256)) - 512);  // [-2, last + 2)
  if (kind < 90) return int32_t(int64_t(rng() % uint64_t(last_level + 3)) - 1) * 256 + int32_t(rng() % 3) - 1 +
                        (rng() % 2 ? 128 : 0);  // on level and rounding boundaries
  return int32_t(int16_t(uint16_t(rng())));
}

// A request with derivatives: a footprint from 1/8 texel to 8x the texture, anisotropy up to 8,
// any direction; 1 in 16 with raw 32-bit derivatives.
Request footprint(std::mt19937_64& rng, int lw, int lh) {
  Request r;
  r.has_derivatives = true;
  if (rng() % 16 == 0) {
    r.deriv = {int32_t(uint32_t(rng())), int32_t(uint32_t(rng())), int32_t(uint32_t(rng())), int32_t(uint32_t(rng()))};
    return r;
  }
  std::uniform_real_distribution<double> unit(0, 1);
  const double major = std::exp2(-3 + unit(rng) * (std::max(lw, lh) + 6));
  const double minor = major / (rng() % 3 == 0 ? 1.0 : 1.0 + 7.0 * unit(rng));
  const double a = unit(rng) * 2 * M_PI, w = std::ldexp(1.0, lw), h = std::ldexp(1.0, lh);
  const bool x_major = rng() % 2;
  const double lx = x_major ? major : minor, ly = x_major ? minor : major;
  auto q = [](double x) { return int32_t(std::clamp(std::lround(x * 16777216.0), -2147483647L, 2147483647L)); };
  r.deriv = {q(lx * std::cos(a) / w), q(lx * std::sin(a) / h), q(-ly * std::sin(a) / w), q(ly * std::cos(a) / h)};
  return r;
}

std::vector<Request> random_requests(std::mt19937_64& rng, const TextureTable& table, size_t samplers, size_t n) {
  std::vector<Request> out(n);
  uint8_t tex = 0, smp = 0;
  for (size_t i = 0; i < n; ++i) {
    if (rng() % 4 != 0) tex = uint8_t(rng() % table.size());  // mostly a new texture, runs now and then
    if (rng() % 4 != 0) smp = uint8_t(rng() % samplers);      // and a new sampler
    const int lw = log2_ceil(table[tex].pyramid->extent0().w), lh = log2_ceil(table[tex].pyramid->extent0().h), last = std::max(lw, lh);
    Request& r = out[i];
    if (rng() % 4 == 0) r = footprint(rng, lw, lh);
    r.u = coordinate(rng, lw, last);
    r.v = coordinate(rng, lh, last);
    r.lod = lod_value(rng, last);
    if (rng() % 4 == 0) r.bias = lod_value(rng, last);  // the request's own LOD bias
    r.texture = tex;
    r.sampler = smp;
    r.tag = uint32_t(i);
  }
  return out;
}

Pyramid random_pyramid(Extent size, uint64_t seed) {
  Image img(size.w, size.h, 8);
  std::mt19937_64 rng(seed);
  for (Texel& t : img.texels)
    for (uint16_t& c : t) c = uint16_t(rng() & 255);
  return build_pyramid(std::move(img), PyramidMode::Exact);
}

// A random sampler: filters (a third anisotropic), address modes, border colour, LOD controls.
SamplerConfig random_sampler(std::mt19937_64& rng) {
  SamplerConfig s;
  const Filter filters[] = {{TexelFilter::Nearest, MipMode::None},   {TexelFilter::Nearest, MipMode::Nearest},
                            {TexelFilter::Nearest, MipMode::Linear}, {TexelFilter::Linear, MipMode::None},
                            {TexelFilter::Linear, MipMode::Nearest}, {TexelFilter::Linear, MipMode::Linear}};
  s.filter = rng() % 2 ? Filter{} : filters[rng() % 6];
  if (rng() % 3 == 0) {
    s.filter = {TexelFilter::Linear, MipMode::Linear, true};
    s.max_aniso = 1 + int(rng() % kMaxAniso);
    s.aniso_pow2 = rng() % 4 == 0;
  }
  if (rng() % 3 == 0) s.filter.mag = TexelFilter(1 - int(s.filter.texel));  // magnifies apart
  s.wrap_u = Wrap(rng() % kWrapModes);
  s.wrap_v = Wrap(rng() % kWrapModes);
  s.border = BorderColor(rng() % kBorderColors);
  for (uint16_t& v : s.border_custom) v = uint16_t(rng());
  s.lod_bias = rng() % 2 ? 0 : int32_t(int64_t(rng() % 1537) - 768);
  if (rng() % 2) {
    s.min_lod = int32_t(int64_t(rng() % 1537) - 512);
    s.max_lod = s.min_lod + int32_t(rng() % 2049);
  }
  if (rng() % 6 == 0) rtltest::make_unnormalized(rng, s);  // (its requests: texel coordinates, random_case)
  return s;
}

// A random case: 2 to 4 textures (the first of the largest size; of the others half any size, half
// powers of two), 1 to 16 random samplers, block
// order, base, cache geometry, FIFO limit, memory and stimulus.
Case random_case(uint64_t seed, size_t requests, bool errors) {
  std::mt19937_64 rng(seed);
  Case c;
  const int n = 2 + int(rng() % (kTextures - 1));
  c.pyramids.reserve(size_t(n));
  for (int i = 0; i < n; ++i) {
    Extent size{1 << kMaxLog2W, 1 << kMaxLog2H};
    if (i > 0 && rng() % 2) size = {1 << (rng() % (kMaxLog2W + 1)), 1 << (rng() % (kMaxLog2H + 1))};
    else if (i > 0) size = {1 + int(rng() % (1u << kMaxLog2W)), 1 + int(rng() % (1u << kMaxLog2H))};
    c.pyramids.push_back(random_pyramid(size, rng()));
    if (i > 0 && rng() % 3 == 0) {  // a view: its chain cut (DESC_ATTR's last level)
      const int b = int(rng() % uint64_t(c.pyramids.back().levels.size()));
      c.pyramids.back() = view_pyramid(c.pyramids.back(), b, b + int(rng() % 3));
    }
    c.table.push_back({&c.pyramids.back()});
  }
  const int ns = rng() % 4 == 0 ? kSamplers : 1 + int(rng() % kSamplers);
  for (int i = 0; i < ns; ++i) c.samplers.push_back(random_sampler(rng));
  c.layout.block_w = kBlockW;
  c.layout.block_h = kBlockH;
  c.layout.order = BlockOrder(rng() % 2);
  c.layout.base = uint32_t(rng() % 64) * 4096u + uint32_t(rng() % 64) * kLineBytes;
  c.log2_ways = int(rng() % (log2i(kMaxWays) + 1));
  c.log2_sets = 2 + int(rng() % uint64_t(log2i(kLines) - c.log2_ways - 1));  // 4 sets .. LINES / ways
  c.fifo_limit = rng() % 3 == 0 ? 1 + uint32_t(rng() % kFifoDepth) : 0;
  c.memory.latency = rng() % 2 ? 1 + uint32_t(rng() % 8) : 20 + uint32_t(rng() % 80);
  c.memory.jitter = rng() % 2 ? uint32_t(rng() % 30) : 0;
  c.memory.arready_p = rng() % 2 ? 1.0 : 0.3 + 0.6 * double(rng() % 100) / 100;
  c.memory.rgap_p = rng() % 2 ? 0.0 : 0.4;
  c.memory.max_outstanding = rng() % 3 ? 64 : 1 + uint32_t(rng() % 8);
  if (errors)  // 2 to 6 line reads among the first 1500 answered with an error
    for (int k = 2 + int(rng() % 5); k > 0; --k) c.memory.error_reads.push_back(1 + rng() % 1500);
  std::sort(c.memory.error_reads.begin(), c.memory.error_reads.end());
  c.memory.error_reads.erase(std::unique(c.memory.error_reads.begin(), c.memory.error_reads.end()),
                             c.memory.error_reads.end());
  c.stim.gap_p = rng() % 2 ? 0.0 : 0.3;
  c.stim.stall_p = rng() % 2 ? 0.05 : 0.3;
  c.stim.long_stall_p = 0.002;
  c.stim.long_stall = 50 + int(rng() % 100);
  c.requests = random_requests(rng, c.table, c.samplers.size(), requests);
  rtltest::texel_coordinates_where_unnormalized(rng, c.requests, c.samplers,
                                       [&](int t) { return c.table[size_t(t)].pyramid->extent0(); });
  return c;
}


// Counter i as the register map defines it, for a read whose AR edge is `ar`: the events of the
// edges from the clear's to the one before the read's (to the freeze's edge, if frozen there).
uint64_t expected_counter(const AxiTop& top, int i, uint64_t clear_edge, uint64_t ar, uint64_t freeze_edge) {
  const uint64_t until = std::min(ar - 1, freeze_edge);
  return top.sums_before(until)[size_t(i)] - top.sums_before(clear_edge)[size_t(i)];
}

// Programs the unit for case `c` over AXI4-Lite: geometry and filter in reset, then the
// descriptors `desc` (wrap modes from `rtl_table`), then the counters cleared (its edge in
// `clear_edge`). Refused writes along the way must answer SLVERR and change nothing.
void program(AxiTop& top, const Case& c, const std::vector<TextureDescriptor>& desc, uint64_t& clear_edge,
             std::vector<std::string>& failures) {
  auto expect_write = [&](uint32_t addr, uint32_t data, uint32_t want, const char* what) {
    const uint32_t got = top.write(addr, data);
    if (got != want)
      failures.push_back(std::string(what) + ": write " + hex(data) + " to " + hex(addr) + " answered " +
                         std::to_string(got) + ", want " + std::to_string(want));
  };
  auto expect_read = [&](uint32_t addr, uint32_t want, const char* what) {
    const auto [data, resp] = top.read(addr);
    if (data != want || resp != kOkay)
      failures.push_back(std::string(what) + ": read " + hex(addr) + " gave " + hex(data) + " resp " +
                         std::to_string(resp) + ", want " + hex(want));
  };
  expect_write(kControl, kUnitReset, kOkay, "CONTROL: hold the unit in reset");
  expect_read(kControl, kUnitReset, "CONTROL");
  expect_read(kId, kIdValue, "ID");
  expect_read(kVersion, kVersionValue, "VERSION");
  expect_read(kCaps0, uint32_t(kMaxLog2W | kMaxLog2H << 4 | kTextures << 8 | kSamplers << 20), "CAPS0");
  expect_read(kCaps1, uint32_t(log2i(kLines) | kMaxWays << 8 | log2i(kFifoDepth) << 16 | log2i(kLineBytes) << 24 |
                               log2i(kBeatBytes) << 28),
              "CAPS1");
  const uint32_t cache = uint32_t(c.log2_ways) << 16 | uint32_t(c.log2_sets) << 8 |
                         uint32_t(c.layout.order == BlockOrder::Morton);
  expect_write(kFifoLimit, c.fifo_limit, kOkay, "FIFO_LIMIT");
  // A commit while the unit is in reset would be lost: refused.
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT in reset");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT in reset");
  // The geometry, then the release as soon as allowed (BREADY high at once: the CONTROL write's
  // edge 2 clocks after the CACHE write's when AW and W come together).
  top.bready_p = 1.0;
  expect_write(kCache, cache, kOkay, "CACHE in reset");
  expect_write(kControl, 0, kOkay, "CONTROL: release the unit");
  top.bready_p = 0.7;
  expect_read(kCache, cache, "CACHE");
  // The geometry is fixed while the unit runs.
  expect_write(kCache, cache ^ 1u, kSlverr, "CACHE while the unit runs");
  expect_read(kCache, cache, "CACHE after the refused write");
  for (size_t i = 0; i < desc.size(); ++i) {
    const MemoryLayout& l = desc[i].layout;
    expect_write(kDescBase, l.params().base, kOkay, "DESC_BASE");
    expect_write(kDescAttr, desc_attr_word(l), kOkay, "DESC_ATTR");
    expect_write(kDescSize, desc_size_word(l.size0()), kOkay, "DESC_SIZE");
    expect_write(kDescCommit, uint32_t(i), kOkay, "DESC_COMMIT");
    expect_read(kDescCommit, uint32_t(i), "DESC_COMMIT");
  }
  // Refused commits: an entry beyond the table, a base off the line, a size beyond MAX_LOG2_W, 0.
  const uint32_t last = uint32_t(desc.size() - 1);
  expect_write(kDescCommit, kTextures, kSlverr, "DESC_COMMIT beyond TEXTURES");
  expect_write(kDescBase, desc.back().layout.params().base + 4, kOkay, "DESC_BASE off the line");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a base off the line");
  expect_write(kDescBase, desc.back().layout.params().base, kOkay, "DESC_BASE");
  expect_write(kDescSize, desc_size_word({(1 << kMaxLog2W) + 1, 1}), kOkay, "DESC_SIZE too wide");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a texture beyond MAX_LOG2_W");
  expect_write(kDescSize, desc_size_word({1, 0}), kOkay, "DESC_SIZE of height 0");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a texture of height 0");
  expect_read(kDescCommit, last, "DESC_COMMIT after the refused commits");
  // The sampler table: each entry staged, committed and read back.
  for (size_t i = 0; i < c.samplers.size(); ++i) {
    const SamplerConfig& s = c.samplers[i];
    expect_write(kFilter, filter_word(s), kOkay, "FILTER");
    expect_write(kLodBias, uint16_t(s.lod_bias), kOkay, "LOD_BIAS");
    expect_write(kMinLod, uint16_t(s.min_lod), kOkay, "MIN_LOD");
    expect_write(kMaxLod, uint16_t(s.max_lod), kOkay, "MAX_LOD");
    expect_write(kBorderRg, border_rg_word(s), kOkay, "BORDER_RG");
    expect_write(kBorderBa, border_ba_word(s), kOkay, "BORDER_BA");
    expect_write(kWrap, wrap_word(s), kOkay, "WRAP");
    expect_read(kFilter, filter_word(s), "FILTER");
    expect_read(kMinLod, uint16_t(s.min_lod), "MIN_LOD");
    expect_read(kBorderBa, border_ba_word(s), "BORDER_BA");
    expect_read(kWrap, wrap_word(s), "WRAP");
    expect_write(kSmpCommit, uint32_t(i), kOkay, "SMP_COMMIT");
    expect_read(kSmpCommit, uint32_t(i), "SMP_COMMIT");
  }
  // Refused sampler commits: an entry beyond the table, an address mode 5..7, mip mode 3. (The
  // staged fields stay: the last sampler's are written back before the next case.)
  const uint32_t last_smp = uint32_t(c.samplers.size() - 1);
  const SamplerConfig& ls = c.samplers.back();
  expect_write(kSmpCommit, kSamplers, kSlverr, "SMP_COMMIT beyond SAMPLERS");
  expect_write(kWrap, 5u | 1u << 4, kOkay, "WRAP with mode 5");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of address mode 5");
  expect_write(kWrap, 7u << 4, kOkay, "WRAP with mode 7");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of address mode 7");
  expect_write(kWrap, wrap_word(ls), kOkay, "WRAP");
  expect_write(kFilter, filter_word(ls) | 3u << 4, kOkay, "FILTER with mip mode 3");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of mip mode 3");
  expect_write(kFilter, filter_word(ls), kOkay, "FILTER");
  expect_read(kSmpCommit, last_smp, "SMP_COMMIT after the refused commits");
  if (top.write(kControl, kClear, &clear_edge) != kOkay) failures.push_back("CONTROL: clear refused");
  expect_read(kControl, 0, "CONTROL after the clear");
}

// One case through the unit: programmed over AXI4-Lite, every response against the model (the
// model's table and error reads: the RTL's unless a test plants others), the lines read against
// the model's misses, the counters against the pins and the model.
CaseResult run_case(AxiTop& top, const Case& c, const SamplerTable* model_samplers_in = nullptr,
                    const std::vector<uint64_t>* model_errors_in = nullptr) {
  CaseResult r;
  const SamplerTable& model_samplers = model_samplers_in ? *model_samplers_in : c.samplers;
  const std::vector<uint64_t>& model_errors = model_errors_in ? *model_errors_in : c.memory.error_reads;
  EngineOptions eo;
  eo.layout = c.layout;
  const std::vector<TextureDescriptor> desc = texture_descriptors(c.table, eo);
  // The memory image: the pyramids packed from the layout's base.
  std::vector<uint8_t> image;
  for (size_t i = 0; i < desc.size(); ++i) {
    const std::vector<uint8_t> bytes = build_memory_image(*c.table[i].pyramid, desc[i].layout);
    const size_t at = desc[i].layout.params().base - c.layout.base;
    if (image.size() < at + bytes.size()) image.resize(at + bytes.size());
    std::copy(bytes.begin(), bytes.end(), image.begin() + std::ptrdiff_t(at));
  }
  top.set_memory(c.layout.base, std::move(image), c.memory);

  // The model: each request's value and flag, the lines it misses.
  SamplerPairs samplers(c.table, model_samplers);
  TextureCache model(texture_descriptors(c.table, eo),
                     CacheParams{(1 << (c.log2_sets + c.log2_ways)) * kLineBytes, 1 << c.log2_ways}, model_samplers);
  model.set_error_reads(model_errors);
  std::vector<uint32_t> predicted;
  std::vector<uint32_t> want(c.requests.size());
  std::vector<uint8_t> want_error(c.requests.size());
  uint64_t want_flagged = 0;
  for (size_t i = 0; i < c.requests.size(); ++i) {
    const Request& q = c.requests[i];
    want_error[i] = model.lookup_sample(q, &predicted).error;
    want[i] = want_error[i] ? 0 : pack_rgba8(samplers.at(q).sample(q));
    want_flagged += want_error[i];
  }

  uint64_t clear_edge = 0;
  if (top.failure().empty()) program(top, c, desc, clear_edge, r.failures);
  if (!top.failure().empty()) {
    r.failures.insert(r.failures.begin(), top.failure());
    return r;
  }

  // The stream, with counter reads (LO, then HI) now and then.
  const uint64_t never = ~uint64_t(0);
  std::vector<std::pair<int, uint64_t>> mid_reads;  // LOOKUPS / MISSES read while running
  auto check_read = [&](int i, uint32_t lo, uint32_t lo_resp, uint64_t lo_edge, uint32_t hi, uint32_t hi_resp,
                        uint64_t freeze_edge) {
    const uint64_t got = uint64_t(hi) << 32 | lo;
    r.counter_reads += freeze_edge == never;
    if (lo_resp != kOkay || hi_resp != kOkay)
      r.failures.push_back(std::string(kCounterNames[i]) + ": read answered " + std::to_string(lo_resp) + "/" +
                           std::to_string(hi_resp));
    if (pin_visible(i)) {
      const uint64_t want_v = expected_counter(top, i, clear_edge, lo_edge, freeze_edge);
      if (got != want_v)
        r.failures.push_back(std::string(kCounterNames[i]) + " read at clock " + std::to_string(lo_edge) + ": " +
                             std::to_string(got) + ", the pins showed " + std::to_string(want_v));
    } else if (hi != 0) {
      r.failures.push_back(std::string(kCounterNames[i]) + ": high word " + std::to_string(hi));
    }
    return got;
  };
  bool counter_read_busy = false;
  auto read_counter = [&](int i, std::function<void(uint64_t)> then, uint64_t freeze_edge) {
    counter_read_busy = true;
    auto lo = std::make_shared<std::array<uint64_t, 3>>();  // data, resp, edge of the LO read
    top.queue_read(kCounterBase + 8 * uint32_t(i),
                   [lo](uint32_t d, uint32_t resp, uint64_t e) { *lo = {d, resp, e}; });
    top.queue_read(kCounterBase + 8 * uint32_t(i) + 4, [&, i, lo, then, freeze_edge](uint32_t d, uint32_t resp, uint64_t) {
      counter_read_busy = false;
      then(check_read(i, uint32_t((*lo)[0]), uint32_t((*lo)[1]), (*lo)[2], d, resp, freeze_edge));
    });
  };

  std::mt19937_64 rng(c.requests.size() * 31 + c.layout.base);
  uint64_t next_counter_read = top.edge() + 50 + rng() % 300;
  const uint64_t t0 = top.edge();
  top.start_stream(c.requests, c.stim, [&](size_t i, uint32_t rgba, bool error) {
    r.flagged += error;
    ++r.samples;
    if (!r.first_mismatch.empty()) return;
    const Request& q = c.requests[i];
    if (error != bool(want_error[i]))
      r.first_mismatch = "sample " + std::to_string(i) + " " + describe(q) + ": RTL rsp_error " +
                         std::to_string(error) + ", model " + std::to_string(want_error[i]);
    else if (rgba != want[i])
      r.first_mismatch = "sample " + std::to_string(i) + " " + describe(q) + ": RTL " + describe(unpack_rgba8(rgba)) +
                         ", model " + describe(unpack_rgba8(want[i])) + (error ? " (flagged: must be 0)" : "");
  });
  const uint64_t limit = 400 * c.requests.size() + 20000;
  while (!top.stream_done() && top.failure().empty()) {
    if (top.edge() - t0 > limit) {
      top.fail("time-out: " + std::to_string(r.samples) + " of " + std::to_string(c.requests.size()) + " answered");
      break;
    }
    if (top.edge() >= next_counter_read && !counter_read_busy) {
      const int i = int(rng() % kCounters);
      read_counter(i, [&, i](uint64_t v) { if (!pin_visible(i)) mid_reads.push_back({i, v}); }, never);
      next_counter_read = top.edge() + 50 + rng() % 300;
    }
    top.clock();
  }
  top.end_stream();
  top.run_until([&] { return top.lite_idle() && top.memory_idle(); }, 2000);
  top.idle(10);
  r.clocks = top.edge() - t0;

  // The lines read: the model's misses, in order.
  const std::vector<uint32_t>& actual = top.ar_log();
  r.reads = actual.size();
  if (actual != predicted) {
    size_t i = 0;
    while (i < actual.size() && i < predicted.size() && actual[i] == predicted[i]) ++i;
    r.failures.push_back("miss stream differs at read " + std::to_string(i) + " of " + std::to_string(actual.size()) +
                         " (model " + std::to_string(predicted.size()) + "): RTL " +
                         (i < actual.size() ? hex(actual[i]) : "none") + ", model " +
                         (i < predicted.size() ? hex(predicted[i]) : "none"));
  }

  // Freeze, then every counter, 64 bits.
  uint64_t freeze_edge = 0;
  if (top.write(kControl, kFreeze, &freeze_edge) != kOkay) r.failures.push_back("CONTROL: freeze refused");
  for (int i = 0; i < kCounters; ++i) {
    read_counter(i, [&, i](uint64_t v) { r.counters[size_t(i)] = v; }, freeze_edge);
    top.run_until([&] { return !counter_read_busy; }, 1000);
  }
  if (!top.failure().empty()) {
    r.failures.push_back(top.failure());
    return r;
  }
  const AxiTop::Totals& k = r.counters;
  auto expect_eq = [&](const char* what, uint64_t got, uint64_t want_v) {
    if (got != want_v)
      r.failures.push_back(std::string(what) + ": " + std::to_string(got) + ", want " + std::to_string(want_v));
  };
  expect_eq("SAMPLES = requests", k[kSamples], c.requests.size());
  expect_eq("SAMPLE_ERRORS = flagged responses", k[kSampleErrors], r.flagged);
  expect_eq("SAMPLE_ERRORS = the model's flagged samples", k[kSampleErrors], want_flagged);
  expect_eq("LOOKUPS = the model's lookups", k[kLookups], model.stats().total_lookups());
  expect_eq("MISSES = the model's misses", k[kMisses], model.stats().total_misses());
  expect_eq("MISSES = AXI reads", k[kMisses], r.reads);
  expect_eq("MEM_BYTES = MISSES x line bytes", k[kMemBytes], k[kMisses] * kLineBytes);
  expect_eq("CYCLES = clocks from the clear to the freeze", k[kCycles], freeze_edge - clear_edge);
  if (k[kMemWait] == 0 && r.reads > 0) r.failures.push_back("MEM_WAIT 0 with " + std::to_string(r.reads) + " reads");
  for (int i : {kSamples, kOutStall, kMemWait, kReqStall})
    if (k[size_t(i)] > k[kCycles]) r.failures.push_back(std::string(kCounterNames[i]) + " above CYCLES");
  for (const auto& [i, v] : mid_reads)
    if (v > k[size_t(i)])
      r.failures.push_back(std::string(kCounterNames[i]) + " read " + std::to_string(v) + " while running, " +
                           std::to_string(k[size_t(i)]) + " at the end");
  return r;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size() && i < 8; ++i) s += "\n  " + v[i];
  if (v.size() > 8) s += "\n  ... " + std::to_string(v.size()) + " in all";
  return s;
}

}  // namespace

// Random cases end to end: the first from the hardware reset, each next one through the soft
// reset (new geometry, descriptors again); every other case with memory errors.
TEST(RtlAxiTop, EndToEndAgainstModel) {
  const auto t0 = std::chrono::steady_clock::now();
  // TEX_SEED_BASE=N: another set of cases (as the lockstep suites).
  const char* env = std::getenv("TEX_SEED_BASE");
  const uint64_t base = env && *env ? std::strtoull(env, nullptr, 0) : 0xA71;
  AxiTop top(base);
  ASSERT_TRUE(top.head_waits_visible()) << "tex_cached_fetch's head_waits is not public (rtl/tex_unit.vlt)";
  uint64_t samples = 0, flagged = 0, reads = 0, clocks = 0, out_stall = 0, req_stall = 0, mem_wait = 0;
  uint64_t lookups = 0, counter_reads = 0;
  const int cases = 10;
  for (int ci = 0; ci < cases; ++ci) {
    const uint64_t seed = base + uint64_t(ci) * 7919;
    const Case c = random_case(seed, 4000, ci % 2 == 1);
    const CaseResult r = run_case(top, c);
    EXPECT_EQ(r.first_mismatch, "") << "case " << ci << " (seed " << seed << ")";
    EXPECT_TRUE(r.failures.empty()) << "case " << ci << " (seed " << seed << "):" << join(r.failures);
    if (!r.first_mismatch.empty() || !r.failures.empty()) break;
    samples += r.samples;
    flagged += r.flagged;
    reads += r.reads;
    clocks += r.clocks;
    out_stall += r.counters[kOutStall];
    req_stall += r.counters[kReqStall];
    mem_wait += r.counters[kMemWait];
    lookups += r.counters[kLookups];
    counter_reads += r.counter_reads;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ axi top  ] %d cases: %llu samples (%llu flagged by memory errors), %llu lines read, %llu lookups, "
              "%llu clocks; counters OUT_STALL %llu, REQ_STALL %llu, MEM_WAIT %llu; %llu counters read while "
              "running (%.1f s)\n",
              cases, (unsigned long long)samples, (unsigned long long)flagged, (unsigned long long)reads,
              (unsigned long long)lookups, (unsigned long long)clocks, (unsigned long long)out_stall,
              (unsigned long long)req_stall, (unsigned long long)mem_wait, (unsigned long long)counter_reads, secs);
  // The checks were not vacuous.
  EXPECT_GT(flagged, 0u);
  EXPECT_LT(flagged, samples / 4);
  EXPECT_GT(out_stall, 0u);
  EXPECT_GT(req_stall, 0u);
  EXPECT_GT(mem_wait, 0u);
  EXPECT_GT(reads, 0u);
  EXPECT_GT(counter_reads, 100u);
}

// The checkers fire: the unit's sampler 1 committed with other wrap modes than the model's table
// gives a sample mismatch; a model that expects the memory error one line read late disagrees on
// a flag. The same case with the model right passes.
TEST(RtlAxiTop, PlantedBugsAreCaught) {
  AxiTop top(11);
  Case c = random_case(0xBAD, 1500, false);
  c.samplers.assign(2, SamplerConfig{});  // trilinear, no LOD clamp
  c.pyramids[1] = random_pyramid({32, 4}, 3);  // (in place: the table points at it)
  c.samplers[1].wrap_u = Wrap::Clamp;
  c.samplers[1].wrap_v = Wrap::Repeat;
  std::mt19937_64 rng(5);
  c.requests = random_requests(rng, c.table, c.samplers.size(), 1500);
  const CaseResult good = run_case(top, c);
  EXPECT_EQ(good.first_mismatch, "");
  EXPECT_TRUE(good.failures.empty()) << join(good.failures);

  SamplerTable rewrapped = c.samplers;  // the model's table: sampler 1 mirrored
  rewrapped[1].wrap_u = Wrap::Mirror;
  rewrapped[1].wrap_v = Wrap::Mirror;
  const CaseResult wrap = run_case(top, c, &rewrapped);
  EXPECT_EQ(wrap.first_mismatch.rfind("sample ", 0), 0u) << "a wrong wrap mode went unnoticed";
  std::printf("[ planted  ] wrap modes: %s\n", wrap.first_mismatch.c_str());

  c.memory.error_reads = {5};
  const std::vector<uint64_t> late = {6};
  const CaseResult flag = run_case(top, c, nullptr, &late);
  EXPECT_NE(flag.first_mismatch.find("rsp_error"), std::string::npos) << flag.first_mismatch;
  std::printf("[ planted  ] error read: %s\n", flag.first_mismatch.c_str());
  const CaseResult right = run_case(top, c);
  EXPECT_EQ(right.first_mismatch, "");
  EXPECT_TRUE(right.failures.empty()) << join(right.failures);
  EXPECT_GT(right.flagged, 0u);
}

// The timing of a descriptor commit (docs/rtl-interface.md, "Descriptor commit"): entry 0
// rewritten from texture 0 to texture 1's pyramid (another size, 7x3), BREADY high at once, then
// requests naming entry 0 offered `after` clocks after the B handshake's edge. The unit takes none
// while it sets the entry up (req_ready low for 1 + 2^LEVEL_W clocks from the clock after
// cfg_desc_we), so every sample is texture 1's, however soon it is offered.
TEST(RtlAxiTop, RequestsRightAfterADescriptorCommit) {
  AxiTop top(13);
  Case c = random_case(0xC0, 200, false);
  c.pyramids[0] = random_pyramid({64, 8}, 1);
  c.pyramids[1] = random_pyramid({7, 3}, 2);
  ASSERT_EQ(run_case(top, c).first_mismatch, "");
  EngineOptions eo;
  eo.layout = c.layout;
  const std::vector<TextureDescriptor> desc = texture_descriptors(c.table, eo);
  Sampler model(*c.table[1].pyramid, c.samplers[0]);
  std::mt19937_64 rng(3);
  TextureTable one = {c.table[1]};
  for (int after = 0; after < 3; ++after) {
    // Texture 0 into entry 0 (settled), then texture 1 into entry 0: the commit under test.
    uint64_t d = 0;
    for (int to : {0, 1}) {
      const TextureDescriptor& e = desc[size_t(to)];
      EXPECT_EQ(top.write(kDescBase, e.layout.params().base), kOkay);
      EXPECT_EQ(top.write(kDescAttr, desc_attr_word(e.layout)), kOkay);
      EXPECT_EQ(top.write(kDescSize, desc_size_word(e.layout.size0())), kOkay);
      top.bready_p = to == 1 ? 1.0 : 0.7;
      EXPECT_EQ(top.write(kDescCommit, 0, &d), kOkay);
      top.bready_p = 0.7;
      if (to == 0) top.idle(5);
    }
    EXPECT_EQ(top.edge(), d + 2) << "BREADY high: the B handshake at the edge after the write's";
    top.idle(after);
    // All of entry 0. The first ones carry derivatives of one texel of texture 1 (lambda 0; 3 with
    // texture 0's size, 64x8): a sample that took the entry's old size would show it.
    std::vector<Request> requests = random_requests(rng, one, 1, 8);
    for (int i = 0; i < 4; ++i) {
      requests[size_t(i)].has_derivatives = true;
      requests[size_t(i)].deriv = {(1 << 24) / 8, 0, 0, (1 << 24) / 2};
    }
    std::string first;
    top.start_stream(requests, StreamTiming{}, [&](size_t i, uint32_t rgba, bool) {
      const uint32_t want = pack_rgba8(model.sample(requests[i]));
      if (rgba != want && first.empty())
        first = "sample " + std::to_string(i) + " " + describe(requests[i]) + ": RTL " +
                describe(unpack_rgba8(rgba)) + ", texture 1 " + describe(unpack_rgba8(want));
    });
    top.run_until([&] { return top.stream_done(); }, 20000);
    top.end_stream();
    const uint64_t edges = top.first_request_edge() - d;
    // BVALID rises at edge d, cfg_desc_we is high after it, the unit registers it at d + 1 and is
    // busy through edge d + 18: the first handshake is at edge d + 19.
    constexpr uint64_t kSetupEdges = 2 + (1u << 4) + 1;
    EXPECT_EQ(edges, kSetupEdges) << "offered " << after << " clocks after the B handshake";
    std::printf("[ commit   ] offered %d clocks after the B handshake, taken %llu edges after BVALID rose: %s\n",
                after, (unsigned long long)edges, first.empty() ? "texture 1's samples" : ("the old entry: " + first).c_str());
    EXPECT_EQ(first, "") << "request " << edges << " edges after the commit";
    EXPECT_EQ(top.failure(), "");
  }
}

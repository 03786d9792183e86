// The harness of tex_axil_config's suite (test_rtl_axil_config.cpp): the Verilated slave with the
// parameters below (tests/rtl/CMakeLists.txt), a reference of the register map of
// docs/rtl-interface.md, a clocked master on both channels and a monitor that checks every clock.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "Vtex_axil_config.h"
#include "Vtex_axil_config___024root.h"
#include "engines/rtl/register_map.h"

namespace axil_harness {

// ---- the Verilated build's parameters (tests/rtl/CMakeLists.txt)
constexpr int kAddrW = 12, kMaxLog2W = 10, kMaxLog2H = 9, kLines = 256, kMaxWays = 4, kFifoDepth = 256;
constexpr int kTextures = 8, kSamplers = 4, kBlockFormats = 1, kSrgb = 1, kLineBytes = 64, kBeatBytes = 16, kCubeMaps = 1;
constexpr int kFifoLimitBits = 9;  // $clog2(FIFO_DEPTH + 1)

// ---- the register map: sim/engines/rtl/register_map.h (test_register_map.cpp checks it against the RTL)
using namespace tex::rtl::axil;
constexpr std::array<uint32_t, 15> kWritable = {kControl, kCache, kFifoLimit, kFilter, kLodBias,
                                                kMinLod,  kMaxLod, kDescBase, kDescAttr, kDescCommit,
                                                kDescSize, kBorderRg, kBorderBa, kWrap, kSmpCommit};

inline int log2i(int v) {
  int k = 0;
  while ((1 << k) < v) ++k;
  return k;
}

// Events on the stat_* pins in one clock.
struct Events {
  bool sample = false, sample_error = false, mem_beat = false, out_stall = false, mem_wait = false,
       req_stall = false;
  uint8_t lookups = 0, misses = 0;
};

// The reference: the registers, the counters, the 64-bit read latch.
struct Reference {
  uint32_t control = 1;                      // unit_reset after reset
  uint32_t cache = (2u << 16) | (6u << 8);   // 4 ways, 64 sets (LINES / MAX_WAYS), row-major
  uint32_t fifo_limit = 0, filter = 0x30023, lod_bias = 0, min_lod = 0x8000, max_lod = 0x7FFF;
  uint32_t desc_base = 0, desc_attr = 0xF00, desc_size = 0x00010001, desc_index = 0, border_rg = 0, border_ba = 0, wrap = 0, smp_index = 0;
  std::array<uint64_t, kCounters> counters{};
  Events ev_q;  // the registered events (counted at the next edge)
  bool snap_valid = false;
  int snap_idx = 0;
  uint32_t snap_hi = 0;

  static bool geometry_ok(uint32_t d) {
    const int ways = (d >> 16) & 3, sets = (d >> 8) & 31;
    return ways <= log2i(kMaxWays) && sets >= 2 && sets + ways <= log2i(kLines);
  }
  bool descriptor_ok(uint32_t d) const {
    const uint32_t index = d & 15, w = desc_size & 0x3FFF, h = (desc_size >> 16) & 0x3FFF;
    const uint32_t format = (desc_attr >> 16) & 31;
    const bool srgb = (desc_attr >> 21) & 1, cube = (desc_attr >> 22) & 1;
    const uint32_t layers = (desc_attr >> 24) + 1;
    return index < kTextures && w >= 1 && w <= (1u << kMaxLog2W) && h >= 1 && h <= (1u << kMaxLog2H) &&
           (format == 0 || (kBlockFormats && ((format != 6 && format <= 10) || (format >= 16 && format <= 29)))) && (!srgb || (kSrgb && format != 4 && format != 5)) &&
           desc_base % kLineBytes == 0 &&
           (!cube || (kCubeMaps && format == 0 && w == h && layers % 6 == 0 && w + 2 <= (1u << std::min(kMaxLog2W, kMaxLog2H))));
  }
  bool sampler_ok(uint32_t d) const {
    auto wrap_ok = [](uint32_t w) { return w <= 4; };  // the five address modes (5..7: none)
    auto clamping = [](uint32_t w) { return w == 1 || w == 3; };  // clamp to edge, to border
    // Unnormalized coordinates as Vulkan allows them: clamping modes, one texel filter, no
    // anisotropy, the base level only (mip mode none, or max LOD <= 0).
    const bool unnormalized_ok = !((filter >> 13) & 1) ||
                                 (clamping(wrap & 7) && clamping((wrap >> 4) & 7) && (filter & 1) == ((filter >> 1) & 1) &&
                                  ((filter >> 8) & 15) == 0 && (((filter >> 4) & 3) == 0 || int16_t(max_lod) <= 0));
    const bool reduction_ok = ((filter >> 14) & 3) <= 2;  // weighted average, min, max
    return (d & 15) < kSamplers && wrap_ok(wrap & 7) && wrap_ok((wrap >> 4) & 7) && ((filter >> 4) & 3) != 3 &&
           unnormalized_ok && reduction_ok;
  }
  // BRESP of a write (the state before its edge).
  uint32_t write_resp(uint32_t addr, uint32_t data, uint8_t strb) const {
    const uint32_t a = addr & ~3u;
    bool ok = strb == 0xF;
    if (a == kCache) ok = ok && (control & 1) && geometry_ok(data);
    else if (a == kDescCommit) ok = ok && !(control & 1) && descriptor_ok(data);
    else if (a == kSmpCommit) ok = ok && !(control & 1) && sampler_ok(data);
    else ok = ok && std::find(kWritable.begin(), kWritable.end(), a) != kWritable.end();
    return ok ? kOkay : kSlverr;
  }
  // The write's effect at its edge (an OKAY write only; CONTROL's clear is count()'s).
  void apply_write(uint32_t addr, uint32_t d) {
    switch (addr & ~3u) {
      case kControl: control = d & 3; break;
      case kCache: cache = d & 0x31F01; break;
      case kFifoLimit: fifo_limit = d & ((1u << kFifoLimitBits) - 1); break;
      case kFilter: filter = d & 0x7FF33; break;
      case kLodBias: lod_bias = d & 0xFFFF; break;
      case kMinLod: min_lod = d & 0xFFFF; break;
      case kMaxLod: max_lod = d & 0xFFFF; break;
      case kDescBase: desc_base = d; break;
      case kDescAttr: desc_attr = d & 0xFF7F0F00; break;
      case kDescSize: desc_size = d & 0x3FFF3FFF; break;
      case kWrap: wrap = d & 0x77; break;
      case kSmpCommit: smp_index = d & 15; break;
      case kBorderRg: border_rg = d; break;
      case kBorderBa: border_ba = d; break;
      case kDescCommit: desc_index = d & 15; break;
    }
  }
  static uint32_t caps0() {
    return kMaxLog2W | kMaxLog2H << 4 | kTextures << 8 | kBlockFormats << 16 | kSrgb << 17 | kCubeMaps << 18 | kSamplers << 20;
  }
  static uint32_t caps1() {
    return log2i(kLines) | kMaxWays << 8 | log2i(kFifoDepth) << 16 | log2i(kLineBytes) << 24 | log2i(kBeatBytes) << 28;
  }
  // A read at its edge: {RDATA, RRESP}; a counter read's effect on the latch is returned in `snap`.
  struct Snap {
    bool set = false, consume = false;
    int idx = 0;
    uint32_t hi = 0;
  };
  std::pair<uint32_t, uint32_t> read(uint32_t addr, Snap& snap) const {
    const uint32_t a = addr & ((1u << kAddrW) - 4);
    if (a >= kCounterBase && a < kCounterBase + 8 * kCounters) {
      const int i = (a - kCounterBase) / 8;
      if ((a & 4) == 0) {
        snap = {true, false, i, uint32_t(counters[i] >> 32)};
        return {uint32_t(counters[i]), kOkay};
      }
      if (snap_valid && snap_idx == i) {
        snap.consume = true;
        return {snap_hi, kOkay};
      }
      return {uint32_t(counters[i] >> 32), kOkay};
    }
    switch (a) {
      case kId: return {0x54455855u, kOkay};
      case kVersion: return {0x00030007u, kOkay};
      case kCaps0: return {caps0(), kOkay};
      case kCaps1: return {caps1(), kOkay};
      case kControl: return {control, kOkay};
      case kCache: return {cache, kOkay};
      case kFifoLimit: return {fifo_limit, kOkay};
      case kFilter: return {filter, kOkay};
      case kLodBias: return {lod_bias, kOkay};
      case kMinLod: return {min_lod, kOkay};
      case kMaxLod: return {max_lod, kOkay};
      case kDescBase: return {desc_base, kOkay};
      case kDescAttr: return {desc_attr, kOkay};
      case kDescSize: return {desc_size, kOkay};
      case kBorderRg: return {border_rg, kOkay};
      case kBorderBa: return {border_ba, kOkay};
      case kDescCommit: return {desc_index, kOkay};
      case kWrap: return {wrap, kOkay};
      case kSmpCommit: return {smp_index, kOkay};
    }
    return {0, kSlverr};
  }
  // The counters at an edge: the events registered at the previous edge count, unless frozen.
  void count(bool clear, const Events& ev) {
    const uint64_t inc[kCounters] = {1, ev_q.sample, ev_q.sample_error, ev_q.lookups, ev_q.misses,
                                     ev_q.mem_beat ? uint64_t(kBeatBytes) : 0, ev_q.out_stall, ev_q.mem_wait,
                                     ev_q.req_stall};
    for (int i = 0; i < kCounters; ++i) {
      if (clear) counters[i] = 0;
      else if (!(control & 2)) counters[i] += inc[i];
    }
    ev_q = ev;
  }
};

struct WriteOp {
  uint32_t addr = 0, data = 0;
  uint8_t strb = 0xF;
  enum Order { kTogether, kAwFirst, kWFirst } order = kTogether;
  int gap = 0;    // clocks between the first half's handshake and the second half's valid
  int delay = 0;  // clocks before the first valid
};
struct ReadOp {
  uint32_t addr = 0;
  int delay = 0;
};
struct ReadResult {
  uint32_t data = 0, resp = 0;
};

class Slave {
 public:
  explicit Slave(uint64_t seed) : ctx_(std::make_unique<VerilatedContext>()), rng_(seed) {
    ctx_->randReset(2);  // registers without reset start random (--x-initial unique)
    ctx_->randSeed(int(seed % 1000) + 1);
    top_ = std::make_unique<Vtex_axil_config>(ctx_.get());
    reset();
  }

  // ---- what the test sets
  double bready_p = 1.0, rready_p = 1.0;  // BREADY / RREADY high in a clock with this probability
  double desc_ready_p = 0.5;              // and the unit's cfg_desc_ready
  bool random_events = false;             // random stat_* events in every clock, else none

  void reset() {
    Vtex_axil_config& t = *top_;
    t.s_axi_awvalid = t.s_axi_wvalid = t.s_axi_arvalid = 0;
    t.s_axi_bready = t.s_axi_rready = 0;
    t.stat_sample = t.stat_sample_error = t.stat_mem_beat = t.stat_out_stall = t.stat_mem_wait = 0;
    t.stat_req_stall = 0;
    t.stat_lookups = t.stat_misses = 0;
    top_->rst = 1;
    for (int i = 0; i < 3; ++i) edge();
    top_->rst = 0;
    ref_ = Reference{};
  }
  // Runs the queued operations to completion (both channels at once); results in order. Stops at
  // the first failure (a broken handshake would otherwise fail in every clock from then on).
  void run() {
    for (int guard = 0; guard < 100000 && busy(); ++guard) {
      if (::testing::Test::HasFailure()) return;
      clock();
    }
    EXPECT_FALSE(busy()) << "transactions did not finish";
  }
  void queue_write(const WriteOp& op) { writes_.push_back(op); }
  void queue_read(const ReadOp& op) { reads_.push_back(op); }
  // One write or read alone; a response of 0xFFFFFFFF when it never came.
  uint32_t write(uint32_t addr, uint32_t data, uint8_t strb = 0xF) {
    const size_t n = bresps.size();
    queue_write({addr, data, strb});
    run();
    return bresps.size() > n ? bresps.back() : ~0u;
  }
  ReadResult read(uint32_t addr) {
    const size_t n = rresults.size();
    queue_read({addr});
    run();
    return rresults.size() > n ? rresults.back() : ReadResult{~0u, ~0u};
  }
  void idle(int clocks) {
    for (int i = 0; i < clocks && !::testing::Test::HasFailure(); ++i) clock();
  }

  std::vector<uint32_t> bresps;        // every write's BRESP, in order
  std::vector<ReadResult> rresults;    // every read's RDATA, RRESP, in order
  int desc_pulses = 0;                 // clocks with cfg_desc_we high
  int smp_pulses = 0;                  // clocks with cfg_smp_we high
  const Reference& ref() const { return ref_; }
  Vtex_axil_config& top() { return *top_; }

  // Sets counter i (the RTL's and the reference's) to v: a test of the 64-bit read latch.
  void preload_counter(int i, uint64_t v) {
    auto& cnt = top_->rootp->tex_axil_config__DOT__cnt;
    cnt[2 * i] = uint32_t(v);
    cnt[2 * i + 1] = uint32_t(v >> 32);
    ref_.counters[i] = v;
  }

 private:
  struct WriteState {
    bool active = false, aw_done = false, w_done = false;
    int wait = 0;  // clocks before the next half may be presented
    WriteOp op;
  };
  struct ReadState {
    bool active = false, ar_done = false;
    int wait = 0;
    ReadOp op;
  };

  bool busy() const {
    return !writes_.empty() || !reads_.empty() || w_.active || r_.active || b_owed_ || r_owed_;
  }
  bool coin(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  uint32_t junk() { return uint32_t(rng_()); }

  void edge() {  // a clock without the monitor (reset)
    top_->clk = 0;
    top_->eval();
    top_->clk = 1;
    top_->eval();
  }

  // One clock: the master's pins, the monitor's checks before and after the edge.
  void clock() {
    // ---- the master: start operations, present valids (held until taken), junk otherwise. The
    // next operation starts as soon as the previous one's addresses are taken, so its valids wait
    // while the previous response is owed (and stalled).
    if (!w_.active && !writes_.empty()) {
      w_ = {true, false, false, writes_.front().delay, writes_.front()};
      writes_.pop_front();
    }
    if (!r_.active && !reads_.empty()) {
      r_ = {true, false, reads_.front().delay, reads_.front()};
      reads_.pop_front();
    }
    bool awvalid = false, wvalid = false, arvalid = false;
    if (w_.active && w_.wait == 0) {
      const auto o = w_.op.order;
      awvalid = !w_.aw_done && (o != WriteOp::kWFirst || w_.w_done);
      wvalid = !w_.w_done && (o != WriteOp::kAwFirst || w_.aw_done);
    }
    if (r_.active && r_.wait == 0) arvalid = !r_.ar_done;
    if (w_.wait > 0) --w_.wait;
    if (r_.wait > 0) --r_.wait;
    Vtex_axil_config& t = *top_;
    t.s_axi_awvalid = awvalid;
    t.s_axi_awaddr = awvalid ? w_.op.addr : junk() & ((1u << kAddrW) - 1);
    t.s_axi_awprot = junk() & 7;
    t.s_axi_wvalid = wvalid;
    t.s_axi_wdata = wvalid ? w_.op.data : junk();
    t.s_axi_wstrb = wvalid ? w_.op.strb : junk() & 15;
    t.s_axi_arvalid = arvalid;
    t.s_axi_araddr = arvalid ? r_.op.addr : junk() & ((1u << kAddrW) - 1);
    t.s_axi_arprot = junk() & 7;
    t.s_axi_bready = coin(bready_p);
    t.s_axi_rready = coin(rready_p);
    t.cfg_desc_ready = coin(desc_ready_p);
    Events ev;
    if (random_events) {
      ev.sample = coin(0.5);
      ev.sample_error = ev.sample && coin(0.1);
      ev.lookups = uint8_t(rng_() % 9);
      ev.misses = uint8_t(rng_() % (ev.lookups + 1));
      ev.mem_beat = coin(0.3);
      ev.out_stall = coin(0.2);
      ev.mem_wait = coin(0.3);
      ev.req_stall = coin(0.2);
    }
    t.stat_sample = ev.sample;
    t.stat_sample_error = ev.sample_error;
    t.stat_lookups = ev.lookups;
    t.stat_misses = ev.misses;
    t.stat_mem_beat = ev.mem_beat;
    t.stat_out_stall = ev.out_stall;
    t.stat_mem_wait = ev.mem_wait;
    t.stat_req_stall = ev.req_stall;
    t.clk = 0;
    t.eval();

    // ---- before the edge: the handshakes, the write and the read that happen at it
    const bool aw_take = t.s_axi_awvalid && t.s_axi_awready;
    const bool w_take = t.s_axi_wvalid && t.s_axi_wready;
    const bool ar_take = t.s_axi_arvalid && t.s_axi_arready;
    const bool b_take = t.s_axi_bvalid && t.s_axi_bready;
    const bool r_take = t.s_axi_rvalid && t.s_axi_rready;
    // one transaction per channel: no address or data taken while one is held or answered
    if (b_owed_ || (w_.active && w_.aw_done)) { EXPECT_FALSE(t.s_axi_awready) << "AWREADY with a write open"; }
    if (b_owed_ || (w_.active && w_.w_done)) { EXPECT_FALSE(t.s_axi_wready) << "WREADY with a write open"; }
    if (r_owed_) { EXPECT_FALSE(t.s_axi_arready) << "ARREADY with an R response owed"; }
    // (a DESC_COMMIT waits, held, while the unit is not ready or the last commit's pulse is out)
    const bool commit_waits = (w_.op.addr & ((1u << kAddrW) - 4)) == kDescCommit && (!t.cfg_desc_ready || t.cfg_desc_we);
    const bool writes_now = w_.active && (w_.aw_done || aw_take) && (w_.w_done || w_take) && !commit_waits;
    const bool desc_ready = t.cfg_desc_ready;
    uint32_t want_bresp = 0;
    if (writes_now) {
      EXPECT_FALSE(b_owed_) << "a write taken while the previous one's B is owed";
      want_bresp = ref_.write_resp(w_.op.addr, w_.op.data, w_.op.strb);
    }
    Reference::Snap snap;
    ReadResult want_r;
    if (ar_take) std::tie(want_r.data, want_r.resp) = ref_.read(r_.op.addr, snap);
    const bool b_stall = t.s_axi_bvalid && !t.s_axi_bready;
    const bool r_stall = t.s_axi_rvalid && !t.s_axi_rready;
    const uint32_t bresp_q = t.s_axi_bresp, rdata_q = t.s_axi_rdata, rresp_q = t.s_axi_rresp;
    if (b_take) {
      EXPECT_TRUE(b_owed_) << "a B response without a write";
      bresps.push_back(t.s_axi_bresp);
      b_owed_.reset();
    }
    if (r_take) {
      EXPECT_TRUE(r_owed_) << "an R response without a read";
      rresults.push_back({t.s_axi_rdata, t.s_axi_rresp});
      r_owed_.reset();
    }
    const WriteOp wop = w_.op;
    const ReadOp rop = r_.op;
    if (aw_take) {
      w_.aw_done = true;
      if (w_.op.order == WriteOp::kAwFirst) w_.wait = w_.op.gap;
    }
    if (w_take) {
      w_.w_done = true;
      if (w_.op.order == WriteOp::kWFirst) w_.wait = w_.op.gap;
    }
    if (writes_now) {
      b_owed_ = w_.op;
      w_.active = false;
    }
    if (ar_take) {
      r_owed_ = r_.op;
      r_.active = false;
    }

    t.clk = 1;
    t.eval();

    // ---- after the edge: responses, held responses, the reference's new state, the pins
    if (b_stall) {
      EXPECT_TRUE(t.s_axi_bvalid && t.s_axi_bresp == bresp_q) << "a stalled B response dropped or changed";
    } else if (writes_now) {
      EXPECT_TRUE(t.s_axi_bvalid) << "no B response after the write's edge";
      EXPECT_EQ(t.s_axi_bresp, want_bresp) << "BRESP of the write of " << std::hex << wop.data << " to " << wop.addr
                                           << " strobes " << int(wop.strb);
    } else {
      EXPECT_FALSE(t.s_axi_bvalid) << "a B response without a write";
    }
    if (r_stall) {
      EXPECT_TRUE(t.s_axi_rvalid && t.s_axi_rdata == rdata_q && t.s_axi_rresp == rresp_q)
          << "a stalled R response dropped or changed";
    } else if (ar_take) {
      EXPECT_TRUE(t.s_axi_rvalid) << "no R response after the read's edge";
      EXPECT_EQ(t.s_axi_rresp, want_r.resp) << "RRESP of the read of " << std::hex << rop.addr;
      EXPECT_EQ(t.s_axi_rdata, want_r.data) << "RDATA of the read of " << std::hex << rop.addr;
    } else {
      EXPECT_FALSE(t.s_axi_rvalid) << "an R response without a read";
    }
    const bool write_ok = writes_now && want_bresp == kOkay;
    const uint32_t wreg = wop.addr & ~3u;
    const bool clear = write_ok && wreg == kControl && (wop.data & 4);
    const bool commit = write_ok && wreg == kDescCommit;
    const bool smp_commit = write_ok && wreg == kSmpCommit;
    ref_.count(clear, ev);  // (with CONTROL's freeze bit of before the edge)
    if (write_ok) ref_.apply_write(wop.addr, wop.data);
    if (clear) ref_.snap_valid = false;
    else if (snap.set) ref_.snap_valid = true, ref_.snap_idx = snap.idx, ref_.snap_hi = snap.hi;
    else if (snap.consume) ref_.snap_valid = false;
    EXPECT_EQ(bool(t.cfg_desc_we), commit) << "cfg_desc_we is the clock after an accepted DESC_COMMIT";
    if (t.cfg_desc_we) { EXPECT_TRUE(desc_ready) << "cfg_desc_we after a clock with cfg_desc_ready low"; }
    desc_pulses += t.cfg_desc_we;
    EXPECT_EQ(bool(t.cfg_smp_we), smp_commit) << "cfg_smp_we is the clock after an accepted SMP_COMMIT";
    smp_pulses += t.cfg_smp_we;
    check_pins();
  }

  void check_pins() {
    const Vtex_axil_config& t = *top_;
    const Reference& r = ref_;
    EXPECT_EQ(bool(t.unit_rst), bool(r.control & 1));
    EXPECT_EQ(t.cfg_desc_index, r.desc_index);
    EXPECT_EQ(t.cfg_desc_base, r.desc_base);
    EXPECT_EQ(t.cfg_desc_w, r.desc_size & 0x3FFF);
    EXPECT_EQ(t.cfg_desc_h, (r.desc_size >> 16) & 0x3FFF);
    EXPECT_EQ(t.cfg_smp_index, r.smp_index);
    EXPECT_EQ(t.cfg_smp_wrap_u, r.wrap & 7);
    EXPECT_EQ(t.cfg_smp_wrap_v, (r.wrap >> 4) & 7);
    EXPECT_EQ(t.cfg_desc_format, (r.desc_attr >> 16) & 31);
    EXPECT_EQ(t.cfg_desc_last_level, (r.desc_attr >> 8) & 15);
    EXPECT_EQ(t.cfg_desc_srgb, (r.desc_attr >> 21) & 1);
    EXPECT_EQ(t.cfg_desc_cube, (r.desc_attr >> 22) & 1);
    EXPECT_EQ(t.cfg_desc_layers_m1, (r.desc_attr >> 24) & 255);
    EXPECT_EQ(t.cfg_smp_border_rgba, uint64_t(r.border_rg) | uint64_t(r.border_ba) << 32);
    EXPECT_EQ(t.cfg_smp_min_linear, r.filter & 1);
    EXPECT_EQ(t.cfg_smp_mag_linear, (r.filter >> 1) & 1);
    EXPECT_EQ(t.cfg_smp_mip_mode, (r.filter >> 4) & 3);
    EXPECT_EQ(t.cfg_smp_max_aniso_m1, (r.filter >> 8) & 15);
    EXPECT_EQ(t.cfg_smp_aniso_pow2, (r.filter >> 12) & 1);
    EXPECT_EQ(t.cfg_smp_unnormalized, (r.filter >> 13) & 1);
    EXPECT_EQ(t.cfg_smp_reduction, (r.filter >> 14) & 3);
    EXPECT_EQ(t.cfg_smp_compare_op, (r.filter >> 16) & 7);
    EXPECT_EQ(t.cfg_smp_lod_bias, r.lod_bias);
    EXPECT_EQ(t.cfg_smp_min_lod, r.min_lod);
    EXPECT_EQ(t.cfg_smp_max_lod, r.max_lod);
    EXPECT_EQ(t.cfg_block_morton, r.cache & 1);
    EXPECT_EQ(t.cfg_log2_sets, (r.cache >> 8) & 31);
    EXPECT_EQ(t.cfg_log2_ways, (r.cache >> 16) & 3);
    EXPECT_EQ(t.cfg_fifo_limit, r.fifo_limit);
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtex_axil_config> top_;
  std::mt19937_64 rng_;
  Reference ref_;
  std::deque<WriteOp> writes_;
  std::deque<ReadOp> reads_;
  WriteState w_;                   // the write whose AW and W are being presented
  ReadState r_;                    // the read whose AR is being presented
  std::optional<WriteOp> b_owed_;  // the write whose B is owed
  std::optional<ReadOp> r_owed_;   // the read whose R is owed
};

// Every readable word of the map, for before/after comparisons.
inline std::vector<uint32_t> defined_registers() {
  std::vector<uint32_t> a = {kId, kVersion, kCaps0, kCaps1};
  a.insert(a.end(), kWritable.begin(), kWritable.end());
  return a;
}

}  // namespace axil_harness

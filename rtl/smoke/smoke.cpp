// Smoke test of tex_unit (not the project's lockstep verification, which lives in sim/rtl and
// tests/rtl): random textures, configurations, requests, input gaps and output stalls; every
// response is checked against the model's stage functions (model/stages.h) and its tag order.
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <random>
#include <vector>

#include "Vtex_unit.h"
#include "stages.h"
#include "verilated.h"

using namespace tex;

struct Req {
  int32_t u, v, lod;
  uint32_t tag;
};

static const int kMaxW = MAXW, kMaxH = MAXH, kCw = CWBITS;

int main(int argc, char** argv) {
  Verilated::commandArgs(argc, argv);
  const unsigned seed = argc > 1 ? unsigned(atoi(argv[1])) : 1;
  std::mt19937 rng(seed);
  auto rnd = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  Vtex_unit top;
  uint64_t cycle = 0;
  auto tick = [&] {
    top.clk = 0;
    top.eval();
    top.clk = 1;
    top.eval();
    ++cycle;
  };
  top.rst = 1;
  top.req_valid = 0;
  top.rsp_ready = 0;
  top.wr_en = 0;
  tick();
  tick();
  top.rst = 0;

  // Latency: one request into an idle unit with rsp_ready high (texture content irrelevant).
  {
    top.cfg_log2_w = 0;
    top.cfg_log2_h = 0;
    top.cfg_mip_mode = 0;
    top.rsp_ready = 1;
    top.req_valid = 1;
    top.req_tag = 77;
    int clocks = 0;
    tick();  // the edge that accepts the request (req_ready is high when idle)
    top.req_valid = 0;
    while (!top.rsp_valid && clocks < 100) {
      tick();
      ++clocks;
    }
    printf("latency: rsp_valid %d clocks after the accepting edge (tag %u)\n", clocks + 1, unsigned(top.rsp_tag));
    tick();
  }
  // Throughput: requests always offered, rsp_ready random 50%: responses must equal the number of
  // cycles with rsp_valid && rsp_ready, and rsp_valid must never drop once the pipe is full.
  {
    long ready_cycles = 0, delivered = 0, idle_with_ready = 0;
    top.req_valid = 1;
    for (int c = 0; c < 20000; ++c) {
      top.rsp_ready = rnd(0, 1);
      top.clk = 0;
      top.eval();
      if (c > 50) {
        ready_cycles += top.rsp_ready;
        delivered += top.rsp_valid && top.rsp_ready;
        idle_with_ready += !top.rsp_valid;
      }
      top.clk = 1;
      top.eval();
      ++cycle;
    }
    top.rsp_ready = 1;
    top.clk = 0;
    top.eval();
    while (!top.req_ready) tick();  // a valid request may only be withdrawn after its handshake
    tick();
    top.req_valid = 0;
    for (int c = 0; c < 40; ++c) tick();
    printf("throughput: %ld responses in %ld rsp_ready cycles (%ld cycles without rsp_valid)\n", delivered,
           ready_cycles, idle_with_ready);
    if (delivered != ready_cycles || idle_with_ready) return 1;
  }

  long checked = 0, errors = 0;
  const uint64_t chan_mask = (uint64_t(1) << kCw) - 1;
  for (int round = 0; round < 40; ++round) {
    const int lw0 = rnd(0, kMaxW), lh0 = rnd(0, kMaxH), q = std::max(lw0, lh0);
    const Wrap wu = Wrap(rnd(0, 2)), wv = Wrap(rnd(0, 2));
    const TexelFilter tf = TexelFilter(rnd(0, 1));
    const MipMode mip = MipMode(rnd(0, 2));
    const int bias = rnd(-300, 300), min_lod = rnd(-600, 200), max_lod = rnd(min_lod, 4000);
    // Random texels per level (the unit does not care whether the pyramid is a box filter).
    std::vector<std::vector<uint64_t>> tex(q + 1);
    for (int k = 0; k <= q; ++k) {
      const int w = 1 << std::max(lw0 - k, 0), h = 1 << std::max(lh0 - k, 0);
      tex[k].resize(size_t(w) * h);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          uint64_t t = 0;
          for (int c = 0; c < 4; ++c) t |= (uint64_t(rng()) & chan_mask) << (c * kCw);
          if (rnd(0, 7) == 0) t = rnd(0, 1) ? 0 : (~uint64_t(0) >> (64 - 4 * kCw));  // extremes
          tex[k][size_t(y) * w + x] = t;
          top.wr_en = 1;
          top.wr_level = k;
          top.wr_x = x;
          top.wr_y = y;
          top.wr_data = t;
          tick();
        }
    }
    top.wr_en = 0;
    top.cfg_log2_w = lw0;
    top.cfg_log2_h = lh0;
    top.cfg_wrap_u = uint8_t(wu);
    top.cfg_wrap_v = uint8_t(wv);
    top.cfg_texel_linear = tf == TexelFilter::Linear;
    top.cfg_mip_mode = uint8_t(mip);
    top.cfg_lod_bias = uint16_t(bias);
    top.cfg_min_lod = uint16_t(min_lod);
    top.cfg_max_lod = uint16_t(max_lod);

    auto expect = [&](const Req& r) {
      const int32_t lod = stage::bias_and_clamp(r.lod, bias, min_lod, max_lod);
      const stage::LevelSelect s = stage::select_levels(lod, mip, q);
      int64_t bil[2][4];
      for (int l = 0; l < 2; ++l) {
        const int k = l == 0 ? s.d : s.d1;
        const int lw = std::max(lw0 - k, 0), lh = std::max(lh0 - k, 0);
        const auto tu = stage::axis_taps(r.u, lw, tf), tv = stage::axis_taps(r.v, lh, tf);
        const int x0 = stage::wrap_index(tu.i0, lw, wu), x1 = stage::wrap_index(tu.i1, lw, wu);
        const int y0 = stage::wrap_index(tv.i0, lh, wv), y1 = stage::wrap_index(tv.i1, lh, wv);
        auto T = [&](int x, int y, int c) { return int64_t((tex[k][(size_t(y) << lw) + x] >> (c * kCw)) & chan_mask); };
        for (int c = 0; c < 4; ++c)
          bil[l][c] = stage::bilerp(T(x0, y0, c), T(x1, y0, c), T(x0, y1, c), T(x1, y1, c), tu.w, tv.w);
      }
      uint64_t px = 0;
      for (int c = 0; c < 4; ++c)
        px |= uint64_t(stage::blend_and_round(bil[0][c], s.two_levels ? bil[1][c] : bil[0][c], s.f)) << (c * kCw);
      return px;
    };

    std::deque<Req> inflight;
    const int n = 3000;
    int sent = 0;
    Req cur{};
    bool have = false;
    const int gap_pct = rnd(0, 2) * 30, stall_pct = rnd(0, 2) * 35;
    const uint64_t start = cycle;
    uint64_t first_accept = 0, first_rsp = 0;
    while ((sent < n || !inflight.empty()) && cycle - start < 100000) {
      if (!have && sent < n && rnd(0, 99) >= gap_pct) {
        const int span = rnd(0, 3);
        auto coord = [&] {
          if (span == 0) return int32_t(rng());  // the whole Q8.24 range
          return int32_t(rnd(-(2 << 24), 3 << 24));
        };
        cur = {coord(), coord(), rnd(0, 9) == 0 ? int32_t(int16_t(rng())) : rnd(-512, (q + 2) * 256), uint32_t(sent)};
        have = true;
      }
      top.req_valid = have;
      top.req_u = uint32_t(cur.u);
      top.req_v = uint32_t(cur.v);
      top.req_lod = uint16_t(cur.lod);
      top.req_tag = cur.tag & 0xffff;
      top.rsp_ready = rnd(0, 99) >= stall_pct;
      top.clk = 0;
      top.eval();
      const bool accept = top.req_valid && top.req_ready;
      const bool deliver = top.rsp_valid && top.rsp_ready;
      if (deliver) {
        if (inflight.empty()) {
          printf("seed %u round %d: response without request\n", seed, round);
          return 1;
        }
        const Req r = inflight.front();
        inflight.pop_front();
        const uint64_t want = expect(r);
        if (top.rsp_tag != (r.tag & 0xffff) || uint64_t(top.rsp_rgba) != want) {
          if (errors++ < 10)
            printf("seed %u round %d: tag %u (want %u) rgba %llx want %llx u=%d v=%d lod=%d cfg lw=%d lh=%d wrap=%d,%d tf=%d mip=%d bias=%d min=%d max=%d\n",
                   seed, round, unsigned(top.rsp_tag), r.tag & 0xffff, (unsigned long long)top.rsp_rgba,
                   (unsigned long long)want, r.u, r.v, r.lod, lw0, lh0, int(wu), int(wv), int(tf), int(mip), bias,
                   min_lod, max_lod);
        }
        ++checked;
        if (checked == 1 && round == 0) first_rsp = cycle;
      }
      if (accept) {
        if (sent == 0 && round == 0) first_accept = cycle;
        inflight.push_back(cur);
        ++sent;
        have = false;
      }
      top.clk = 1;
      top.eval();
      ++cycle;
    }
    if (sent < n || !inflight.empty()) {
      printf("seed %u round %d: time-out, %zu in flight\n", seed, round, inflight.size());
      return 1;
    }
    if (getenv("SMOKE_VERBOSE"))
      printf("round %d lw=%d lh=%d wrap=%d,%d tf=%d mip=%d bias=%d min=%d max=%d: errors so far %ld\n", round, lw0, lh0,
             int(wu), int(wv), int(tf), int(mip), bias, min_lod, max_lod, errors);
    if (round == 0 && gap_pct == 0 && stall_pct == 0)
      printf("latency (accept edge -> rsp seen): %llu clocks\n", (unsigned long long)(first_rsp - first_accept));
  }
  printf("smoke MAX %dx%d CW %d seed %u: %ld responses checked, %ld mismatches\n", kMaxW, kMaxH, kCw, seed, checked, errors);
  return errors ? 1 : 0;
}

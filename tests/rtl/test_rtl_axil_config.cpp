// The AXI4-Lite configuration slave tex_axil_config (rtl/tex_axil_config.sv) on its own, Verilated
// with the parameters below (tests/rtl/CMakeLists.txt), against a reference of the register map of
// docs/rtl-interface.md ("AXI4-Lite configuration (tex_unit_axi)").
//
// A clocked master drives both channels at once (AW before W, W before AW or together, with gaps;
// random BREADY and RREADY) and junk on every payload while its valid is low. In every clock a
// monitor checks the slave against the reference: each write's BRESP and each read's RDATA/RRESP
// (computed from the reference state at the handshake edge), a stalled B or R held with its
// payload, no response without a request, AWREADY/WREADY/ARREADY low while a response waits,
// every cfg_* pin and unit_rst equal to the reference registers, cfg_desc_we (cfg_smp_we) exactly
// in the clock after each accepted DESC_COMMIT (SMP_COMMIT) — a DESC_COMMIT held while the unit's
// cfg_desc_ready (random here) is low or a pulse is on the pins — and the counters (events registered, counted a clock later;
// clear, freeze, the LO-then-HI latch) through every counter read.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "axil_config_harness.h"

namespace {

using namespace axil_harness;

TEST(RtlAxilConfig, IdVersionCapabilitiesAndResetValues) {
  Slave s(1);
  EXPECT_EQ(s.read(kId).data, 0x54455855u);  // "TEXU"
  EXPECT_EQ(s.read(kVersion).data, 0x00030007u);
  EXPECT_EQ(s.read(kCaps0).data, uint32_t(10 | 9 << 4 | 8 << 8 | 1 << 16 | 1 << 17 | 1 << 18 | 4 << 20));
  EXPECT_EQ(s.read(kCaps1).data, uint32_t(8 | 4 << 8 | 8 << 16 | 6 << 24 | 4 << 28));
  // reset: the unit held in reset, the whole cache of 4 ways, trilinear, no LOD clamp
  EXPECT_EQ(s.read(kControl).data, 1u);
  EXPECT_TRUE(s.top().unit_rst);
  EXPECT_EQ(s.read(kCache).data, (2u << 16) | (6u << 8));
  EXPECT_EQ(s.read(kFilter).data, 0x30023u);  // (compare op LESS_OR_EQUAL)
  EXPECT_EQ(s.read(kMinLod).data, 0x8000u);
  EXPECT_EQ(s.read(kMaxLod).data, 0x7FFFu);
  for (uint32_t a : defined_registers()) EXPECT_EQ(s.read(a).resp, kOkay) << std::hex << a;
  for (const ReadResult& r : s.rresults) EXPECT_EQ(r.resp, kOkay);
}

TEST(RtlAxilConfig, EveryRegisterWrittenAndReadBack) {
  Slave s(2);
  std::mt19937_64 rng(2);
  for (int round = 0; round < 20; ++round) {
    // the cache geometry while the unit is in reset (any valid one), then the rest with it running
    const uint32_t ways = rng() % 3, sets = 2 + rng() % (7 - ways);
    ASSERT_EQ(s.write(kControl, 1), kOkay);
    ASSERT_EQ(s.write(kCache, ways << 16 | sets << 8 | (rng() & 1)), kOkay);
    ASSERT_EQ(s.write(kControl, round & 1 ? 0 : 2), kOkay);  // running (sometimes frozen counters)
    for (uint32_t a : kWritable) {
      if (a == kCache || a == kControl) continue;
      uint32_t d = uint32_t(rng());
      if (a == kDescCommit) {  // a valid descriptor: RGBA, line-aligned base
        ASSERT_EQ(s.write(kDescAttr, 0), kOkay);
        ASSERT_EQ(s.write(kDescSize, uint32_t(1 + rng() % 512) << 16 | uint32_t(1 + rng() % 1024)), kOkay);
        ASSERT_EQ(s.write(kDescBase, uint32_t(rng()) & ~63u), kOkay);
        d = (d & ~15u) | uint32_t(rng() % kTextures);
      }
      if (a == kSmpCommit) {  // a valid sampler: address modes 0..4, mip mode 0..2, reduction 0..2
        ASSERT_EQ(s.write(kWrap, uint32_t(rng() % 5) << 4 | uint32_t(rng() % 5)), kOkay);
        ASSERT_EQ(s.write(kFilter, (uint32_t(rng()) & 0x1F03) | uint32_t(rng() % 3) << 4 | uint32_t(rng() % 3) << 14), kOkay);
        d = (d & ~15u) | uint32_t(rng() % kSamplers);
      }
      ASSERT_EQ(s.write(a, d), kOkay) << std::hex << a;
    }
    for (uint32_t a : defined_registers()) s.read(a);  // checked against the reference by the monitor
  }
  EXPECT_EQ(s.desc_pulses, 20);
  EXPECT_EQ(s.smp_pulses, 20);
}

TEST(RtlAxilConfig, ErrorsAnswerSlverrAndChangeNothing) {
  Slave s(3);
  std::mt19937_64 rng(3);
  // something other than the reset values in every register first
  ASSERT_EQ(s.write(kCache, 1u << 16 | 3u << 8 | 1u), kOkay);
  ASSERT_EQ(s.write(kControl, 0), kOkay);
  for (uint32_t a : {kFifoLimit, kFilter, kLodBias, kMinLod, kMaxLod, kDescBase}) ASSERT_EQ(s.write(a, 0x1240), kOkay);
  const Reference before = s.ref();
  const int pulses = s.desc_pulses, smp_pulses = s.smp_pulses;
  auto unchanged = [&](const char* what) {
    const Reference& r = s.ref();
    EXPECT_TRUE(r.control == before.control && r.cache == before.cache && r.fifo_limit == before.fifo_limit &&
                r.filter == before.filter && r.lod_bias == before.lod_bias && r.min_lod == before.min_lod &&
                r.max_lod == before.max_lod && r.desc_base == before.desc_base && r.desc_attr == before.desc_attr &&
                r.desc_index == before.desc_index && r.border_rg == before.border_rg && r.border_ba == before.border_ba &&
                r.wrap == before.wrap && r.smp_index == before.smp_index)
        << what;
    EXPECT_EQ(s.desc_pulses, pulses) << what;
    EXPECT_EQ(s.smp_pulses, smp_pulses) << what;
  };
  // undefined and read-only words of the whole 4 KiB window: writes SLVERR, undefined reads SLVERR
  // with data 0 (the monitor checks the pins every clock, and every read against the reference)
  for (uint32_t a = 0; a < (1u << kAddrW); a += 4) {
    const bool writable = std::find(kWritable.begin(), kWritable.end(), a) != kWritable.end();
    if (writable) continue;
    EXPECT_EQ(s.write(a | (rng() & 3), uint32_t(rng())), kSlverr) << std::hex << a;
    const ReadResult r = s.read(a);
    const bool readable = a < 0x10 || (a >= kCounterBase && a < kCounterBase + 8 * kCounters);
    EXPECT_EQ(r.resp, readable ? kOkay : kSlverr) << std::hex << a;
    if (!readable) { EXPECT_EQ(r.data, 0u) << std::hex << a; }
  }
  unchanged("undefined and read-only addresses");
  // partial strobes on every register (a write is of all 4 bytes)
  for (uint32_t a : kWritable)
    for (uint8_t strb = 0; strb < 15; ++strb) EXPECT_EQ(s.write(a, uint32_t(rng()), strb), kSlverr);
  unchanged("partial strobes");
  // CACHE while the unit runs; then in reset, geometries the caches lack
  EXPECT_EQ(s.write(kCache, 1u << 16 | 4u << 8), kSlverr);
  unchanged("CACHE while running");
  ASSERT_EQ(s.write(kControl, 1), kOkay);
  const Reference in_reset = s.ref();
  for (uint32_t g : {3u << 16 | 3u << 8, 0u << 16 | 1u << 8, 0u << 16 | 9u << 8, 2u << 16 | 7u << 8, 1u << 16 | 31u << 8})
    EXPECT_EQ(s.write(kCache, g), kSlverr) << std::hex << g;
  EXPECT_EQ(s.ref().cache, in_reset.cache);
  // DESC_COMMIT while in reset (the unit drops cfg_desc_we under rst) and of invalid descriptors
  EXPECT_EQ(s.write(kDescCommit, 1), kSlverr);
  ASSERT_EQ(s.write(kControl, 0), kOkay);
  // (format 6, 15 and 30, 31 are none; sRGB BC4, BC5 and EAC (11..14) do not exist)
  const uint32_t bad_attr[] = {6u << 16,  15u << 16, 30u << 16, 31u << 16, 1u << 21 | 4u << 16, 1u << 21 | 5u << 16,
                               1u << 21 | 11u << 16, 1u << 21 | 14u << 16};
  for (uint32_t attr : bad_attr) {
    ASSERT_EQ(s.write(kDescAttr, attr), kOkay);
    EXPECT_EQ(s.write(kDescCommit, 2), kSlverr) << std::hex << attr;
  }
  ASSERT_EQ(s.write(kDescAttr, 0x204335), kOkay);  // sRGB RGBA (bits 15:0 reserved, ignored): valid
  // sizes 0 and beyond the largest (1024 x 512 here; 14 bits each, bits 15:14 ignored)
  for (uint32_t size : {0u, 5u, 1u << 16, 1025u | 1u << 16, 1u | 513u << 16, 0xC000u | 1u << 16}) {
    ASSERT_EQ(s.write(kDescSize, size), kOkay);
    EXPECT_EQ(s.write(kDescCommit, 2), kSlverr) << std::hex << size;
  }
  ASSERT_EQ(s.write(kDescSize, 1000u | 37u << 16), kOkay);  // any size up to the largest
  EXPECT_EQ(s.write(kDescCommit, kTextures), kSlverr);  // index beyond the table
  ASSERT_EQ(s.write(kDescBase, 0x1000 + 32), kOkay);     // not line-aligned
  EXPECT_EQ(s.write(kDescCommit, 2), kSlverr);
  EXPECT_EQ(s.desc_pulses, pulses);
  ASSERT_EQ(s.write(kDescBase, 0x1000), kOkay);
  EXPECT_EQ(s.write(kDescCommit, 2), kOkay);
  EXPECT_EQ(s.desc_pulses, pulses + 1);
  // SMP_COMMIT of samplers the unit cannot take: address modes 5..7, mip mode 3, an entry beyond
  // the table; in reset (the pulse would be lost)
  ASSERT_EQ(s.write(kFilter, 0x23), kOkay);
  for (uint32_t w : {5u, 6u << 4, 7u, 7u << 4 | 7u}) {
    ASSERT_EQ(s.write(kWrap, w), kOkay);
    EXPECT_EQ(s.write(kSmpCommit, 1), kSlverr) << std::hex << w;
  }
  ASSERT_EQ(s.write(kWrap, 4u << 4 | 3u), kOkay);  // mirror-clamp / border: valid
  ASSERT_EQ(s.write(kFilter, 0x33), kOkay);        // mip mode 3
  EXPECT_EQ(s.write(kSmpCommit, 1), kSlverr);
  // Unnormalized coordinates (FILTER bit 13) only as Vulkan allows them; reductions 0..2 (bits 14-15)
  ASSERT_EQ(s.write(kMaxLod, 0x0100), kOkay);  // 1.0
  const uint32_t kUnnorm = 1u << 13;
  struct Case { uint32_t wrap, filter; bool ok; const char* what; };
  for (const Case& c : {Case{0x11, kUnnorm | 0x03, true, "clamp, linear, mip none"},
                        Case{0x33, kUnnorm | 0x00, true, "border, nearest, mip none"},
                        Case{0x13, kUnnorm | 0x13, false, "mip nearest with max LOD 1"},
                        Case{0x10, kUnnorm | 0x03, false, "repeat"},
                        Case{0x21, kUnnorm | 0x03, false, "mirror"},
                        Case{0x41, kUnnorm | 0x03, false, "mirror-clamp"},
                        Case{0x11, kUnnorm | 0x01, false, "min linear, mag nearest"},
                        Case{0x11, kUnnorm | 0x103, false, "anisotropic"},
                        Case{0x10, 0x03, true, "normalized repeat"},
                        Case{0x10, 2u << 14 | 0x23, true, "max reduction"},
                        Case{0x10, 3u << 14 | 0x23, false, "reduction 3 (none)"}}) {
    ASSERT_EQ(s.write(kWrap, c.wrap), kOkay);
    ASSERT_EQ(s.write(kFilter, c.filter), kOkay);
    EXPECT_EQ(s.write(kSmpCommit, 1), c.ok ? kOkay : kSlverr) << c.what;
  }
  ASSERT_EQ(s.write(kMaxLod, 0), kOkay);  // mip nearest reads level 0 only with max LOD 0 (Vulkan's rule)
  ASSERT_EQ(s.write(kWrap, 0x13), kOkay);
  ASSERT_EQ(s.write(kFilter, kUnnorm | 0x13), kOkay);
  EXPECT_EQ(s.write(kSmpCommit, 1), kOkay);
  const int unnormalized_pulses = 5;  // the OKAY commits above
  ASSERT_EQ(s.write(kWrap, 4u << 4 | 3u), kOkay);
  ASSERT_EQ(s.write(kFilter, 0x23), kOkay);
  EXPECT_EQ(s.write(kSmpCommit, kSamplers), kSlverr);
  ASSERT_EQ(s.write(kControl, 1), kOkay);
  EXPECT_EQ(s.write(kSmpCommit, 1), kSlverr);
  ASSERT_EQ(s.write(kControl, 0), kOkay);
  EXPECT_EQ(s.smp_pulses, smp_pulses + unnormalized_pulses);
  EXPECT_EQ(s.write(kSmpCommit, kSamplers - 1), kOkay);
  EXPECT_EQ(s.smp_pulses, smp_pulses + unnormalized_pulses + 1);
}

TEST(RtlAxilConfig, WriteChannelInEitherOrder) {
  Slave s(4);
  std::mt19937_64 rng(4);
  for (auto order : {WriteOp::kTogether, WriteOp::kAwFirst, WriteOp::kWFirst})
    for (int gap = 0; gap < 5; ++gap)
      for (int delay = 0; delay < 3; ++delay) {
        WriteOp op{kLodBias, uint32_t(rng()) & 0xFFFF, 0xF, order, gap, delay};
        s.queue_write(op);
        s.run();
        EXPECT_EQ(s.bresps.back(), kOkay);
        EXPECT_EQ(s.read(kLodBias).data, op.data);
        EXPECT_EQ(s.top().cfg_smp_lod_bias, op.data);
      }
  EXPECT_EQ(s.bresps.size(), 45u);  // one B per write
}

TEST(RtlAxilConfig, ResponsesHeldUnderBackpressureBothChannelsAtOnce) {
  // Random reads and writes of every kind (defined, undefined, read-only, partial, commits) on both
  // channels at once, random BREADY and RREADY, random events: every response, pin and counter
  // read checked against the reference by the monitor in every clock.
  for (double p : {0.2, 0.6}) {
    Slave s(5 + uint64_t(p * 10));
    s.bready_p = p;
    s.rready_p = p;
    s.random_events = true;
    std::mt19937_64 rng(7);
    const std::vector<uint32_t> regs = defined_registers();
    auto any_addr = [&]() -> uint32_t {
      switch (rng() % 4) {
        case 0: return uint32_t(rng() % (1u << kAddrW));                              // anywhere
        case 1: return kCounterBase + uint32_t(rng() % (8 * kCounters + 8)) / 4 * 4;  // counters
        default: return regs[rng() % regs.size()] | uint32_t(rng() & 3);               // registers
      }
    };
    for (int i = 0; i < 3000; ++i) {
      WriteOp w;
      w.addr = any_addr();
      w.data = uint32_t(rng());
      if ((w.addr & ~3u) == kCache) w.data = uint32_t(rng() % 3) << 16 | uint32_t(rng() % 8) << 8 | (w.data & 1);
      if ((w.addr & ~3u) == kControl) w.data &= (rng() % 8 == 0) ? 7 : 3;  // a clear now and then
      if ((w.addr & ~3u) == kDescBase && rng() % 2) w.data &= ~63u;
      if ((w.addr & ~3u) == kDescAttr) w.data &= 0x3F3311u;  // (format 0..31, sRGB)
      if ((w.addr & ~3u) == kDescSize) w.data &= rng() % 2 ? 0x01FF03FFu : 0xFFFFFFFFu;  // mostly valid
      if ((w.addr & ~3u) == kWrap) w.data &= 0x33u | (rng() % 4 ? 0u : 0x44u);  // mostly valid
      if ((w.addr & ~3u) == kSmpCommit && rng() % 2) w.data &= 3u;
      w.strb = rng() % 10 == 0 ? uint8_t(rng() % 16) : 0xF;
      w.order = WriteOp::Order(rng() % 3);
      w.gap = int(rng() % 3);
      w.delay = int(rng() % 3);
      s.queue_write(w);
      s.queue_read({any_addr(), int(rng() % 3)});
      if (i % 16 == 15) s.run();
    }
    s.run();
    EXPECT_EQ(s.bresps.size(), 3000u);
    EXPECT_EQ(s.rresults.size(), 3000u);
    EXPECT_GT(s.desc_pulses, 0);
    EXPECT_GT(s.smp_pulses, 0);
  }
}

TEST(RtlAxilConfig, DescriptorCommitPulsesOnce) {
  Slave s(6);
  ASSERT_EQ(s.write(kControl, 0), kOkay);
  ASSERT_EQ(s.write(kDescBase, 0x12340040), kOkay);
  ASSERT_EQ(s.write(kDescAttr, 1u << 21 | 7u << 16), kOkay);  // BC7 sRGB
  ASSERT_EQ(s.write(kDescSize, 511u << 16 | 1000u), kOkay);
  EXPECT_EQ(s.desc_pulses, 0);
  // the pulse: exactly the clock after the commit's edge (checked by the monitor), with the staged
  // descriptor on the pins
  ASSERT_EQ(s.write(kDescCommit, 5), kOkay);
  EXPECT_EQ(s.desc_pulses, 1);
  EXPECT_EQ(s.top().cfg_desc_index, 5);
  EXPECT_EQ(s.top().cfg_desc_base, 0x12340040u);
  EXPECT_EQ(s.top().cfg_desc_format, 7);
  EXPECT_EQ(s.top().cfg_desc_srgb, 1);
  EXPECT_EQ(s.top().cfg_desc_w, 1000);
  EXPECT_EQ(s.top().cfg_desc_h, 511);
  s.idle(5);
  EXPECT_EQ(s.desc_pulses, 1);
  for (int i = 0; i < kTextures; ++i) ASSERT_EQ(s.write(kDescCommit, uint32_t(i)), kOkay);
  EXPECT_EQ(s.desc_pulses, 1 + kTextures);
}

// While tex_unit_cached sets a descriptor up (cfg_desc_ready low), a DESC_COMMIT is held: no B
// response, no pulse, however long; the other registers answer meanwhile (the read channel is
// free). When the unit is ready, the commit happens, once.
TEST(RtlAxilConfig, DescriptorCommitWaitsForTheUnit) {
  Slave s(16);
  ASSERT_EQ(s.write(kControl, 0), kOkay);
  ASSERT_EQ(s.write(kDescSize, 500u << 16 | 1000u), kOkay);
  s.desc_ready_p = 0.0;
  const size_t bresps = s.bresps.size();
  s.queue_write({kDescCommit, 3});
  s.queue_read({kDescSize});
  s.idle(200);
  EXPECT_EQ(s.bresps.size(), bresps) << "a DESC_COMMIT answered while the unit was not ready";
  EXPECT_EQ(s.desc_pulses, 0);
  ASSERT_FALSE(s.rresults.empty());
  EXPECT_EQ(s.rresults.back().data, 500u << 16 | 1000u) << "reads wait for a held commit";
  s.desc_ready_p = 1.0;
  s.run();
  ASSERT_EQ(s.bresps.size(), bresps + 1);
  EXPECT_EQ(s.bresps.back(), kOkay);
  EXPECT_EQ(s.desc_pulses, 1);
  EXPECT_EQ(s.top().cfg_desc_index, 3);
}

TEST(RtlAxilConfig, SoftResetGuardsTheCacheGeometry) {
  Slave s(7);
  EXPECT_TRUE(s.top().unit_rst);
  EXPECT_EQ(s.write(kCache, 0u << 16 | 2u << 8 | 1u), kOkay);  // direct-mapped, 4 sets, Morton
  EXPECT_EQ(s.top().cfg_log2_sets, 2);
  EXPECT_EQ(s.write(kControl, 0), kOkay);
  EXPECT_FALSE(s.top().unit_rst);
  EXPECT_EQ(s.write(kCache, 2u << 16 | 6u << 8), kSlverr);
  EXPECT_EQ(s.top().cfg_log2_sets, 2);
  EXPECT_EQ(s.write(kControl, 1), kOkay);
  EXPECT_TRUE(s.top().unit_rst);
  EXPECT_EQ(s.write(kCache, 2u << 16 | 6u << 8), kOkay);
  EXPECT_EQ(s.top().cfg_log2_ways, 2);
  // a system reset puts the unit back in reset with the reset geometry
  s.write(kControl, 0);
  s.reset();
  EXPECT_TRUE(s.top().unit_rst);
  EXPECT_EQ(s.read(kCache).data, (2u << 16) | (6u << 8));
}

TEST(RtlAxilConfig, CountersCountClearAndFreeze) {
  Slave s(8);
  s.random_events = true;
  s.idle(500);
  for (int i = 0; i < kCounters; ++i) {  // LO then HI of each, checked against the reference
    s.read(kCounterBase + 8 * i);
    s.read(kCounterBase + 8 * i + 4);
  }
  EXPECT_GT(s.ref().counters[kLookups], 500u);
  EXPECT_GT(s.ref().counters[kMemBytes], 500u * kBeatBytes / 10);
  EXPECT_LE(s.ref().counters[kMisses], s.ref().counters[kLookups]);
  // frozen: nothing moves, not even CYCLES
  ASSERT_EQ(s.write(kControl, 2), kOkay);
  const uint32_t cycles = s.read(kCounterBase + 8 * kCycles).data;
  s.idle(50);
  EXPECT_EQ(s.read(kCounterBase + 8 * kCycles).data, cycles);
  // clear (and unfreeze): every counter restarts from 0
  ASSERT_EQ(s.write(kControl, 4), kOkay);
  for (int i = 0; i < kCounters; ++i) EXPECT_LT(s.ref().counters[i], 40u * kBeatBytes) << i;
  s.random_events = false;
  ASSERT_EQ(s.write(kControl, 4), kOkay);
  s.idle(10);
  for (int i = 1; i < kCounters; ++i) EXPECT_EQ(s.read(kCounterBase + 8 * i).data, 0u) << i;
  EXPECT_GT(s.read(kCounterBase + 8 * kCycles).data, 10u);
}

TEST(RtlAxilConfig, SixtyFourBitReadIsConsistentAcrossACarry) {
  Slave s(9);
  for (int i = 0; i < kCounters; ++i) {
    // just below a carry into the HI word: the carry comes between the LO and the HI read
    s.preload_counter(i, 0x00000007FFFFFFC0ull);
    s.idle(1);
    s.random_events = true;
    const uint32_t lo = s.read(kCounterBase + 8 * i).data;
    s.idle(3000);  // events go on: the counter passes the carry
    const uint32_t hi = s.read(kCounterBase + 8 * i + 4).data;
    s.random_events = false;
    EXPECT_EQ(hi, 7u) << "counter " << i << ": the HI word latched by the LO read";
    EXPECT_GE(lo, 0xFFFFFFC0u) << i;
    EXPECT_GE(s.ref().counters[i], 0x0000000800000000ull) << "counter " << i << " did not carry";
    // a HI read without its LO read: the live word
    EXPECT_EQ(s.read(kCounterBase + 8 * i + 4).data, 8u) << i;
  }
}

}  // namespace

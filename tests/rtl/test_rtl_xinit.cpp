// Verilator is 2-state: an X becomes 0 or 1. Built with --x-assign unique --x-initial unique,
// every register without reset (and every X assignment) starts from Verilator's random seed.
// The unit must give the same pins, clock by clock, whatever those values are: after reset
// nothing may depend on them. (The 4-state check with X itself is `make xprop`, in Icarus.)
#include <gtest/gtest.h>

#include <random>

#include "lockstep.h"
#include "model/image.h"
#include "model/pyramid.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

struct Trace {
  std::vector<rtl::PinsOut> before_reset;  // outputs in the first reset clocks: the start values show
  std::vector<rtl::PinsOut> after_reset;   // every clock after the first reset: must not depend on the seed
};

// One fixed stimulus (requests, random stalls and gaps, a reset in the middle of traffic),
// clocked through a unit whose unreset registers start from `verilator_seed`.
Trace run_with_seed(uint64_t verilator_seed) {
  const rtl::RtlConfig* config = nullptr;
  for (const rtl::RtlConfig& c : rtl::compiled_configs())
    if (c.max_log2_w == 4 && c.max_log2_h == 4 && c.cw == 8) config = &c;
  rtl::DriverOptions o;
  o.seed = verilator_seed;
  auto unit = rtl::Driver::create(*config, o);
  Trace t;
  rtl::PinsIn first;  // reset held from the first clock: the data registers keep their start values
  first.rst = true;
  first.rsp_ready = false;
  for (int i = 0; i < 3; ++i) t.before_reset.push_back(unit->tick(first));

  const Pyramid pyr = build_pyramid(make_pattern("noise", 16, 16));
  unit->reset();
  unit->load(pyr, LoadMethod::Backdoor);
  std::mt19937_64 rng(99);  // the stimulus is the same for every seed
  size_t next = 0;
  for (int part = 0; part < 2; ++part) {
    for (const Filter& flt : all_filters()) {
      SamplerConfig cfg;
      cfg.filter = flt;
      cfg.wrap_u = Wrap(rng() % 3);
      cfg.wrap_v = Wrap(rng() % 3);
      unit->configure(cfg, pyr);
      const auto reqs = random_requests(rng, 4, 4, 400);
      next = 0;
      rtl::PinsIn in;
      for (int clock = 0; clock < 1200; ++clock) {
        if (!in.req_valid && next < reqs.size() && rng() % 4 != 0) {  // offered until taken
          in.req_valid = true;
          rtl::set_request_pins(in, reqs[next]);
          in.req_tag = uint16_t(next);
        }
        in.rsp_ready = rng() % 3 != 0;
        const rtl::PinsOut out = unit->tick(in);
        t.after_reset.push_back(out);
        if (in.req_valid && out.req_ready) {
          in.req_valid = false;
          ++next;
        }
      }
      if (part == 0 && flt.texel == TexelFilter::Linear) {  // reset with requests in flight
        rtl::PinsIn rst;
        rst.rst = true;
        rst.rsp_ready = false;
        t.after_reset.push_back(unit->tick(rst));
        t.after_reset.push_back(unit->tick(rst));
      }
    }
  }
  return t;
}

bool same(const rtl::PinsOut& a, const rtl::PinsOut& b) {
  // Data pins count only while their valid is high: with valid low they may hold anything.
  return a.req_ready == b.req_ready && a.rsp_valid == b.rsp_valid &&
         (!a.rsp_valid || (a.rsp_rgba == b.rsp_rgba && a.rsp_tag == b.rsp_tag));
}

}  // namespace

TEST(RtlXInitial, OutputsDoNotDependOnTheValuesOfUnresetRegisters) {
  const Trace a = run_with_seed(1), b = run_with_seed(2);
  // The seeds do give different start values (else this test could not fail): the data pins of
  // the output register, which has no reset, differ during the first reset.
  bool differ = false;
  for (size_t i = 0; i < a.before_reset.size(); ++i)
    differ |= a.before_reset[i].rsp_rgba != b.before_reset[i].rsp_rgba || a.before_reset[i].rsp_tag != b.before_reset[i].rsp_tag;
  EXPECT_TRUE(differ) << "Verilator's seed does not change the unreset registers";

  ASSERT_EQ(a.after_reset.size(), b.after_reset.size());
  size_t responses = 0;
  for (size_t i = 0; i < a.after_reset.size(); ++i) {
    ASSERT_TRUE(same(a.after_reset[i], b.after_reset[i]))
        << "clock " << i << " after reset: seed 1 gives req_ready " << a.after_reset[i].req_ready << " rsp_valid "
        << a.after_reset[i].rsp_valid << " rgba " << a.after_reset[i].rsp_rgba << ", seed 2 gives req_ready "
        << b.after_reset[i].req_ready << " rsp_valid " << b.after_reset[i].rsp_valid << " rgba "
        << b.after_reset[i].rsp_rgba;
    responses += a.after_reset[i].rsp_valid;
  }
  EXPECT_GT(responses, 4000u);
}

// The LOD unit tex_lambda (rtl/tex_lambda.sv) on its own against the model's tex_lambda
// (model/lod.cpp), bit for bit: hand-worked values, every edge of the Q8.24 format, and 1 M random
// derivative sets over every texture size, with random clock-enable stalls (the output must hold
// while en is low and follow 2 enabled clocks after its input).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "Vtex_lambda.h"
#include "model/formats.h"
#include "model/lod.h"

using namespace tex;

namespace {

struct Input {
  LodDerivatives d;
  int w = 1, h = 1;  // the level-0 size, any value 1..8192
};

class Unit {
 public:
  Unit() : ctx_(std::make_unique<VerilatedContext>()), top_(std::make_unique<Vtex_lambda>(ctx_.get())) {}
  // One clock with `in` on the pins and clock enable `en`; returns lambda after the edge.
  int32_t clock(const Input& in, bool en) {
    top_->dudx = uint32_t(in.d.dudx);
    top_->dvdx = uint32_t(in.d.dvdx);
    top_->dudy = uint32_t(in.d.dudy);
    top_->dvdy = uint32_t(in.d.dvdy);
    top_->w = uint16_t(in.w);
    top_->h = uint16_t(in.h);
    top_->en = en;
    top_->clk = 0;
    top_->eval();
    top_->clk = 1;
    top_->eval();
    return int16_t(top_->lambda);
  }

 private:
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtex_lambda> top_;
};

// Streams the inputs through the unit (en low in about `stall` of the clocks) and checks every
// output against the model: after the k-th enabled edge the output is the model's lambda of the
// input taken at enabled edge k - 1 (the pipeline's second register).
void check_stream(const std::vector<Input>& inputs, double stall, uint64_t seed) {
  Unit unit;
  std::mt19937_64 rng(seed);
  std::deque<int32_t> expected;  // of the inputs taken so far, in order
  size_t next = 0, enabled = 0, checked = 0;
  int32_t last = 0;
  while (checked < inputs.size()) {
    const bool en = std::uniform_real_distribution<double>(0, 1)(rng) >= stall;
    const Input in = next < inputs.size() ? inputs[next] : Input{};
    const int32_t out = unit.clock(in, en);
    if (en) {
      expected.push_back(tex_lambda(in.d, {in.w, in.h}));
      ++next;
      if (++enabled >= 2) {
        const Input& src = inputs[checked < inputs.size() ? checked : 0];
        ASSERT_EQ(out, expected.front()) << "input " << checked << ": " << src.d.dudx << " " << src.d.dvdx << " "
                                         << src.d.dudy << " " << src.d.dvdy << " size " << src.w << "x" << src.h;
        expected.pop_front();
        ++checked;
        last = out;
      }
    } else if (enabled >= 2) {
      ASSERT_EQ(out, last) << "the output moved while en was low";
    }
  }
}

}  // namespace

TEST(RtlLambda, EdgesOfTheFormatBitExact) {
  const int32_t values[] = {0, 1, -1, 2, 255, 256, 1 << 16, (1 << 24) - 1, 1 << 24, -(1 << 24), (1 << 23) + 12345,
                            INT32_MAX, INT32_MIN, INT32_MIN + 1, 0x12345678, -0x0FEDCBA9};
  std::vector<Input> inputs;
  for (int lw : {0, 1, 7, 13})
    for (int lh : {0, 5, 13})
      for (int32_t a : values)
        for (int32_t b : {0, 1, 1 << 20, INT32_MIN})
          inputs.push_back({{a, b, b / 3, a / 7}, lw, lh});
  check_stream(inputs, 0.0, 1);
}

TEST(RtlLambda, RandomDerivativesBitExactUnderStalls) {
  std::mt19937_64 rng(2026);
  std::vector<Input> inputs(1'000'000);
  for (Input& in : inputs) {
    // Magnitudes log-uniform over the whole format, random signs, and some zeros.
    auto value = [&] {
      if (rng() % 16 == 0) return int32_t(0);
      const int bits = int(rng() % 32);
      const int64_t mag = int64_t(rng() & ((uint64_t(1) << bits) - 1)) | (int64_t(1) << bits >> 1);
      return int32_t(rng() & 1 ? -std::min<int64_t>(mag, INT32_MAX) : std::min<int64_t>(mag, INT32_MAX));
    };
    in.d = {value(), value(), value(), value()};
    // Sides: half powers of two 1..8192, half any size 1..8192.
    in.w = rng() & 1 ? 1 << int(rng() % 14) : int(rng() % 8192) + 1;
    in.h = rng() & 1 ? 1 << int(rng() % 14) : int(rng() % 8192) + 1;
  }
  check_stream(inputs, 0.3, 7);
}

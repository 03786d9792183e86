// The cube face unit tex_cube (rtl/tex_cube.sv) on its own against the model's stage::cube_face and
// stage::cube_derivatives, bit for bit: the face, the exact s and t, the four derivatives, for
// directions of every length (ties between axes, the 2^-24 edges, zero, INT32_MIN) and derivatives
// of every magnitude, with random clock-enable stalls and 2D requests between (cube low: the
// registers must not move) - the output follows 6 enabled cube clocks after its input.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "Vtex_cube.h"
#include "model/stages.h"

using namespace tex;

namespace {

struct Input {
  int32_t r[3] = {};
  int32_t dx[3] = {}, dy[3] = {};
};
struct Output {
  int face = 0;
  int32_t s = 0, t = 0, d[4] = {};
  bool operator==(const Output& o) const {
    return face == o.face && s == o.s && t == o.t && d[0] == o.d[0] && d[1] == o.d[1] && d[2] == o.d[2] && d[3] == o.d[3];
  }
};
std::ostream& operator<<(std::ostream& os, const Output& o) {
  return os << "face " << o.face << " s " << o.s << " t " << o.t << " d " << o.d[0] << " " << o.d[1] << " " << o.d[2]
            << " " << o.d[3];
}

Output model_of(const Input& in) {
  const stage::CubeFace f = stage::cube_face(in.r[0], in.r[1], in.r[2]);
  const std::array<int32_t, 2> x = stage::cube_derivatives(f, in.dx[0], in.dx[1], in.dx[2]);
  const std::array<int32_t, 2> y = stage::cube_derivatives(f, in.dy[0], in.dy[1], in.dy[2]);
  return {f.face, f.s, f.t, {x[0], x[1], y[0], y[1]}};
}

class Unit {
 public:
  Unit() : ctx_(std::make_unique<VerilatedContext>()), top_(std::make_unique<Vtex_cube>(ctx_.get())) {}
  Output clock(const Input& in, bool en, bool cube) {
    top_->rx = uint32_t(in.r[0]);
    top_->ry = uint32_t(in.r[1]);
    top_->rz = uint32_t(in.r[2]);
    top_->dxdx = uint32_t(in.dx[0]);
    top_->dydx = uint32_t(in.dx[1]);
    top_->dzdx = uint32_t(in.dx[2]);
    top_->dxdy = uint32_t(in.dy[0]);
    top_->dydy = uint32_t(in.dy[1]);
    top_->dzdy = uint32_t(in.dy[2]);
    top_->en = en;
    top_->cube = cube;
    top_->clk = 0;
    top_->eval();
    top_->clk = 1;
    top_->eval();
    return {int(top_->face), int32_t(top_->s), int32_t(top_->t),
            {int32_t(top_->dsdx), int32_t(top_->dtdx), int32_t(top_->dsdy), int32_t(top_->dtdy)}};
  }

 private:
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtex_cube> top_;
};

// Streams the inputs with en low in about `stall` of the clocks and a 2D request (cube low, random
// pins) in about `other` of the enabled ones; a cube input taken at enabled edge n is on the outputs
// after enabled edge n + 5 (the sixth register), and they hold until the next cube reaches them.
void check_stream(const std::vector<Input>& inputs, double stall, double other, uint64_t seed) {
  Unit unit;
  std::mt19937_64 rng(seed);
  auto chance = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
  std::deque<std::pair<bool, size_t>> line;  // per enabled edge: a cube, and which
  size_t next = 0, checked = 0;
  Output last{};
  bool have_last = false;
  while (checked < inputs.size()) {
    const bool en = !chance(stall);
    const bool cube = next < inputs.size() && !chance(other);
    Input in = cube ? inputs[next] : Input{};
    if (!cube)
      for (int c = 0; c < 3; ++c) in.r[c] = int32_t(uint32_t(rng())), in.dx[c] = int32_t(uint32_t(rng()));
    const Output out = unit.clock(in, en, cube);
    if (!en) {
      if (have_last) {
        ASSERT_EQ(out, last) << "the outputs moved while en was low";
      }
      continue;
    }
    line.emplace_back(cube, cube ? next : 0);
    if (cube) ++next;
    if (line.size() == 7) line.pop_front();
    if (line.size() == 6) {
      const auto [was_cube, index] = line.front();
      if (was_cube) {
        const Input& src = inputs[index];
        ASSERT_EQ(out, model_of(src)) << "input " << index << ": r " << src.r[0] << " " << src.r[1] << " " << src.r[2]
                                      << " dx " << src.dx[0] << " " << src.dx[1] << " " << src.dx[2] << " dy "
                                      << src.dy[0] << " " << src.dy[1] << " " << src.dy[2];
        last = out;
        have_last = true;
        ++checked;
      } else if (have_last) {
        ASSERT_EQ(out, last) << "a 2D request moved the outputs";
      }
    }
    if (next == inputs.size() && line.size() == 6 && !line.back().first) {
      // (flush: feed 2D clocks until the last cube leaves)
    }
  }
}

int32_t any_value(std::mt19937_64& rng) {
  if (rng() % 16 == 0) return 0;
  const int bits = int(rng() % 33);
  const int64_t mag = bits == 0 ? 0 : int64_t(rng() & ((uint64_t(1) << (bits - 1)) - 1)) | (int64_t(1) << (bits - 1));
  const int64_t v = rng() & 1 ? -mag : mag;
  return int32_t(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX));
}

}  // namespace

TEST(RtlCube, EdgesOfTheFormatBitExact) {
  const int32_t values[] = {0, 1, -1, 2, 3, (1 << 24) - 1, 1 << 24, -(1 << 24), (1 << 23) + 12345, INT32_MAX,
                            INT32_MIN, INT32_MIN + 1, 0x12345678, -0x0FEDCBA9};
  std::vector<Input> inputs;
  for (int32_t a : values)
    for (int32_t b : values)
      for (int32_t c : {0, 1, -1, 1 << 24, INT32_MIN, INT32_MAX, 0x00ABCDEF})
        for (int order = 0; order < 3; ++order) {
          Input in;
          in.r[order] = a;
          in.r[(order + 1) % 3] = b;
          in.r[(order + 2) % 3] = c;
          in.dx[0] = b / 3, in.dx[1] = a, in.dx[2] = c;
          in.dy[0] = INT32_MIN, in.dy[1] = c / 5, in.dy[2] = a / 7;
          inputs.push_back(in);
        }
  for (int32_t a : values) {  // exact ties of two and three axes, every sign
    for (int signs = 0; signs < 8; ++signs) {
      Input in;
      for (int c = 0; c < 3; ++c) in.r[c] = (signs >> c & 1) && a != INT32_MIN ? -a : a;
      in.dx[0] = 1 << 20, in.dy[2] = -(1 << 18);
      inputs.push_back(in);
      in.r[2] /= 2;
      inputs.push_back(in);
    }
  }
  check_stream(inputs, 0.0, 0.0, 1);
}

TEST(RtlCube, RandomDirectionsBitExactUnderStallsAnd2DRequests) {
  std::mt19937_64 rng(2027);
  std::vector<Input> inputs(300'000);
  for (Input& in : inputs) {
    switch (rng() % 3) {
      case 0:  // any length
        for (int32_t& c : in.r) c = any_value(rng);
        break;
      case 1:  // on the unit cube, near a seam or a corner
        for (int32_t& c : in.r) c = int32_t(rng() % (2u << 24)) - (1 << 24);
        in.r[rng() % 3] = rng() & 1 ? 1 << 24 : -(1 << 24);
        if (rng() & 1) in.r[rng() % 3] = (rng() & 1 ? 1 : -1) * ((1 << 24) - int32_t(rng() % 64));
        break;
      default:  // a unit direction in [-1, 1]^3
        for (int32_t& c : in.r) c = int32_t(rng() % (2u << 24)) - (1 << 24);
    }
    if (rng() % 8 == 0) in.r[1] = rng() % 2 ? in.r[0] : -in.r[0];  // ties
    for (int c = 0; c < 3; ++c) {
      in.dx[c] = rng() % 2 ? any_value(rng) : int32_t(rng() % (1u << 20)) - (1 << 19);
      in.dy[c] = rng() % 2 ? any_value(rng) : int32_t(rng() % (1u << 20)) - (1 << 19);
    }
  }
  check_stream(inputs, 0.3, 0.3, 7);
}

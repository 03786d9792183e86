// Stage functions of docs/numerics.md against their definitions in real numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "model/stages.h"

using namespace tex;

TEST(Stages, AxisTapsLinearIsRoundedTexelCoordinate) {
  for (int lw = 0; lw <= kMaxLog2Size; ++lw)
    for (int32_t u = -(1 << 25); u < (1 << 25); u += 9973) {
      const stage::AxisTaps t = stage::axis_taps(u, lw, TexelFilter::Linear);
      const double x = std::ldexp(double(u), lw - kCoordFracBits) - 0.5;
      const double p = std::floor(x * 256 + 0.5);
      EXPECT_EQ(t.i0, int32_t(std::floor(p / 256))) << "u=" << u << " lw=" << lw;
      EXPECT_EQ(t.w, int(p - 256 * std::floor(p / 256)));
      EXPECT_EQ(t.i1, t.i0 + 1);
    }
}

// tex_lerp: one linear interpolation with one multiply, exact (docs/numerics.md stage 5).
//   y = (a << 8) + (b - a) * w
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   a, b : unsigned IN_W bits, any fixed-point format Qi.f (both the same)
//   w    : unsigned 8 bits, 0..255 = weight of b in 1/256 (a gets 1 - w, so w = 0 is exactly a)
//   y    : unsigned IN_W + 8 bits, format Qi.(f+8), no rounding
// The true result lies in [0, (2^IN_W - 1) * 256], so computing modulo 2^(IN_W+8) is exact.
module tex_lerp #(
  parameter int IN_W = 8
) (
  input  logic [IN_W-1:0]   a,
  input  logic [IN_W-1:0]   b,
  input  logic [7:0]        w,
  output logic [IN_W+7:0]   y
);
  localparam int OUT_W = IN_W + 8;
  logic [OUT_W-1:0] diff;  // b - a modulo 2^OUT_W (two's complement)
  localparam int WB = tex_pkg::WEIGHT_BITS;  // 8: the ports above are written for it
  assign diff = {WB'(0), b} - {WB'(0), a};
  assign y = {a, WB'(0)} + diff * {IN_W'(0), w};
endmodule

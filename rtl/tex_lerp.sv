// tex_lerp: one linear interpolation, exact (docs/numerics.md stage 5; part of the model's
// `filter` stage).
//   y = (a << 8) + (b - a) * w
// with one multiply and no rounding. The true y lies in [0, 2^(IN_W + 8)), so it can be computed
// modulo 2^(IN_W + 8); two equivalent forms, chosen by width:
//   IN_W >= 8: unsigned, modulo 2^(IN_W + 8): the difference b - a wraps (two's complement) and
//              one (IN_W + 8) x 8-bit multiply gives y. Verilator emits plain C++ arithmetic.
//   IN_W <  8: the signed difference (IN_W + 1 bits) times the weight, a signed
//              (IN_W + 1) x 9-bit multiply: fewer iCE40 LUTs when the operands are narrow
//              (2-bit channels: 51 LUTs against 83 for the unsigned form; at IN_W = 8 it is 241
//              against 222).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   a, b : unsigned IN_W bits, any fixed-point format Qi.f (both the same)
//   w    : unsigned WEIGHT_BITS, 0..255 = weight of b in 1/256 (a gets 1 - w, so w = 0 is a)
//   y    : unsigned IN_W + WEIGHT_BITS bits, format Qi.(f+8); at most (2^IN_W - 1) * 256
module tex_lerp #(
  parameter int IN_W = 8
) (
  input  logic [IN_W-1:0]                       a,
  input  logic [IN_W-1:0]                       b,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]       w,
  output logic [IN_W+tex_pkg::WEIGHT_BITS-1:0]  y
);
  localparam int WB    = tex_pkg::WEIGHT_BITS;
  localparam int OUT_W = IN_W + WB;
  generate
    if (IN_W >= 8) begin : g_modular
      logic [OUT_W-1:0] diff;  // b - a modulo 2^OUT_W
      assign diff = OUT_W'(b) - OUT_W'(a);
      assign y    = {a, WB'(0)} + diff * OUT_W'(w);
    end else begin : g_signed
      logic signed [IN_W:0]  diff;     // b - a in [-(2^IN_W - 1), 2^IN_W - 1]
      logic signed [WB:0]    weight;   // w as a non-negative signed operand
      logic signed [OUT_W:0] step;     // (b - a) * w, |step| < 2^OUT_W
      logic signed [OUT_W:0] sum;      // (a << 8) + step, in [0, (2^IN_W - 1) * 256]
      logic                  sum_sign_unused;  // always 0 (sum is never negative)
      assign diff   = $signed({1'b0, b}) - $signed({1'b0, a});
      assign weight = $signed({1'b0, w});
      assign step   = diff * weight;  // both operands sign-extended to OUT_W + 1 bits
      assign sum    = $signed({1'b0, a, WB'(0)}) + step;
      assign sum_sign_unused = sum[OUT_W];
      assign y      = sum[OUT_W-1:0];
    end
  endgenerate
endmodule

// tex_address: the model's `address` stage (docs/numerics.md stage 2) for one axis at one of the
// two levels a sample reads (a slot: level d or d1).
//   linear:  p = (t9 - 255) >>> 1, i0 = p >>> 8, w = p & 255   (round half up of u*size - 1/2)
//   nearest: i0 = t9 >>> 9, w = 0                               (floor of u*size)
// Handshake: stall-enable; the registers load when en is high.
// Latency: 1 clock (tex_unit clock 4). Throughput: 1 per clock.
// Ports:
//   t9     : signed TW bits, floor(u' * size * 512) of the slot's level (tex_scale)
//   linear : 1 = linear texel filter, 0 = nearest
//   i0     : signed IW bits, integer texel index of the first tap (unwrapped, in [-2n-1, 2n])
//   i1     : signed IW bits, i0 + 1, the second tap: (p + 512) >>> 9, an adder beside p's rather
//            than a carry chain after the register (it would sit in clock 5, before the wrap
//            and the memory read: nextpnr's critical path)
//   w      : unsigned WEIGHT_BITS, weight of the second tap in 1/256
module tex_address #(
  parameter int TW = tex_pkg::MAX_LOG2_SIZE + 12,  // from tex_scale
  parameter int IW = TW - 8                        // |i0| <= 2^(TW - 10) + 1
) (
  input  logic                                 clk,
  input  logic                                 en,
  input  logic signed [TW-1:0]                 t9,
  input  logic                                 linear,
  output logic signed [IW-1:0]                 i0,
  output logic signed [IW-1:0]                 i1,
  output logic [tex_pkg::WEIGHT_BITS-1:0]      w
);
  localparam int WB = tex_pkg::WEIGHT_BITS;
  localparam int XW = TW + 1;  // one more bit: t9 - 255 must not overflow
  // p = t9 - 255 (linear) or t9 (nearest); then linear i0 = (p >>> 1) >>> 8 = p >>> 9 and
  // w = (p >>> 1) & 255 = p[8:1]; nearest i0 = t9 >>> 9. One arithmetic shift either way.
  always_ff @(posedge clk) begin
    if (en) begin
      logic signed [XW-1:0] p, p1;
      p  = linear ? XW'(t9) - XW'((1 << WB) - 1) : XW'(t9);  // a size cast of a signed value sign-extends
      p1 = linear ? XW'(t9) + XW'((1 << WB) + 1) : XW'(t9) + XW'(1 << (WB + 1));  // p + 512
      i0 <= IW'(p >>> (WB + 1));
      i1 <= IW'(p1 >>> (WB + 1));
      w  <= linear ? p[WB:1] : '0;
    end
  end
endmodule

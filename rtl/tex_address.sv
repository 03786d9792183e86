// tex_address: the model's `address` stage (docs/numerics.md stage 2) for one axis at one of the
// two levels a sample reads (a slot: level d or d1).
//   t9 = scaled >>> level                   (see tex_scale: floors of arithmetic shifts compose)
//   linear:  p = (t9 - 255) >>> 1, i0 = p >>> 8, w = p & 255   (round half up of u*size - 1/2)
//   nearest: i0 = t9 >>> 9, w = 0                               (floor of u*size)
// Handshake: stall-enable; the registers load when en is high.
// Latency: 1 clock (tex_unit clock 4). Throughput: 1 per clock.
// Ports:
//   scaled : signed SW bits, floor(coord * 2^log2_size0 * 512) (from tex_scale)
//   level  : integer 0..11, the mip level whose texel coordinates are wanted
//   linear : 1 = linear texel filter, 0 = nearest
//   i0     : signed IW bits, integer texel index of the first tap (unwrapped)
//   i1     : signed IW bits, i0 + 1, the second tap: (p + 512) >>> 9, an adder beside p's rather
//            than a carry chain after the register (it would sit in clock 5, before the wrap
//            and the memory read: nextpnr's critical path)
//   w      : unsigned WEIGHT_BITS, weight of the second tap in 1/256
module tex_address #(
  parameter int SW = tex_pkg::SCALED_W,  // from tex_scale
  parameter int IW = tex_pkg::INDEX_W    // SW - 7: |i0| < 2^(SW - 10), and i1
) (
  input  logic                                 clk,
  input  logic                                 en,
  input  logic signed [SW-1:0]                 scaled,
  input  logic [tex_pkg::LEVEL_W-1:0]          level,
  input  logic                                 linear,
  output logic signed [IW-1:0]                 i0,
  output logic signed [IW-1:0]                 i1,
  output logic [tex_pkg::WEIGHT_BITS-1:0]      w
);
  localparam int WB = tex_pkg::WEIGHT_BITS;
  localparam int XW = SW + 1;  // one more bit: t9 - 255 must not overflow
  // p = t9 - 255 (linear) or t9 (nearest); then linear i0 = (p >>> 1) >>> 8 = p >>> 9 and
  // w = (p >>> 1) & 255 = p[8:1]; nearest i0 = t9 >>> 9. One arithmetic shift either way.
  // Inside the enable: a simulator skips the shifts in the clocks in which the stage holds.
  always_ff @(posedge clk) begin
    if (en) begin
      logic signed [XW-1:0] t9, p, p1;
      t9 = XW'(scaled) >>> level;  // a size cast of a signed value sign-extends
      p  = linear ? t9 - XW'((1 << WB) - 1) : t9;
      p1 = linear ? t9 + XW'((1 << WB) + 1) : t9 + XW'(1 << (WB + 1));  // p + 512
      i0 <= IW'(p >>> (WB + 1));
      i1 <= IW'(p1 >>> (WB + 1));
      w  <= linear ? p[WB:1] : '0;
    end
  end
endmodule

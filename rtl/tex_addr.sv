// tex_addr: stage 2 of docs/numerics.md for one axis at one selected level (d or d1).
//   t9 = scaled >>> level                   (see tex_scale: floors of arithmetic shifts compose)
//   linear:  p = (t9 - 255) >>> 1, i0 = p >>> 8, w = p & 255
//   nearest: i0 = t9 >>> 9, w = 0
// Handshake: stall-enable; the registers load when en is high.
// Latency: 1 clock. Throughput: 1 per clock.
// Ports:
//   scaled : signed SCALED_W bits, floor(coord * 2^log2_size0 * 512) (from tex_scale)
//   level  : integer 0..11, the mip level whose texel coordinates are wanted
//   linear : 1 = linear texel filter, 0 = nearest
//   i0     : signed INDEX_W bits, integer texel index of the first tap (unwrapped)
//   w      : unsigned 8 bits, weight of the second tap i0 + 1 in 1/256
module tex_addr (
  input  logic                                 clk,
  input  logic                                 en,
  input  logic signed [tex_pkg::SCALED_W-1:0]  scaled,
  input  logic [3:0]                           level,
  input  logic                                 linear,
  output logic signed [tex_pkg::INDEX_W-1:0]   i0,
  output logic [7:0]                           w
);
  localparam int XW = tex_pkg::SCALED_W + 1;  // one more bit: t9 - 255 must not overflow
  logic signed [XW-1:0] wide, t9, p;
  assign wide = XW'(scaled);  // a size cast of a signed value sign-extends
  assign t9   = wide >>> level;
  assign p    = (t9 - XW'(255)) >>> 1;
  always_ff @(posedge clk) begin
    if (en) begin
      if (linear) begin
        i0 <= tex_pkg::INDEX_W'(p >>> 8);
        w  <= p[7:0];
      end else begin
        i0 <= tex_pkg::INDEX_W'(t9 >>> 9);
        w  <= 8'd0;
      end
    end
  end
endmodule

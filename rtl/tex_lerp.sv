// tex_lerp: one linear interpolation, exact (docs/numerics.md stage 5).
//   y = (a << 8) + (b - a) * w
// computed as the one multiply's partial products without a subtraction:
//   (a << 8) + (b - a) * w = a + sum_j 2^j * (w[j] ? b : a)     (since 256 - w = ~w + 1)
// i.e. 8 rows of IN_W bits, each a 2:1 select, summed by a balanced adder tree. This is the
// array multiplier of (b - a) * w with the subtraction folded into the row selects; it is half
// the iCE40 LUTs of Yosys' generic (IN_W+8) x 8 $mul.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   a, b : unsigned IN_W bits, any fixed-point format Qi.f (both the same)
//   w    : unsigned 8 bits, 0..255 = weight of b in 1/256 (a gets 1 - w, so w = 0 is exactly a)
//   y    : unsigned IN_W + 8 bits, format Qi.(f+8), no rounding; at most (2^IN_W - 1) * 256
module tex_lerp #(
  parameter int IN_W = 8
) (
  input  logic [IN_W-1:0]                       a,
  input  logic [IN_W-1:0]                       b,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]       w,
  output logic [IN_W+tex_pkg::WEIGHT_BITS-1:0]  y
);
  localparam int OUT_W = IN_W + tex_pkg::WEIGHT_BITS;  // the tree below is written for 8 weight bits
  logic [IN_W-1:0] r0, r1, r2, r3, r4, r5, r6, r7;  // row j: w[j] ? b : a, weight 2^j
  logic [IN_W+1:0] p0, p1, p2, p3;                  // rows 2i + 2i+1
  logic [IN_W+3:0] q0, q1;                          // rows 0-3, 4-7
  assign r0 = w[0] ? b : a;
  assign r1 = w[1] ? b : a;
  assign r2 = w[2] ? b : a;
  assign r3 = w[3] ? b : a;
  assign r4 = w[4] ? b : a;
  assign r5 = w[5] ? b : a;
  assign r6 = w[6] ? b : a;
  assign r7 = w[7] ? b : a;
  assign p0 = (IN_W+2)'(r0) + ((IN_W+2)'(r1) << 1);
  assign p1 = (IN_W+2)'(r2) + ((IN_W+2)'(r3) << 1);
  assign p2 = (IN_W+2)'(r4) + ((IN_W+2)'(r5) << 1);
  assign p3 = (IN_W+2)'(r6) + ((IN_W+2)'(r7) << 1);
  assign q0 = (IN_W+4)'(p0) + ((IN_W+4)'(p1) << 2);
  assign q1 = (IN_W+4)'(p2) + ((IN_W+4)'(p3) << 2);
  assign y  = (OUT_W'(q0) + OUT_W'(a)) + (OUT_W'(q1) << 4);
endmodule

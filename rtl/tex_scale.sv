// tex_scale: the model's `scale` stage (docs/numerics.md stage 2): a reduced coordinate in one
// level's texels,
//   t9 = (reduced * n) >>> 15       = floor(u' * n * 512), 9 sub-texel bits
// n the level's size along the axis, any value 1..2^ML. Where n is a power of two 2^a this is
// the paper's binary shift u' >>> (15 - a); a side that is not one takes the multiply (GL's
// u * w_k). tex_front computes n = max(1, size0 >> level) for each slot.
// An unnormalized coordinate arrives as t9 already (tex_reduce's): it passes, level 0's texels.
// Handshake: none (combinational: it feeds tex_address's clock-4 registers). Latency: 0.
// Throughput: 1 per clock.
// Ports:
//   reduced      : signed Q2.24 (RW bits), tex_reduce's; unnormalized: t9 (|t9| <= 2^(ML+10))
//   n            : unsigned ML + 1 bits, 1..2^ML texels
//   unnormalized : the sampler's unnormalized coordinates
//   t9      : signed TW = ML + 12 bits (|t9| <= 2^(ML + 10))
module tex_scale #(
  parameter int ML = tex_pkg::MAX_LOG2_SIZE,          // the unit's largest log2 size
  parameter int RW = tex_pkg::COORD_FRAC + 3,         // tex_reduce's width
  parameter int TW = ML + 12                          // derived: do not override
) (
  input  logic signed [RW-1:0]           reduced,
  input  logic [ML:0]                    n,
  input  logic                           unnormalized,
  output logic signed [TW-1:0]           t9
);
  localparam int PW = RW + ML + 2;  // the signed product
  logic signed [PW-1:0] product;
  assign product = PW'(reduced) * $signed({1'b0, n});
  assign t9      = unnormalized ? TW'(reduced) : TW'(product >>> (tex_pkg::COORD_FRAC - 9));
endmodule

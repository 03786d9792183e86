// tex_reduce: the model's `reduce` stage (docs/numerics.md stage 2): the coordinate brought into
// one period of its address mode before tex_scale multiplies it by a level's size:
//   repeat: u mod 1 (u & (2^24 - 1))   mirror: u mod 2 (u & (2^25 - 1))
//   clamp, border, mirror-clamp: clamp(u, -2, 2)   (the unused codes 5..7 as clamp)
// An unnormalized coordinate (Q16.16 texels; its sampler clamps to edge or border) is brought to
// tex_scale's t9 here, floor(u * 512) clamped to +-2^(ML+1) texels (the largest side's 2n: every
// tap beyond reads what the model's clamp to +-2n reads, an edge or a border texel).
// Every tap reads the texel it would read without it (repeat and mirror are periodic, beyond
// +-2 the clamping modes read only edge or border texels); the product u * n is then 27 x SIZE_W
// bits and the texel indices stay within [-2n - 1, 2n] (tex_wrap compares instead of a modulo).
// Handshake: stall-enable; the register loads when en is high.
// Latency: 1 clock (tex_unit clock 2). Throughput: 1 per clock.
// Ports:
//   coord        : signed Q8.24 (REQ_COORD_W bits, u or v), normalized; unnormalized: signed
//                  Q16.16 texels
//   mode         : tex_pkg::WRAP_*, the sampler's address mode along this axis
//   unnormalized : the sampler's unnormalized coordinates
//   reduced      : signed Q2.24, RW = COORD_FRAC + 3 bits, in [-2, 2]; unnormalized: t9, signed
//                  texels with 9 fraction bits, |t9| <= 2^(ML+10)
`include "tex_param_error.svh"
module tex_reduce #(
  parameter int ML = tex_pkg::MAX_LOG2_SIZE,  // the unit's largest log2 size
  parameter int RW = tex_pkg::COORD_FRAC + 3  // derived: do not override
) (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] coord,
  input  logic [tex_pkg::WRAP_W-1:0]             mode,
  input  logic                                   unnormalized,
  output logic signed [RW-1:0]                   reduced
);
  localparam int F = tex_pkg::COORD_FRAC;
  localparam int CW = tex_pkg::REQ_COORD_W;
  localparam int TF = tex_pkg::TEXEL_COORD_FRAC;
  localparam logic signed [CW-1:0] TWO = CW'(2) <<< F;
  localparam logic signed [CW-1:0] TWO_N = CW'(1) <<< (ML + 1 + TF);  // 2^(ML+1) texels, Q16.16
  generate
    if (ML < 0 || ML + 11 > RW || ML + 2 + TF > CW) begin : g_bad_ml
      `TEX_PARAM_ERROR("tex_reduce: parameter ML must be 0..16 (2^(ML+1) texels within t9's RW bits and Q16.16)")
    end
  endgenerate
  always_ff @(posedge clk) begin
    if (en) begin
      if (unnormalized)
        reduced <= RW'(((coord > TWO_N) ? TWO_N : (coord < -TWO_N) ? -TWO_N : coord) >>> (TF - 9));
      else case (mode)
        tex_pkg::WRAP_REPEAT: reduced <= RW'({1'b0, coord[F-1:0]});
        tex_pkg::WRAP_MIRROR: reduced <= RW'({1'b0, coord[F:0]});
        default:              reduced <= (coord > TWO) ? RW'(TWO) : (coord < -TWO) ? -RW'(TWO) : RW'(coord);
      endcase
    end
  end
endmodule

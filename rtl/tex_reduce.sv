// tex_reduce: the model's `reduce` stage (docs/numerics.md stage 2): the coordinate brought into
// one period of its address mode before tex_scale multiplies it by a level's size:
//   repeat: u mod 1 (u & (2^24 - 1))   mirror: u mod 2 (u & (2^25 - 1))
//   clamp, border, mirror-clamp: clamp(u, -2, 2)   (the unused codes 5..7 as clamp)
// Every tap reads the texel it would read without it (repeat and mirror are periodic, beyond
// +-2 the clamping modes read only edge or border texels); the product u * n is then 27 x SIZE_W
// bits and the texel indices stay within [-2n - 1, 2n] (tex_wrap compares instead of a modulo).
// Handshake: stall-enable; the register loads when en is high.
// Latency: 1 clock (tex_unit clock 2). Throughput: 1 per clock.
// Ports:
//   coord   : signed Q8.24 (REQ_COORD_W bits, u or v), normalized
//   mode    : tex_pkg::WRAP_*, the sampler's address mode along this axis
//   reduced : signed Q2.24, RW = COORD_FRAC + 3 bits, in [-2, 2]
module tex_reduce #(
  parameter int RW = tex_pkg::COORD_FRAC + 3  // derived: do not override
) (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] coord,
  input  logic [tex_pkg::WRAP_W-1:0]             mode,
  output logic signed [RW-1:0]                   reduced
);
  localparam int F = tex_pkg::COORD_FRAC;
  localparam int CW = tex_pkg::REQ_COORD_W;
  localparam logic signed [CW-1:0] TWO = CW'(2) <<< F;
  always_ff @(posedge clk) begin
    if (en) begin
      case (mode)
        tex_pkg::WRAP_REPEAT: reduced <= RW'({1'b0, coord[F-1:0]});
        tex_pkg::WRAP_MIRROR: reduced <= RW'({1'b0, coord[F:0]});
        default:              reduced <= (coord > TWO) ? RW'(TWO) : (coord < -TWO) ? -RW'(TWO) : RW'(coord);
      endcase
    end
  end
endmodule

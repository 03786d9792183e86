// tex_scale: the model's `scale` stage (docs/numerics.md stage 2): the one configuration-dependent
// shift of a coordinate,
//   scaled = coord >>> (15 - log2_size0)
// so that level k's t9 = scaled >>> k (tex_address) is a shift by the level alone: the paper's
// binary shift (floors of arithmetic shifts compose). Levels past the last one along this axis
// are 1 texel wide and wrap to index 0 whatever t9 is.
// Handshake: stall-enable; the register loads when en is high.
// Latency: 1 clock (tex_unit clock 2). Throughput: 1 per clock.
// Ports:
//   coord      : signed Q8.24 (REQ_COORD_W bits, u or v), normalized
//   log2_size0 : integer 0..MAX_LOG2, level-0 size along this axis (larger values act as MAX_LOG2)
//   scaled     : signed SW = 17 + MAX_LOG2 bits: floor(coord * 2^log2_size0 * 512), 9 fraction
//                bits (|coord| < 128: |scaled| < 2^(16 + MAX_LOG2))
module tex_scale #(
  parameter int MAX_LOG2 = tex_pkg::MAX_LOG2_SIZE,  // the unit's largest log2 size, 0..MAX_LOG2_SIZE
  parameter int SW       = 17 + MAX_LOG2            // derived
) (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] coord,
  input  logic [tex_pkg::LEVEL_W-1:0]            log2_size0,
  output logic signed [SW-1:0]                   scaled
);
  localparam int VW = tex_pkg::LEVEL_W;
  // 15 = COORD_FRAC - 9: the result keeps 9 fraction bits of a level-0 texel.
  localparam logic [VW-1:0] ML     = VW'(MAX_LOG2);
  localparam logic [VW-1:0] SHIFT0 = VW'(tex_pkg::COORD_FRAC - 9);
  logic [VW-1:0] shift;  // 15 - MAX_LOG2 .. 15
  assign shift = SHIFT0 - ((log2_size0 > ML) ? ML : log2_size0);
  always_ff @(posedge clk) if (en) scaled <= SW'(coord >>> shift);
endmodule

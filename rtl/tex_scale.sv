// tex_scale: the one configuration-dependent shift of a coordinate (docs/numerics.md stage 2).
//   scaled = coord >>> (15 - log2_size0), so that level k's t9 = scaled >>> k is a FIXED shift
//   per level memory (the paper's binary shift; floors of floors compose exactly). Levels past the
//   last one along this axis are 1 texel wide and wrap to index 0 whatever t9 is.
// Handshake: stall-enable; the register loads when en is high.
// Latency: 1 clock. Throughput: 1 per clock.
// Ports:
//   coord      : signed Q8.24 (u or v), normalized
//   log2_size0 : integer 0..11, level-0 size along this axis (values above 11 act as 11)
//   scaled     : signed SCALED_W = 28 bits: floor(coord * 2^log2_size0 * 512)
module tex_scale (
  input  logic                                  clk,
  input  logic                                  en,
  input  logic signed [31:0]                    coord,
  input  logic [3:0]                            log2_size0,
  output logic signed [tex_pkg::SCALED_W-1:0]   scaled
);
  // 15 = COORD_FRAC - 9: the result keeps 9 fraction bits of a level-0 texel.
  localparam logic [3:0] MAX_LOG2 = 4'(tex_pkg::MAX_LOG2_SIZE);
  localparam logic [3:0] SHIFT0   = 4'(tex_pkg::COORD_FRAC - 9);
  logic [3:0] shift;  // 4..15
  assign shift = SHIFT0 - ((log2_size0 > MAX_LOG2) ? MAX_LOG2 : log2_size0);
  always_ff @(posedge clk) if (en) scaled <= tex_pkg::SCALED_W'(coord >>> shift);
endmodule

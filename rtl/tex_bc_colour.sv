// tex_bc_colour: one texel of a BC1 colour block, also BC2's and BC3's (docs/numerics.md
// "Block-compressed formats"): endpoints c0, c1 as 5:6:5 widened to 8 bits by replicating their
// top bits, 16 two-bit indices. Four colours (c0 > c1, or always for BC2/BC3): c0, c1,
// (2 c0 + c1 + 1) / 3, (c0 + 2 c1 + 1) / 3; three colours: c0, c1, (c0 + c1 + 1) / 2 and a
// transparent black. The thirds are multiplications by 683 / 2^11, exact for numerators up to 766.
// Handshake: none (combinational; the cached unit's taps). Latency: 0. Throughput: 1 per clock.
// Ports:
//   block       : the 64-bit colour block, little-endian (c0 in bits 15..0, the indices from bit 32)
//   texel       : 0..15, x + 4 y inside the block
//   four_only   : 1 for BC2 and BC3 (their colour block never takes the three-colour mode)
//   rgb         : unorm8 R (bits 7..0), G (15..8), B (23..16)
//   transparent : 1 for BC1's index 3 in the three-colour mode (the texel is (0, 0, 0, 0))
module tex_bc_colour (
  input  logic [63:0] block,
  input  logic [3:0]  texel,
  input  logic        four_only,
  output logic [23:0] rgb,
  output logic        transparent
);
  logic [15:0] c0, c1;
  logic [1:0]  index;
  logic        four;
  logic [23:0] e0, e1;   // the endpoints widened, R G B from bit 0
  assign c0    = block[15:0];
  assign c1    = block[31:16];
  assign index = block[32 + 2 * texel +: 2];
  assign four  = four_only || c0 > c1;
  assign e0    = {c0[4:0], c0[4:2], c0[10:5], c0[10:9], c0[15:11], c0[15:13]};
  assign e1    = {c1[4:0], c1[4:2], c1[10:5], c1[10:9], c1[15:11], c1[15:13]};
  generate
    for (genvar c = 0; c < 3; c++) begin : g_channel
      logic [7:0]  a, b;
      logic [9:0]  third;   // 2a + b + 1 (index 2) or a + 2b + 1 (index 3), at most 766
      logic [20:0] scaled;  // third * 683: third / 3 in bits 18..11
      logic [8:0]  half;    // a + b + 1: the rounded half in bits 8..1
      logic [7:0]  out;
      logic [13:0] rest_unused;   // the bits of scaled and half beside the quotients
      assign a      = e0[8 * c +: 8];
      assign b      = e1[8 * c +: 8];
      assign third  = index == 2'd2 ? {1'b0, a, 1'b0} + 10'(b) + 10'd1 : 10'(a) + {1'b0, b, 1'b0} + 10'd1;
      assign scaled = 21'(third) * 21'd683;
      assign half   = 9'(a) + 9'(b) + 9'd1;
      always_comb begin
        case (index)
          2'd0:    out = a;
          2'd1:    out = b;
          2'd2:    out = four ? scaled[18:11] : half[8:1];
          default: out = four ? scaled[18:11] : 8'd0;
        endcase
      end
      assign rgb[8 * c +: 8] = out;
      assign rest_unused     = {scaled[20:19], scaled[10:0], half[0]};
    end
  endgenerate
  assign transparent = !four && index == 2'd3;
endmodule

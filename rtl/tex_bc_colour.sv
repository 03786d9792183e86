// tex_bc_colour: one texel of a BC1 colour block, also BC2's and BC3's (docs/numerics.md
// "Block-compressed formats"): endpoints c0, c1 as 5:6:5 widened to 8 bits by replicating their
// top bits, 16 two-bit indices. Four colours (c0 > c1, or always for BC2/BC3): c0, c1,
// (2 c0 + c1 + 1) / 3, (c0 + 2 c1 + 1) / 3; three colours: c0, c1, (c0 + c1 + 1) / 2 and a
// transparent black. The thirds are multiplications by 683 / 2^11, exact for numerators up to 766.
// A function, not a module, so that a simulator evaluates it only for the taps that read a block
// (tex_tap_select calls it through tex_bc_decode inside the taps' condition).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call (8 calls per clock).
// texel_rgb(block, texel, four_only) -> {transparent, rgb}:
//   block       : the 64-bit colour block, little-endian (c0 in bits 15..0, the indices from bit 32)
//   texel       : 0..15, x + 4 y inside the block
//   four_only   : 1 for BC2 and BC3 (their colour block never takes the three-colour mode)
//   rgb         : bits 23..0, unorm8 R (bits 7..0), G (15..8), B (23..16)
//   transparent : bit 24, 1 for BC1's index 3 in the three-colour mode (the texel is (0, 0, 0, 0))
package tex_bc_colour;
  function automatic logic [24:0] texel_rgb(input logic [63:0] block, input logic [3:0] texel,
                                            input logic four_only);
    logic [15:0] c0, c1;
    logic [1:0]  index;
    logic        four;
    logic [23:0] e0, e1;   // the endpoints widened, R G B from bit 0
    logic [23:0] rgb;
    logic [7:0]  a, b, out;
    logic [9:0]  third;    // 2a + b + 1 (index 2) or a + 2b + 1 (index 3), at most 766
    logic [20:0] scaled;   // third * 683: third / 3 in bits 18..11
    logic [8:0]  half;     // a + b + 1: the rounded half in bits 8..1
    c0    = block[15:0];
    c1    = block[31:16];
    index = block[32 + 2 * texel +: 2];
    four  = four_only || c0 > c1;
    e0    = {c0[4:0], c0[4:2], c0[10:5], c0[10:9], c0[15:11], c0[15:13]};
    e1    = {c1[4:0], c1[4:2], c1[10:5], c1[10:9], c1[15:11], c1[15:13]};
    rgb   = '0;
    for (int c = 0; c < 3; c++) begin
      a      = e0[8 * c +: 8];
      b      = e1[8 * c +: 8];
      third  = index == 2'd2 ? {1'b0, a, 1'b0} + 10'(b) + 10'd1 : 10'(a) + {1'b0, b, 1'b0} + 10'd1;
      scaled = 21'(third) * 21'd683;
      half   = 9'(a) + 9'(b) + 9'd1;
      case (index)
        2'd0:    out = a;
        2'd1:    out = b;
        2'd2:    out = four ? 8'(scaled >> 11) : 8'(half >> 1);
        default: out = four ? 8'(scaled >> 11) : 8'd0;
      endcase
      rgb = {out, rgb[23:8]};  // (channel c ends at bits 8c..: no write at a variable index, which
                               // a function that Verilator does not inline cannot have)
    end
    texel_rgb = {!four && index == 2'd3, rgb};
  endfunction
endpackage

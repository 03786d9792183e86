// tex_astc_top: a test and synthesis harness only, not part of the design: the tex_astc package's
// decoder on its own (tests/rtl/test_rtl_block_decode.cpp checks it against the model).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   fw, fh : the footprint, 4..12 (one of the LDR profile's 14)
//   srgb   : sRGB endpoints ((c << 8) | 0x80)
//   block  : 128 bits, byte i at bits 8i+7..8i
//   x, y   : the texel in the block
//   rgba   : unorm8 R (bits 7..0), G, B, A (31..24)
module tex_astc_top (
  input  logic [3:0]   fw,
  input  logic [3:0]   fh,
  input  logic         srgb,
  input  logic [127:0] block,
  input  logic [3:0]   x,
  input  logic [3:0]   y,
  output logic [31:0]  rgba
);
  assign rgba = tex_astc::texel(block, fw, fh, x, y, srgb);
endmodule

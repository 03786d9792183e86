// tex_etc2_top: a test and synthesis harness only, not part of the design: the tex_etc2 package's
// decoders on their own (tests/rtl/test_rtl_block_decode.cpp checks them against the model).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   kind  : 0 ETC2 RGB8, 1 ETC2 RGB8A1, 2 ETC2 RGBA8 (EAC alpha in bytes 0..7, colour in 8..15)
//   block : 128 bits, byte i at bits 8i+7..8i; RGB8 and RGB8A1 use bits 63..0
//   texel : 0..15, x + 4 y inside the block
//   rgba  : unorm8 R (bits 7..0), G, B, A (31..24)
module tex_etc2_top (
  input  logic [1:0]   kind,
  input  logic [127:0] block,
  input  logic [3:0]   texel,
  output logic [31:0]  rgba
);
  logic [31:0] colour;
  assign colour = tex_etc2::colour(kind == 2'd2 ? block[127:64] : block[63:0], texel, kind == 2'd1);
  assign rgba   = kind == 2'd2 ? {tex_etc2::alpha(block[63:0], texel), colour[23:0]} : colour;
endmodule

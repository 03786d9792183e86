// tex_eac_top: a synthesis harness only, not part of the design: one EAC R11 channel decoder of
// the tex_etc2 package (tex_etc2::r11), unsigned and signed from the port: an EAC R11 texel, or
// one of the two channels of an RG11 texel (a tap's tex_bc_decode calls it twice for RG11).
// Checked against the model inside tex_bc_decode (tests/rtl/test_rtl_block_decode.cpp).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   block : the 8-byte EAC block, byte i at bits 8i+7..8i
//   texel : 0..15, x + 4 y inside the block
//   snorm : the signed form
//   code  : the 16-bit code: unsigned, or signed in offset binary (value + 32768)
module tex_eac_top (
  input  logic [63:0] block,
  input  logic [3:0]  texel,
  input  logic        snorm,
  output logic [15:0] code
);
  assign code = tex_etc2::r11(block, texel, snorm);
endmodule

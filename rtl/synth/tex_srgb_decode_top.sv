// tex_srgb_decode_top: a harness only (not part of the design): the sRGB decode function
// tex_srgb_decode::linear as a module, to simulate it alone (tests/rtl's RtlBlockDecode.*, all
// 256 codes against the model's table) and synthesize it alone (scripts/synth.sh's decoder table).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   code   : unsigned 8 bits, an sRGB code value (0..255 = 0..1 encoded)
//   linear : unsigned 16 bits, unorm16 linear value (0..65535 = 0..1)
module tex_srgb_decode_top (
  input  logic [7:0]  code,
  output logic [15:0] linear
);
  always_comb linear = tex_srgb_decode::linear(code);
endmodule

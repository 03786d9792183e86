// tex_border: the model's stage::border_texel (docs/numerics.md stage 3): the sampler's border
// colour, RGBA unorm16, in the filter's channel width: round(c * (2^CW - 1) / 65535) per channel,
// exact: x = c * (2^CW - 1) + 32767, then floor(x / 65535) = (x + (x >> 16) + 1) >> 16 for every
// x below 2^32 that occurs (tests/model/test_stages.cpp checks the identity for every c and CW).
// Handshake: none (combinational on static configuration). Latency: 0. Throughput: -.
// Ports:
//   rgba16 : {A, B, G, R}, unsigned 16 bits each (65535 = 1.0)
//   rgba   : {A, B, G, R}, unsigned CW bits each
`include "tex_param_error.svh"
module tex_border #(
  parameter int CW = 8
) (
  input  logic [63:0]     rgba16,
  output logic [4*CW-1:0] rgba
);
  generate
    if (CW < 1 || CW > 16) begin : g_param_error
      `TEX_PARAM_ERROR("tex_border: parameter CW must be in 1..16")
    end
  endgenerate
  always_comb begin
    for (int c = 0; c < 4; c++) begin
      logic [32:0] x;
      x = ((33'(rgba16[c*16 +: 16]) << CW) - 33'(rgba16[c*16 +: 16])) + 33'd32767;
      rgba[c*CW +: CW] = CW'((x + (x >> 16) + 33'd1) >> 16);  // (< 2^CW: the quotient)
    end
  end
endmodule

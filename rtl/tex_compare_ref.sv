// tex_compare_ref: a depth compare's reference in the depth's codes (the model's
// stage::compare_reference): Dref clamped to [0, 1] (Vulkan clamps a unorm depth's reference),
// then round(Dref * (2^CW - 1)), half up: (r * 2^CW - r + 2^23) >> 24, a shift and two adds. The
// test then compares CW-bit codes (tex_filter), and EQUAL means the same code.
// Handshake: none. Latency: 0 (combinational, at tex_unit_cached's request port, into tex_probe's
//   tag). Throughput: 1 per clock.
// Ports:
//   dref  : signed REQ_COORD_W bits, Q8.24 (1.0 = 2^24)
//   code : unsigned CW bits, the reference as a CW-bit unorm code
`include "tex_param_error.svh"
module tex_compare_ref #(
  parameter int CW = 8  // bits of the texels' channels (the depth is the R channel)
) (
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dref,
  output logic [CW-1:0]                          code
);
  localparam int FR = tex_pkg::COORD_FRAC;
  generate
    if (CW < 1 || CW > tex_pkg::MAX_CW) begin : g_bad_cw
      `TEX_PARAM_ERROR("tex_compare_ref: CW must be in 1..16 (tex_pkg::MAX_CW)")
    end
  endgenerate
  logic [FR:0]      clamped;  // 0 .. 2^24
  logic [FR+CW:0]   scaled;   // clamped * (2^CW - 1) + 2^23
  always_comb begin
    if (dref < 0) clamped = '0;
    else if (dref > (tex_pkg::REQ_COORD_W)'(1 << FR)) clamped = (FR+1)'(1 << FR);
    else clamped = dref[FR:0];
    scaled = ((FR+CW+1)'(clamped) << CW) - (FR+CW+1)'(clamped) + (FR+CW+1)'(1 << (FR - 1));
  end
  assign code = scaled[FR +: CW];
  logic unused_low;
  assign unused_low = ^{scaled[FR-1:0], scaled[FR+CW]};
endmodule

// tex_ice40_top: place-and-route harness only (scripts/synth.sh), not part of the design.
// tex_unit has about 240 ports, more than an HX8K package's pins: every input is fed from one
// shift register loaded through pin `sin`, and the response is folded to one pin by XOR, so no
// logic of tex_unit is optimized away and its timing is measured register to register.
// Handshake: none of its own (a measurement wrapper). Latency: that of tex_unit plus the
//   shift-in. Ports: clk, rst, sin (serial input bit), req_ready, rsp_valid, sout (XOR of the
//   response data and tag).
module tex_ice40_top #(
  parameter int MAX_LOG2_W = 4,
  parameter int MAX_LOG2_H = 4,
  parameter int CW         = 8,
  parameter int TAG_W      = 16
) (
  input  logic clk,
  input  logic rst,
  input  logic sin,
  output logic req_ready,
  output logic rsp_valid,
  output logic sout
);
  localparam int NIN = 4 + 4 + 2 + 2 + 1 + 2 + 16 * 3      // cfg
                     + 1 + 4 + 11 + 11 + 4 * CW             // write port
                     + 1 + 32 + 32 + 16 + TAG_W             // request
                     + 1;                                    // rsp_ready
  logic [NIN-1:0] in_bits;
  always_ff @(posedge clk) in_bits <= {in_bits[NIN-2:0], sin};

  logic [4*CW-1:0]  rsp_rgba;
  logic [TAG_W-1:0] rsp_tag;
  tex_unit #(.MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W)) u_unit (
    .clk(clk), .rst(rst),
    .cfg_log2_w(in_bits[3:0]), .cfg_log2_h(in_bits[7:4]), .cfg_wrap_u(in_bits[9:8]),
    .cfg_wrap_v(in_bits[11:10]), .cfg_texel_linear(in_bits[12]), .cfg_mip_mode(in_bits[14:13]),
    .cfg_lod_bias(in_bits[30:15]), .cfg_min_lod(in_bits[46:31]), .cfg_max_lod(in_bits[62:47]),
    .wr_en(in_bits[63]), .wr_level(in_bits[67:64]), .wr_x(in_bits[78:68]), .wr_y(in_bits[89:79]),
    .wr_data(in_bits[90 +: 4*CW]),
    .req_valid(in_bits[90+4*CW]), .req_ready(req_ready), .req_u(in_bits[91+4*CW +: 32]),
    .req_v(in_bits[123+4*CW +: 32]), .req_lod(in_bits[155+4*CW +: 16]),
    .req_tag(in_bits[171+4*CW +: TAG_W]),
    .rsp_valid(rsp_valid), .rsp_ready(in_bits[NIN-1]), .rsp_rgba(rsp_rgba), .rsp_tag(rsp_tag)
  );
  always_ff @(posedge clk) sout <= ^{rsp_rgba, rsp_tag};
endmodule

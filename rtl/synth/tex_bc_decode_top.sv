// tex_bc_decode_top: a synthesis harness only (scripts/synth.sh's decoder table), not part of the
// design: tex_bc_decode with `en` tied high and, with FORMAT >= 0, the format fixed, so that Yosys
// keeps only that format's decoder; FORMAT = -1 (the default) takes it from the port: every format.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   format : tex_pkg::FMT_* (used when FORMAT < 0)
//   block  : 128 bits, byte i at bits 8i+7..8i; BC1 and BC4 use bits 63..0
//   x, y   : the texel's place in the block (0..3; ASTC 0..F-1)
//   srgb   : an sRGB texture (ASTC's endpoints)
//   rgba   : unorm8 R (bits 7..0), G, B, A (31..24)
`include "tex_param_error.svh"
module tex_bc_decode_top #(
  parameter int FORMAT = -1
) (
  input  logic [tex_pkg::FORMAT_W-1:0] format,
  input  logic [127:0]                 block,
  input  logic [3:0]                   x,
  input  logic [3:0]                   y,
  input  logic                         srgb,
  output logic [31:0]                  rgba
);
  generate
    if (FORMAT < -1 || FORMAT >= (1 << tex_pkg::FORMAT_W)) begin : g_bad_format
      `TEX_PARAM_ERROR("tex_bc_decode_top: parameter FORMAT must be -1 (the port) or a tex_pkg::FMT_* code")
    end
  endgenerate
  tex_bc_decode u_decode (.en(1'b1), .format(FORMAT < 0 ? format : tex_pkg::FORMAT_W'(FORMAT)), .block(block),
                          .x(x), .y(y), .srgb(srgb), .rgba(rgba));
endmodule

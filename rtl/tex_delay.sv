// tex_delay: a stall-enable delay line of DEPTH clocks for W bits of data and a valid bit: what
// enters at an edge with en high leaves DEPTH such edges later. The data sit in a ring of
// 2^ceil(log2(DEPTH + 1)) entries (one written per enabled edge, the oldest read in place) rather
// than in DEPTH shifting registers: a small RAM on an FPGA (LUT RAM), and one entry written per
// clock in a simulator instead of DEPTH copies. The valid bits shift and reset.
// Handshake: stall-enable (en: the line advances). Latency: DEPTH enabled clocks. Throughput: 1 per
//   clock.
// Ports: in_valid, in_data (W bits) -> out_valid, out_data (combinational on the ring and its
//   pointer: registers).
`include "tex_param_error.svh"
module tex_delay #(
  parameter int W     = 1,
  parameter int DEPTH = 4   // >= 1
) (
  input  logic         clk,
  input  logic         rst,
  input  logic         en,
  input  logic         in_valid,
  input  logic [W-1:0] in_data,
  output logic         out_valid,
  output logic [W-1:0] out_data
);
  localparam int AW = $clog2(DEPTH + 1);
  generate
    if (DEPTH < 1 || W < 1) begin : g_bad_params
      `TEX_PARAM_ERROR("tex_delay: parameters DEPTH and W must be at least 1")
    end
  endgenerate
  logic [W-1:0]     ring [1 << AW];
  logic [AW-1:0]    wp;      // the entry the next enabled edge writes
  logic [DEPTH-1:0] valid;
  always_ff @(posedge clk) begin
    if (rst) begin
      wp    <= '0;
      valid <= '0;
    end else if (en) begin
      wp    <= wp + 1'b1;
      valid <= DEPTH'({valid, in_valid});  // (the oldest bit leaves)
    end
    if (en) ring[wp] <= in_data;
  end
  assign out_valid = valid[DEPTH-1];
  assign out_data  = ring[wp - AW'(DEPTH)];
endmodule

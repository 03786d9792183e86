// Formal environment of tex_skid (scripts/formal.sh): a reset in the first clock, then every
// input free in every clock (valid, data, ready, and further resets). The properties are tex_skid's
// own, under `ifdef FORMAL in rtl/tex_skid.sv.
module tex_skid_formal #(
  parameter int W = 2
) (
  input logic         clk,
  input logic         rst,
  input logic         in_valid,
  input logic [W-1:0] in_data,
  input logic         out_ready
);
  logic         in_ready, out_valid;
  logic [W-1:0] out_data;

  tex_skid #(.W(W)) dut (
    .clk, .rst, .in_valid, .in_ready, .in_data, .out_valid, .out_ready, .out_data,
    .f_skid_data()
  );

  always_comb if ($initstate) assume (rst);
endmodule

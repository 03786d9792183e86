// tex_skid: two-entry skid buffer that registers the ready path of a valid/ready channel.
// Handshake: valid/ready on both sides; in_ready is a register (!skid_valid), so it never depends
//   combinationally on out_ready. The producer advances on in_valid && in_ready.
// Latency: 1 clock (in -> out register; tex_unit clock 10). Throughput: 1 per clock; the output
//   is valid in every cycle in which an item is stored, so the only bubbles are the producer's.
// Ports: in_data / out_data: W bits, opaque. Only the two valid bits are reset.
module tex_skid #(
  parameter int W = 8
) (
  input  logic         clk,
  input  logic         rst,
  input  logic         in_valid,
  output logic         in_ready,
  input  logic [W-1:0] in_data,
  output logic         out_valid,
  input  logic         out_ready,
  output logic [W-1:0] out_data
);
  logic         skid_valid;
  logic [W-1:0] skid_data;

  assign in_ready = !skid_valid;

  // Control: the output register refills from the skid entry first (order), else from the input.
  always_ff @(posedge clk) begin
    if (rst) begin
      out_valid  <= 1'b0;
      skid_valid <= 1'b0;
    end else if (out_ready || !out_valid) begin
      out_valid  <= skid_valid || in_valid;
      skid_valid <= 1'b0;
    end else if (in_valid && !skid_valid) begin
      skid_valid <= 1'b1;  // output stalled: park the accepted item
    end
  end

  always_ff @(posedge clk) begin
    if (out_ready || !out_valid) out_data <= skid_valid ? skid_data : in_data;
    else if (in_valid && !skid_valid) skid_data <= in_data;
  end
endmodule

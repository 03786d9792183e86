// Formal harness of tex_skid (scripts/formal.sh; docs/verification.md, "Formal proofs").
// The producer sends the sequence numbers 0, 1, 2, ... (mod 2^W) as data, offered until taken;
// the consumer's out_ready is free. Proven for every input sequence, by induction:
//   order    - every item leaves with the next sequence number: none lost, duplicated or reordered;
//   hold     - out_valid stays high with out_data stable until out_ready;
//   capacity - items held = accepted - emitted <= 2, and equals out_valid + the skid entry.
// (in_ready never depending combinationally on out_ready is a structural check in formal.sh.)
module tex_skid_formal #(
  parameter int W = 4
) (
  input logic clk,
  input logic rst,
  input logic in_valid,
  input logic out_ready
);
  logic         in_ready, out_valid;
  logic [W-1:0] in_data, out_data;
  logic [W-1:0] sent, received;  // sequence numbers accepted / emitted
  logic         started = 1'b0;  // the first clock is a reset
  logic         out_stalled_q;
  logic [W-1:0] out_data_q;

  tex_skid #(.W(W)) dut (
    .clk, .rst, .in_valid, .in_ready, .in_data, .out_valid, .out_ready, .out_data
  );

  assign in_data = sent;

  always_ff @(posedge clk) begin
    started <= 1'b1;
    out_stalled_q <= !rst && out_valid && !out_ready;
    out_data_q <= out_data;
    if (rst) begin
      sent <= '0;
      received <= '0;
    end else begin
      sent <= sent + W'(in_valid && in_ready);
      received <= received + W'(out_valid && out_ready);
    end
  end

`ifdef FORMAL
  always_comb if (!started) assume (rst);
  always_comb begin
    if (started && !rst) begin
      // order: the item at the output is the oldest not yet emitted
      if (out_valid) assert (out_data == received);
      // capacity: held items match the valid bits, at most 2
      assert (W'(sent - received) == W'(out_valid) + W'(!in_ready));
      assert (W'(sent - received) <= W'(2));
      // the skid entry is only used behind a valid output
      if (!in_ready) assert (out_valid);
      // hold: a stalled response stays, unchanged
      if (out_stalled_q) assert (out_valid && out_data == out_data_q);
    end
  end
`endif
endmodule

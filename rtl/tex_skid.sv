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
`ifdef FORMAL
  ,
  output logic [W-1:0] f_skid_data  // the skid entry, for tex_unit's formal invariants
`endif
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

`ifdef FORMAL
  // ---------------------------------------------------------------- formal properties
  // Proven by scripts/formal.sh (k-induction, Yosys), standalone and inside tex_unit. They hold
  // from the first reset on, for any inputs, also with a reset in mid-traffic. The tracked item:
  // the f_pick-th accepted (mod 8; f_pick any constant), its data taken when it is accepted.
  assign f_skid_data = skid_data;

  logic       f_reset_done = 1'b0;  // a reset has been applied (the valid bits are defined)
  logic [2:0] f_held;               // items accepted minus emitted since the reset
  logic [2:0] f_emitted;            // items emitted since the reset, mod 8
  (* anyconst *) logic [2:0] f_pick;
  logic [W-1:0] f_pick_data;
  logic [2:0] f_pos;                // the tracked item's place: 0 output register, 1 skid entry
  logic       f_stalled_q;          // out_valid && !out_ready in the previous cycle, no reset
  logic [W-1:0] f_out_data_q;
  logic       f_in_take, f_out_take;

  assign f_in_take  = in_valid && in_ready;
  assign f_out_take = out_valid && out_ready;
  assign f_pos      = f_pick - f_emitted;
  always_ff @(posedge clk) begin
    f_stalled_q  <= !rst && out_valid && !out_ready;
    f_out_data_q <= out_data;
    // (an item accepted now is number f_emitted + f_held: it is f_pick when f_pos == f_held)
    if (f_in_take && f_pos == f_held) f_pick_data <= in_data;
    if (rst) begin
      f_reset_done <= 1'b1;
      f_held       <= '0;
      f_emitted    <= '0;
    end else begin
      f_held    <= f_held + 3'(f_in_take) - 3'(f_out_take);
      f_emitted <= f_emitted + 3'(f_out_take);
    end
  end

  always_comb begin
    if (f_reset_done) begin
      // capacity: the items held are the valid bits; the skid entry only behind a valid output
      assert (f_held == 3'(out_valid) + 3'(skid_valid));
      assert (!skid_valid || out_valid);
      assert (f_held <= 3'd2);
      // order: the tracked item leaves as the f_pick-th emitted, with its data (none lost,
      // duplicated or reordered); while held it sits at place f_pos with its data
      if (out_valid && f_pos == 3'd0) assert (out_data == f_pick_data);
      if (skid_valid && f_pos == 3'd1) assert (skid_data == f_pick_data);
      // hold: a stalled output stays valid with the same data
      if (f_stalled_q) assert (out_valid && out_data == f_out_data_q);
    end
  end
`endif
endmodule

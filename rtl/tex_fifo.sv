// tex_fifo: a first-in first-out queue of W-bit entries in a memory of DEPTH entries (a power of
// two), read asynchronously (LUT RAM). The cached fetch's sample FIFO.
// Handshake: push writes push_data at the tail (the caller pushes only with room: count < DEPTH
//   or a pop in the same clock); pop removes the head (only when count != 0). head is the oldest
//   entry (undefined when empty).
// Latency: an entry pushed in clock n is the head from clock n+1 (the FIFO empty). Throughput:
//   one push and one pop per clock.
// Ports:
//   count      : entries held (0..DEPTH, unsigned)
//   count_next : entries held after this clock's push and pop (for a registered "room" signal)
`include "tex_param_error.svh"
module tex_fifo #(
  parameter int W     = 8,
  parameter int DEPTH = 4,                   // power of two, >= 2
  parameter int CNW   = $clog2(DEPTH + 1)    // derived, do not override
) (
  input  logic           clk,
  input  logic           rst,
  input  logic           push,
  input  logic [W-1:0]   push_data,
  input  logic           pop,
  output logic [W-1:0]   head,
  output logic [CNW-1:0] count,
  output logic [CNW-1:0] count_next
);
  /*verilator inline_module*/  // (one evaluation with its caller)
  localparam int PW = $clog2(DEPTH);
  generate
    if (DEPTH < 2 || (DEPTH & (DEPTH - 1)) != 0) begin : g_bad_depth
      `TEX_PARAM_ERROR("tex_fifo: parameter DEPTH must be a power of two, at least 2")
    end
  endgenerate

  logic [W-1:0]  mem [DEPTH];
  logic [PW-1:0] wr, rd;
  always_ff @(posedge clk)
    if (push) mem[wr] <= push_data;
  assign head       = mem[rd];
  assign count_next = count + CNW'(push) - CNW'(pop);
  always_ff @(posedge clk) begin
    if (rst) begin
      wr    <= '0;
      rd    <= '0;
      count <= '0;
    end else begin
      wr    <= wr + PW'(push);
      rd    <= rd + PW'(pop);
      count <= count_next;
    end
  end
endmodule

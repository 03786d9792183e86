// tex_fill_fifo: lines from memory on their way into the cache (docs/memory.md §3): the read
// port's beats assembled in place, line by line, oldest first, each with an error mark.
// Handshake: mem_rsp is valid/ready; mem_rsp_ready (a function of registers only) is high while
//   there is room for one more line. retire: the head line is written into its cache in this
//   clock and leaves (only when count != 0).
// Latency: a line whose last beat comes in clock n is the head from clock n+1 (the FIFO empty).
// Throughput: one beat in and one line out per clock.
// Ports:
//   mem_rsp_data  : one beat, MEM_W bits: bytes [i*MEM_W/8 +: MEM_W/8] of the line in beat i;
//                   LINE_BITS / MEM_W beats per line, in order
//   mem_rsp_error : the beat came with an error (AXI RRESP SLVERR or DECERR)
//   head_line     : the oldest line (LINE_BITS, as memory holds it); head_error: any of its
//                   beats came with an error
//   count         : lines held (0..DEPTH, unsigned); line_done: a line's last beat is taken in
//                   this clock; mid_line: some beats of a line are taken, not yet its last
`include "tex_param_error.svh"
module tex_fill_fifo #(
  parameter int DEPTH     = 4,    // lines (power of two)
  parameter int MEM_W     = 128,  // bits of a beat (divides LINE_BITS)
  parameter int LINE_BITS = 512,
  parameter int LCW       = $clog2(DEPTH + 1)  // derived, do not override
) (
  input  logic                 clk,
  input  logic                 rst,
  input  logic                 mem_rsp_valid,
  output logic                 mem_rsp_ready,
  input  logic [MEM_W-1:0]     mem_rsp_data,
  input  logic                 mem_rsp_error,
  input  logic                 retire,
  output logic [LINE_BITS-1:0] head_line,
  output logic                 head_error,
  output logic [LCW-1:0]       count,
  output logic                 line_done,
  output logic                 mid_line
);
  /*verilator inline_module*/  // (one evaluation with its caller, as before the split)
  localparam int BEATS = LINE_BITS / MEM_W;
  localparam int BTW   = (BEATS > 1) ? $clog2(BEATS) : 1;
  localparam int LPW   = (DEPTH > 1) ? $clog2(DEPTH) : 1;
  generate
    if (DEPTH < 1 || (DEPTH & (DEPTH - 1)) != 0) begin : g_bad_depth
      `TEX_PARAM_ERROR("tex_fill_fifo: parameter DEPTH must be a power of two")
    end
    if (MEM_W < 1 || LINE_BITS % MEM_W != 0) begin : g_bad_mem_w
      `TEX_PARAM_ERROR("tex_fill_fifo: parameter MEM_W must divide LINE_BITS")
    end
  endgenerate

  logic [LINE_BITS-1:0] lines [DEPTH];
  logic [DEPTH-1:0]     line_err;  // the line came with an error in any beat
  logic [LPW-1:0]       wr, rd;
  logic [BTW-1:0]       beat;
  logic                 beat_take;
  logic                 beat_err;  // an earlier beat of the line being received did
  assign mem_rsp_ready = count != LCW'(DEPTH);
  assign beat_take     = mem_rsp_valid && mem_rsp_ready;
  assign line_done     = beat_take && (BEATS == 1 || beat == BTW'(BEATS - 1));
  assign mid_line      = beat != '0;
  assign head_line     = lines[rd];
  assign head_error    = line_err[rd];
  always_ff @(posedge clk) begin
    if (beat_take) lines[wr][32'(beat)*MEM_W +: MEM_W] <= mem_rsp_data;  // (beat is 0 if BEATS = 1)
    if (line_done) line_err[wr] <= beat_err || mem_rsp_error;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      wr       <= '0;
      rd       <= '0;
      count    <= '0;
      beat     <= '0;
      beat_err <= 1'b0;
    end else begin
      if (beat_take) beat <= line_done ? '0 : beat + 1'b1;
      if (beat_take) beat_err <= !line_done && (beat_err || mem_rsp_error);
      if (line_done) wr <= (DEPTH > 1) ? wr + 1'b1 : '0;
      if (retire)    rd <= (DEPTH > 1) ? rd + 1'b1 : '0;
      count <= count + LCW'(line_done) - LCW'(retire);
    end
  end

`ifdef FORMAL
  // R channel (scripts/formal.sh): a beat is taken only with room for its line.
  always_comb
    if (!rst) p_rready_1: assert (!(beat_take && count == LCW'(DEPTH)) && count <= LCW'(DEPTH));
`endif
endmodule

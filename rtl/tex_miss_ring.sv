// tex_miss_ring: the cached fetch's misses not yet written into a cache, in the order the tag
// stage found them (docs/memory.md §3): [ret, iss) asked of memory, [iss, wr) waiting for the
// read port. A sample writes up to 8 misses in one clock, so the ring is 8 banks: entry p in bank
// p mod 8, row p / 8, and a sample's k-th miss (at wr + k) goes to a bank of its own, one write
// port each, through an 8-way multiplexer. (One memory with 8 write ports, built of flip-flops and
// their write multiplexers, was most of the unit: 220 k of 256 k ECP5 LUT4s at DEPTH 512.) Reads
// are asynchronous: the banks map to LUT RAM. The line numbers are read where memory is asked
// (iss), the destinations where lines are written into the cache (ret).
// Handshake: push writes the sample's `fills` misses (the caller pushes only with room for 8:
//   used <= DEPTH - 8). mem_req is valid/ready: valid while a miss waits, mem_req_valid and
//   mem_req_addr functions of registers only; a miss leaves mem_req when mem_req_ready. retire:
//   the oldest asked miss's line is written into its cache in this clock (dest is where).
// Latency: a miss pushed in clock n is on mem_req from clock n+1 (the ring empty). Throughput: 8
//   misses in, one request out and one retired per clock.
// Ports:
//   misses        : the k-th miss at [k*MEW +: MEW] (k < fills), {line number (LNW bits),
//                   destination (DSW bits)}; tex_tag_stage's order
//   mem_req_addr  : byte address of the line, line aligned (tex_pkg::MEM_ADDR_W bits)
//   dest          : the oldest asked miss's destination, {line kind, cache, line slot}
//   used          : misses held (asked or not, not yet retired); unissued: those not yet asked
`include "tex_param_error.svh"
module tex_miss_ring #(
  parameter int DEPTH   = 64,  // misses held at most (power of two, >= 16)
  parameter int LNW     = 26,  // bits of a line number
  parameter int DSW     = 10,  // bits of a destination
  parameter int LOG2_LB = 6,   // log2 of a line's bytes: the address's zero low bits
  parameter int MEW     = LNW + DSW,                 // derived, do not override
  parameter int MCW     = $clog2(DEPTH + 1)
) (
  input  logic                           clk,
  input  logic                           rst,
  input  logic                           push,
  input  logic [3:0]                     fills,
  input  logic [8*MEW-1:0]               misses,
  output logic                           mem_req_valid,
  input  logic                           mem_req_ready,
  output logic [tex_pkg::MEM_ADDR_W-1:0] mem_req_addr,
  input  logic                           retire,
  output logic [DSW-1:0]                 dest,
  output logic [MCW-1:0]                 used,
  output logic [MCW-1:0]                 unissued
);
  /*verilator inline_module*/  // (one evaluation with its caller, as before the split)
  localparam int MPW = $clog2(DEPTH);
  localparam int RBW = 3;          // log2 of the 8 banks
  localparam int RRW = MPW - RBW;  // row bits (DEPTH >= 16)
  generate
    if (DEPTH < 16 || (DEPTH & (DEPTH - 1)) != 0) begin : g_bad_depth
      `TEX_PARAM_ERROR("tex_miss_ring: parameter DEPTH must be a power of two, at least 16")
    end
    if (LNW + LOG2_LB != tex_pkg::MEM_ADDR_W) begin : g_bad_lnw
      `TEX_PARAM_ERROR("tex_miss_ring: LNW + LOG2_LB must be tex_pkg::MEM_ADDR_W")
    end
  endgenerate

  logic [MPW-1:0] wr, iss, ret;
  logic           issue;
  logic [LNW-1:0] bank_line [8];  // bank rb's line number at iss's row
  logic [DSW-1:0] bank_dest [8];  // bank rb's destination at ret's row
  logic [MEW-1:0] miss_k [8];     // the sample's k-th miss (an array: a bank picks one by a mux)
  always_comb
    for (int k = 0; k < 8; k++) miss_k[k] = misses[k*MEW +: MEW];
  genvar rb;
  generate
    for (rb = 0; rb < 8; rb = rb + 1) begin : g_ring_bank
      logic [LNW-1:0] line_mem [1 << RRW];
      logic [DSW-1:0] dest_mem [1 << RRW];
      always_ff @(posedge clk) begin
        if (push) begin
          logic [RBW-1:0] k;    // the sample's miss that lands in this bank: (rb - wr) mod 8
          logic [RRW-1:0] row;  // its row: its place in the ring, wr + k, over 8
          k   = RBW'(rb) - wr[RBW-1:0];
          row = RRW'((wr + MPW'(k)) >> RBW);
          if ({1'b0, k} < fills) begin
            line_mem[row] <= miss_k[k][MEW-1 -: LNW];
            dest_mem[row] <= miss_k[k][DSW-1:0];
          end
        end
      end
      assign bank_line[rb] = line_mem[iss[MPW-1:RBW]];
      assign bank_dest[rb] = dest_mem[ret[MPW-1:RBW]];
    end
  endgenerate
  assign issue         = mem_req_valid && mem_req_ready;
  assign mem_req_valid = unissued != '0;
  assign mem_req_addr  = {bank_line[iss[RBW-1:0]], LOG2_LB'(0)};  // a line: aligned
  assign dest          = bank_dest[ret[RBW-1:0]];
  always_ff @(posedge clk) begin
    if (rst) begin
      wr       <= '0;
      iss      <= '0;
      ret      <= '0;
      used     <= '0;
      unissued <= '0;
    end else begin
      wr       <= wr + (push ? MPW'(fills) : '0);
      iss      <= iss + MPW'(issue);
      ret      <= ret + MPW'(retire);
      used     <= used + (push ? MCW'(fills) : '0) - MCW'(retire);
      unissued <= unissued + (push ? MCW'(fills) : '0) - MCW'(issue);
    end
  end

`ifdef FORMAL
  // The ring's accounting (scripts/formal.sh, with tex_cached_fetch's AXI4 read-channel
  // properties, which these make inductive): the pointers agree with the counts.
  always_comb begin
    if (!rst) p_aroutstanding_2: assert (unissued <= used && used <= MCW'(DEPTH));
    if (!rst) p_aroutstanding_6: assert (MPW'(wr - iss) == MPW'(unissued) && MPW'(wr - ret) == MPW'(used));
  end
`endif
endmodule

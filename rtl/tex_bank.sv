// tex_bank: one parity bank of a level memory: simple dual-port RAM, synchronous read (BRAM style).
// Handshake: none. Write: one word per clock when we; readable from the next clock.
//   Read: rdata <= mem[raddr] at the clock edge when re is high, held otherwise (so a stalled
//   pipeline keeps its read data). Read and write of the same word on one edge: old or new data.
// Latency: 1 clock (raddr -> rdata). Throughput: 1 read and 1 write per clock.
// Ports: waddr/raddr: AW-bit word address (DEPTH words); wdata/rdata: DW bits, opaque (a texel).
module tex_bank #(
  parameter int AW    = 1,
  parameter int DEPTH = 2,
  parameter int DW    = 32
) (
  input  logic          clk,
  input  logic          we,
  input  logic [AW-1:0] waddr,
  input  logic [DW-1:0] wdata,
  input  logic          re,
  input  logic [AW-1:0] raddr,
  output logic [DW-1:0] rdata
);
  logic [DW-1:0] mem [0:DEPTH-1];
  always_ff @(posedge clk) begin
    if (we) mem[waddr] <= wdata;
    if (re) rdata <= mem[raddr];
  end
endmodule

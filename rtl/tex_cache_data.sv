// tex_cache_data: the data of one texture cache (docs/memory.md §2): 4 banks, each a simple
// dual-port RAM of LINES words of a quarter line. A line of texels (wr_kind 0) is spread by texel
// parity: word `slot` of bank b holds the BW*BH/4 texels of line `slot` whose parity
// (y & 1)*2 + (x & 1) is b, texel (x, y) of the line at offset ((y >> 1) * (BW/2) + (x >> 1)).
// A line of 4x4 blocks of a block format (wr_kind 1: 8-byte blocks, 2: 16-byte blocks; built when
// BLOCKS) is spread by block parity the same way: the line holds 2^a x 2^b blocks (a = b or b + 1,
// in row-major order in memory), bank b's word holds those whose parity (by & 1)*2 + (bx & 1) is
// b, block (bx, by) at block offset ((by >> 1) * 2^(a-1) + (bx >> 1)). Either way any 2x2
// footprint, even one straddling four lines, is one read per bank.
// Handshake: none. Write: the whole line wr_line into slot wr_slot at the clock edge when wr_en
//   (all 4 banks at once). Read: at the clock edge when re, bank b's rd_word <= word rd_slot of
//   bank b (a read of the word written at the same edge gets the old data); held otherwise.
// Latency: 1 clock. Throughput: 4 word reads and 1 line write per clock.
// Ports:
//   wr_line   : the line, texel j = (y mod BH)*BW + (x mod BW) at [j*DW +: DW], each {A, B, G, R}
//               of CW bits; a block line: its bytes as memory holds them (byte i at [8i +: 8])
//   wr_kind   : 0 texels, 1 8-byte blocks, 2 16-byte blocks (only when BLOCKS)
//   rd_slot   : bank b's line slot at [b*SLW +: SLW]
//   rd_word   : bank b's word at [b*WW +: WW] (WW = BW*BH*DW/4); the reader picks a texel or a block
module tex_cache_data #(
  parameter int LINES  = 128,
  parameter int BW     = 4,   // line width and height in texels: 2, 4 or 8
  parameter int BH     = 4,
  parameter int DW     = 32,  // bits of a texel: 4 * CW
  parameter int BLOCKS = 0,   // 1: block lines too (needs DW = 32 and 4 blocks of 16 bytes per line)
  parameter int SLW    = $clog2(LINES),  // derived
  parameter int WW     = BW * BH * DW / 4
) (
  input  logic                   clk,
  input  logic                   wr_en,
  input  logic [SLW-1:0]         wr_slot,
  input  logic [BW*BH*DW-1:0]    wr_line,
  input  logic [1:0]             wr_kind,
  input  logic                   re,
  input  logic [4*SLW-1:0]       rd_slot,
  output logic [4*WW-1:0]        rd_word
);
  localparam int TPW = BW * BH / 4;  // texels per word
  // Block lines: 2^A x 2^(L-A) blocks per line, L = log2(blocks), A = ceil(L / 2).
  localparam int L8  = $clog2(BW * BH * DW / 64);   // 8-byte blocks
  localparam int L16 = $clog2(BW * BH * DW / 128);  // 16-byte blocks
  localparam int A8  = (L8 + 1) / 2;
  localparam int A16 = (L16 + 1) / 2;
  localparam int H8  = (A8 > 0) ? A8 - 1 : 0;    // log2 of a word's blocks per row (>= 0 when BLOCKS)
  localparam int H16 = (A16 > 0) ? A16 - 1 : 0;
  localparam int S8  = (WW >= 64) ? 64 : WW;    // an 8-byte, a 16-byte block's bits (narrower
  localparam int S16 = (WW >= 128) ? 128 : WW;  // only in units without BLOCKS, never used there)

  // The line's word for bank b in the arrangement `kind` (constant loop bounds per kind).
  function automatic logic [WW-1:0] bank_word(input logic [BW*BH*DW-1:0] line, input logic [1:0] kind,
                                               input int b);
    bank_word = '0;
    if (BLOCKS == 0 || kind == 2'd0) begin
      for (int o = 0; o < TPW; o++)
        bank_word[o*DW +: DW] = line[((2*(o / (BW/2)) + b/2)*BW + 2*(o % (BW/2)) + b%2)*DW +: DW];
    end else if (kind == 2'd1) begin
      for (int o = 0; o < WW / 64; o++)
        bank_word[o*S8 +: S8] =
            line[(((2*(o >> H8) + b/2) << A8) + 2*(o & ((1 << H8) - 1)) + b%2)*S8 +: S8];
    end else begin
      for (int o = 0; o < WW / 128; o++)
        bank_word[o*S16 +: S16] =
            line[(((2*(o >> H16) + b/2) << A16) + 2*(o & ((1 << H16) - 1)) + b%2)*S16 +: S16];
    end
  endfunction

  genvar b;
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_bank
      logic [WW-1:0] mem [LINES];
      logic [WW-1:0] word;  // the read register (RAM style)
      // The read comes first and the write is blocking: a read of the word written at the same
      // edge gets the old data, as with a non-blocking write, since `mem` is private to this
      // process; Verilator then keeps no delayed-write shadow (flag, slot, word) per bank, which
      // it would clear on every clock (waiver in rtl/tex_unit.vlt).
      always_ff @(posedge clk) begin
        if (re) word <= mem[rd_slot[b*SLW +: SLW]];  // the old data if written now
        // (the reordering inside the write: a simulator skips it in clocks without a write)
        if (wr_en) mem[wr_slot] = bank_word(wr_line, wr_kind, b);  // blocking, after the read
      end
      assign rd_word[b*WW +: WW] = word;
    end
  endgenerate
endmodule

// tex_cache_data: the data of one texture cache (docs/memory.md §2): 4 texel-parity banks, each
// a simple dual-port RAM of LINES words; word `slot` of bank b holds the BW*BH/4 texels of line
// `slot` whose parity (y & 1)*2 + (x & 1) is b, texel (x, y) of the block at offset
// ((y >> 1) * (BW/2) + (x >> 1)) of the word. Any 2x2 footprint, even one straddling four lines,
// is one read per bank.
// Handshake: none. Write: the whole line wr_line into slot wr_slot at the clock edge when wr_en
//   (all 4 banks at once). Read: at the clock edge when re, bank b's rd_texel <= the texel at
//   rd_offset of word rd_slot (a read of the word written at the same edge gets the old data);
//   held otherwise.
// Latency: 1 clock. Throughput: 4 texel reads and 1 line write per clock.
// Ports:
//   wr_line   : the line's texels in block order, texel j = (y mod BH)*BW + (x mod BW) at
//               [j*DW +: DW], each {A, B, G, R} of CW bits
//   rd_slot   : bank b's line slot at [b*SLW +: SLW];  rd_offset: bank b's texel at [b*OFW +: OFW]
//   rd_texel  : bank b's texel at [b*DW +: DW] (from the read register through a TPW:1 mux)
module tex_cache_data #(
  parameter int LINES = 128,
  parameter int BW    = 4,   // block width and height in texels: 2, 4 or 8
  parameter int BH    = 4,
  parameter int DW    = 32,  // bits of a texel: 4 * CW
  parameter int SLW   = $clog2(LINES),              // derived
  parameter int OFW   = $clog2(BW * BH / 4) > 0 ? $clog2(BW * BH / 4) : 1  // derived
) (
  input  logic                   clk,
  input  logic                   wr_en,
  input  logic [SLW-1:0]         wr_slot,
  input  logic [BW*BH*DW-1:0]    wr_line,
  input  logic                   re,
  input  logic [4*SLW-1:0]       rd_slot,
  input  logic [4*OFW-1:0]       rd_offset,
  output logic [4*DW-1:0]        rd_texel
);
  localparam int TPW = BW * BH / 4;  // texels per word
  genvar b;
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_bank
      logic [TPW*DW-1:0] mem [LINES];
      logic [TPW*DW-1:0] word;    // the read register (RAM style), then the texel mux
      logic [OFW-1:0]    offset;
      // The read comes first and the write is blocking: a read of the word written at the same
      // edge gets the old data, as with a non-blocking write, since `mem` is private to this
      // process; Verilator then keeps no delayed-write shadow (flag, slot, word) per bank, which
      // it would clear on every clock (waiver in rtl/tex_unit.vlt).
      always_ff @(posedge clk) begin
        if (re) begin
          word   <= mem[rd_slot[b*SLW +: SLW]];  // the old data if written at this edge
          offset <= rd_offset[b*OFW +: OFW];
        end
        if (wr_en) begin
          // The line's texels of parity b, in word order (inside the write: a simulator skips
          // the reordering in clocks without a write).
          logic [TPW*DW-1:0] wr_word;
          for (int o = 0; o < TPW; o++)
            wr_word[o*DW +: DW] = wr_line[((2*(o / (BW/2)) + b/2)*BW + 2*(o % (BW/2)) + b%2)*DW +: DW];
          mem[wr_slot] = wr_word;  // blocking, after the read: see above
        end
      end
      assign rd_texel[b*DW +: DW] = word[offset*DW +: DW];
    end
  endgenerate
endmodule

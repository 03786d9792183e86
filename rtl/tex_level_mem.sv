// tex_level_mem: the memory of one mip level (part of the model's `fetch` stage), split into 4
// tex_banks by texel parity: bank b = (y & 1) * 2 + (x & 1) holds word
// (y >> 1) * 2^(XB-1) + (x >> 1), a fixed stride of the largest texture this level can hold
// (2^XB x 2^YB texels; stride 1 when XB <= 1). A 2x2 footprint after wrap has x taps that are
// equal or of different parity (likewise y), so each bank serves at most one word: the whole
// footprint is read in one clock.
// Handshake: none. Write: one texel per clock when we and wlevel = LEVEL and (wx, wy) lies inside
//   2^XB x 2^YB (ignored otherwise; each tex_bank decodes it). Read: when re (the pipeline enable)
//   and rsel (this level is d or d1), every bank reads the word of slot sel (0 or 1) at the clock
//   edge; otherwise the banks hold their data.
// Latency: 1 clock (raddr -> rdata0..3; tex_unit clock 5). Throughput: one 2x2 footprint per
//   clock, plus 1 write.
// Ports:
//   wlevel     : integer, the level of the write
//   wx, wy     : unsigned COORD_W bits, texel coordinate of the write in its level
//   wdata      : DW bits, texel {A, B, G, R}
//   raddr      : 2 slots x 4 banks of RAW-bit word addresses, slot s bank b at
//                [(s*4 + b)*RAW +: RAW], in this level's layout when the slot's level is LEVEL
//                (it then fits the bank: the bits above the bank's address width are zero)
//   rdata0..3  : the read words of banks 0..3 (one port each: tex_fetch stores them straight into
//                its array of bank words); a bank that cannot exist reads as 0
module tex_level_mem #(
  parameter int LEVEL      = 0,   // mip level (0 = largest)
  parameter int MAX_LOG2_W = 4,   // tex_unit's parameters
  parameter int MAX_LOG2_H = 4,
  parameter int DW         = 32,
  parameter int RAW        = 8    // bits of each word address in raddr (level 0's address width)
) (
  input  logic                         clk,
  input  logic                         we,
  input  logic [tex_pkg::LEVEL_W-1:0]  wlevel,
  input  logic [tex_pkg::COORD_W-1:0]  wx,
  input  logic [tex_pkg::COORD_W-1:0]  wy,
  input  logic [DW-1:0]                wdata,
  input  logic                         re,
  input  logic                         rsel,
  input  logic                         sel,
  input  logic [8*RAW-1:0]             raddr,
  output logic [DW-1:0]                rdata0,
  output logic [DW-1:0]                rdata1,
  output logic [DW-1:0]                rdata2,
  output logic [DW-1:0]                rdata3
);
  localparam int XB = (MAX_LOG2_W > LEVEL) ? MAX_LOG2_W - LEVEL : 0;  // largest log2 width
  localparam int YB = (MAX_LOG2_H > LEVEL) ? MAX_LOG2_H - LEVEL : 0;
  localparam int BX = (XB > 1) ? XB - 1 : 0;  // word-address bits from x >> 1
  localparam int BY = (YB > 1) ? YB - 1 : 0;
  localparam int AW = (BX + BY > 0) ? BX + BY : 1;

  // The bits of raddr above this level's AW are zero (and those of the other slot, unused).
  logic [8*RAW-1:0] raddr_unused;
  assign raddr_unused = raddr;

  genvar b;
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_bank
      logic [DW-1:0] word;  // the bank's read register
      if ((b[0] && XB == 0) || (b[1] && YB == 0)) begin : g_absent
        // A 1-texel side has no odd texels: this bank would never be written.
        assign word = '0;
      end else begin : g_present
        tex_bank #(.LEVEL(LEVEL), .PARITY(b), .XB(XB), .YB(YB), .DW(DW)) u_bank (
          .clk   (clk),
          .we    (we),
          .wlevel(wlevel),
          .wx    (wx),
          .wy    (wy),
          .wdata (wdata),
          .re    (re),
          .rsel  (rsel),
          .raddr (sel ? raddr[(4 + b)*RAW +: AW] : raddr[b*RAW +: AW]),
          .rdata (word)
        );
      end
    end
  endgenerate
  assign rdata0 = g_bank[0].word;
  assign rdata1 = g_bank[1].word;
  assign rdata2 = g_bank[2].word;
  assign rdata3 = g_bank[3].word;
endmodule

// tex_fetch: the model's `fetch` stage: the banked level memories (one tex_level_mem per level,
// 4 tex_banks each), the read of the 2x2 footprints of the sample's two levels (slot 0 = level d,
// slot 1 = level d1), and the routing of bank words to taps
//   a = T(x0,y0), b = T(x1,y0), c = T(x0,y1), e = T(x1,y1),  tap bank = (y&1)*2 + (x&1).
// Only the memories of levels d and d1 read (level k takes slot 0's addresses if k = d, else
// slot 1's); the others hold their words, which the routing does not use. 8 texel reads per
// clock. The write port (registered copies of tex_unit's wr_* pins) writes one texel per clock.
// Handshake: stall-enable; every register and read port loads when en is high. Writes are always
//   accepted (they do not depend on en).
// Latency: 2 clocks: tex_unit clock 5 (bank read registers; level, parity) and clock 6 (taps).
// Throughput: one sample (8 texels) per clock, plus one write per clock.
// Ports:
//   wr_en, wr_level, wr_x, wr_y, wr_data : write of texel (wr_x, wr_y) of level wr_level (unsigned
//                integers; wr_data {A, B, G, R}, CW bits each); outside the level's largest size
//                or beyond the last level: ignored
//   level      : 2 slots of LEVEL_W bits, slot s at [s*LEVEL_W +: LEVEL_W], integers 0..NL-1
//   x, y       : wrapped texel indices of the footprints, unsigned XW (YW) bits; slot s, tap j
//                (0: index i0, 1: i0 + 1) at [(s*2 + j)*XW +: XW]; each fits its level
//   taps       : slot s tap t (0 a, 1 b, 2 c, 3 e) at [(s*4 + t)*DW +: DW], texel {A, B, G, R}
module tex_fetch #(
  parameter int MAX_LOG2_W = 4,
  parameter int MAX_LOG2_H = 4,
  parameter int CW         = 8,
  parameter int XW         = (MAX_LOG2_W > 0) ? MAX_LOG2_W : 1,  // derived, do not override
  parameter int YW         = (MAX_LOG2_H > 0) ? MAX_LOG2_H : 1
) (
  input  logic                         clk,
  input  logic                         en,
  input  logic                         wr_en,
  input  logic [tex_pkg::LEVEL_W-1:0]  wr_level,
  input  logic [tex_pkg::COORD_W-1:0]  wr_x,
  input  logic [tex_pkg::COORD_W-1:0]  wr_y,
  input  logic [4*CW-1:0]              wr_data,
  input  logic [2*tex_pkg::LEVEL_W-1:0] level,
  input  logic [4*XW-1:0]              x,
  input  logic [4*YW-1:0]              y,
  output logic [8*4*CW-1:0]            taps
);
  localparam int VW = tex_pkg::LEVEL_W;
  localparam int NL = ((MAX_LOG2_W > MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H) + 1;
  localparam int DW = 4 * CW;
  localparam int BX0 = (MAX_LOG2_W > 1) ? MAX_LOG2_W - 1 : 0;  // level 0's word-address bits
  localparam int BY0 = (MAX_LOG2_H > 1) ? MAX_LOG2_H - 1 : 0;
  localparam int RAW = (BX0 + BY0 > 0) ? BX0 + BY0 : 1;       // bits of a slot's word address
  localparam int WAW = RAW + tex_pkg::COORD_W;                 // room for the address arithmetic
  localparam int PB  = 4;                                      // parity bits of a footprint

  // ---------------------------------------------------------------- clock 5: read levels d, d1
  // Word address of each bank in each slot's level: bank (py, px) takes the x tap of parity px
  // and the y tap of parity py; word = (y >> 1) << (XB - 1) | (x >> 1), XB of the slot's level.
  logic [8*RAW-1:0] raddr;    // slot s bank b at [(s*4 + b)*RAW +: RAW]
  logic [2*PB-1:0]  parity;   // slot s at [s*PB +: PB]: {y1, y0, x1, x0} & 1 of its footprint
  genvar s, b, k;
  generate
    for (s = 0; s < 2; s = s + 1) begin : g_slot
      logic [VW-1:0]  row_shift;  // log2 of the word stride of the slot's level
      logic [XW-1:0]  x0, x1;
      logic [YW-1:0]  y0, y1;
      if (BX0 > 0) begin : g_stride
        // max(BX0 - level, 0), written without a branch (a mask of the borrow) for Verilator.
        logic [VW:0] diff;
        assign diff      = {1'b0, VW'(BX0)} - {1'b0, level[s*VW +: VW]};
        assign row_shift = diff[VW-1:0] & ~{VW{diff[VW]}};
      end else begin : g_stride_1
        assign row_shift = '0;  // every level is at most 2 texels wide: stride 1
      end
      assign x0        = x[(s*2 + 0)*XW +: XW];
      assign x1        = x[(s*2 + 1)*XW +: XW];
      assign y0        = y[(s*2 + 0)*YW +: YW];
      assign y1        = y[(s*2 + 1)*YW +: YW];
      assign parity[s*PB +: PB] = {y1[0], y0[0], x1[0], x0[0]};
      for (b = 0; b < 4; b = b + 1) begin : g_bank
        logic [XW-1:0] xs;  // the x tap of parity b[0] (either, if both are equal)
        logic [YW-1:0] ys;
        // (x0[0] == b[0]) ? x0 : x1 as a mask: the tap parities are data, and Verilator's C++
        // would branch on them.
        assign xs   = x0 ^ ({XW{x0[0] ^ b[0]}} & (x0 ^ x1));
        assign ys   = y0 ^ ({YW{y0[0] ^ b[1]}} & (y0 ^ y1));
        // < 2^(BX0 + BY0): the cast loses nothing.
        assign raddr[(s*4 + b)*RAW +: RAW] = RAW'(((WAW'(ys) >> 1) << row_shift) | (WAW'(xs) >> 1));
      end
    end
  endgenerate

  // Level memory k reads slot 0's footprint if k = d, slot 1's if k = d1, nothing otherwise (the
  // enable and the level's select go to the banks separately: Verilator then tests en once).
  logic [NL-1:0] read_level;  // bit k: level k is d or d1
  assign read_level = (NL'(1) << level[0 +: VW]) | (NL'(1) << level[VW +: VW]);
  // Bank read registers by level and bank; 2^LEVEL_W levels so that any level index is in range
  // (levels NL and above read as 0: never addressed).
  logic [DW-1:0] bank_word [1 << VW][4];
  generate
    for (k = NL; k < (1 << VW); k = k + 1) begin : g_no_level
      for (b = 0; b < 4; b = b + 1) begin : g_word
        assign bank_word[k][b] = '0;
      end
    end
    for (k = 0; k < NL; k = k + 1) begin : g_level
      logic sel;
      assign sel = level[0 +: VW] != VW'(k);
      tex_level_mem #(.LEVEL(k), .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .DW(DW),
                      .RAW(RAW)) u_mem (
        .clk(clk), .we(wr_en), .wlevel(wr_level), .wx(wr_x), .wy(wr_y), .wdata(wr_data),
        .re(en), .rsel(read_level[k]), .sel(sel), .raddr(raddr),
        .rdata0(bank_word[k][0]), .rdata1(bank_word[k][1]), .rdata2(bank_word[k][2]),
        .rdata3(bank_word[k][3])
      );
    end
  endgenerate

  logic [2*VW-1:0] level_s5;   // slot s at [s*VW +: VW]
  logic [2*PB-1:0] parity_s5;  // slot s at [s*PB +: PB]
  always_ff @(posedge clk) begin
    if (en) begin
      level_s5  <= level;
      parity_s5 <= parity;
    end
  end

  // ---------------------------------------------------------------- clock 6: bank words -> taps
  // Per slot: the 4 bank words of the slot's level (NL:1 level muxes, shared by the slot's taps),
  // then per tap t = (ty, tx) the bank {y parity of tap ty, x parity of tap tx} (4:1 muxes).
  generate
    for (s = 0; s < 2; s = s + 1) begin : g_route
      always_ff @(posedge clk) begin : p_route
        logic [DW-1:0] slot_word [4];  // bank b of the slot's level (a temporary, not a register)
        if (en) begin
          for (int bk = 0; bk < 4; bk = bk + 1) slot_word[bk] = bank_word[level_s5[s*VW +: VW]][bk];
          for (int t = 0; t < 4; t = t + 1) begin  // t: the tap, bit 0 = tx, bit 1 = ty
            taps[(s*4 + t)*DW +: DW] <= slot_word[{parity_s5[s*PB + 2 + t/2], parity_s5[s*PB + t%2]}];
          end
        end
      end
    end
  endgenerate
endmodule

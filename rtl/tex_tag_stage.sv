// tex_tag_stage: the cached fetch's tag stage (docs/memory.md §2-3), on tex_front's clock-4
// outputs. For each slot (0: level d, 1: level d1 when f != 0) it finds the blocks of the 2x2
// footprint the sample needs (a tap of weight 0 or outside its level in address mode border
// needs none), their line numbers (row-major or Morton order of the level's blocks from
// tex_desc_table's entry) and sets; looks them up in the tags of the slot's cache (tex_cache_tags:
// cache 0 holds even levels, cache 1 odd ones), and lists the misses in the order memory is asked
// (slot 0, then slot 1; block parity 0..3), with where each line goes. It also tells each of the
// 8 data-bank reads which line slot and offset it reads, for the sample FIFO.
// Handshake: none; the lookups are made and the tags updated (LRU, victims) only in a clock with
//   push (en && a sample enters the FIFO). Everything else is 0 without push (so a simulator
//   skips the stage while the front waits: the inside of an `if` is not evaluated).
// Latency: 0 (combinational from the inputs; the tags update at the clock edge). Throughput: one
//   sample per clock, up to 4 lookups per cache.
// Ports (formats as tex_front's; XW, YW wrapped index bits):
//   push               : a sample enters in this clock (en_front && front_valid)
//   en                 : en_front, the tags' update enable
//   c0                 : slot 0's cache (bit 0 of level d); slot 1 uses the other
//   f, w, size, x, y   : tex_front's weights, level sizes and tap indices per slot
//   border_x, border_y : a tap outside its level in address mode border (reads no line)
//   line, pitch, square: per slot, tex_desc_table's entry: first line, row-major pitch in
//                        blocks, Morton square's log2
//   fmt                : the texture's format (FMT_RGBA8 without push); log2_lw, log2_lh the
//                        line's units across and down (log2): a unit is a texel (RGBA8) or a
//                        block of the format's footprint (tex_pkg::footprint: 4 x 4, or ASTC's),
//                        unit column x / F of texel column x (docs/memory.md §1)
//   misses             : the sample's k-th miss at [k*MEW +: MEW] (k < fills), {line number,
//                        line kind, cache, line slot}; 0 beyond
//   fills, lookups     : misses (0..8) and lines looked up (0..8) of the sample
//   reads              : slot s bank b's read at [(s*4 + b)*RD +: RD]: {line slot, offset of the
//                        texel or block in the bank word}
//   need               : slot s bank b reads a line the sample looked up (its error counts)
//   tap_low            : per slot at [s*4*PB +: 4*PB]: {y1, y0, x1, x0}, each its unit's parity
//                        (the tap's bank) and, with BLOCK_FORMATS, below it its place in the block
//                        (4 bits, 0..F-1): {parity, place}
module tex_tag_stage #(
  parameter int MAX_LOG2_W    = 10,
  parameter int MAX_LOG2_H    = 10,
  parameter int BW            = 4,   // line width and height in texels: 2, 4, 8
  parameter int BH            = 4,
  parameter int LINES         = 256, // lines per cache (power of two)
  parameter int MAX_WAYS      = 4,
  parameter int BLOCK_FORMATS = 0,   // 1: lines of blocks too (banks by block parity)
  parameter int LNW           = 26,  // bits of a line number
  parameter int XW            = (MAX_LOG2_W > 0) ? MAX_LOG2_W : 1,  // derived, do not override
  parameter int YW            = (MAX_LOG2_H > 0) ? MAX_LOG2_H : 1,
  parameter int PTW           = ((MAX_LOG2_W > MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H) + 1,
  parameter int SLW           = $clog2(LINES),
  parameter int OFW           = ($clog2(BW) + $clog2(BH) - 2 > 0) ? $clog2(BW) + $clog2(BH) - 2 : 1,
  parameter int RD            = SLW + OFW,
  parameter int PB            = (BLOCK_FORMATS != 0) ? 5 : 1,
  parameter int MEW           = LNW + tex_pkg::LINE_KIND_W + 1 + SLW
) (
  input  logic                              clk,
  input  logic                              rst,
  input  logic                              en,
  input  logic                              push,
  input  logic                              c0,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]   f,
  input  logic [4*tex_pkg::WEIGHT_BITS-1:0] w,
  input  logic [4*tex_pkg::SIZE_W-1:0]      size,
  input  logic [4*XW-1:0]                   x,
  input  logic [4*YW-1:0]                   y,
  input  logic [3:0]                        border_x,
  input  logic [3:0]                        border_y,
  input  logic [2*LNW-1:0]                  line,
  input  logic [2*PTW-1:0]                  pitch,
  input  logic [2*tex_pkg::LEVEL_W-1:0]     square,
  input  logic [tex_pkg::FORMAT_W-1:0]      fmt,
  input  logic [tex_pkg::LEVEL_W-1:0]       log2_lw,
  input  logic [tex_pkg::LEVEL_W-1:0]       log2_lh,
  input  logic                              cfg_block_morton,
  input  logic [tex_pkg::LOG2_SETS_W-1:0]   cfg_log2_sets,
  input  logic [tex_pkg::LOG2_WAYS_W-1:0]   cfg_log2_ways,
  output logic [8*MEW-1:0]                  misses,
  output logic [3:0]                        fills,
  output logic [3:0]                        lookups,
  output logic [8*RD-1:0]                   reads,
  output logic [7:0]                        need,
  output logic [8*PB-1:0]                   tap_low
);
  /*verilator inline_module*/  // (one evaluation with its caller, as before the split)
  localparam int VW  = tex_pkg::LEVEL_W;
  localparam int WB  = tex_pkg::WEIGHT_BITS;
  localparam int NW  = tex_pkg::SIZE_W;
  localparam int SHW = SLW - 2;  // bits of a set >> 2

  // A tap's stored coordinate has one bit more than its index: a block format keeps the repeat
  // seam's copy of a side n < 2^XW at n rounded up to 4, which may be 2^XW.
  localparam int XSW = XW + 1, YSW = YW + 1;
  // Morton interleave: a bit 0 at bit 0, b bit 0 at bit 1, a bit 1 at bit 2, ...
  localparam int MCW2 = 2 * ((XSW > YSW) ? XSW : YSW);
  function automatic logic [MCW2-1:0] interleave(input logic [XSW-1:0] a, input logic [YSW-1:0] b);
    interleave = '0;
    for (int i = 0; i < XSW; i++) interleave[2*i]     = a[i];
    for (int i = 0; i < YSW; i++) interleave[2*i + 1] = b[i];
  endfunction
  // A tap's unit (its texel's block, or the texel) and its place in the block: x / F and x mod F
  // for a footprint side F; the repeat seam's second tap (stage::wrap gives it index n on a side
  // with a copy) reads unit column 0's copy, kept at ceil(n / F), at place 0 (docs/memory.md §1).
  // {unit (16 bits), place (4 bits)}.
  function automatic logic [19:0] unit_of(input logic [NW-1:0] i, input logic [NW-1:0] n, input logic [3:0] fp,
                                          input logic second);
    logic [15:0] u;
    if (second && i == n) begin
      u = tex_pkg::div_footprint(16'(i) + 16'(fp) - 16'd1, fp);
      unit_of = {u, 4'd0};
    end else begin
      u = tex_pkg::div_footprint(16'(i), fp);
      unit_of = {u, 4'(16'(i) - u * 16'(fp))};
    end
  endfunction
  // The set index >> 2 (docs/memory.md §2): (xh ^ reverse_k(yh mod 2^k) ^ (yh >> k)) mod 2^k with
  // xh = bx >> 1, yh = by >> 1, k = log2(sets) - 2; rows, columns and neighbouring block rows
  // spread over the sets. tex_cache_tags masks it to k bits. Reversing k bits = reversing SHW bits,
  // then shifting down by SHW - k.
  logic [tex_pkg::LOG2_SETS_W-1:0] set_k;
  assign set_k = cfg_log2_sets - tex_pkg::LOG2_SETS_W'(2);
  function automatic logic [SHW-1:0] set_high(input logic [XSW-1:0] a, input logic [YSW-1:0] b,
                                              input logic [tex_pkg::LOG2_SETS_W-1:0] k);
    logic [YSW+SHW-1:0] yh;  // wide enough for any YSW against SHW
    logic [SHW-1:0]    xh, yl, rev;
    xh = SHW'((XSW+SHW)'(a) >> 1);
    yh = (YSW+SHW)'(b) >> 1;
    yl = SHW'(yh);
    for (int i = 0; i < SHW; i++) rev[i] = yl[SHW-1-i];
    set_high = SHW'(xh) ^ (rev >> (32'(SHW) - 32'(k))) ^ SHW'(yh >> k);
  endfunction

  logic [3:0] fw, fh;  // the format's footprint (RGBA8: 1 x 1)
  assign {fh, fw} = tex_pkg::footprint(fmt);
  // A tap's tap_low: its unit's parity, and with BLOCK_FORMATS its place in the block below it.
  function automatic logic [PB-1:0] low_of(input logic parity, input logic [3:0] place);
    low_of = (PB > 1) ? PB'({parity, place}) : PB'(parity);
  endfunction

  // Per slot s and block parity p = {y parity, x parity}: the lookup, its line number and set.
  logic [3:0]       look [2];
  logic [4*LNW-1:0] look_line [2];
  logic [4*SHW-1:0] look_set_hi [2];
  logic [7:0]       bank_block [2];  // texel bank b: the parity of its tap's block at [b*2 +: 2]
  logic [4*OFW-1:0] bank_offset [2];
  logic [4*PB-1:0]  low [2];         // tap_low's halves
  assign tap_low = {low[1], low[0]};
  genvar s;
  generate
    for (s = 0; s < 2; s = s + 1) begin : g_slot
      always_comb begin : p_lookups
        logic [VW-1:0]  m;            // Morton: the interleaved square's log2
        logic [PTW-1:0] pt;           // row-major: blocks per block row
        logic [NW-1:0]  nw, nh;       // the level's size
        logic [XSW-1:0] x0, x1, bx0, bx1, bx;  // the taps' units, their lines' columns
        logic [YSW-1:0] y0, y1, by0, by1, by;
        logic [3:0]     rx0, rx1, ry0, ry1;    // the taps' places in their blocks
        logic [19:0]    ux0, ux1, uy0, uy1;    // unit_of's {unit, place}
        logic [LNW-1:0] row0, row1;   // row-major: the first block of by0's (by1's) row
        logic          nx1, ny1;     // the second tap along x (y) is needed: its weight != 0
        logic          nx0, ny0;     // the first tap along x (y) is inside its level (not a border tap)
        logic          has_x, has_y;
        logic [LNW-1:0] index;       // a block's number in its level
        logic [LNW-1:0] level_base;  // the level's first line
        logic [XSW-1:0] xs;
        logic [YSW-1:0] ys;
        logic          px0, py0;  // tap 0's bank parity: of its unit
        // (temporaries too: a value on every path, no latch)
        {m, pt, nw, nh, x0, x1, bx0, bx1, bx, y0, y1, by0, by1, by, row0, row1} = '0;
        {rx0, rx1, ry0, ry1, ux0, ux1, uy0, uy1} = '0;
        {nx0, ny0, nx1, ny1, has_x, has_y, index, level_base, xs, ys, px0, py0} = '0;
        look[s]        = '0;
        look_line[s]   = '0;
        look_set_hi[s] = '0;
        bank_block[s]  = '0;
        bank_offset[s] = '0;
        low[s]         = '0;
        // level d always; d1 when f != 0
        if (push && (s == 0 || f != '0)) begin
          level_base = line[s*LNW +: LNW];
          pt    = pitch[s*PTW +: PTW];
          m     = square[s*VW +: VW];
          nw    = size[(s*2 + 0)*NW +: NW];
          nh    = size[(s*2 + 1)*NW +: NW];
          ux0  = unit_of(NW'(x[(s*2 + 0)*XW +: XW]), nw, fw, 1'b0);
          ux1  = unit_of(NW'(x[(s*2 + 1)*XW +: XW]), nw, fw, 1'b1);
          uy0  = unit_of(NW'(y[(s*2 + 0)*YW +: YW]), nh, fh, 1'b0);
          uy1  = unit_of(NW'(y[(s*2 + 1)*YW +: YW]), nh, fh, 1'b1);
          x0   = XSW'(ux0 >> 4);
          x1   = XSW'(ux1 >> 4);
          y0   = YSW'(uy0 >> 4);
          y1   = YSW'(uy1 >> 4);
          {rx0, rx1, ry0, ry1} = {ux0[3:0], ux1[3:0], uy0[3:0], uy1[3:0]};
          bx0  = x0 >> log2_lw;
          bx1  = x1 >> log2_lw;
          by0  = y0 >> log2_lh;
          by1  = y1 >> log2_lh;
          if (!cfg_block_morton) begin
            row0 = LNW'(by0) * LNW'(pt);
            row1 = LNW'(by1) * LNW'(pt);
          end
          // A border tap reads no line (model TextureCache::lookup).
          nx0  = !border_x[s*2];
          ny0  = !border_y[s*2];
          nx1  = w[(s*2 + 0)*WB +: WB] != '0 && !border_x[s*2 + 1];
          ny1  = w[(s*2 + 1)*WB +: WB] != '0 && !border_y[s*2 + 1];
          low[s] = {low_of(y1[0], ry1), low_of(y0[0], ry0), low_of(x1[0], rx1), low_of(x0[0], rx0)};
          px0 = x0[0];
          py0 = y0[0];
          for (int q = 0; q < 4; q++) begin
            // The needed x taps whose block has x parity q[0] (likewise y): bx0 if its parity
            // matches, else bx1 (two distinct blocks of a footprint differ in parity).
            has_x = (nx0 && bx0[0] == q[0]) || (nx1 && bx1[0] == q[0]);
            has_y = (ny0 && by0[0] == q[1]) || (ny1 && by1[0] == q[1]);
            bx    = (nx0 && bx0[0] == q[0]) ? bx0 : bx1;
            by    = (ny0 && by0[0] == q[1]) ? by0 : by1;
            look[s][q] = has_x && has_y;
            if (!cfg_block_morton) begin
              index = ((ny0 && by0[0] == q[1]) ? row0 : row1) + LNW'(bx);
            end else begin
              index = LNW'(interleave(bx & XSW'((1 << m) - 1), by & YSW'((1 << m) - 1)))
                    | (((LNW'(bx) >> m) | (LNW'(by) >> m)) << (2 * m));
            end
            look_line[s][q*LNW +: LNW]   = level_base + index;
            look_set_hi[s][q*SHW +: SHW] = set_high(bx, by, set_k);
          end
          for (int k = 0; k < 4; k++) begin
            // What bank k reads: the x tap of bank parity k[0], the y tap of parity k[1] (either
            // one if both are equal; as masks: Verilator's C++ would branch on data), the parity
            // of its line (which tag bank has its line slot) and its offset in the bank word (of
            // the texel, or of the 4x4 block: docs/memory.md §2, tex_cache_data).
            xs = x0 ^ ({XSW{px0 ^ k[0]}} & (x0 ^ x1));
            ys = y0 ^ ({YSW{py0 ^ k[1]}} & (y0 ^ y1));
            bank_block[s][k*2 +: 2] = {(py0 == k[1]) ? by0[0] : by1[0], (px0 == k[0]) ? bx0[0] : bx1[0]};
            bank_offset[s][k*OFW +: OFW] =
                OFW'((((32'(ys) >> 1) & ((32'd1 << (log2_lh - VW'(1))) - 1)) << (log2_lw - VW'(1)))
                     | ((32'(xs) >> 1) & ((32'd1 << (log2_lw - VW'(1))) - 1)));
          end
        end
      end
    end
  endgenerate

  // ---------------------------------------------------------------- the two caches' tags
  // Cache c takes the lookups of the slot whose level has parity c (slot 1 reads the other
  // cache even when it needs nothing: each data bank then has one reader).
  logic [3:0]       hit_c  [2];
  logic [4*SLW-1:0] slot_c [2];
  genvar c;
  generate
    for (c = 0; c < 2; c = c + 1) begin : g_cache
      logic sc;  // the slot that uses cache c
      assign sc = (c0 != 1'(c));
      tex_cache_tags #(.LINES(LINES), .MAX_WAYS(MAX_WAYS), .LNW(LNW)) u_tags (
        .clk(clk), .rst(rst), .en(en), .cfg_log2_sets(cfg_log2_sets),
        .cfg_log2_ways(cfg_log2_ways), .look_valid(look[sc]), .look_set_hi(look_set_hi[sc]),
        .look_line(look_line[sc]), .hit(hit_c[c]), .slot(slot_c[c])
      );
    end
  endgenerate

  // Per slot: its cache's answers; the misses in order (slot 0, then slot 1; block parity 0..3).
  // Only in a clock with a push, as the lookups.
  logic [7:0]     miss;
  logic [MEW-1:0] miss_entry [8];  // miss i's entry (i = slot * 4 + block parity)
  logic [2:0]     miss_rank [8];   // the misses before miss i
  always_comb begin
    logic [3:0]       hit_s;
    logic [4*SLW-1:0] slot_s;
    logic             cache_s;
    {hit_s, slot_s, cache_s} = '0;
    miss    = '0;
    reads   = '0;
    need    = '0;
    fills   = '0;
    lookups = '0;
    for (int i = 0; i < 8; i++) begin
      miss_entry[i] = '0;
      miss_rank[i]  = '0;
    end
    if (push) begin
      for (int sl = 0; sl < 2; sl++) begin
        cache_s = c0 ^ 1'(sl);
        hit_s   = hit_c[cache_s];
        slot_s  = slot_c[cache_s];
        for (int q = 0; q < 4; q++) begin
          miss[sl*4 + q] = look[sl][q] && !hit_s[q];
          miss_entry[sl*4 + q] =
              {look_line[sl][q*LNW +: LNW], (BLOCK_FORMATS != 0) ? tex_pkg::line_kind(fmt) : tex_pkg::LINE_TEXELS,
               cache_s, slot_s[q*SLW +: SLW]};
          miss_rank[sl*4 + q]  = fills[2:0];
          fills = fills + 4'(miss[sl*4 + q]);
          lookups = lookups + 4'(look[sl][q]);
        end
        for (int k = 0; k < 4; k++) begin
          reads[(sl*4 + k)*RD +: RD] =
              {slot_s[bank_block[sl][k*2 +: 2]*SLW +: SLW], bank_offset[sl][k*OFW +: OFW]};
          need[sl*4 + k] = look[sl][bank_block[sl][k*2 +: 2]];
        end
      end
    end
  end

  // The sample's misses in order: its k-th (k < fills) at [k*MEW +: MEW], an AND-OR of the 8.
  always_comb begin
    for (int k = 0; k < 8; k++) begin
      logic [MEW-1:0] e;
      e = '0;
      if (push)
        for (int i = 0; i < 8; i++)
          if (miss[i] && miss_rank[i] == 3'(k)) e = e | miss_entry[i];
      misses[k*MEW +: MEW] = e;
    end
  end
endmodule

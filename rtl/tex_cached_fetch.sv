// tex_cached_fetch: the model's `fetch` stage in cached mode (docs/memory.md): the pyramid lives
// in external memory and is read through two texture caches (cache 0: even levels, cache 1: odd
// levels), with the latency hidden by a sample FIFO (Igehy, Eldridge & Proudfoot 1998).
//   tag stage  (on tex_front's clock-4 outputs): which taps the sample needs, their blocks, line
//              addresses; up to 4 lookups per cache (tex_cache_tags), LRU update, victims chosen;
//              misses go into the miss ring (to mem_req) in the order of docs/memory.md; the
//              sample, with its taps' line slots and texel offsets, into the sample FIFO.
//   H (head)   the FIFO's oldest sample writes its fills (lines from mem_rsp, in order) into the
//              data banks, one line per clock; it leaves when the last one is written.
//   R          reads the data banks (tex_cache_data), 4 banks x 2 caches.
//   T          routes bank words to the 8 taps (slot 0 = level d, slot 1 = level d1): a texel, or
//              a block format's 4x4 block decoded by one tex_bc_decode per tap (BLOCK_FORMATS);
//              with SRGB an sRGB texture's R, G, B through tex_srgb_decode (24 per sample).
//   taps       registered outputs, into tex_filter.
// Handshake: two stall-enable halves. The front (tex_front and the tag stage) advances when
//   en_front is high: a register output, high when the FIFO has room for one more sample and the
//   miss ring for 8 more misses after this clock. The back (H, R, T, taps, and the filter after
//   it) advances when en_back is high (the top's skid buffer has room). Fills are written only
//   when en_back is high: a sample in R reads the banks at that same edge, before the write.
//   A stage's data registers load only when a sample moves into it (out_tag, taps, out_w, out_f
//   hold their last sample while out_valid is low): a simulator skips the empty stages.
//   mem_req / mem_rsp are valid/ready (tex_unit_cached maps them onto its AXI4 read master: one
//   burst per line, beats in order); mem_req_valid, mem_req_addr and mem_rsp_ready are functions
//   of registers only.
// Memory errors: a line any of whose beats came with mem_rsp_error is written into its slot as it
//   came and marked; a sample whose lookups include a marked line leaves with out_error (the mark
//   goes with the next line written into that slot).
// Latency: front_valid at clock 4 -> out_valid 5 clocks later when every line hits (FIFO push,
//   H, R, T, taps); a miss adds the memory's latency. Throughput: 1 sample per clock while lines
//   hit; a sample with k fills occupies H for max(k, 1) clocks.
// Ports (formats as tex_front's; XW, YW wrapped index bits):
//   front_valid, front_tag          : the clock-4 register holds a request, and its tag
//   level_odd, f, w, size, x, y     : tex_front's outputs (level_odd: bit 0 of slot 0's level)
//   border_x, border_y              : tex_front's too: a tap outside its level in address mode
//                                     border looks no line up and takes the border colour
//   front_line, front_pitch, front_square : per slot, its level's entry in tex_desc_table: the
//                                     first line, the block grid's pitch NBX, the Morton square
//   front_format, front_srgb, front_log2_lw, front_log2_lh : the sample's texture's format
//                                     (tex_pkg::FMT_*; FMT_RGBA8 unless BLOCK_FORMATS), sRGB flag
//                                     (SRGB only) and line shape (log2 texels across, down)
//   front_smp                       : the sample's sampler-table entry: its border colour
//   smp_we, smp_index, smp_border_rgba : a sampler write: entry smp_index's border colour is
//                                     smp_border_rgba, {A, B, G, R} unorm16 (kept here in the
//                                     filter's width, converted once at the write)
//   cfg_block_morton                : 0 row-major, 1 Morton order of the blocks of a level
//   cfg_log2_sets, cfg_log2_ways    : cache geometry (both caches), see tex_cache_tags
//   cfg_fifo_limit                  : samples the FIFO holds at most (0 or > FIFO_DEPTH: FIFO_DEPTH)
//   mem_req_addr                    : byte address of a line (MEM_ADDR_W bits, line aligned)
//   mem_rsp_data                    : one beat, MEM_W bits: bytes [i*MEM_W/8 +: MEM_W/8] of the
//                                     line in beat i; LINE_BITS / MEM_W beats per line, in order;
//                                     a line of texels of 4 channels of CW bits (SRGB: 8) in 4
//                                     (CW > 8: 8) bytes, or of 4x4 blocks
//   mem_rsp_error                   : the beat came with an error (AXI RRESP SLVERR or DECERR)
//   out_valid, out_tag, taps, out_w, out_f : as tex_fetch's taps with the weights beside them
//                                     (SRGB: an sRGB texture's R, G, B linear unorm16, A x 257; a
//                                     linear texture's 8-bit channels zero-extended)
//   out_error                       : a line the sample looked up came with a memory error
//   stat_lookups, stat_misses       : lines the tag stage looks up in this clock (0..8, both
//                                     caches), and of those missing (unsigned, for counters)
//   stat_mem_wait                   : the FIFO's head waits for memory in this clock
// The harness reads fifo_count (the FIFO's occupancy) and head_waits (the head sample waits for
// memory) for its statistics (public in Verilator, rtl/tex_unit.vlt).
module tex_cached_fetch #(
  parameter int MAX_LOG2_W = 10,
  parameter int MAX_LOG2_H = 10,
  parameter int CW         = 8,
  parameter int TAG_W      = 16,
  parameter int BW         = 4,    // block (= cache line) width and height in texels: 2, 4, 8
  parameter int BH         = 4,
  parameter int LINES      = 256,  // lines per cache, at most (power of two)
  parameter int MAX_WAYS   = 4,    // 1, 2, 4
  parameter int FIFO_DEPTH = 256,  // samples waiting for their lines (power of two)
  parameter int MISS_DEPTH = 64,   // misses not yet written into the cache (power of two, >= 8)
  parameter int FILL_DEPTH = 4,    // lines received, not yet written (power of two)
  parameter int MEM_W      = 128,  // bits of a memory response beat
  parameter int SAMPLERS   = 16,   // sampler-table entries (power of two, 1..16)
  parameter int BLOCK_FORMATS = 0, // 1: block-format textures too (needs 8-bit memory channels and
                                   //    >= 16 texels per line)
  parameter int SRGB       = 0,    // 1: memory holds 8-bit channels, the taps are CW = 16 bits: sRGB
                                   //    textures' R, G, B decoded to linear by tex_srgb_decode
  parameter int XW         = (MAX_LOG2_W > 0) ? MAX_LOG2_W : 1,  // derived, do not override
  parameter int YW         = (MAX_LOG2_H > 0) ? MAX_LOG2_H : 1,
  parameter int SXW        = (SAMPLERS > 1) ? $clog2(SAMPLERS) : 1,
  parameter int PTW        = ((MAX_LOG2_W > MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H) + 1,  // tex_desc_table's
  parameter int LNW        = tex_pkg::MEM_ADDR_W - $clog2(BW * BH * (((SRGB == 0) && CW > 8) ? 8 : 4))
) (
  input  logic                              clk,
  input  logic                              rst,
  output logic                              en_front,
  input  logic                              en_back,

  input  logic                              front_valid,
  input  logic [TAG_W-1:0]                  front_tag,
  input  logic [SXW-1:0]                    front_smp,
  input  logic                              level_odd,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]   f,
  input  logic [4*tex_pkg::WEIGHT_BITS-1:0] w,
  input  logic [4*tex_pkg::SIZE_W-1:0]      size,
  input  logic [4*XW-1:0]                   x,
  input  logic [4*YW-1:0]                   y,
  input  logic [3:0]                        border_x,
  input  logic [3:0]                        border_y,

  input  logic                              smp_we,
  input  logic [SXW-1:0]                    smp_index,
  input  logic [63:0]                       smp_border_rgba,

  input  logic [2*LNW-1:0]                  front_line,
  input  logic [2*PTW-1:0]                  front_pitch,
  input  logic [2*tex_pkg::LEVEL_W-1:0]     front_square,
  input  logic [tex_pkg::FORMAT_W-1:0]      front_format,
  input  logic                              front_srgb,
  input  logic [tex_pkg::LEVEL_W-1:0]       front_log2_lw,
  input  logic [tex_pkg::LEVEL_W-1:0]       front_log2_lh,
  input  logic                              cfg_block_morton,
  input  logic [tex_pkg::LOG2_SETS_W-1:0]   cfg_log2_sets,
  input  logic [tex_pkg::LOG2_WAYS_W-1:0]   cfg_log2_ways,
  input  logic [$clog2(FIFO_DEPTH+1)-1:0]   cfg_fifo_limit,

  output logic                              mem_req_valid,
  input  logic                              mem_req_ready,
  output logic [tex_pkg::MEM_ADDR_W-1:0]    mem_req_addr,
  input  logic                              mem_rsp_valid,
  output logic                              mem_rsp_ready,
  input  logic [MEM_W-1:0]                  mem_rsp_data,
  input  logic                              mem_rsp_error,

  output logic                              out_valid,
  output logic [TAG_W-1:0]                  out_tag,
  output logic [32*CW-1:0]                  taps,
  output logic [4*tex_pkg::WEIGHT_BITS-1:0] out_w,
  output logic [tex_pkg::WEIGHT_BITS-1:0]   out_f,
  output logic                              out_error,

  output logic [3:0]                        stat_lookups,
  output logic [3:0]                        stat_misses,
  output logic                              stat_mem_wait
);
  localparam int VW   = tex_pkg::LEVEL_W;
  localparam int WB   = tex_pkg::WEIGHT_BITS;
  localparam int DW   = 4 * CW;                     // a tap's texel
  localparam int CCW  = (SRGB != 0) ? 8 : CW;       // bits of a channel in the cache
  localparam int DWC  = 4 * CCW;                    // a texel in the cache
  localparam int TB   = (CCW > 8) ? 8 : 4;          // bytes of a texel in memory
  localparam int LBW  = $clog2(BW);                 // log2 block width, height
  localparam int LBH  = $clog2(BH);
  localparam int LINE_BITS = BW * BH * TB * 8;
  localparam int LOG2_LB   = $clog2(BW * BH * TB);  // log2 line bytes
  localparam int NW   = tex_pkg::SIZE_W;
  localparam int SLW  = $clog2(LINES);              // bits of a line slot
  localparam int SHW  = SLW - 2;                    // bits of a set >> 2
  localparam int OFW  = (LBW + LBH - 2 > 0) ? LBW + LBH - 2 : 1;  // texel offset in a bank word
  localparam int BEATS = LINE_BITS / MEM_W;
  localparam int FCW  = $clog2(FIFO_DEPTH + 1);
  localparam int MCW  = $clog2(MISS_DEPTH + 1);
  localparam int LCW  = $clog2(FILL_DEPTH + 1);
  localparam int BTW  = (BEATS > 1) ? $clog2(BEATS) : 1;
  localparam int RD   = SLW + OFW;                  // a bank read: {slot, offset}
  localparam int FW   = tex_pkg::FORMAT_W;
  localparam int PB   = (BLOCK_FORMATS != 0) ? 3 : 1;  // low bits of a tap coordinate the taps need
  localparam int WW   = LINE_BITS / 4;              // bits of a bank word
  localparam int KW   = 2;                          // a line's kind in the banks (tex_cache_data)

  // Its kind in the data banks: 0 texels, 1 8-byte blocks, 2 16-byte blocks.
  function automatic logic [KW-1:0] line_kind(input logic [FW-1:0] fmt);
    if (BLOCK_FORMATS == 0 || fmt == tex_pkg::FMT_RGBA8) line_kind = 2'd0;
    else if (fmt == tex_pkg::FMT_BC1 || fmt == tex_pkg::FMT_BC4) line_kind = 2'd1;
    else line_kind = 2'd2;
  endfunction

  // ---------------------------------------------------------------- tag stage
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
  // The stored coordinate of a second tap (the only one the repeat seam moves: stage::wrap gives
  // it index n on a side n that is not a power of two): a block format's copy is at n rounded up
  // to a whole 4x4 block; texels keep theirs at n.
  function automatic logic [NW:0] block_seam(input logic [NW-1:0] n);
    block_seam = ({1'b0, n} + (NW+1)'(3)) & ~(NW+1)'(3);
  endfunction
  function automatic logic [XSW-1:0] stored_x(input logic [XW-1:0] i, input logic [NW-1:0] n, input logic bc);
    stored_x = (bc && (NW+1)'(i) == {1'b0, n}) ? XSW'(block_seam(n)) : XSW'(i);
  endfunction
  function automatic logic [YSW-1:0] stored_y(input logic [YW-1:0] i, input logic [NW-1:0] n, input logic bc);
    stored_y = (bc && (NW+1)'(i) == {1'b0, n}) ? YSW'(block_seam(n)) : YSW'(i);
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

  // A sample enters the tag stage (and the FIFO) in this clock. Everything the tag stage computes
  // is used only then, so it is computed only then and is 0 otherwise: the same registers result,
  // and a simulator skips the stage in the clocks in which the front waits (Verilator evaluates
  // every continuous assignment in every clock, but not the inside of an `if`).
  logic push;
  assign push = en_front && front_valid;
  logic c0;                 // the cache of slot 0 (level d's parity); slot 1 uses the other
  assign c0 = level_odd;
  // The sample's texture format, its line shape and bank kind (tex_desc_table's entry).
  logic [FW-1:0] fmt;
  logic [VW-1:0] lbw, lbh;  // log2 of the line's texels across, down
  logic          blk;       // a block format: banks by 4x4-block parity, not texel parity
  assign fmt        = push ? front_format : tex_pkg::FMT_RGBA8;
  assign lbw        = front_log2_lw;
  assign lbh        = front_log2_lh;
  assign blk        = fmt != tex_pkg::FMT_RGBA8;
  logic srgb;               // the sample's texture is sRGB
  assign srgb       = push && front_srgb;

  // Per slot s and block parity p = {y parity, x parity}: the lookup, its line number and set.
  logic [3:0]       look [2];
  logic [4*LNW-1:0] look_line [2];
  logic [4*SHW-1:0] look_set_hi [2];
  logic [7:0]       bank_block [2];  // texel bank b: the parity of its tap's block at [b*2 +: 2]
  logic [4*OFW-1:0] bank_offset [2];
  logic [4*PB-1:0]  tap_low [2];     // {y1, y0, x1, x0} mod 2^PB
  genvar s, b;
  generate
    for (s = 0; s < 2; s = s + 1) begin : g_slot
      always_comb begin : p_lookups
        logic [VW-1:0]  m;            // Morton: the interleaved square's log2
        logic [PTW-1:0] pitch;        // row-major: blocks per block row
        logic [NW-1:0]  nw, nh;       // the level's size
        logic [XSW-1:0] x0, x1, bx0, bx1, bx;
        logic [YSW-1:0] y0, y1, by0, by1, by;
        logic [LNW-1:0] row0, row1;   // row-major: the first block of by0's (by1's) row
        logic          nx1, ny1;     // the second tap along x (y) is needed: its weight != 0
        logic          nx0, ny0;     // the first tap along x (y) is inside its level (not a border tap)
        logic          has_x, has_y;
        logic [LNW-1:0] index;       // a block's number in its level
        logic [LNW-1:0] level_base;  // the level's first line
        logic [XSW-1:0] xs;
        logic [YSW-1:0] ys;
        logic          px0, py0;  // tap 0's bank parity: of its texel (bit 0) or 4x4 block (bit 2)
        logic [4:0]    pq;                  // the parity bit's position + 1
        // (temporaries too: a value on every path, no latch)
        {m, pitch, nw, nh, x0, x1, bx0, bx1, bx, y0, y1, by0, by1, by, row0, row1} = '0;
        {nx0, ny0, nx1, ny1, has_x, has_y, index, level_base, xs, ys, px0, py0, pq} = '0;
        look[s]        = '0;
        look_line[s]   = '0;
        look_set_hi[s] = '0;
        bank_block[s]  = '0;
        bank_offset[s] = '0;
        tap_low[s]     = '0;
        // level d always; d1 when f != 0
        if (push && (s == 0 || f != '0)) begin
          level_base = front_line[s*LNW +: LNW];
          pitch = front_pitch[s*PTW +: PTW];
          m     = front_square[s*VW +: VW];
          nw    = size[(s*2 + 0)*NW +: NW];
          nh    = size[(s*2 + 1)*NW +: NW];
          x0    = XSW'(x[(s*2 + 0)*XW +: XW]);
          x1    = stored_x(x[(s*2 + 1)*XW +: XW], nw, blk);
          y0    = YSW'(y[(s*2 + 0)*YW +: YW]);
          y1    = stored_y(y[(s*2 + 1)*YW +: YW], nh, blk);
          bx0  = x0 >> lbw;
          bx1  = x1 >> lbw;
          by0  = y0 >> lbh;
          by1  = y1 >> lbh;
          if (!cfg_block_morton) begin
            row0 = LNW'(by0) * LNW'(pitch);
            row1 = LNW'(by1) * LNW'(pitch);
          end
          // A border tap reads no line (model TextureCache::lookup).
          nx0  = !border_x[s*2];
          ny0  = !border_y[s*2];
          nx1  = w[(s*2 + 0)*WB +: WB] != '0 && !border_x[s*2 + 1];
          ny1  = w[(s*2 + 1)*WB +: WB] != '0 && !border_y[s*2 + 1];
          tap_low[s] = {PB'(y1), PB'(y0), PB'(x1), PB'(x0)};
          pq  = blk ? 5'd3 : 5'd1;
          px0 = 1'(32'(x0) >> (pq - 5'd1));
          py0 = 1'(32'(y0) >> (pq - 5'd1));
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
                OFW'((((32'(ys) >> pq) & ((32'd1 << (lbh - VW'(pq))) - 1)) << (lbw - VW'(pq)))
                     | ((32'(xs) >> pq) & ((32'd1 << (lbw - VW'(pq))) - 1)));
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
        .clk(clk), .rst(rst), .en(en_front), .cfg_log2_sets(cfg_log2_sets),
        .cfg_log2_ways(cfg_log2_ways), .look_valid(look[sc]), .look_set_hi(look_set_hi[sc]),
        .look_line(look_line[sc]), .hit(hit_c[c]), .slot(slot_c[c])
      );
    end
  endgenerate

  // Per slot: its cache's answers; the misses in order (slot 0, then slot 1; block parity 0..3).
  // Only in a clock with a push, as the lookups.
  localparam int MEW = LNW + KW + 1 + SLW;  // a miss: {line number, bank kind, cache, line slot}
  logic [7:0]       miss;
  logic [MEW-1:0]   miss_entry [8];  // miss i's entry (i = slot * 4 + block parity)
  logic [2:0]       miss_rank [8];   // the misses before miss i
  logic [8*RD-1:0]  reads;           // slot s bank b at [(s*4 + b)*RD +: RD]: {line slot, offset}
  logic [7:0]       need;            // slot s bank b reads a line the sample looked up (its error counts)
  logic [3:0]       fills;           // misses of this sample: 0..8
  logic [3:0]       lookups;         // lines it looks up: 0..8
  always_comb begin
    logic [3:0]       hit_s;
    logic [4*SLW-1:0] slot_s;
    logic             cache_s;
    {hit_s, slot_s, cache_s} = '0;
    miss       = '0;
    reads      = '0;
    need       = '0;
    fills      = '0;
    lookups    = '0;
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
              {look_line[sl][q*LNW +: LNW], line_kind(fmt), cache_s, slot_s[q*SLW +: SLW]};
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

  assign stat_lookups = lookups;
  assign stat_misses  = fills;

  // ---------------------------------------------------------------- miss ring
  // Misses not yet written into the cache, in order: [retire, issue) sent to memory, [issue,
  // write) waiting for mem_req. The tag stage writes up to 8 per clock, so the ring is 8 banks:
  // entry p in bank p mod 8, row p / 8, and a sample's k-th miss (at ring_wr + k) goes to its own
  // bank, one write port each, through an 8-way multiplexer. (One memory with 8 write ports, built of flip-flops and their write
  // multiplexers, was most of the unit: 220 k of 256 k ECP5 LUT4s at MISS_DEPTH 512.) Reads are
  // asynchronous, as before: the banks map to LUT RAM and no clock changes. The line numbers are
  // read where memory is asked (ring_iss), the destinations where lines are written (ring_ret).
  localparam int MPW = $clog2(MISS_DEPTH);
  localparam int RBW = 3;           // log2 of the 8 banks
  localparam int RRW = MPW - RBW;   // row bits (MISS_DEPTH >= 16)
  localparam int DSW = MEW - LNW;   // a destination: {bank kind, cache, line slot}
  logic [MPW-1:0] ring_wr, ring_iss, ring_ret;
  logic [MCW-1:0] ring_used, ring_unissued;
  logic           issue, retire;
  logic [LNW-1:0] ring_line [8];    // bank rb's line number at ring_iss's row
  logic [DSW-1:0] ring_dest [8];    // bank rb's destination at ring_ret's row
  // The sample's misses in order: miss_k[k] is its k-th (k < fills), an AND-OR of the 8 entries.
  logic [MEW-1:0] miss_k [8];
  always_comb begin
    for (int k = 0; k < 8; k++) begin
      logic [MEW-1:0] e;
      e = '0;
      if (push)
        for (int i = 0; i < 8; i++)
          if (miss[i] && miss_rank[i] == 3'(k)) e = e | miss_entry[i];
      miss_k[k] = e;
    end
  end
  genvar rb;
  generate
    for (rb = 0; rb < 8; rb = rb + 1) begin : g_ring_bank
      logic [LNW-1:0] line_mem [1 << RRW];
      logic [DSW-1:0] dest_mem [1 << RRW];
      always_ff @(posedge clk) begin
        if (push) begin
          logic [RBW-1:0] k;    // the sample's miss that lands in this bank: (rb - ring_wr) mod 8
          logic [RRW-1:0] row;  // its row: its place in the ring, ring_wr + k, over 8
          k   = RBW'(rb) - ring_wr[RBW-1:0];
          row = RRW'((ring_wr + MPW'(k)) >> RBW);
          if ({1'b0, k} < fills) begin
            line_mem[row] <= miss_k[k][MEW-1 -: LNW];
            dest_mem[row] <= miss_k[k][DSW-1:0];
          end
        end
      end
      assign ring_line[rb] = line_mem[ring_iss[MPW-1:RBW]];
      assign ring_dest[rb] = dest_mem[ring_ret[MPW-1:RBW]];
    end
  endgenerate
  assign issue = mem_req_valid && mem_req_ready;
  assign mem_req_valid = ring_unissued != '0;
  assign mem_req_addr  = {ring_line[ring_iss[RBW-1:0]], LOG2_LB'(0)};  // a line: aligned
  always_ff @(posedge clk) begin
    if (rst) begin
      ring_wr       <= '0;
      ring_iss      <= '0;
      ring_ret      <= '0;
      ring_used     <= '0;
      ring_unissued <= '0;
    end else begin
      ring_wr       <= ring_wr + (push ? MPW'(fills) : '0);
      ring_iss      <= ring_iss + MPW'(issue);
      ring_ret      <= ring_ret + MPW'(retire);
      ring_used     <= ring_used + (push ? MCW'(fills) : '0) - MCW'(retire);
      ring_unissued <= ring_unissued + (push ? MCW'(fills) : '0) - MCW'(issue);
    end
  end

  // ---------------------------------------------------------------- fill FIFO
  // Lines from memory, assembled beat by beat in place, oldest first.
  localparam int LPW = (FILL_DEPTH > 1) ? $clog2(FILL_DEPTH) : 1;
  logic [LINE_BITS-1:0] fill_mem [FILL_DEPTH];
  logic [LPW-1:0]       fill_wr, fill_rd;
  logic [LCW-1:0]       fill_count;
  logic [BTW-1:0]       beat;
  logic                 beat_take, line_done;
  logic [FILL_DEPTH-1:0] fill_err;  // the line came with an error in any beat
  logic                 beat_err;   // an earlier beat of the line being received did
  assign mem_rsp_ready = fill_count != LCW'(FILL_DEPTH);
  assign beat_take     = mem_rsp_valid && mem_rsp_ready;
  assign line_done     = beat_take && (BEATS == 1 || beat == BTW'(BEATS - 1));
  always_ff @(posedge clk) begin
    if (beat_take) fill_mem[fill_wr][32'(beat)*MEM_W +: MEM_W] <= mem_rsp_data;  // (beat is 0 if BEATS = 1)
    if (line_done) fill_err[fill_wr] <= beat_err || mem_rsp_error;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      fill_wr    <= '0;
      fill_rd    <= '0;
      fill_count <= '0;
      beat       <= '0;
      beat_err   <= 1'b0;
    end else begin
      if (beat_take) beat <= line_done ? '0 : beat + 1'b1;
      if (beat_take) beat_err <= !line_done && (beat_err || mem_rsp_error);
      if (line_done) fill_wr <= (FILL_DEPTH > 1) ? fill_wr + 1'b1 : '0;
      if (retire)    fill_rd <= (FILL_DEPTH > 1) ? fill_rd + 1'b1 : '0;
      fill_count <= fill_count + LCW'(line_done) - LCW'(retire);
    end
  end

`ifdef FORMAL
  // ---------------------------------------------------------------- AXI4 read-channel properties
  // mem_req is the AR channel, mem_rsp the R channel (tex_unit_cached adds the constant ARLEN,
  // ARSIZE, ARBURST, ARID). Proven by scripts/formal.sh, BMC from reset and k-induction
  // (rtl/formal/tex_cached_fetch_formal.sv: every input free; the slave assumed to send no beat
  // without an open burst):
  //   ar_hold        - mem_req_valid stays high and mem_req_addr unchanged until mem_req_ready
  //   ar_burst       - every read is of a whole, aligned line
  //   ar_outstanding - at most MISS_DEPTH reads accepted and not yet written into the cache; the
  //                    bursts open are those accepted less those fully received (accounting)
  //   r_ready        - a beat is taken only with room for its line (at most FILL_DEPTH lines held)
  logic             f_req_stalled;
  logic [tex_pkg::MEM_ADDR_W-1:0] f_req_addr;
  logic [MCW:0]     f_open;  // bursts accepted, last beat not yet taken
  always_ff @(posedge clk) begin
    f_req_stalled <= !rst && mem_req_valid && !mem_req_ready;
    f_req_addr    <= mem_req_addr;
    if (rst) f_open <= '0;
    else f_open <= f_open + (MCW+1)'(issue) - (MCW+1)'(line_done);
  end
  always_comb begin
    if (!rst && mem_rsp_valid) assume (f_open != '0);
    if (!rst && f_req_stalled) p_arhold_1: assert (mem_req_valid && mem_req_addr == f_req_addr);
    if (!rst && mem_req_valid) p_arburst_1: assert (mem_req_addr[LOG2_LB-1:0] == '0);
    if (!rst) p_aroutstanding_1: assert (ring_used <= MCW'(MISS_DEPTH) && f_open <= (MCW+1)'(MISS_DEPTH));
    if (!rst) p_rready_1: assert (!(beat_take && fill_count == LCW'(FILL_DEPTH)) && fill_count <= LCW'(FILL_DEPTH));
    // (invariants that make them inductive: the ring's and the fill FIFO's accounting)
    if (!rst) p_aroutstanding_2: assert (ring_unissued <= ring_used);
    if (!rst) p_aroutstanding_3: assert (32'(f_open) + 32'(fill_count) == 32'(ring_used) - 32'(ring_unissued));
    if (!rst) p_aroutstanding_4: assert (f_open != '0 || beat == '0);
    if (!rst) p_aroutstanding_5: assert (!en_front || ring_used <= MCW'(MISS_DEPTH - 8));
    if (!rst) p_aroutstanding_6: assert (MPW'(ring_wr - ring_iss) == MPW'(ring_unissued)
                                         && MPW'(ring_wr - ring_ret) == MPW'(ring_used));
  end
`endif

  // ---------------------------------------------------------------- sample FIFO
  // An entry: {tag, w, f, sampler, border taps, sRGB, format, c0, needed bank reads, taps' low
  // coordinate bits (slot 1, slot 0), bank reads, fills}.
  localparam int P_TAPS = 4 + 8*RD;          // field positions
  localparam int P_NEED = P_TAPS + 8*PB;
  localparam int P_C0   = P_NEED + 8;
  localparam int P_FMT  = P_C0 + 1;
  localparam int P_SRGB = P_FMT + FW;
  localparam int P_BORD = P_SRGB + 1;
  localparam int P_SMP  = P_BORD + 8;
  localparam int EW     = P_SMP + SXW + 5*WB + TAG_W;
  // Tap i = slot * 4 + t is outside its level in mode border when its x (t bit 0) or y (t bit 1) is.
  logic [7:0] border_tap;
  always_comb
    for (int i = 0; i < 8; i++) border_tap[i] = border_x[i/4*2 + i%2] || border_y[i/4*2 + i%4/2];
  localparam int FPW = $clog2(FIFO_DEPTH);
  logic [EW-1:0]  fifo [FIFO_DEPTH];
  logic [FPW-1:0] fifo_wr, fifo_rd;
  logic [FCW-1:0] fifo_count;
  logic           fifo_pop;
  logic [FCW-1:0] fifo_next;
  logic [MCW-1:0] ring_next;
  always_ff @(posedge clk) begin
    if (push) fifo[fifo_wr] <= {front_tag, w, f, front_smp, border_tap, srgb, fmt, c0, need, tap_low[1], tap_low[0], reads, fills};
  end
  assign fifo_next = fifo_count + FCW'(push) - FCW'(fifo_pop);
  logic [FCW-1:0] fifo_limit;  // the FIFO's depth in use
  assign fifo_limit = (cfg_fifo_limit == '0 || cfg_fifo_limit > FCW'(FIFO_DEPTH)) ? FCW'(FIFO_DEPTH)
                                                                                 : cfg_fifo_limit;
  assign ring_next = ring_used + (push ? MCW'(fills) : '0) - MCW'(retire);
  always_ff @(posedge clk) begin
    if (rst) begin
      fifo_wr    <= '0;
      fifo_rd    <= '0;
      fifo_count <= '0;
      en_front   <= 1'b0;
    end else begin
      fifo_wr    <= fifo_wr + FPW'(push);
      fifo_rd    <= fifo_rd + FPW'(fifo_pop);
      fifo_count <= fifo_next;
      // Room after this clock for one more sample and its (at most 8) misses.
      en_front   <= fifo_next < fifo_limit && ring_next <= MCW'(MISS_DEPTH - 8);
    end
  end

  // ---------------------------------------------------------------- H: the head writes its fills
  logic          h_valid, h_go;
  logic [EW-1:0] h_entry;
  logic [3:0]    h_fills;   // fills still to write
  logic          fill_write;
  logic          head_waits;
  assign fill_write = en_back && h_valid && h_fills != '0 && fill_count != '0;
  assign retire     = fill_write;
  assign h_go       = en_back && h_valid && (h_fills == '0 || (h_fills == 4'd1 && fill_write));
  assign fifo_pop   = (!h_valid || h_go) && fifo_count != '0;
  assign head_waits = en_back && h_valid && !h_go;
  assign stat_mem_wait = head_waits;
  always_ff @(posedge clk) begin
    if (rst) begin
      h_valid <= 1'b0;
    end else begin
      if (fifo_pop) h_valid <= 1'b1;
      else if (h_go) h_valid <= 1'b0;
    end
    if (fifo_pop) begin
      h_entry <= fifo[fifo_rd];
      h_fills <= fifo[fifo_rd][3:0];
    end else if (fill_write) begin
      h_fills <= h_fills - 1'b1;
    end
  end

  // The line at the head of the fill FIFO in the cache's format: texel j, channel k at
  // [(j*4 + k)*CCW +: CCW] from memory bytes [j*TB + k*TB/4 +: TB/4]. Only in a clock that writes
  // it (0 otherwise), as the tag stage.
  logic [BW*BH*DWC-1:0] fill_line;
  always_comb begin
    fill_line = '0;
    if (fill_write)
      for (int j = 0; j < BW * BH; j++)
        for (int k = 0; k < 4; k++)
          fill_line[(j*4 + k)*CCW +: CCW] = fill_mem[fill_rd][(j*TB + k*TB/4)*8 +: CCW];
  end

  // The fill's destination: the oldest miss in the ring.
  logic             fill_cache;
  logic [SLW-1:0]   fill_slot;
  logic [KW-1:0]    fill_kind;
  assign {fill_kind, fill_cache, fill_slot} = ring_dest[ring_ret[RBW-1:0]];

  // ---------------------------------------------------------------- R: read the data banks
  logic          r_valid;
  logic [EW-1:0] r_entry;
  always_ff @(posedge clk) begin
    if (rst) r_valid <= 1'b0;
    else if (en_back) r_valid <= h_go;
    if (en_back && h_go) r_entry <= h_entry;
  end
  logic [8*RD-1:0] r_reads;
  logic            r_c0;
  assign r_reads = r_entry[4 +: 8*RD];
  assign r_c0    = r_entry[P_C0];

  // Memory errors: a mark per line slot of each cache, written with the line. The sample in R
  // reads the marks of the lines it looked up at the edge the banks are read (before a write).
  logic [LINES-1:0] line_err [2];
  always_ff @(posedge clk)
    if (fill_write) line_err[fill_cache][fill_slot] <= fill_err[fill_rd];
  logic [7:0] r_need;
  logic       r_err;
  assign r_need = r_entry[P_NEED +: 8];
  always_comb begin
    r_err = 1'b0;
    if (r_valid)
      for (int sl = 0; sl < 2; sl++)
        for (int k = 0; k < 4; k++)
          r_err = r_err || (r_need[sl*4 + k] && line_err[r_c0 ^ 1'(sl)][r_reads[(sl*4 + k)*RD + OFW +: SLW]]);
  end

  logic [4*WW-1:0] bank_word [2];  // cache c, bank b's word at [b*WW +: WW] (clock T)
  generate
    for (c = 0; c < 2; c = c + 1) begin : g_data
      logic [4*SLW-1:0] rd_slot;
      logic             sc;
      assign sc = (r_c0 != 1'(c));
      for (b = 0; b < 4; b = b + 1) begin : g_bank
        assign rd_slot[b*SLW +: SLW] = r_reads[(sc*4 + b)*RD + OFW +: SLW];
      end
      tex_cache_data #(.LINES(LINES), .BW(BW), .BH(BH), .DW(DWC), .BLOCKS(BLOCK_FORMATS)) u_data (
        .clk(clk), .wr_en(fill_write && fill_cache == 1'(c)), .wr_slot(fill_slot),
        .wr_line(fill_line), .wr_kind(fill_kind), .re(en_back && r_valid), .rd_slot(rd_slot),
        .rd_word(bank_word[c])
      );
    end
  endgenerate

  // ---------------------------------------------------------------- T: bank words -> taps
  logic          t_valid, t_err;
  logic [EW-1:0] t_entry;
  always_ff @(posedge clk) begin
    if (rst) t_valid <= 1'b0;
    else if (en_back) t_valid <= r_valid;
    if (en_back && r_valid) begin
      t_entry <= r_entry;
      t_err   <= r_err;
    end
  end
  logic            t_c0, t_blk;
  logic [FW-1:0]   t_fmt;
  logic [8*PB-1:0] t_low;    // slot s at [s*4*PB +: 4*PB]: {y1, y0, x1, x0} mod 2^PB
  logic [8*RD-1:0] t_reads;  // the bank reads of the sample: their offsets in the words
  assign t_c0    = t_entry[P_C0];
  assign t_fmt   = t_entry[P_FMT +: FW];
  assign t_blk   = t_fmt != tex_pkg::FMT_RGBA8;
  assign t_low   = t_entry[P_TAPS +: 8*PB];
  assign t_reads = t_entry[4 +: 8*RD];
  // Tap i = sl*4 + t (t bit 0: the x tap, bit 1: the y tap) reads the bank of its parity: of its
  // texel, or of its 4x4 block; at that bank's offset, a texel or a block in the bank's word.
  // Only while a sample is in T (a simulator skips it in the clocks in between).
  logic [8*2-1:0]   tap_bank;    // tap i's bank at [i*2 +: 2]
  logic [8*OFW-1:0] tap_offset;  // and its offset in the bank's word
  always_comb begin
    logic [PB-1:0] xl, yl;  // the tap's low coordinate bits
    {xl, yl} = '0;
    tap_bank   = '0;
    tap_offset = '0;
    if (t_valid)
      for (int i = 0; i < 8; i++) begin
        xl = t_low[(i/4*4 + i%2)*PB +: PB];
        yl = t_low[(i/4*4 + 2 + i%4/2)*PB +: PB];
        tap_bank[i*2 +: 2] = t_blk ? {yl[PB-1], xl[PB-1]} : {yl[0], xl[0]};
        tap_offset[i*OFW +: OFW] = t_reads[(i/4*4 + 32'(tap_bank[i*2 +: 2]))*RD +: OFW];
      end
  end

  logic [8*DWC-1:0] decoded;  // tap i's texel of a block format at [i*DWC +: DWC]
  generate
    if (BLOCK_FORMATS != 0) begin : g_decode
      // One decoder per tap (all 8 texels of a trilinear sample in this clock); their inputs
      // are 0 unless a block-format sample is in T.
      logic [8*128-1:0] dec_block;
      logic [8*4-1:0]   dec_texel;
      always_comb begin
        dec_block = '0;
        dec_texel = '0;
        if (t_valid && t_blk)
          for (int i = 0; i < 8; i++) begin
            // (8-byte blocks: the low half; a word holds whole blocks, WW >= 128 with the formats)
            if (line_kind(t_fmt) == 2'd1)
              dec_block[i*128 +: 64] =
                  bank_word[t_c0 ^ 1'(i/4)][32'(tap_bank[i*2 +: 2])*WW + 32'(tap_offset[i*OFW +: OFW])*64 +: 64];
            else
              dec_block[i*128 +: 128] =
                  bank_word[t_c0 ^ 1'(i/4)][32'(tap_bank[i*2 +: 2])*WW + 32'(tap_offset[i*OFW +: OFW])*128 +: 128];
            dec_texel[i*4 +: 4] = {t_low[(i/4*4 + 2 + i%4/2)*PB +: 2], t_low[(i/4*4 + i%2)*PB +: 2]};
          end
      end
      for (b = 0; b < 8; b = b + 1) begin : g_tap
        logic [31:0] rgba;
        tex_bc_decode u_dec (.format(t_fmt), .block(dec_block[b*128 +: 128]), .texel(dec_texel[b*4 +: 4]),
                             .rgba(rgba));
        assign decoded[b*DWC +: DWC] = DWC'(rgba);
      end
    end else begin : g_no_decode
      assign decoded = '0;
    end
  endgenerate

  // Each tap's texel as the cache holds its channels: from its bank word, or decoded (only while
  // a sample is in T: a simulator skips it in the clocks in between).
  logic [8*DWC-1:0] cached;
  always_comb begin
    cached = '0;
    if (t_valid)
      for (int i = 0; i < 8; i++)
        cached[i*DWC +: DWC] =
            t_blk ? decoded[i*DWC +: DWC]
                  : bank_word[t_c0 ^ 1'(i/4)][32'(tap_bank[i*2 +: 2])*WW + 32'(tap_offset[i*OFW +: OFW])*DWC +: DWC];
  end

  // SRGB: the 8-bit channels into the CW = 16 filter. An sRGB texture's R, G, B through the decode
  // table (24 ROM reads per sample), its alpha widened exactly (a * 257 = {a, a}); a linear
  // texture's channels as they are (the filter's arithmetic is exact, so 8-bit values give the
  // 8-bit filter's result in the low bits).
  logic [8*DW-1:0] widened;
  generate
    if (SRGB != 0) begin : g_srgb
      logic t_srgb;
      assign t_srgb = t_entry[P_SRGB];
      for (b = 0; b < 8; b = b + 1) begin : g_tap
        logic [47:0] rgb;  // linear unorm16 R, G, B
        logic [7:0]  a;
        for (genvar k = 0; k < 3; k = k + 1) begin : g_channel
          tex_srgb_decode u_rom (.code(cached[b*32 + k*8 +: 8]), .linear(rgb[k*16 +: 16]));
        end
        assign a = cached[b*32 + 24 +: 8];
        assign widened[b*DW +: DW] = t_srgb ? DW'({a, a, rgb})
                                            : DW'({8'd0, a, 8'd0, cached[b*32 + 16 +: 8], 8'd0, cached[b*32 + 8 +: 8],
                                                   8'd0, cached[b*32 +: 8]});
      end
    end else begin : g_linear
      assign widened = cached;
    end
  endgenerate

  // Address mode border: a tap outside its level takes its sampler's border colour (model
  // BankedMipMemory::fetch), in the filter's width: CW bits (tex_border); SRGB: an sRGB
  // texture's filter takes 16-bit linear channels, a linear texture's 8-bit ones zero-extended.
  // The table holds each colour converted (tex_border at the write, off the sample path); the
  // sample's colour is read in R and registered into T beside its bank words.
  localparam int BCW = (SRGB != 0) ? 64 + 32 : DW;  // SRGB: {8-bit, 16-bit}
  logic [BCW-1:0] border_table [SAMPLERS];
  logic [BCW-1:0] border_write;
  generate
    if (SRGB != 0) begin : g_border_srgb
      logic [31:0] b8;
      tex_border #(.CW(8)) u_border8 (.rgba16(smp_border_rgba), .rgba(b8));
      assign border_write = {b8, smp_border_rgba};
    end else begin : g_border
      tex_border #(.CW(CW)) u_border (.rgba16(smp_border_rgba), .rgba(border_write));
    end
  endgenerate
  always_ff @(posedge clk)
    if (smp_we) border_table[smp_index] <= border_write;
  logic [BCW-1:0] r_border;      // the sample in R's border colour
  logic [DW-1:0]  r_border_texel;
  logic [DW-1:0]  border_texel;  // the sample in T's
  assign r_border = border_table[r_entry[P_SMP +: SXW]];
  generate
    if (SRGB != 0) begin : g_border_srgb_read
      assign r_border_texel = r_entry[P_SRGB] ? DW'(r_border[63:0])
                                              : DW'({8'd0, r_border[64+24 +: 8], 8'd0, r_border[64+16 +: 8],
                                                     8'd0, r_border[64+8 +: 8], 8'd0, r_border[64 +: 8]});
    end else begin : g_border_read
      assign r_border_texel = DW'(r_border);
    end
  endgenerate
  always_ff @(posedge clk)
    if (en_back && r_valid) border_texel <= r_border_texel;
  logic [8*DW-1:0] t_taps;
  always_comb
    for (int i = 0; i < 8; i++)
      t_taps[i*DW +: DW] = t_entry[P_BORD + i] ? border_texel : widened[i*DW +: DW];

  always_ff @(posedge clk) begin
    if (rst) out_valid <= 1'b0;
    else if (en_back) out_valid <= t_valid;
    if (en_back && t_valid) begin
      {out_tag, out_w, out_f} <= t_entry[EW-1 -: TAG_W + 5*WB];
      out_error <= t_err;
      taps <= t_taps;
    end
  end
endmodule

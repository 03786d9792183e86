// tex_cached_fetch: the model's `fetch` stage in cached mode (docs/memory.md): the pyramid lives
// in external memory and is read through two texture caches (cache 0: even levels, cache 1: odd
// levels), with the latency hidden by a sample FIFO (Igehy, Eldridge & Proudfoot 1998). A sample
// goes request -> tag -> FIFO -> H -> R -> T -> taps; its misses go tag -> miss ring -> memory ->
// fill FIFO -> H. The stages by file:
//   tex_tag_stage  (on tex_front's clock-4 outputs) which blocks the sample needs, their line
//                  numbers and sets; up to 4 lookups per cache (tex_cache_tags), LRU update,
//                  victims chosen; the misses in the order of docs/memory.md.
//   tex_miss_ring  the misses not yet written into a cache; asks memory for them (mem_req).
//   tex_fill_fifo  lines from memory (mem_rsp), beat by beat, oldest first.
//   tex_fifo       the sample FIFO: each sample with its taps' line slots and offsets.
//   H (head, here) the FIFO's oldest sample writes its fills into the data banks, one line per
//                  clock; it leaves when the last one is written.
//   R (here)       reads the data banks (tex_cache_data), 4 banks x 2 caches, and the sample's
//                  border colour (its sampler's, from the table written by smp_we).
//   tex_tap_select (T) bank words to the 8 taps: texels, block-format texels (tex_bc_decode), sRGB
//                  (tex_srgb_decode); a border tap takes the border colour here.
//   taps           registered outputs, into tex_filter.
// (tex_desc_table, before it in tex_unit_cached, gives each sample its levels' lines and the
// texture's format; tex_axi_read, after it, maps mem_req / mem_rsp onto the AXI4 read channels.)
// Handshake: two stall-enable halves. The front (tex_front and the tag stage) advances when
//   en_front is high: a register output, high when the FIFO has room for one more sample and the
//   miss ring for 8 more misses after this clock. The back (H, R, T, taps, and the filter after
//   it) advances when en_back is high (the top's skid buffer has room). Fills are written only
//   when en_back is high: a sample in R reads the banks at that same edge, before the write.
//   A stage's data registers load only when a sample moves into it (out_tag, taps, out_w, out_f
//   hold their last sample while out_valid is low): a simulator skips the empty stages.
//   mem_req / mem_rsp are valid/ready (tex_axi_read maps them onto the AXI4 read channels: one
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
  localparam int WB   = tex_pkg::WEIGHT_BITS;
  localparam int DW   = 4 * CW;                     // a tap's texel
  localparam int CCW  = (SRGB != 0) ? 8 : CW;       // bits of a channel in the cache
  localparam int DWC  = 4 * CCW;                    // a texel in the cache
  localparam int TB   = (CCW > 8) ? 8 : 4;          // bytes of a texel in memory
  localparam int LBW  = $clog2(BW);                 // log2 block width, height
  localparam int LBH  = $clog2(BH);
  localparam int LINE_BITS = BW * BH * TB * 8;
  localparam int LOG2_LB   = $clog2(BW * BH * TB);  // log2 line bytes
  localparam int SLW  = $clog2(LINES);              // bits of a line slot
  localparam int OFW  = (LBW + LBH - 2 > 0) ? LBW + LBH - 2 : 1;  // texel offset in a bank word
  localparam int FCW  = $clog2(FIFO_DEPTH + 1);
  localparam int MCW  = $clog2(MISS_DEPTH + 1);
  localparam int LCW  = $clog2(FILL_DEPTH + 1);
  localparam int RD   = SLW + OFW;                  // a bank read: {slot, offset}
  localparam int FW   = tex_pkg::FORMAT_W;
  localparam int PB   = (BLOCK_FORMATS != 0) ? 5 : 1;  // a tap coordinate's unit parity and place in its block
  localparam int WW   = LINE_BITS / 4;              // bits of a bank word
  localparam int KW   = tex_pkg::LINE_KIND_W;
  localparam int DSW  = KW + 1 + SLW;               // a miss's destination: {line kind, cache, line slot}
  localparam int MEW  = LNW + DSW;                  // a miss: {line number, destination}

  // A sample enters the tag stage (and the FIFO) in this clock. Everything the tag stage computes
  // is used only then, so it is computed only then and is 0 otherwise: the same registers result,
  // and a simulator skips the stage in the clocks in which the front waits (Verilator evaluates
  // every continuous assignment in every clock, but not the inside of an `if`).
  logic push;
  assign push = en_front && front_valid;
  logic c0;                 // the cache of slot 0 (level d's parity); slot 1 uses the other
  assign c0 = level_odd;
  logic [FW-1:0] fmt;       // the sample's texture format (tex_desc_table's entry)
  assign fmt = push ? front_format : tex_pkg::FMT_RGBA8;
  logic srgb;               // the sample's texture is sRGB
  assign srgb = push && front_srgb;

  // ---------------------------------------------------------------- tag stage
  logic [8*MEW-1:0] misses;   // the sample's misses in order (tex_tag_stage)
  logic [8*RD-1:0]  reads;    // slot s bank b at [(s*4 + b)*RD +: RD]: {line slot, offset}
  logic [7:0]       need;     // slot s bank b reads a line the sample looked up (its error counts)
  logic [3:0]       fills;    // misses of this sample: 0..8
  logic [8*PB-1:0]  tap_low;  // per slot {y1, y0, x1, x0} mod 2^PB
  tex_tag_stage #(
    .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .BW(BW), .BH(BH), .LINES(LINES),
    .MAX_WAYS(MAX_WAYS), .BLOCK_FORMATS(BLOCK_FORMATS), .LNW(LNW)
  ) u_tag (
    .clk(clk), .rst(rst), .en(en_front), .push(push), .c0(c0), .f(f), .w(w), .size(size), .x(x), .y(y),
    .border_x(border_x), .border_y(border_y), .line(front_line), .pitch(front_pitch),
    .square(front_square), .fmt(fmt), .log2_lw(front_log2_lw), .log2_lh(front_log2_lh),
    .cfg_block_morton(cfg_block_morton), .cfg_log2_sets(cfg_log2_sets), .cfg_log2_ways(cfg_log2_ways),
    .misses(misses), .fills(fills), .lookups(stat_lookups), .reads(reads), .need(need), .tap_low(tap_low)
  );
  assign stat_misses = fills;

  // ---------------------------------------------------------------- miss ring -> mem_req
  logic             retire;         // the head sample writes the oldest fill into its cache
  logic [DSW-1:0]   fill_dest;      // where: the oldest miss's destination
  logic [MCW-1:0]   ring_used, ring_unissued;
  tex_miss_ring #(.DEPTH(MISS_DEPTH), .LNW(LNW), .DSW(DSW), .LOG2_LB(LOG2_LB)) u_ring (
    .clk(clk), .rst(rst), .push(push), .fills(fills), .misses(misses), .mem_req_valid(mem_req_valid),
    .mem_req_ready(mem_req_ready), .mem_req_addr(mem_req_addr), .retire(retire), .dest(fill_dest),
    .used(ring_used), .unissued(ring_unissued)
  );

  // ---------------------------------------------------------------- mem_rsp -> fill FIFO
  logic [LINE_BITS-1:0] fill_head;   // the oldest line received, as memory holds it
  logic                 fill_head_error;
  logic [LCW-1:0]       fill_count;
  logic                 line_done, mid_line;
  tex_fill_fifo #(.DEPTH(FILL_DEPTH), .MEM_W(MEM_W), .LINE_BITS(LINE_BITS)) u_fill (
    .clk(clk), .rst(rst), .mem_rsp_valid(mem_rsp_valid), .mem_rsp_ready(mem_rsp_ready),
    .mem_rsp_data(mem_rsp_data), .mem_rsp_error(mem_rsp_error), .retire(retire), .head_line(fill_head),
    .head_error(fill_head_error), .count(fill_count), .line_done(line_done), .mid_line(mid_line)
  );

`ifdef FORMAL
  // ---------------------------------------------------------------- AXI4 read-channel properties
  // mem_req is the AR channel, mem_rsp the R channel (tex_axi_read adds the constant ARLEN,
  // ARSIZE, ARBURST, ARID). Proven by scripts/formal.sh, BMC from reset and k-induction
  // (rtl/formal/tex_cached_fetch_formal.sv: every input free; the slave assumed to send no beat
  // without an open burst), with the ring's and the fill FIFO's own (tex_miss_ring, tex_fill_fifo):
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
    else f_open <= f_open + (MCW+1)'(mem_req_valid && mem_req_ready) - (MCW+1)'(line_done);
  end
  always_comb begin
    if (!rst && mem_rsp_valid) assume (f_open != '0);
    if (!rst && f_req_stalled) p_arhold_1: assert (mem_req_valid && mem_req_addr == f_req_addr);
    if (!rst && mem_req_valid) p_arburst_1: assert (mem_req_addr[LOG2_LB-1:0] == '0);
    if (!rst) p_aroutstanding_1: assert (ring_used <= MCW'(MISS_DEPTH) && f_open <= (MCW+1)'(MISS_DEPTH));
    // (invariants that make them inductive: the ring's and the fill FIFO's accounting)
    if (!rst) p_aroutstanding_3: assert (32'(f_open) + 32'(fill_count) == 32'(ring_used) - 32'(ring_unissued));
    if (!rst) p_aroutstanding_4: assert (f_open != '0 || !mid_line);
    if (!rst) p_aroutstanding_5: assert (!en_front || ring_used <= MCW'(MISS_DEPTH - 8));
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
  logic [EW-1:0]  fifo_head;
  logic [FCW-1:0] fifo_count;  // (read by the harness: rtl/tex_unit.vlt)
  logic [FCW-1:0] fifo_next;
  logic           fifo_pop;
  tex_fifo #(.W(EW), .DEPTH(FIFO_DEPTH)) u_samples (
    .clk(clk), .rst(rst), .push(push),
    .push_data({front_tag, w, f, front_smp, border_tap, srgb, fmt, c0, need, tap_low, reads, fills}),
    .pop(fifo_pop), .head(fifo_head), .count(fifo_count), .count_next(fifo_next)
  );
  logic [FCW-1:0] fifo_limit;  // the FIFO's depth in use
  assign fifo_limit = (cfg_fifo_limit == '0 || cfg_fifo_limit > FCW'(FIFO_DEPTH)) ? FCW'(FIFO_DEPTH)
                                                                                 : cfg_fifo_limit;
  logic [MCW-1:0] ring_next;
  assign ring_next = ring_used + (push ? MCW'(fills) : '0) - MCW'(retire);
  always_ff @(posedge clk) begin
    if (rst) en_front <= 1'b0;
    // Room after this clock for one more sample and its (at most 8) misses.
    else en_front <= fifo_next < fifo_limit && ring_next <= MCW'(MISS_DEPTH - 8);
  end

  // ---------------------------------------------------------------- H: the head writes its fills
  logic          h_valid, h_go;
  logic [EW-1:0] h_entry;
  logic [3:0]    h_fills;   // fills still to write
  logic          fill_write;
  logic          head_waits;  // (read by the harness: rtl/tex_unit.vlt)
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
      h_entry <= fifo_head;
      h_fills <= fifo_head[3:0];
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
          fill_line[(j*4 + k)*CCW +: CCW] = fill_head[(j*TB + k*TB/4)*8 +: CCW];
  end

  // The fill's destination: the oldest miss in the ring.
  logic             fill_cache;
  logic [SLW-1:0]   fill_slot;
  logic [KW-1:0]    fill_kind;
  assign {fill_kind, fill_cache, fill_slot} = fill_dest;

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
    if (fill_write) line_err[fill_cache][fill_slot] <= fill_head_error;
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
  genvar c, b;
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
  logic [8*DW-1:0] texels;  // the taps' texels in the filter's width (tex_tap_select)
  tex_tap_select #(
    .CW(CW), .BW(BW), .BH(BH), .LINES(LINES), .BLOCK_FORMATS(BLOCK_FORMATS), .SRGB(SRGB)
  ) u_taps (
    .valid(t_valid), .c0(t_entry[P_C0]), .fmt(t_entry[P_FMT +: FW]), .srgb(t_entry[P_SRGB]),
    .low(t_entry[P_TAPS +: 8*PB]), .reads(t_entry[4 +: 8*RD]), .word0(bank_word[0]), .word1(bank_word[1]),
    .texels(texels)
  );

  // Address mode border: a tap outside its level takes its sampler's border colour (model
  // BankedMipMemory::fetch), in the filter's width: CW bits (tex_border); SRGB: an sRGB or EAC
  // texture's filter takes 16-bit channels, a linear 8-bit texture's 8-bit ones zero-extended.
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
      assign r_border_texel = (r_entry[P_SRGB] || tex_pkg::eac(r_entry[P_FMT +: FW])) ? DW'(r_border[63:0])
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
      t_taps[i*DW +: DW] = t_entry[P_BORD + i] ? border_texel : texels[i*DW +: DW];

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

// tex_tap_select: the cached fetch's clock T (docs/memory.md §2): the data banks' words to the
// sample's 8 taps (tap i = slot*4 + t; slot 0 level d in cache c0, slot 1 level d1 in the other;
// t bit 0 the second x tap, bit 1 the second y tap). Each tap reads the bank of its parity (of its
// texel, or of its 4x4 block) at that bank's offset: a texel of the word, or a block decoded by
// one tex_bc_decode per tap (BLOCK_FORMATS); with SRGB an sRGB texture's R, G, B through the
// function tex_srgb_decode::linear (24 per sample), its alpha widened exactly; an EAC texture's
// 16-bit R and G as they are, with B 0 (signed: 32768, offset binary's 0.0) and A 65535. The decoders are
// functions called only for the taps that need them: a simulator spends nothing on them in the
// clocks that read RGBA8 texels (as plain modules, Verilator evaluated all 8 every clock).
// Handshake: none (combinational). Everything is 0 unless `valid` (a sample is in T), so that a
// simulator skips the taps in the clocks in between.
// Latency: 0. Throughput: 8 taps per clock.
// Ports:
//   c0, fmt, srgb : slot 0's cache, the texture's format (tex_pkg::FMT_*), sRGB (SRGB only)
//   low           : slot s at [s*4*PB +: 4*PB]: {y1, y0, x1, x0}, each {its unit's parity, with
//                   BLOCK_FORMATS its place in the block (4 bits)} (tex_tag_stage)
//   reads         : the sample's bank reads, slot s bank b at [(s*4 + b)*RD +: RD]: {line slot,
//                   offset}; the offsets place each tap in its word
//   word0, word1  : cache 0's (1's) bank b's word at [b*WW +: WW] (tex_cache_data, read in R)
//   texels        : tap i's texel at [i*DW +: DW], DW = 4*CW, {A, B, G, R}: the cache's channels
//                   (SRGB: an sRGB texture's R, G, B linear unorm16 and A x 257; EAC's 16-bit
//                   codes; a linear texture's 8-bit channels zero-extended)
module tex_tap_select #(
  parameter int CW            = 8,
  parameter int BW            = 4,
  parameter int BH            = 4,
  parameter int LINES         = 256,
  parameter int BLOCK_FORMATS = 0,
  parameter int SRGB          = 0,
  parameter int CCW           = (SRGB != 0) ? 8 : CW,  // derived, do not override: a channel in the cache
  parameter int DWC           = 4 * CCW,               // a texel in the cache
  parameter int WW            = BW * BH * DWC / 4,     // a bank word
  parameter int DW            = 4 * CW,
  parameter int SLW           = $clog2(LINES),
  parameter int OFW           = ($clog2(BW) + $clog2(BH) - 2 > 0) ? $clog2(BW) + $clog2(BH) - 2 : 1,
  parameter int RD            = SLW + OFW,
  parameter int PB            = (BLOCK_FORMATS != 0) ? 5 : 1
) (
  input  logic                         valid,
  input  logic                         c0,
  input  logic [tex_pkg::FORMAT_W-1:0] fmt,
  input  logic                         srgb,
  input  logic [8*PB-1:0]              low,
  input  logic [8*RD-1:0]              reads,
  input  logic [4*WW-1:0]              word0,
  input  logic [4*WW-1:0]              word1,
  output logic [8*DW-1:0]              texels
);
  /*verilator inline_module*/  // (one evaluation with its caller, as before the split)

  // Each tap's bank and its offset in the bank's word (only while a sample is in T).
  logic [8*2-1:0]   tap_bank;    // tap i's bank at [i*2 +: 2]
  logic [8*OFW-1:0] tap_offset;  // and its offset in the bank word
  logic [7:0]       tap_cache;   // and its cache: c0 for slot 0, the other for slot 1
  always_comb begin
    logic [PB-1:0] xl, yl;  // the tap's low coordinate bits
    {xl, yl} = '0;
    tap_bank   = '0;
    tap_offset = '0;
    tap_cache  = '0;
    if (valid)
      for (int i = 0; i < 8; i++) begin
        xl = low[(i/4*4 + i%2)*PB +: PB];
        yl = low[(i/4*4 + 2 + i%4/2)*PB +: PB];
        tap_bank[i*2 +: 2] = {yl[PB-1], xl[PB-1]};
        tap_offset[i*OFW +: OFW] = reads[(i/4*4 + 32'(tap_bank[i*2 +: 2]))*RD +: OFW];
        tap_cache[i] = c0 ^ 1'(i/4);
      end
  end

  // Tap i's n bits (a texel, or an 8- or 16-byte block) in its cache's bank word: read only inside
  // the taps' condition (no copy of the words in the other clocks).
  `define TAP_AT(i, n) (32'(tap_bank[(i)*2 +: 2])*WW + 32'(tap_offset[(i)*OFW +: OFW])*(n))
  `define TAP_BITS(i, n) (tap_cache[i] ? word1[`TAP_AT(i, n) +: (n)] : word0[`TAP_AT(i, n) +: (n)])

  // Each tap's texel as the cache holds its channels: from its bank word, or decoded from its
  // block by the tap's tex_bc_decode, which evaluates its decoders only with `en` (a block sample
  // in T), so that the clocks without one cost a simulator a test there.
  logic [8*DWC-1:0] cached;
  generate
    if (BLOCK_FORMATS != 0) begin : g_decode
      logic blk;
      assign blk = fmt != tex_pkg::FMT_RGBA8;
      logic [8*128-1:0] blocks;  // tap i's block at [i*128 +: 128] (8-byte blocks in the low half;
                                 // a word holds whole blocks, WW >= 128)
      logic [8*32-1:0]  rgbas;   // and its decoded texel, unorm8
      always_comb begin
        logic [63:0] block8;
        block8 = '0;
        blocks = '0;
        if (valid && blk)
          for (int i = 0; i < 8; i++)
            if (tex_pkg::line_kind(fmt) == tex_pkg::LINE_BLOCKS8) begin
              block8 = `TAP_BITS(i, 64);
              blocks[i*128 +: 128] = 128'(block8);
            end else
              blocks[i*128 +: 128] = `TAP_BITS(i, 128);
      end
      for (genvar g = 0; g < 8; g++) begin : g_tap
        tex_bc_decode u_dec (.en(valid && blk), .format(fmt), .block(blocks[g*128 +: 128]),
                             .x(low[(g/4*4 + g%2)*PB +: 4]), .y(low[(g/4*4 + 2 + g%4/2)*PB +: 4]), .srgb(srgb),
                             .rgba(rgbas[g*32 +: 32]));
      end
      always_comb begin
        cached = '0;
        if (valid && blk)
          for (int i = 0; i < 8; i++)
            cached[i*DWC +: DWC] = DWC'(rgbas[i*32 +: 32]);
        else if (valid)
          for (int i = 0; i < 8; i++)
            cached[i*DWC +: DWC] = `TAP_BITS(i, DWC);
      end
    end else begin : g_texels
      logic fmt_unused;  // (RGBA8 only without BLOCK_FORMATS)
      assign fmt_unused = ^fmt;
      always_comb begin
        cached = '0;
        if (valid)
          for (int i = 0; i < 8; i++)
            cached[i*DWC +: DWC] = `TAP_BITS(i, DWC);
      end
    end
  endgenerate

  // SRGB: the 8-bit channels into the CW = 16 filter. An sRGB texture's R, G, B through the decode
  // table (24 reads per sample, called only for sRGB textures), its alpha widened exactly
  // (a * 257 = {a, a}); a linear texture's channels as they are (the filter's arithmetic is exact,
  // so 8-bit values give the 8-bit filter's result in the low bits).
  generate
    if (SRGB != 0) begin : g_srgb
      // (the calls under an `if` of their own: Verilator turns an if/else of two single
      // assignments into a ?: and calls the functions before it, in every clock)
      always_comb begin
        logic [31:0] t;
        logic [47:0] rgb;  // linear unorm16 R, G, B
        t = '0;
        rgb = '0;
        texels = '0;
        if (valid && srgb)
          for (int i = 0; i < 8; i++) begin
            t   = cached[i*32 +: 32];
            rgb = {tex_srgb_decode::linear(t[23:16]), tex_srgb_decode::linear(t[15:8]), tex_srgb_decode::linear(t[7:0])};
            texels[i*DW +: DW] = DW'({t[31:24], t[31:24], rgb});
          end
        else if (valid && tex_pkg::eac(fmt))
          for (int i = 0; i < 8; i++) begin
            t = cached[i*32 +: 32];
            texels[i*DW +: DW] = DW'({16'hFFFF, tex_pkg::snorm(fmt), 15'd0, t});
          end
        else
          for (int i = 0; i < 8; i++) begin
            t = cached[i*32 +: 32];
            texels[i*DW +: DW] = DW'({8'd0, t[31:24], 8'd0, t[23:16], 8'd0, t[15:8], 8'd0, t[7:0]});
          end
      end
    end else begin : g_linear
      logic srgb_unused;  // (no sRGB textures without SRGB)
      assign srgb_unused = srgb;
      assign texels = cached;
    end
  endgenerate
  `undef TAP_AT
  `undef TAP_BITS
endmodule

// tex_tap_select: the cached fetch's clock T (docs/memory.md §2): the data banks' words to the
// sample's 8 taps (tap i = slot*4 + t; slot 0 level d in cache c0, slot 1 level d1 in the other;
// t bit 0 the second x tap, bit 1 the second y tap). Each tap reads the bank of its parity (of its
// texel, or of its 4x4 block) at that bank's offset: a texel of the word, or a block decoded by
// one tex_bc_decode per tap (BLOCK_FORMATS); with SRGB an sRGB texture's R, G, B through
// tex_srgb_decode (24 per sample), its alpha widened exactly.
// Handshake: none (combinational). Everything is 0 unless `valid` (a sample is in T), so that a
// simulator skips the taps in the clocks in between.
// Latency: 0. Throughput: 8 taps per clock.
// Ports:
//   c0, fmt, srgb : slot 0's cache, the texture's format (tex_pkg::FMT_*), sRGB (SRGB only)
//   low           : slot s at [s*4*PB +: 4*PB]: {y1, y0, x1, x0} mod 2^PB (tex_tag_stage)
//   reads         : the sample's bank reads, slot s bank b at [(s*4 + b)*RD +: RD]: {line slot,
//                   offset}; the offsets place each tap in its word
//   word0, word1  : cache 0's (1's) bank b's word at [b*WW +: WW] (tex_cache_data, read in R)
//   texels        : tap i's texel at [i*DW +: DW], DW = 4*CW, {A, B, G, R}: the cache's channels
//                   (SRGB: an sRGB texture's R, G, B linear unorm16 and A x 257; a linear
//                   texture's 8-bit channels zero-extended)
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
  parameter int PB            = (BLOCK_FORMATS != 0) ? 3 : 1
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
  logic blk;
  assign blk = fmt != tex_pkg::FMT_RGBA8;

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
        tap_bank[i*2 +: 2] = blk ? {yl[PB-1], xl[PB-1]} : {yl[0], xl[0]};
        tap_offset[i*OFW +: OFW] = reads[(i/4*4 + 32'(tap_bank[i*2 +: 2]))*RD +: OFW];
        tap_cache[i] = c0 ^ 1'(i/4);
      end
  end

  // Tap i's n bits (a texel, or an 8- or 16-byte block) in its cache's bank word: read only inside
  // the taps' condition (no copy of the words in the other clocks).
  `define TAP_AT(i, n) (32'(tap_bank[(i)*2 +: 2])*WW + 32'(tap_offset[(i)*OFW +: OFW])*(n))
  `define TAP_BITS(i, n) (tap_cache[i] ? word1[`TAP_AT(i, n) +: (n)] : word0[`TAP_AT(i, n) +: (n)])

  genvar b;
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
        if (valid && blk)
          for (int i = 0; i < 8; i++) begin
            // (8-byte blocks: the low half; a word holds whole blocks, WW >= 128 with the formats)
            if (tex_pkg::line_kind(fmt) == tex_pkg::LINE_BLOCKS8)
              dec_block[i*128 +: 64] = `TAP_BITS(i, 64);
            else
              dec_block[i*128 +: 128] = `TAP_BITS(i, 128);
            dec_texel[i*4 +: 4] = {low[(i/4*4 + 2 + i%4/2)*PB +: 2], low[(i/4*4 + i%2)*PB +: 2]};
          end
      end
      for (b = 0; b < 8; b = b + 1) begin : g_tap
        logic [31:0] rgba;
        tex_bc_decode u_dec (.format(fmt), .block(dec_block[b*128 +: 128]), .texel(dec_texel[b*4 +: 4]),
                             .rgba(rgba));
        assign decoded[b*DWC +: DWC] = DWC'(rgba);
      end
    end else begin : g_no_decode
      assign decoded = '0;
    end
  endgenerate

  // Each tap's texel as the cache holds its channels: from its bank word, or decoded.
  logic [8*DWC-1:0] cached;
  always_comb begin
    cached = '0;
    if (valid)
      for (int i = 0; i < 8; i++)
        cached[i*DWC +: DWC] = blk ? decoded[i*DWC +: DWC]
                                   : `TAP_BITS(i, DWC);
  end

  // SRGB: the 8-bit channels into the CW = 16 filter. An sRGB texture's R, G, B through the decode
  // table (24 ROM reads per sample), its alpha widened exactly (a * 257 = {a, a}); a linear
  // texture's channels as they are (the filter's arithmetic is exact, so 8-bit values give the
  // 8-bit filter's result in the low bits).
  generate
    if (SRGB != 0) begin : g_srgb
      for (b = 0; b < 8; b = b + 1) begin : g_tap
        logic [47:0] rgb;  // linear unorm16 R, G, B
        logic [7:0]  a;
        for (genvar k = 0; k < 3; k = k + 1) begin : g_channel
          tex_srgb_decode u_rom (.code(cached[b*32 + k*8 +: 8]), .linear(rgb[k*16 +: 16]));
        end
        assign a = cached[b*32 + 24 +: 8];
        assign texels[b*DW +: DW] = srgb ? DW'({a, a, rgb})
                                         : DW'({8'd0, a, 8'd0, cached[b*32 + 16 +: 8], 8'd0, cached[b*32 + 8 +: 8],
                                                8'd0, cached[b*32 +: 8]});
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

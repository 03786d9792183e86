// tex_bc_decode: one texel of a block of any block format (docs/numerics.md
// "Block-compressed formats"): BC1 (with its transparent index), BC2 (4-bit alpha), BC3 (BC4-style
// alpha), BC4 (R, 0, 0, 255), BC5 (R, G, 0, 255), BC7, ETC2 RGB8, RGB8A1 and RGBA8 and EAC R11 and
// RG11 (tex_etc2), and ASTC of every footprint, linear or sRGB (tex_astc). The model's decode_texel
// (model/block_formats.h) is its specification, bit for bit (EAC: decode_block into Texel).
// The formats' decoders are functions (packages tex_bc_colour, tex_bc_channel, tex_bc7) called
// inside `if (en)` and only for their formats, so that a simulator spends nothing on them in the
// clocks without a block texel (Verilator evaluates a module's continuous logic every clock, but
// keeps an `if` as a branch); the module around them is elaborated once for the 8 taps. One colour
// decoder serves BC1 (low half) and BC2/BC3 (high half), one channel decoder BC3's alpha, BC4 and
// BC5's red, a second BC5's green.
// Handshake: none (combinational; the cached unit's taps decode the 8 texels of a trilinear
// sample with 8 of these in the filter's clock). Latency: 0. Throughput: 1 per clock.
// Ports:
//   en     : decode (else rgba is 0 and nothing is evaluated)
//   format : tex_pkg::FMT_* (FMT_RGBA8 gives 0: not a block format)
//   block  : 128 bits, byte i at bits 8i+7..8i; BC1, BC4, ETC2 RGB8 and RGB8A1 use bits 63..0
//   x, y   : the texel's place in the block, 0..3 (ASTC: 0..F-1 of its footprint)
//   srgb   : the texture is sRGB (ASTC widens its endpoints differently; the others ignore it)
//   rgba   : unorm8 R (bits 7..0), G, B, A (31..24); EAC: 16-bit codes R (15..0) and G (31..16; R11:
//            0, signed 32768), for tex_tap_select to widen to {A, B, G, R} = {65535, 0 or 32768, G, R}
module tex_bc_decode (
  input  logic                         en,
  input  logic [tex_pkg::FORMAT_W-1:0] format,
  input  logic [127:0]                 block,
  input  logic [3:0]                   x,
  input  logic [3:0]                   y,
  input  logic                         srgb,
  output logic [31:0]                  rgba
);
  logic [3:0] texel;  // x + 4 y in a 4x4 block
  logic [3:0] fw, fh; // an ASTC footprint
  assign texel    = {y[1:0], x[1:0]};
  assign {fh, fw} = tex_pkg::footprint(format);
  // The texel from the formats' parts: BC1's colour (black if transparent), BC2's 4-bit alpha,
  // BC3's channel alpha, BC4's red, BC5's red and green, BC7's texel.
  function automatic logic [31:0] texel_of(input logic [tex_pkg::FORMAT_W-1:0] f, input logic [24:0] colour,
                                           input logic [7:0] low, input logic [7:0] high, input logic [3:0] nibble,
                                           input logic [31:0] bc7, input logic [31:0] etc2,
                                           input logic [7:0] eac, input logic [31:0] r11, input logic [31:0] astc);
    if (tex_pkg::astc(f)) texel_of = astc;
    else if (tex_pkg::eac(f)) texel_of = r11;
    else case (f)
      tex_pkg::FMT_BC1: texel_of = colour[24] ? 32'd0 : {8'd255, colour[23:0]};
      tex_pkg::FMT_BC2: texel_of = {nibble, nibble, colour[23:0]};  // x 17
      tex_pkg::FMT_BC3: texel_of = {low, colour[23:0]};
      tex_pkg::FMT_BC4: texel_of = {8'd255, 16'd0, low};
      tex_pkg::FMT_BC5: texel_of = {8'd255, 8'd0, high, low};
      tex_pkg::FMT_BC7: texel_of = bc7;
      tex_pkg::FMT_ETC2, tex_pkg::FMT_ETC2_A1: texel_of = etc2;
      tex_pkg::FMT_ETC2_RGBA: texel_of = {eac, etc2[23:0]};
      default:          texel_of = 32'd0;
    endcase
  endfunction

  logic        bc1;
  logic [3:0]  nibble;   // BC2's alpha
  assign bc1    = format == tex_pkg::FMT_BC1;
  assign nibble = 4'(block >> (4 * texel));
`ifdef SYNTHESIS
  logic [24:0] colour;   // {transparent, rgb}
  logic [7:0]  low, high;
  logic [31:0] bc7, etc2, astc, r11;
  logic [7:0]  eac;
  // Yosys inlines a function where it is called: inside an `if`, every assignment of its body
  // becomes a multiplexer (Yosys's `proc` took minutes for the 8 taps); as continuous logic, none
  // does. The same values as below.
  assign colour = tex_bc_colour::texel_rgb(bc1 ? block[63:0] : block[127:64], texel, !bc1);
  assign low    = tex_bc_channel::value(block[63:0], texel);
  assign high   = tex_bc_channel::value(block[127:64], texel);
  assign bc7    = tex_bc7::rgba(block, texel);
  assign etc2   = tex_etc2::colour(format == tex_pkg::FMT_ETC2_RGBA ? block[127:64] : block[63:0], texel,
                                   format == tex_pkg::FMT_ETC2_A1);
  assign eac    = tex_etc2::alpha(block[63:0], texel);
  assign r11    = {(format == tex_pkg::FMT_EAC_RG11 || format == tex_pkg::FMT_EAC_RG11_SNORM)
                       ? tex_etc2::r11(block[127:64], texel, tex_pkg::snorm(format))
                       : {tex_pkg::snorm(format), 15'd0},
                   tex_etc2::r11(block[63:0], texel, tex_pkg::snorm(format))};
`ifdef TEX_SYNTH_NO_ASTC
  // (make synth's whole-unit runs: Yosys 0.23's resource sharing runs out of memory on 8 ASTC
  // decoders; scripts/synth.sh measures tex_astc alone, docs/rtl.md)
  assign astc   = 32'd0;
  logic unused_astc;
  assign unused_astc = ^{fw, fh, y[3:2], x[3:2], srgb};
`else
  assign astc   = tex_astc::texel(block, fw, fh, x, y, srgb);
`endif
  assign rgba = en ? texel_of(format, colour, low, high, nibble, bc7, etc2, eac, r11, astc) : 32'd0;
`else
  // A simulator: nothing without `en` (the clocks without a block sample cost a test), and each
  // format's decoder only for that format. (No `else` branches: Verilator makes a ?: of an
  // if/else of two single assignments and calls the functions before it, in every clock.)
  always_comb begin
    logic [24:0] colour;   // {transparent, rgb}
    logic [7:0]  low, high;
    logic [31:0] bc7, etc2, astc, r11;
    logic [7:0]  eac;
    rgba = '0;
    {colour, low, high, bc7, etc2, eac, r11, astc} = '0;
    if (en) begin
      if (bc1 || format == tex_pkg::FMT_BC2 || format == tex_pkg::FMT_BC3)
        colour = tex_bc_colour::texel_rgb(bc1 ? block[63:0] : block[127:64], texel, !bc1);
      if (format == tex_pkg::FMT_BC3 || format == tex_pkg::FMT_BC4 || format == tex_pkg::FMT_BC5)
        low = tex_bc_channel::value(block[63:0], texel);
      if (format == tex_pkg::FMT_BC5)
        high = tex_bc_channel::value(block[127:64], texel);
      if (format == tex_pkg::FMT_BC7)
        bc7 = tex_bc7::rgba(block, texel);
      if (format == tex_pkg::FMT_ETC2 || format == tex_pkg::FMT_ETC2_A1)
        etc2 = tex_etc2::colour(block[63:0], texel, format == tex_pkg::FMT_ETC2_A1);
      if (format == tex_pkg::FMT_ETC2_RGBA) begin
        etc2 = tex_etc2::colour(block[127:64], texel, 1'b0);
        eac  = tex_etc2::alpha(block[63:0], texel);
      end
      if (tex_pkg::eac(format)) begin
        r11[15:0]  = tex_etc2::r11(block[63:0], texel, tex_pkg::snorm(format));
        r11[31:16] = {tex_pkg::snorm(format), 15'd0};  // R11's G: 0.0
      end
      if (format == tex_pkg::FMT_EAC_RG11 || format == tex_pkg::FMT_EAC_RG11_SNORM)
        r11[31:16] = tex_etc2::r11(block[127:64], texel, tex_pkg::snorm(format));
      if (tex_pkg::astc(format))
        astc = tex_astc::texel(block, fw, fh, x, y, srgb);
      rgba = texel_of(format, colour, low, high, nibble, bc7, etc2, eac, r11, astc);
    end
  end
`endif
endmodule

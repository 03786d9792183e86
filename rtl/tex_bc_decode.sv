// tex_bc_decode: one texel of a 4x4 block of any block format (docs/numerics.md
// "Block-compressed formats"): BC1 (with its transparent index), BC2 (4-bit alpha), BC3 (BC4-style
// alpha), BC4 (R, 0, 0, 255), BC5 (R, G, 0, 255), BC7. The model's decode_texel
// (model/block_formats.h) is its specification, bit for bit.
// Handshake: none (combinational; the cached unit's taps decode the 8 texels of a trilinear sample
// with 8 of these in the filter's clock). Latency: 0. Throughput: 1 per clock.
// Ports:
//   format : tex_pkg::FMT_* (FMT_RGBA8 gives 0: not a block format)
//   block  : 128 bits, byte i at bits 8i+7..8i; BC1 and BC4 use bits 63..0
//   texel  : 0..15, x + 4 y inside the block
//   rgba   : unorm8 R (bits 7..0), G, B, A (31..24)
module tex_bc_decode (
  input  logic [tex_pkg::FORMAT_W-1:0] format,
  input  logic [127:0]                 block,
  input  logic [3:0]                   texel,
  output logic [31:0]                  rgba
);
  logic [23:0] bc1_rgb, bc23_rgb;
  logic        bc1_clear, bc23_clear_unused;
  logic [7:0]  low_channel, high_channel, bc2_alpha;
  logic [31:0] bc7_rgba;
  logic [3:0]  nibble;
  // BC1: the colour block alone; BC2/BC3: the colour block in the high half, four colours.
  tex_bc_colour u_bc1 (.block(block[63:0]), .texel(texel), .four_only(1'b0), .rgb(bc1_rgb), .transparent(bc1_clear));
  tex_bc_colour u_bc23 (.block(block[127:64]), .texel(texel), .four_only(1'b1), .rgb(bc23_rgb),
                        .transparent(bc23_clear_unused));
  // BC3's alpha, BC4's red and BC5's red (low half); BC5's green (high half).
  tex_bc_channel u_low (.block(block[63:0]), .texel(texel), .value(low_channel));
  tex_bc_channel u_high (.block(block[127:64]), .texel(texel), .value(high_channel));
  tex_bc7 u_bc7 (.block(block), .texel(texel), .rgba(bc7_rgba));
  assign nibble    = block[4 * texel +: 4];
  assign bc2_alpha = {nibble, nibble};  // x 17
  always_comb begin
    case (format)
      tex_pkg::FMT_BC1: rgba = bc1_clear ? 32'd0 : {8'd255, bc1_rgb};
      tex_pkg::FMT_BC2: rgba = {bc2_alpha, bc23_rgb};
      tex_pkg::FMT_BC3: rgba = {low_channel, bc23_rgb};
      tex_pkg::FMT_BC4: rgba = {8'd255, 16'd0, low_channel};
      tex_pkg::FMT_BC5: rgba = {8'd255, 8'd0, high_channel, low_channel};
      tex_pkg::FMT_BC7: rgba = bc7_rgba;
      default:          rgba = 32'd0;
    endcase
  end
endmodule

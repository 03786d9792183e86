// tex_bc7: one texel of a BC7 block (ARB_texture_compression_bptc; docs/numerics.md
// "Block-compressed formats"). The mode is the number of zeros below the low byte's lowest one;
// one tex_bc7_mode per mode reads the block's fields as that mode, the block's own is kept, and
// each channel is ((64 - w) e0 + w e1 + 32) >> 6, then the rotation swaps A with R, G or B. The
// reserved mode 8 (low byte 0) gives (0, 0, 0, 0), as D3D11 says.
// Handshake: none (combinational; the cached unit's taps). Latency: 0. Throughput: 1 per clock.
// Ports:
//   block : the 128-bit block, byte i at bits 8i+7..8i (little-endian, as memory holds it)
//   texel : 0..15, x + 4 y inside the block
//   rgba  : unorm8 R (bits 7..0), G, B, A (31..24)
module tex_bc7 (
  input  logic [127:0] block,
  input  logic [3:0]   texel,
  output logic [31:0]  rgba
);
  // Each mode's reading, mode m at [m * width +: width] (flat: Yosys keeps wires, not memories).
  logic [8*32-1:0] e0, e1;
  logic [8*7-1:0]  colour_w, alpha_w;
  logic [8*2-1:0]  rotation;
  generate
    for (genvar m = 0; m < 8; m++) begin : g_mode
      tex_bc7_mode #(.MODE(m)) u_mode (
        .block(block), .texel(texel), .e0(e0[32 * m +: 32]), .e1(e1[32 * m +: 32]), .colour_w(colour_w[7 * m +: 7]),
        .alpha_w(alpha_w[7 * m +: 7]), .rotation(rotation[2 * m +: 2]));
    end
  endgenerate

  logic [2:0]  mode;
  logic        reserved;
  logic [31:0] a, b, mixed;
  logic [6:0]  wc, wa;
  logic [1:0]  rot;
  always_comb begin
    mode = 3'd0;
    for (int m = 7; m >= 0; m--)
      if (block[m]) mode = 3'(m);
  end
  assign reserved = block[7:0] == 8'd0;
  assign a   = e0[32 * mode +: 32];
  assign b   = e1[32 * mode +: 32];
  assign wc  = colour_w[7 * mode +: 7];
  assign wa  = alpha_w[7 * mode +: 7];
  assign rot = rotation[2 * mode +: 2];
  generate
    for (genvar c = 0; c < 4; c++) begin : g_channel
      logic [6:0]  w, w0;     // the weights of e1 and e0 in 64ths
      logic [14:0] sum;       // (64 - w) e0 + w e1 + 32, at most 64 * 255 + 32 < 2^14
      logic [6:0]  sum_rest_unused;
      assign w   = c < 3 ? wc : wa;
      assign w0  = 7'd64 - w;
      assign sum = 15'(w0) * 15'(a[8 * c +: 8]) + 15'(w) * 15'(b[8 * c +: 8]) + 15'd32;
      assign mixed[8 * c +: 8] = sum[13:6];
      assign sum_rest_unused = {sum[14], sum[5:0]};
    end
  endgenerate
  always_comb begin
    rgba = mixed;
    case (rot)
      2'd1: begin rgba[7:0] = mixed[31:24];   rgba[31:24] = mixed[7:0];   end
      2'd2: begin rgba[15:8] = mixed[31:24];  rgba[31:24] = mixed[15:8];  end
      2'd3: begin rgba[23:16] = mixed[31:24]; rgba[31:24] = mixed[23:16]; end
      default: ;
    endcase
    if (reserved) rgba = 32'd0;
  end
endmodule

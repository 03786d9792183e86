// tex_etc2: one texel of an ETC2 colour block (RGB8 and ETC1, RGB8A1) and of an EAC alpha block
// (ETC2 RGBA8's), as the model's etc2_colour_texel and eac_alpha_texel (model/etc2.h,
// docs/numerics.md "ETC2") decode them, bit for bit. Functions, as tex_bc_colour's, so that the
// block decoder (tex_bc_decode) calls them only for the taps that read such a block (also tested
// alone through rtl/synth/tex_etc2_top.sv).
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call.
// colour(block, texel, punch_through) -> rgba:
//   block         : the 64-bit colour block as stored, byte i at bits 8i+7..8i (ETC's big-endian
//                   word is byte 0 first: its bit 63 is bit 7 here)
//   texel         : 0..15, x + 4 y inside the block
//   punch_through : 1 for RGB8A1 (bit 33 reads "opaque"; no individual mode)
//   rgba          : unorm8 R (bits 7..0), G, B, A (31..24)
// alpha(block, texel) -> unorm8 alpha of the EAC block (the first 8 bytes of an RGBA8 block)
// r11(block, texel, snorm) -> the 16-bit code of an EAC R11 block's texel (each channel of EAC R11
//   and RG11; model/etc2.h eac_r11_code): the 11-bit value widened by replicating its top bits,
//   unsigned, or with `snorm` signed and then offset by 32768 (offset binary, 32768 = 0.0)
package tex_etc2;
  // ETC's big-endian word from the bytes as stored.
  function automatic logic [63:0] word(input logic [63:0] block);
    word = {block[7:0], block[15:8], block[23:16], block[31:24], block[39:32], block[47:40], block[55:48], block[63:56]};
  endfunction

  function automatic logic [7:0] clamp8(input logic signed [13:0] v);
    clamp8 = v < 0 ? 8'd0 : v > 14'sd255 ? 8'd255 : v[7:0];
  endfunction

  // ETC1's modifier pairs (a, b) by table codeword, and the T and H modes' distances.
  function automatic logic [7:0] modifier_a(input logic [2:0] table_index);
    case (table_index)
      3'd0: modifier_a = 8'd2;   3'd1: modifier_a = 8'd5;   3'd2: modifier_a = 8'd9;   3'd3: modifier_a = 8'd13;
      3'd4: modifier_a = 8'd18;  3'd5: modifier_a = 8'd24;  3'd6: modifier_a = 8'd33;  default: modifier_a = 8'd47;
    endcase
  endfunction
  function automatic logic [7:0] modifier_b(input logic [2:0] table_index);
    case (table_index)
      3'd0: modifier_b = 8'd8;   3'd1: modifier_b = 8'd17;  3'd2: modifier_b = 8'd29;  3'd3: modifier_b = 8'd42;
      3'd4: modifier_b = 8'd60;  3'd5: modifier_b = 8'd80;  3'd6: modifier_b = 8'd106; default: modifier_b = 8'd183;
    endcase
  endfunction
  function automatic logic [7:0] distance(input logic [2:0] index);
    case (index)
      3'd0: distance = 8'd3;   3'd1: distance = 8'd6;   3'd2: distance = 8'd11;  3'd3: distance = 8'd16;
      3'd4: distance = 8'd23;  3'd5: distance = 8'd32;  3'd6: distance = 8'd41;  default: distance = 8'd64;
    endcase
  endfunction

  // n-bit components widened to 8 bits by replicating their top bits.
  function automatic logic [7:0] ext4(input logic [3:0] c); ext4 = {c, c}; endfunction
  function automatic logic [7:0] ext5(input logic [4:0] c); ext5 = {c, c[4:2]}; endfunction
  function automatic logic [7:0] ext6(input logic [5:0] c); ext6 = {c, c[5:4]}; endfunction
  function automatic logic [7:0] ext7(input logic [6:0] c); ext7 = {c, c[6]}; endfunction

  // A base colour plus a signed offset per channel, clamped: {B, G, R}. (No loop: a loop variable
  // in a function called inside an `if` is a latch to Yosys.)
  function automatic logic [7:0] offset1(input logic [7:0] c, input logic signed [9:0] d);
    offset1 = clamp8(14'($signed({2'b0, c})) + 14'(d));
  endfunction
  function automatic logic [23:0] offset(input logic [23:0] c, input logic signed [9:0] d);
    offset = {offset1(c[23:16], d), offset1(c[15:8], d), offset1(c[7:0], d)};
  endfunction

  // One planar channel: clamp((x (h - o) + y (v - o) + 4 o + 2) >> 2), an arithmetic shift. (x, y
  // are 0..3: the products are shifts and adds, not multipliers.)
  function automatic logic [7:0] plane(input logic [1:0] x, input logic [1:0] y, input logic [7:0] o,
                                       input logic [7:0] h, input logic [7:0] v);
    logic signed [13:0] dh, dv, sum;
    dh  = 14'($signed({1'b0, h})) - 14'($signed({1'b0, o}));
    dv  = 14'($signed({1'b0, v})) - 14'($signed({1'b0, o}));
    sum = (x[1] ? dh <<< 1 : 14'sd0) + (x[0] ? dh : 14'sd0) + (y[1] ? dv <<< 1 : 14'sd0) + (y[0] ? dv : 14'sd0) +
          14'($signed({1'b0, o, 2'b10}));
    plane = clamp8(sum >>> 2);
  endfunction

  function automatic logic [31:0] colour(input logic [63:0] block, input logic [3:0] texel, input logic punch_through);
    logic [63:0] w;
    logic [1:0]  x, y, index;
    logic [3:0]  p;
    logic [6:0]  sum_r, sum_g, sum_b;  // base + signed delta, -4..34 as 7-bit two's complement
    logic        individual, mode_t, mode_h, planar, see_through, second, order;
    logic [23:0] base, c1, c2;
    logic [7:0]  a, b, d;
    logic [2:0]  table_index;
    logic signed [9:0] m;
    w           = word(block);
    x           = texel[1:0];
    y           = texel[3:2];
    p           = {x, y};  // (column-major)
    index       = {w[16 + 32'(p)], w[32'(p)]};
    sum_r       = 7'(w[63:59]) + {{4{w[58]}}, w[58:56]};
    sum_g       = 7'(w[55:51]) + {{4{w[50]}}, w[50:48]};
    sum_b       = 7'(w[47:43]) + {{4{w[42]}}, w[42:40]};
    individual  = !punch_through && !w[33];
    mode_t      = !individual && (sum_r[6] || sum_r[5]);
    mode_h      = !individual && !mode_t && (sum_g[6] || sum_g[5]);
    planar      = !individual && !mode_t && !mode_h && (sum_b[6] || sum_b[5]);
    see_through = punch_through && !w[33];
    colour      = '0;
    if (see_through && index == 2'd2 && !planar) begin
      colour = '0;  // RGB8A1's transparent black
    end else if (planar) begin
      colour = {8'd255,
                plane(x, y, ext6({w[48], w[44:43], w[41:39]}), ext6(w[24:19]), ext6(w[5:0])),
                plane(x, y, ext7({w[56], w[54:49]}), ext7(w[31:25]), ext7(w[12:6])),
                plane(x, y, ext6(w[62:57]), ext6({w[38:34], w[32]}), ext6(w[18:13]))};
    end else if (mode_t) begin
      c1 = {ext4(w[51:48]), ext4(w[55:52]), ext4({w[60:59], w[57:56]})};
      c2 = {ext4(w[39:36]), ext4(w[43:40]), ext4(w[47:44])};
      d  = distance({w[35:34], w[32]});
      case (index)
        2'd0:    colour = {8'd255, c1};
        2'd1:    colour = {8'd255, offset(c2, 10'($signed({2'b0, d})))};
        2'd2:    colour = {8'd255, c2};
        default: colour = {8'd255, offset(c2, -(10'($signed({2'b0, d}))))};
      endcase
    end else if (mode_h) begin
      // The distance's low bit is the order of the two 12-bit colours.
      order = {w[62:59], w[58:56], w[52], w[51], w[49:47]} >= w[46:35];
      c1    = {ext4({w[51], w[49:47]}), ext4({w[58:56], w[52]}), ext4(w[62:59])};
      c2    = {ext4(w[38:35]), ext4(w[42:39]), ext4(w[46:43])};
      d     = distance({w[34], w[32], order});
      case (index)
        2'd0:    colour = {8'd255, offset(c1, 10'($signed({2'b0, d})))};
        2'd1:    colour = {8'd255, offset(c1, -(10'($signed({2'b0, d}))))};
        2'd2:    colour = {8'd255, offset(c2, 10'($signed({2'b0, d})))};
        default: colour = {8'd255, offset(c2, -(10'($signed({2'b0, d}))))};
      endcase
    end else begin
      // Individual or differential: two sub-blocks (bit 32: 4x2 above each other, else 2x4).
      second      = w[32] ? y[1] : x[1];
      table_index = second ? w[36:34] : w[39:37];
      if (individual)
        base = second ? {ext4(w[43:40]), ext4(w[51:48]), ext4(w[59:56])}
                      : {ext4(w[47:44]), ext4(w[55:52]), ext4(w[63:60])};
      else
        base = second ? {ext5(sum_b[4:0]), ext5(sum_g[4:0]), ext5(sum_r[4:0])}
                      : {ext5(w[47:43]), ext5(w[55:51]), ext5(w[63:59])};
      a = see_through ? 8'd0 : modifier_a(table_index);  // (RGB8A1 not opaque: index 0 adds 0)
      b = modifier_b(table_index);
      case (index)
        2'd0:    m = 10'($signed({2'b0, a}));
        2'd1:    m = 10'($signed({2'b0, b}));
        2'd2:    m = -(10'($signed({2'b0, a})));
        default: m = -(10'($signed({2'b0, b})));
      endcase
      colour = {8'd255, offset(base, m)};
    end
  endfunction

  // EAC's modifier tables: entry `index` of table `table_index`.
  function automatic logic signed [4:0] eac_modifier(input logic [3:0] table_index, input logic [2:0] index);
    logic [39:0] row;  // the table's 8 values, index 0 in bits 4..0
    case (table_index)
      4'd0:    row = {5'sd14, 5'sd8, 5'sd5, 5'sd2, -5'sd15, -5'sd9, -5'sd6, -5'sd3};
      4'd1:    row = {5'sd12, 5'sd9, 5'sd6, 5'sd2, -5'sd13, -5'sd10, -5'sd7, -5'sd3};
      4'd2:    row = {5'sd12, 5'sd7, 5'sd4, 5'sd1, -5'sd13, -5'sd8, -5'sd5, -5'sd2};
      4'd3:    row = {5'sd12, 5'sd5, 5'sd3, 5'sd1, -5'sd13, -5'sd6, -5'sd4, -5'sd2};
      4'd4:    row = {5'sd11, 5'sd7, 5'sd5, 5'sd2, -5'sd12, -5'sd8, -5'sd6, -5'sd3};
      4'd5:    row = {5'sd10, 5'sd8, 5'sd6, 5'sd2, -5'sd11, -5'sd9, -5'sd7, -5'sd3};
      4'd6:    row = {5'sd10, 5'sd7, 5'sd6, 5'sd3, -5'sd11, -5'sd8, -5'sd7, -5'sd4};
      4'd7:    row = {5'sd10, 5'sd7, 5'sd4, 5'sd2, -5'sd11, -5'sd8, -5'sd5, -5'sd3};
      4'd8:    row = {5'sd9, 5'sd7, 5'sd5, 5'sd1, -5'sd10, -5'sd8, -5'sd6, -5'sd2};
      4'd9:    row = {5'sd9, 5'sd7, 5'sd4, 5'sd1, -5'sd10, -5'sd8, -5'sd5, -5'sd2};
      4'd10:   row = {5'sd9, 5'sd7, 5'sd3, 5'sd1, -5'sd10, -5'sd8, -5'sd4, -5'sd2};
      4'd11:   row = {5'sd9, 5'sd6, 5'sd4, 5'sd1, -5'sd10, -5'sd7, -5'sd5, -5'sd2};
      4'd12:   row = {5'sd9, 5'sd6, 5'sd3, 5'sd2, -5'sd10, -5'sd7, -5'sd4, -5'sd3};
      4'd13:   row = {5'sd9, 5'sd2, 5'sd1, 5'sd0, -5'sd10, -5'sd3, -5'sd2, -5'sd1};
      4'd14:   row = {5'sd8, 5'sd7, 5'sd5, 5'sd3, -5'sd9, -5'sd8, -5'sd6, -5'sd4};
      default: row = {5'sd8, 5'sd6, 5'sd4, 5'sd2, -5'sd9, -5'sd7, -5'sd5, -5'sd3};
    endcase
    eac_modifier = 5'(row >> ((32'(index) << 2) + 32'(index)));  // (5 index as a shift and an add)
  endfunction

  function automatic logic [7:0] alpha(input logic [63:0] block, input logic [3:0] texel);
    logic [63:0] w;
    logic [3:0]  p;
    logic [2:0]  index;
    logic signed [13:0] m, sum;
    w     = word(block);
    p     = {texel[1:0], texel[3:2]};  // (column-major)
    index = 3'(w >> (45 - ((32'(p) << 1) + 32'(p))));  // (3 p as a shift and an add)
    // base + modifier x multiplier (4 bits): shifts and adds.
    m     = 14'(eac_modifier(w[51:48], index));
    sum   = 14'($signed({1'b0, w[63:56]}));
    for (int i = 0; i < 4; i++) sum = sum + (w[52 + i] ? m <<< i : 14'sd0);
    alpha = clamp8(sum);
  endfunction

  // EAC R11: base x 8 (+ 4 unsigned) + modifier x multiplier x 8 (multiplier 0: the modifier
  // alone), clamped to 0..2047 or -1023..1023, widened to 16 bits.
  function automatic logic [15:0] r11(input logic [63:0] block, input logic [3:0] texel, input logic snorm);
    logic [63:0] w;
    logic [3:0]  p;
    logic [2:0]  index;
    logic signed [13:0] m, base, sum;
    logic [10:0] u;    // the unsigned value
    logic [9:0]  mag;  // the signed one's magnitude
    w     = word(block);
    p     = {texel[1:0], texel[3:2]};  // (column-major)
    index = 3'(w >> (45 - ((32'(p) << 1) + 32'(p))));
    m     = 14'(eac_modifier(w[51:48], index));
    // the base: unsigned x 8 + 4; signed a two's-complement byte (-128 read as -127) x 8
    base  = snorm ? ((w[63:56] == 8'h80) ? -14'sd1016 : 14'($signed(w[63:56])) <<< 3)
                  : 14'($signed({3'b0, w[63:56], 3'b100}));
    // modifier x multiplier x 8 as shifts and adds; multiplier 0: the modifier alone
    sum = base + ((w[55:52] == 4'd0) ? m : 14'sd0);
    for (int i = 0; i < 4; i++) sum = sum + (w[52 + i] ? m <<< (i + 3) : 14'sd0);
    u   = sum < 0 ? 11'd0 : sum > 14'sd2047 ? 11'd2047 : sum[10:0];
    mag = (sum < -14'sd1023 || sum > 14'sd1023) ? 10'd1023 : sum < 0 ? 10'(-sum) : sum[9:0];
    // widened: u << 5 | u >> 6; the signed magnitude's mag << 5 | mag >> 5 (15 bits), +- from 32768
    if (!snorm) r11 = {u, u[10:6]};
    else if (sum < 0) r11 = 16'd32768 - {1'b0, mag, mag[9:5]};
    else r11 = 16'd32768 + {1'b0, mag, mag[9:5]};
  endfunction
endpackage

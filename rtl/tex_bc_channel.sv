// tex_bc_channel: one texel of a BC4-style channel block (BC3's alpha, BC4's red, BC5's red and
// green; docs/numerics.md "Block-compressed formats"): two 8-bit endpoints a0, a1 and 16 three-bit
// indices. a0 > a1: a0, a1, ((7-k) a0 + k a1 + 3) / 7 for k = 1..6; else a0, a1,
// ((5-k) a0 + k a1 + 2) / 5 for k = 1..4, 0, 255. The divisions round to nearest; they are
// multiplications by 2341 / 2^14 and 1639 / 2^13, exact for every numerator here (at most 1788
// and 1277; tests/rtl/test_rtl_block_decode.cpp checks every endpoint pair and index).
// A function, not a module: a simulator evaluates it only for the taps that read a block.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call (8 calls per clock).
// value(block, texel):
//   block  : the 64-bit block, byte i at bits 8i+7..8i (little-endian, as memory holds it)
//   texel  : 0..15, x + 4 y inside the block
//   result : unsigned 8 bits, unorm8 (0..255 = 0..1)
package tex_bc_channel;
  function automatic logic [7:0] value(input logic [63:0] block, input logic [3:0] texel);
    logic [7:0]  a0, a1;
    logic [2:0]  index, k, k7, k5;  // index - 1, 7 - k, 5 - k
    logic [10:0] sevenths;          // (7-k) a0 + k a1 + 3, at most 7 * 255 + 3
    logic [10:0] fifths;            // (5-k) a0 + k a1 + 2, at most 5 * 255 + 2
    logic [21:0] by7;               // sevenths * 2341: sevenths / 7 in bits 21..14
    logic [20:0] by5;               // fifths * 1639: fifths / 5 in bits 20..13
    a0       = block[7:0];
    a1       = block[15:8];
    index    = block[16 + 3 * texel +: 3];
    k        = index - 3'd1;
    k7       = 3'd7 - k;
    k5       = 3'd5 - k;
    sevenths = 11'(k7) * 11'(a0) + 11'(k) * 11'(a1) + 11'd3;
    fifths   = 11'(k5) * 11'(a0) + 11'(k) * 11'(a1) + 11'd2;
    by7      = 22'(sevenths) * 22'd2341;
    by5      = 21'(fifths) * 21'd1639;
    if (index == 3'd0) value = a0;
    else if (index == 3'd1) value = a1;
    else if (a0 > a1) value = 8'(by7 >> 14);  // six interpolated entries
    else if (index == 3'd6) value = 8'd0;
    else if (index == 3'd7) value = 8'd255;
    else value = 8'(by5 >> 13);
  endfunction
endpackage

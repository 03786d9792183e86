// tex_bc7: one texel of a BC7 block (ARB_texture_compression_bptc; docs/numerics.md
// "Block-compressed formats"). The mode is the number of zeros below the low byte's lowest one;
// the block's fields are read as that mode (Table.M) at constant offsets, one reading per mode of
// which the block's own is kept, its indices are read by one shifter (for all modes: the 128-bit
// shifts are most of the area), the weights looked up, and each channel is
// ((64 - w) e0 + w e1 + 32) >> 6; then the rotation swaps A with R, G or B. The reserved mode 8
// (low byte 0) gives (0, 0, 0, 0), as D3D11 says.
// A function, not a module: a simulator evaluates it only for the taps that read a BC7 block
// (and, inside, only the block's own mode), where a module would be evaluated every clock.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per call (8 calls per clock).
// rgba(block, texel):
//   block  : the 128-bit block, byte i at bits 8i+7..8i (little-endian, as memory holds it)
//   texel  : 0..15, x + 4 y inside the block
//   result : unorm8 R (bits 7..0), G, B, A (31..24)
package tex_bc7;
  // The partition (modes 0: 4 bits, 1, 2, 3, 7: 6 bits after the mode bits) gives the texel's
  // subset and the anchors (an anchor's index has one bit less), for whichever mode it is.
  // partition2 (Table.P2: bit t = the subset of texel t)
  function automatic logic [15:0] partition2(input logic [5:0] p);
    case (p)
      6'd0: partition2 = 16'hcccc;
      6'd1: partition2 = 16'h8888;
      6'd2: partition2 = 16'heeee;
      6'd3: partition2 = 16'hecc8;
      6'd4: partition2 = 16'hc880;
      6'd5: partition2 = 16'hfeec;
      6'd6: partition2 = 16'hfec8;
      6'd7: partition2 = 16'hec80;
      6'd8: partition2 = 16'hc800;
      6'd9: partition2 = 16'hffec;
      6'd10: partition2 = 16'hfe80;
      6'd11: partition2 = 16'he800;
      6'd12: partition2 = 16'hffe8;
      6'd13: partition2 = 16'hff00;
      6'd14: partition2 = 16'hfff0;
      6'd15: partition2 = 16'hf000;
      6'd16: partition2 = 16'hf710;
      6'd17: partition2 = 16'h008e;
      6'd18: partition2 = 16'h7100;
      6'd19: partition2 = 16'h08ce;
      6'd20: partition2 = 16'h008c;
      6'd21: partition2 = 16'h7310;
      6'd22: partition2 = 16'h3100;
      6'd23: partition2 = 16'h8cce;
      6'd24: partition2 = 16'h088c;
      6'd25: partition2 = 16'h3110;
      6'd26: partition2 = 16'h6666;
      6'd27: partition2 = 16'h366c;
      6'd28: partition2 = 16'h17e8;
      6'd29: partition2 = 16'h0ff0;
      6'd30: partition2 = 16'h718e;
      6'd31: partition2 = 16'h399c;
      6'd32: partition2 = 16'haaaa;
      6'd33: partition2 = 16'hf0f0;
      6'd34: partition2 = 16'h5a5a;
      6'd35: partition2 = 16'h33cc;
      6'd36: partition2 = 16'h3c3c;
      6'd37: partition2 = 16'h55aa;
      6'd38: partition2 = 16'h9696;
      6'd39: partition2 = 16'ha55a;
      6'd40: partition2 = 16'h73ce;
      6'd41: partition2 = 16'h13c8;
      6'd42: partition2 = 16'h324c;
      6'd43: partition2 = 16'h3bdc;
      6'd44: partition2 = 16'h6996;
      6'd45: partition2 = 16'hc33c;
      6'd46: partition2 = 16'h9966;
      6'd47: partition2 = 16'h0660;
      6'd48: partition2 = 16'h0272;
      6'd49: partition2 = 16'h04e4;
      6'd50: partition2 = 16'h4e40;
      6'd51: partition2 = 16'h2720;
      6'd52: partition2 = 16'hc936;
      6'd53: partition2 = 16'h936c;
      6'd54: partition2 = 16'h39c6;
      6'd55: partition2 = 16'h639c;
      6'd56: partition2 = 16'h9336;
      6'd57: partition2 = 16'h9cc6;
      6'd58: partition2 = 16'h817e;
      6'd59: partition2 = 16'he718;
      6'd60: partition2 = 16'hccf0;
      6'd61: partition2 = 16'h0fcc;
      6'd62: partition2 = 16'h7744;
      6'd63: partition2 = 16'hee22;
      default: partition2 = '0;
    endcase
  endfunction
  // partition3 (Table.P3: bits 2t+1..2t = the subset of texel t)
  function automatic logic [31:0] partition3(input logic [5:0] p);
    case (p)
      6'd0: partition3 = 32'haa685050;
      6'd1: partition3 = 32'h6a5a5040;
      6'd2: partition3 = 32'h5a5a4200;
      6'd3: partition3 = 32'h5450a0a8;
      6'd4: partition3 = 32'ha5a50000;
      6'd5: partition3 = 32'ha0a05050;
      6'd6: partition3 = 32'h5555a0a0;
      6'd7: partition3 = 32'h5a5a5050;
      6'd8: partition3 = 32'haa550000;
      6'd9: partition3 = 32'haa555500;
      6'd10: partition3 = 32'haaaa5500;
      6'd11: partition3 = 32'h90909090;
      6'd12: partition3 = 32'h94949494;
      6'd13: partition3 = 32'ha4a4a4a4;
      6'd14: partition3 = 32'ha9a59450;
      6'd15: partition3 = 32'h2a0a4250;
      6'd16: partition3 = 32'ha5945040;
      6'd17: partition3 = 32'h0a425054;
      6'd18: partition3 = 32'ha5a5a500;
      6'd19: partition3 = 32'h55a0a0a0;
      6'd20: partition3 = 32'ha8a85454;
      6'd21: partition3 = 32'h6a6a4040;
      6'd22: partition3 = 32'ha4a45000;
      6'd23: partition3 = 32'h1a1a0500;
      6'd24: partition3 = 32'h0050a4a4;
      6'd25: partition3 = 32'haaa59090;
      6'd26: partition3 = 32'h14696914;
      6'd27: partition3 = 32'h69691400;
      6'd28: partition3 = 32'ha08585a0;
      6'd29: partition3 = 32'haa821414;
      6'd30: partition3 = 32'h50a4a450;
      6'd31: partition3 = 32'h6a5a0200;
      6'd32: partition3 = 32'ha9a58000;
      6'd33: partition3 = 32'h5090a0a8;
      6'd34: partition3 = 32'ha8a09050;
      6'd35: partition3 = 32'h24242424;
      6'd36: partition3 = 32'h00aa5500;
      6'd37: partition3 = 32'h24924924;
      6'd38: partition3 = 32'h24499224;
      6'd39: partition3 = 32'h50a50a50;
      6'd40: partition3 = 32'h500aa550;
      6'd41: partition3 = 32'haaaa4444;
      6'd42: partition3 = 32'h66660000;
      6'd43: partition3 = 32'ha5a0a5a0;
      6'd44: partition3 = 32'h50a050a0;
      6'd45: partition3 = 32'h69286928;
      6'd46: partition3 = 32'h44aaaa44;
      6'd47: partition3 = 32'h66666600;
      6'd48: partition3 = 32'haa444444;
      6'd49: partition3 = 32'h54a854a8;
      6'd50: partition3 = 32'h95809580;
      6'd51: partition3 = 32'h96969600;
      6'd52: partition3 = 32'ha85454a8;
      6'd53: partition3 = 32'h80959580;
      6'd54: partition3 = 32'haa141414;
      6'd55: partition3 = 32'h96960000;
      6'd56: partition3 = 32'haaaa1414;
      6'd57: partition3 = 32'ha05050a0;
      6'd58: partition3 = 32'ha0a5a5a0;
      6'd59: partition3 = 32'h96000000;
      6'd60: partition3 = 32'h40804080;
      6'd61: partition3 = 32'ha9a8a9a8;
      6'd62: partition3 = 32'haaaaaa44;
      6'd63: partition3 = 32'h2a4a5254;
      default: partition3 = '0;
    endcase
  endfunction
  // anchor2 (Table.A2: the anchor texel of subset 1 of 2)
  function automatic logic [3:0] anchor2(input logic [5:0] p);
    case (p)
      6'd0: anchor2 = 4'd15;
      6'd1: anchor2 = 4'd15;
      6'd2: anchor2 = 4'd15;
      6'd3: anchor2 = 4'd15;
      6'd4: anchor2 = 4'd15;
      6'd5: anchor2 = 4'd15;
      6'd6: anchor2 = 4'd15;
      6'd7: anchor2 = 4'd15;
      6'd8: anchor2 = 4'd15;
      6'd9: anchor2 = 4'd15;
      6'd10: anchor2 = 4'd15;
      6'd11: anchor2 = 4'd15;
      6'd12: anchor2 = 4'd15;
      6'd13: anchor2 = 4'd15;
      6'd14: anchor2 = 4'd15;
      6'd15: anchor2 = 4'd15;
      6'd16: anchor2 = 4'd15;
      6'd17: anchor2 = 4'd2;
      6'd18: anchor2 = 4'd8;
      6'd19: anchor2 = 4'd2;
      6'd20: anchor2 = 4'd2;
      6'd21: anchor2 = 4'd8;
      6'd22: anchor2 = 4'd8;
      6'd23: anchor2 = 4'd15;
      6'd24: anchor2 = 4'd2;
      6'd25: anchor2 = 4'd8;
      6'd26: anchor2 = 4'd2;
      6'd27: anchor2 = 4'd2;
      6'd28: anchor2 = 4'd8;
      6'd29: anchor2 = 4'd8;
      6'd30: anchor2 = 4'd2;
      6'd31: anchor2 = 4'd2;
      6'd32: anchor2 = 4'd15;
      6'd33: anchor2 = 4'd15;
      6'd34: anchor2 = 4'd6;
      6'd35: anchor2 = 4'd8;
      6'd36: anchor2 = 4'd2;
      6'd37: anchor2 = 4'd8;
      6'd38: anchor2 = 4'd15;
      6'd39: anchor2 = 4'd15;
      6'd40: anchor2 = 4'd2;
      6'd41: anchor2 = 4'd8;
      6'd42: anchor2 = 4'd2;
      6'd43: anchor2 = 4'd2;
      6'd44: anchor2 = 4'd2;
      6'd45: anchor2 = 4'd15;
      6'd46: anchor2 = 4'd15;
      6'd47: anchor2 = 4'd6;
      6'd48: anchor2 = 4'd6;
      6'd49: anchor2 = 4'd2;
      6'd50: anchor2 = 4'd6;
      6'd51: anchor2 = 4'd8;
      6'd52: anchor2 = 4'd15;
      6'd53: anchor2 = 4'd15;
      6'd54: anchor2 = 4'd2;
      6'd55: anchor2 = 4'd2;
      6'd56: anchor2 = 4'd15;
      6'd57: anchor2 = 4'd15;
      6'd58: anchor2 = 4'd15;
      6'd59: anchor2 = 4'd15;
      6'd60: anchor2 = 4'd15;
      6'd61: anchor2 = 4'd2;
      6'd62: anchor2 = 4'd2;
      6'd63: anchor2 = 4'd15;
      default: anchor2 = '0;
    endcase
  endfunction
  // anchor3a (Table.A3a: the anchor texel of subset 1 of 3)
  function automatic logic [3:0] anchor3a(input logic [5:0] p);
    case (p)
      6'd0: anchor3a = 4'd3;
      6'd1: anchor3a = 4'd3;
      6'd2: anchor3a = 4'd15;
      6'd3: anchor3a = 4'd15;
      6'd4: anchor3a = 4'd8;
      6'd5: anchor3a = 4'd3;
      6'd6: anchor3a = 4'd15;
      6'd7: anchor3a = 4'd15;
      6'd8: anchor3a = 4'd8;
      6'd9: anchor3a = 4'd8;
      6'd10: anchor3a = 4'd6;
      6'd11: anchor3a = 4'd6;
      6'd12: anchor3a = 4'd6;
      6'd13: anchor3a = 4'd5;
      6'd14: anchor3a = 4'd3;
      6'd15: anchor3a = 4'd3;
      6'd16: anchor3a = 4'd3;
      6'd17: anchor3a = 4'd3;
      6'd18: anchor3a = 4'd8;
      6'd19: anchor3a = 4'd15;
      6'd20: anchor3a = 4'd3;
      6'd21: anchor3a = 4'd3;
      6'd22: anchor3a = 4'd6;
      6'd23: anchor3a = 4'd10;
      6'd24: anchor3a = 4'd5;
      6'd25: anchor3a = 4'd8;
      6'd26: anchor3a = 4'd8;
      6'd27: anchor3a = 4'd6;
      6'd28: anchor3a = 4'd8;
      6'd29: anchor3a = 4'd5;
      6'd30: anchor3a = 4'd15;
      6'd31: anchor3a = 4'd15;
      6'd32: anchor3a = 4'd8;
      6'd33: anchor3a = 4'd15;
      6'd34: anchor3a = 4'd3;
      6'd35: anchor3a = 4'd5;
      6'd36: anchor3a = 4'd6;
      6'd37: anchor3a = 4'd10;
      6'd38: anchor3a = 4'd8;
      6'd39: anchor3a = 4'd15;
      6'd40: anchor3a = 4'd15;
      6'd41: anchor3a = 4'd3;
      6'd42: anchor3a = 4'd15;
      6'd43: anchor3a = 4'd5;
      6'd44: anchor3a = 4'd15;
      6'd45: anchor3a = 4'd15;
      6'd46: anchor3a = 4'd15;
      6'd47: anchor3a = 4'd15;
      6'd48: anchor3a = 4'd3;
      6'd49: anchor3a = 4'd15;
      6'd50: anchor3a = 4'd5;
      6'd51: anchor3a = 4'd5;
      6'd52: anchor3a = 4'd5;
      6'd53: anchor3a = 4'd8;
      6'd54: anchor3a = 4'd5;
      6'd55: anchor3a = 4'd10;
      6'd56: anchor3a = 4'd5;
      6'd57: anchor3a = 4'd10;
      6'd58: anchor3a = 4'd8;
      6'd59: anchor3a = 4'd13;
      6'd60: anchor3a = 4'd15;
      6'd61: anchor3a = 4'd12;
      6'd62: anchor3a = 4'd3;
      6'd63: anchor3a = 4'd3;
      default: anchor3a = '0;
    endcase
  endfunction
  // anchor3b (Table.A3b: the anchor texel of subset 2 of 3)
  function automatic logic [3:0] anchor3b(input logic [5:0] p);
    case (p)
      6'd0: anchor3b = 4'd15;
      6'd1: anchor3b = 4'd8;
      6'd2: anchor3b = 4'd8;
      6'd3: anchor3b = 4'd3;
      6'd4: anchor3b = 4'd15;
      6'd5: anchor3b = 4'd15;
      6'd6: anchor3b = 4'd3;
      6'd7: anchor3b = 4'd8;
      6'd8: anchor3b = 4'd15;
      6'd9: anchor3b = 4'd15;
      6'd10: anchor3b = 4'd15;
      6'd11: anchor3b = 4'd15;
      6'd12: anchor3b = 4'd15;
      6'd13: anchor3b = 4'd15;
      6'd14: anchor3b = 4'd15;
      6'd15: anchor3b = 4'd8;
      6'd16: anchor3b = 4'd15;
      6'd17: anchor3b = 4'd8;
      6'd18: anchor3b = 4'd15;
      6'd19: anchor3b = 4'd3;
      6'd20: anchor3b = 4'd15;
      6'd21: anchor3b = 4'd8;
      6'd22: anchor3b = 4'd15;
      6'd23: anchor3b = 4'd8;
      6'd24: anchor3b = 4'd3;
      6'd25: anchor3b = 4'd15;
      6'd26: anchor3b = 4'd6;
      6'd27: anchor3b = 4'd10;
      6'd28: anchor3b = 4'd15;
      6'd29: anchor3b = 4'd15;
      6'd30: anchor3b = 4'd10;
      6'd31: anchor3b = 4'd8;
      6'd32: anchor3b = 4'd15;
      6'd33: anchor3b = 4'd3;
      6'd34: anchor3b = 4'd15;
      6'd35: anchor3b = 4'd10;
      6'd36: anchor3b = 4'd10;
      6'd37: anchor3b = 4'd8;
      6'd38: anchor3b = 4'd9;
      6'd39: anchor3b = 4'd10;
      6'd40: anchor3b = 4'd6;
      6'd41: anchor3b = 4'd15;
      6'd42: anchor3b = 4'd8;
      6'd43: anchor3b = 4'd15;
      6'd44: anchor3b = 4'd3;
      6'd45: anchor3b = 4'd6;
      6'd46: anchor3b = 4'd6;
      6'd47: anchor3b = 4'd8;
      6'd48: anchor3b = 4'd15;
      6'd49: anchor3b = 4'd3;
      6'd50: anchor3b = 4'd15;
      6'd51: anchor3b = 4'd15;
      6'd52: anchor3b = 4'd15;
      6'd53: anchor3b = 4'd15;
      6'd54: anchor3b = 4'd15;
      6'd55: anchor3b = 4'd15;
      6'd56: anchor3b = 4'd15;
      6'd57: anchor3b = 4'd15;
      6'd58: anchor3b = 4'd15;
      6'd59: anchor3b = 4'd15;
      6'd60: anchor3b = 4'd3;
      6'd61: anchor3b = 4'd15;
      6'd62: anchor3b = 4'd15;
      6'd63: anchor3b = 4'd8;
      default: anchor3b = '0;
    endcase
  endfunction

  // Interpolation weights in 64ths of 2-, 3- and 4-bit indices.
  function automatic logic [6:0] weight(input logic [2:0] bits, input logic [3:0] i);
    logic [6:0] w;
    w = 7'd0;
    if (bits == 3'd2) begin
      case (i[1:0])
        2'd0: w = 7'd0;   2'd1: w = 7'd21;  2'd2: w = 7'd43;  default: w = 7'd64;
      endcase
    end else if (bits == 3'd3) begin
      case (i[2:0])
        3'd0: w = 7'd0;   3'd1: w = 7'd9;   3'd2: w = 7'd18;  3'd3: w = 7'd27;
        3'd4: w = 7'd37;  3'd5: w = 7'd46;  3'd6: w = 7'd55;  default: w = 7'd64;
      endcase
    end else begin
      case (i)
        4'd0: w = 7'd0;   4'd1: w = 7'd4;   4'd2: w = 7'd9;   4'd3: w = 7'd13;
        4'd4: w = 7'd17;  4'd5: w = 7'd21;  4'd6: w = 7'd26;  4'd7: w = 7'd30;
        4'd8: w = 7'd34;  4'd9: w = 7'd38;  4'd10: w = 7'd43; 4'd11: w = 7'd47;
        4'd12: w = 7'd51; 4'd13: w = 7'd55; 4'd14: w = 7'd60; default: w = 7'd64;
      endcase
    end
    weight = w;
  endfunction

  // Table.M for mode m (constant functions: for a constant m, Yosys and Verilator fold them, so
  // that each mode's fields are read at constant offsets): subsets, partition, rotation and
  // index-selection bits, colour and alpha bits, P-bits per endpoint or shared per subset, index
  // and secondary index bits; then where each field starts (the last ends at bit 128).
  function automatic int ns_of(input int m);  ns_of  = (m == 0 || m == 2) ? 3 : (m == 1 || m == 3 || m == 7) ? 2 : 1; endfunction
  function automatic int pb_of(input int m);  pb_of  = m == 0 ? 4 : (m == 1 || m == 2 || m == 3 || m == 7) ? 6 : 0; endfunction
  function automatic int rb_of(input int m);  rb_of  = (m == 4 || m == 5) ? 2 : 0; endfunction
  function automatic int isb_of(input int m); isb_of = m == 4 ? 1 : 0; endfunction
  function automatic int cb_of(input int m);  cb_of  = m == 0 ? 4 : m == 1 ? 6 : (m == 2 || m == 4 || m == 7) ? 5 : 7; endfunction
  function automatic int ab_of(input int m);  ab_of  = m == 4 ? 6 : m == 5 ? 8 : m == 6 ? 7 : m == 7 ? 5 : 0; endfunction
  function automatic int epb_of(input int m); epb_of = (m == 0 || m == 3 || m == 6 || m == 7) ? 1 : 0; endfunction
  function automatic int spb_of(input int m); spb_of = m == 1 ? 1 : 0; endfunction
  function automatic int ib_of(input int m);  ib_of  = (m == 0 || m == 1) ? 3 : m == 6 ? 4 : 2; endfunction
  function automatic int ib2_of(input int m); ib2_of = m == 4 ? 3 : m == 5 ? 2 : 0; endfunction
  function automatic int r_at_of(input int m);  r_at_of  = m + 1 + pb_of(m); endfunction
  function automatic int s_at_of(input int m);  s_at_of  = r_at_of(m) + rb_of(m); endfunction
  function automatic int c_at_of(input int m);  c_at_of  = s_at_of(m) + isb_of(m); endfunction
  function automatic int a_at_of(input int m);  a_at_of  = c_at_of(m) + 6 * ns_of(m) * cb_of(m); endfunction
  function automatic int ep_at_of(input int m); ep_at_of = a_at_of(m) + 2 * ns_of(m) * ab_of(m); endfunction
  function automatic int sp_at_of(input int m); sp_at_of = ep_at_of(m) + 2 * ns_of(m) * epb_of(m); endfunction
  function automatic int i_at_of(input int m);  i_at_of  = sp_at_of(m) + ns_of(m) * spb_of(m); endfunction
  function automatic int i2_at_of(input int m); i2_at_of = i_at_of(m) + 16 * ib_of(m) - ns_of(m); endfunction

  // bits (at most 8) of the block from bit `at`
  function automatic logic [7:0] field(input logic [127:0] block, input int at, input int bits);
    field = 8'(block >> at) & 8'((1 << bits) - 1);
  endfunction

  // Mode m's endpoint e of the texel's subset, unorm8 RGBA (alpha 255 in modes without it): each
  // field read at its constant offset for every subset, then the subset's kept (a select at a
  // variable offset would be a 128-bit shifter per field); (stored bits, P-bit) in the top bits,
  // then their top bits again below them.
  function automatic logic [31:0] endpoint(input int m, input int e, input logic [127:0] block, input logic [1:0] subset);
    logic [31:0] out;
    logic [23:0] raws;   // subset s's stored bits at [8s +: 8]
    logic [2:0]  pbits;  // and its P-bit
    logic [7:0]  raw, value;
    logic        pbit;
    int          stored, nb;
    int          c, s;  // (loop variables declared here: Yosys makes latches of `for (int ...)` ones in a
                        // function called under an `if`)
    out = '0;
    for (c = 0; c < 4; c++) begin
      stored = c < 3 ? cb_of(m) : ab_of(m);
      nb     = stored + epb_of(m) + spb_of(m);
      for (s = 0; s < 3; s++) begin
        raws  = {s < ns_of(m) ? (c < 3 ? field(block, c_at_of(m) + ((c * ns_of(m) + s) * 2 + e) * cb_of(m), cb_of(m))
                                       : field(block, a_at_of(m) + (s * 2 + e) * ab_of(m), ab_of(m)))
                              : 8'd0, raws[23:8]};
        pbits = {s < ns_of(m) && epb_of(m) > 0 ? block[ep_at_of(m) + 2 * s + e]
                 : s < ns_of(m) && spb_of(m) > 0 ? block[sp_at_of(m) + s] : 1'b0, pbits[2:1]};
      end
      raw   = 8'(raws >> (8 * subset));
      pbit  = pbits[subset];
      value = epb_of(m) + spb_of(m) > 0 ? 8'({raw, pbit} << (8 - nb)) : 8'(raw << (8 - nb));
      // (channel c ends at bits 8c..: no write at a variable index, which a function that is not
      // inlined cannot have in Verilator)
      out = {stored == 0 ? 8'd255 : value | 8'(value >> nb), out[31:8]};
    end
    endpoint = out;
  endfunction

  function automatic logic [31:0] rgba(input logic [127:0] block, input logic [3:0] texel);
    /*verilator no_inline_task*/  // (one C++ function for the 8 taps' decoders)
    logic [2:0]  mode;
    logic [1:0]  subsets;         // of the mode: 1..3
    logic [5:0]  part;
    logic [15:0] p2;
    logic [31:0] p3;
    logic [1:0]  subset, earlier;
    logic [3:0]  anchor_1, anchor_2;
    logic        is_anchor;
    // The block's mode's reading for this texel.
    logic [31:0] e0, e1;          // unorm8 RGBA endpoints of the texel's subset
    logic [6:0]  index_at, index2_at;
    logic [3:0]  index_mask, index2_mask;
    logic [2:0]  ibits, ib2bits;
    logic        sel;             // colour from the secondary index (mode 4)
    logic [1:0]  rot;             // swap A with nothing, R, G or B (modes 4, 5)
    logic [3:0]  index, index2;   // this texel's, from the one shifter
    logic [6:0]  wc, wa, w;       // weights of e1 in 64ths: colour, alpha, this channel
    logic signed [8:0]  diff;     // e1 - e0
    logic signed [16:0] sum;      // 64 e0 + (e1 - e0) w + 32, in [0, 64 * 255 + 32]
    logic [31:0] mixed, out;

    mode = 3'd0;
    for (int m = 7; m >= 0; m--)
      if (block[m]) mode = 3'(m);
    case (mode)
      3'd0:    begin subsets = 2'd3; part = {2'd0, block[4:1]}; end
      3'd1:    begin subsets = 2'd2; part = block[7:2];         end
      3'd2:    begin subsets = 2'd3; part = block[8:3];         end
      3'd3:    begin subsets = 2'd2; part = block[9:4];         end
      3'd7:    begin subsets = 2'd2; part = block[13:8];        end
      default: begin subsets = 2'd1; part = 6'd0;               end
    endcase
    p2        = partition2(part);
    p3        = partition3(part);
    subset    = subsets == 2'd1 ? 2'd0 : subsets == 2'd2 ? {1'b0, p2[texel]} : p3[2 * texel +: 2];
    anchor_1  = subsets == 2'd2 ? anchor2(part) : anchor3a(part);
    anchor_2  = anchor3b(part);
    is_anchor = texel == 4'd0 || (subsets != 2'd1 && texel == anchor_1) || (subsets == 2'd3 && texel == anchor_2);
    earlier   = 2'(subsets != 2'd1 && anchor_1 < texel) + 2'(subsets == 2'd3 && anchor_2 < texel);

    // The endpoints: each mode's read at its constant offsets, only the block's mode's kept (and,
    // in a simulator, computed). Texel t's index starts ib t bits in, less one per earlier anchor
    // (texel 0 is subset 0's); an anchor texel's index has one bit less.
    // (each mode spelt out, so that m is a constant at every call and a simulator folds the
    // table's offsets as synthesis does)
    case (mode)
      3'd0:    begin e0 = endpoint(0, 0, block, subset); e1 = endpoint(0, 1, block, subset); end
      3'd1:    begin e0 = endpoint(1, 0, block, subset); e1 = endpoint(1, 1, block, subset); end
      3'd2:    begin e0 = endpoint(2, 0, block, subset); e1 = endpoint(2, 1, block, subset); end
      3'd3:    begin e0 = endpoint(3, 0, block, subset); e1 = endpoint(3, 1, block, subset); end
      3'd4:    begin e0 = endpoint(4, 0, block, subset); e1 = endpoint(4, 1, block, subset); end
      3'd5:    begin e0 = endpoint(5, 0, block, subset); e1 = endpoint(5, 1, block, subset); end
      3'd6:    begin e0 = endpoint(6, 0, block, subset); e1 = endpoint(6, 1, block, subset); end
      default: begin e0 = endpoint(7, 0, block, subset); e1 = endpoint(7, 1, block, subset); end
    endcase
    ibits       = 3'(ib_of(32'(mode)));
    ib2bits     = 3'(ib2_of(32'(mode)));
    index_at    = 7'(i_at_of(32'(mode)) + 32'(texel) * ib_of(32'(mode)) - 32'(texel != 4'd0) - 32'(earlier));
    index2_at   = 7'(i2_at_of(32'(mode)) + 32'(texel) * ib2_of(32'(mode)) - 32'(texel != 4'd0));
    index_mask  = 4'((1 << (is_anchor ? ibits - 3'd1 : ibits)) - 1);
    index2_mask = ib2bits == 3'd0 ? 4'd0 : 4'((1 << (texel == 4'd0 ? ib2bits - 3'd1 : ib2bits)) - 1);
    sel         = isb_of(32'(mode)) > 0 ? block[s_at_of(32'(mode))] : 1'b0;
    rot         = rb_of(32'(mode)) > 0 ? 2'(block >> r_at_of(32'(mode))) : 2'd0;

    index  = 4'(block >> index_at) & index_mask;
    index2 = 4'(block >> index2_at) & index2_mask;
    // Colour from the secondary index when the selection bit is 1; alpha from it when there is one
    // and the bit is 0.
    wc = (ib2bits != 3'd0 && sel) ? weight(ib2bits, index2) : weight(ibits, index);
    wa = (ib2bits != 3'd0 && !sel) ? weight(ib2bits, index2) : weight(ibits, index);
    mixed = '0;
    for (int c = 0; c < 4; c++) begin
      // ((64 - w) e0 + w e1 + 32) >> 6 with one multiply: (64 e0 + w (e1 - e0) + 32) >> 6.
      w    = c < 3 ? wc : wa;
      diff = $signed({1'b0, e1[8 * c +: 8]}) - $signed({1'b0, e0[8 * c +: 8]});
      sum  = $signed({3'd0, e0[8 * c +: 8], 6'd0}) + diff * $signed({1'b0, w}) + 17'sd32;
      mixed = {8'(sum >>> 6), mixed[31:8]};
    end
    out = mixed;
    case (rot)
      2'd1: begin out[7:0] = mixed[31:24];   out[31:24] = mixed[7:0];   end
      2'd2: begin out[15:8] = mixed[31:24];  out[31:24] = mixed[15:8];  end
      2'd3: begin out[23:16] = mixed[31:24]; out[31:24] = mixed[23:16]; end
      default: ;
    endcase
    rgba = block[7:0] == 8'd0 ? 32'd0 : out;
  endfunction
endpackage

// tex_bc7_mode: the fields of a BC7 block read as mode MODE (ARB_texture_compression_bptc
// Table.M; docs/numerics.md "Block-compressed formats"), for one texel: the two endpoints of its
// subset widened to 8 bits (stored bits, then the P-bit, then the top bits replicated), and its
// colour and alpha weights in 64ths from its indices (an anchor texel's index has one bit less).
// tex_bc7 has one per mode and keeps the one the block's mode selects.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   block    : the 128-bit block, byte i at bits 8i+7..8i (little-endian, as memory holds it)
//   texel    : 0..15, x + 4 y inside the block
//   e0, e1   : unorm8 RGBA endpoints (R in bits 7..0, A in 31..24); alpha 255 in modes without it
//   colour_w : weight of e1 for R, G, B in 64ths, 0..64
//   alpha_w  : weight of e1 for A in 64ths, 0..64
//   rotation : 0..3 (modes 4, 5): swap A with nothing, R, G or B after the interpolation
module tex_bc7_mode #(
  parameter int MODE = 0
) (
  input  logic [127:0] block,
  input  logic [3:0]   texel,
  output logic [31:0]  e0,
  output logic [31:0]  e1,
  output logic [6:0]   colour_w,
  output logic [6:0]   alpha_w,
  output logic [1:0]   rotation
);
  // Table.M: subsets, partition, rotation and index-selection bits, colour and alpha bits,
  // P-bits per endpoint or shared per subset, index bits and secondary index bits.
  localparam int NS  = (MODE == 0 || MODE == 2) ? 3 : (MODE == 1 || MODE == 3 || MODE == 7) ? 2 : 1;
  localparam int PB  = MODE == 0 ? 4 : (MODE == 1 || MODE == 2 || MODE == 3 || MODE == 7) ? 6 : 0;
  localparam int RB  = (MODE == 4 || MODE == 5) ? 2 : 0;
  localparam int ISB = MODE == 4 ? 1 : 0;
  localparam int CB  = MODE == 0 ? 4 : MODE == 1 ? 6 : (MODE == 2 || MODE == 4 || MODE == 7) ? 5 : 7;
  localparam int AB  = MODE == 4 ? 6 : MODE == 5 ? 8 : MODE == 6 ? 7 : MODE == 7 ? 5 : 0;
  localparam int EPB = (MODE == 0 || MODE == 3 || MODE == 6 || MODE == 7) ? 1 : 0;
  localparam int SPB = MODE == 1 ? 1 : 0;
  localparam int IB  = (MODE == 0 || MODE == 1) ? 3 : MODE == 6 ? 4 : 2;
  localparam int IB2 = MODE == 4 ? 3 : MODE == 5 ? 2 : 0;
  // Where each field starts: mode, partition, rotation, index selection, colour, alpha, P-bits,
  // indices, secondary indices (the last ends at bit 128).
  localparam int P_AT  = MODE + 1;
  localparam int R_AT  = P_AT + PB;
  localparam int S_AT  = R_AT + RB;
  localparam int C_AT  = S_AT + ISB;
  localparam int A_AT  = C_AT + 6 * NS * CB;
  localparam int EP_AT = A_AT + 2 * NS * AB;
  localparam int SP_AT = EP_AT + 2 * NS * EPB;
  localparam int I_AT  = SP_AT + NS * SPB;
  localparam int I2_AT = I_AT + 16 * IB - NS;
  localparam int NBC   = CB + EPB + SPB;  // bits of a colour channel with its P-bit
  localparam int NBA   = AB + EPB + SPB;  // of alpha (modes with alpha)
  // Zero-width fields read one bit, and the value is not used.
  localparam int PBW = PB > 0 ? PB : 1;
  localparam int ABW = AB > 0 ? AB : 1;
  localparam int IB2W = IB2 > 0 ? IB2 : 1;
  // Index masks: an anchor texel's index has one bit less.
  localparam logic [3:0] MASK    = 4'((1 << IB) - 1);
  localparam logic [3:0] MASK_A  = 4'((1 << (IB - 1)) - 1);
  localparam logic [3:0] MASK2   = 4'((1 << IB2W) - 1);
  localparam logic [3:0] MASK2_A = 4'((1 << (IB2W - 1)) - 1);

  // Elaboration-time checks (Icarus 11 has no elaboration-time $error).
  generate
    if (MODE < 0 || MODE > 7) begin : g_bad_mode
`ifdef __ICARUS__
      initial $fatal(1, "tex_bc7_mode: parameter MODE must be in 0..7");
`else
      $error("tex_bc7_mode: parameter MODE must be in 0..7");
`endif
    end
    if (I2_AT + 16 * IB2 - (IB2 > 0 ? 1 : 0) != 128) begin : g_bad_fields
`ifdef __ICARUS__
      initial $fatal(1, "tex_bc7_mode: the fields of a mode must end at bit 128 (Table.M)");
`else
      $error("tex_bc7_mode: the fields of a mode must end at bit 128 (Table.M)");
`endif
    end
  endgenerate

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
  function automatic logic [6:0] weight(input int bits, input logic [3:0] i);
    logic [6:0] w;
    w = 7'd0;
    if (bits == 2) begin
      case (i[1:0])
        2'd0: w = 7'd0;   2'd1: w = 7'd21;  2'd2: w = 7'd43;  default: w = 7'd64;
      endcase
    end else if (bits == 3) begin
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

  logic [5:0]   part;              // partition number
  logic [15:0]  p2;
  logic [31:0]  p3;
  logic [1:0]   subset;            // of this texel
  logic [3:0]   anchor_1, anchor_2;  // anchor texels of subsets 1 and 2
  logic         is_anchor;
  logic [1:0]   earlier;            // anchors of subsets 1, 2 before this texel
  logic [6:0]   at, at2;           // this texel's index and secondary index start
  logic [3:0]   bits, bits2;      // the 4 bits from this texel's index and secondary index on
  logic [3:0]   index, index2;
  logic         select;            // index selection bit (mode 4)
  assign part      = PB > 0 ? 6'(block[P_AT +: PBW]) : 6'd0;
  assign p2        = partition2(part);
  assign p3        = partition3(part);
  assign subset    = NS == 1 ? 2'd0 : NS == 2 ? {1'b0, p2[texel]} : p3[2 * texel +: 2];
  assign anchor_1  = NS == 2 ? anchor2(part) : anchor3a(part);
  assign anchor_2  = anchor3b(part);
  assign is_anchor = texel == 4'd0 || (NS >= 2 && texel == anchor_1) || (NS == 3 && texel == anchor_2);
  assign earlier   = 2'(NS >= 2 && anchor_1 < texel) + 2'(NS == 3 && anchor_2 < texel);
  // Texel t's index starts IB t bits in, less one per earlier anchor (texel 0 is subset 0's).
  assign at        = 7'(I_AT) + 7'(texel) * 7'(IB) - 7'(texel != 4'd0) - 7'(earlier);
  assign at2       = 7'(I2_AT) + 7'(texel) * 7'(IB2W) - 7'(texel != 4'd0);
  assign bits      = 4'(block >> at);
  assign bits2     = 4'(block >> at2);
  assign index     = bits & (is_anchor ? MASK_A : MASK);
  assign index2    = bits2 & (texel == 4'd0 ? MASK2_A : MASK2);
  assign select    = ISB > 0 ? block[S_AT] : 1'b0;
  assign rotation  = RB > 0 ? block[R_AT +: 2] : 2'd0;
  // Colour from the secondary indices when the selection bit is 1; alpha from them when they
  // exist and the bit is 0.
  assign colour_w  = (IB2 > 0 && select) ? weight(IB2, index2) : weight(IB, index);
  assign alpha_w   = (IB2 > 0 && !select) ? weight(IB2, index2) : weight(IB, index);

  generate
    for (genvar e = 0; e < 2; e++) begin : g_endpoint
      logic pbit;
      logic [31:0] rgba;
      if (EPB > 0) begin : g_own
        assign pbit = block[EP_AT + 2 * 32'(subset) + e];
      end else if (SPB > 0) begin : g_shared
        assign pbit = block[SP_AT + 32'(subset)];
      end else begin : g_none
        assign pbit = 1'b0;
      end
      for (genvar c = 0; c < 4; c++) begin : g_channel
        localparam int STORED = c < 3 ? CB : AB;
        localparam int NB     = c < 3 ? NBC : NBA;
        localparam int SW     = STORED > 0 ? STORED : 1;
        logic [SW-1:0] raw;
        logic [7:0]    value, top;
        if (c < 3) begin : g_colour
          assign raw = block[C_AT + ((c * NS + 32'(subset)) * 2 + e) * CB +: SW];
        end else begin : g_alpha
          assign raw = block[A_AT + (32'(subset) * 2 + e) * ABW +: SW];
        end
        // (raw, P-bit) in the top NB bits, then its top bits again below them.
        assign value = (EPB + SPB > 0) ? 8'({raw, pbit}) << (8 - NB) : 8'(raw) << (8 - NB);
        assign top   = value >> NB;
        assign rgba[8 * c +: 8] = STORED == 0 ? 8'd255 : (value | top);
      end
      if (e == 0) begin : g_e0
        assign e0 = rgba;
      end else begin : g_e1
        assign e1 = rgba;
      end
    end
  endgenerate
endmodule

// tex_bc7_mode: the fields of a BC7 block read as mode MODE (ARB_texture_compression_bptc
// Table.M; docs/numerics.md "Block-compressed formats"), for one texel: the two endpoints of its
// subset widened to 8 bits (stored bits, then the P-bit, then the top bits replicated), and where
// its indices are (an anchor texel's index has one bit less). tex_bc7 has one per mode, keeps the
// one the block's mode selects and reads the indices there: one shifter for all modes.
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports:
//   block    : the 128-bit block, byte i at bits 8i+7..8i (little-endian, as memory holds it)
//   texel    : 0..15, x + 4 y inside the block
//   subset, is_anchor, earlier : the texel's subset (0..2), whether it is its subset's anchor, and
//              the anchors of subsets 1 and 2 before it (0..2), from the block's partition (tex_bc7
//              reads the partition tables once for all modes)
//   e0, e1   : unorm8 RGBA endpoints (R in bits 7..0, A in 31..24); alpha 255 in modes without it
//   index_at, index_mask   : the texel's index is (block >> index_at) & index_mask (7 and 4 bits)
//   index2_at, index2_mask : its secondary index likewise (mask 0 in modes without one)
//   index_bits, index2_bits: bits of an index and a secondary index in this mode (2..4; 0: none)
//   select   : the index selection bit (mode 4): colour from the secondary index
//   rotation : 0..3 (modes 4, 5): swap A with nothing, R, G or B after the interpolation
`include "tex_param_error.svh"
module tex_bc7_mode #(
  parameter int MODE = 0
) (
  input  logic [127:0] block,
  input  logic [3:0]   texel,
  input  logic [1:0]   subset,
  input  logic         is_anchor,
  input  logic [1:0]   earlier,
  output logic [31:0]  e0,
  output logic [31:0]  e1,
  output logic [6:0]   index_at,
  output logic [3:0]   index_mask,
  output logic [6:0]   index2_at,
  output logic [3:0]   index2_mask,
  output logic [2:0]   index_bits,
  output logic [2:0]   index2_bits,
  output logic         select,
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
      `TEX_PARAM_ERROR("tex_bc7_mode: parameter MODE must be in 0..7")
    end
    if (I2_AT + 16 * IB2 - (IB2 > 0 ? 1 : 0) != 128) begin : g_bad_fields
      `TEX_PARAM_ERROR("tex_bc7_mode: the fields of a mode must end at bit 128 (Table.M)")
    end
  endgenerate



  // Texel t's index starts IB t bits in, less one per earlier anchor (texel 0 is subset 0's).
  assign index_at    = 7'(I_AT) + 7'(texel) * 7'(IB) - 7'(texel != 4'd0) - 7'(earlier);
  assign index2_at   = 7'(I2_AT) + 7'(texel) * 7'(IB2W) - 7'(texel != 4'd0);
  assign index_mask  = is_anchor ? MASK_A : MASK;
  assign index2_mask = IB2 == 0 ? 4'd0 : texel == 4'd0 ? MASK2_A : MASK2;
  assign index_bits  = 3'(IB);
  assign index2_bits = 3'(IB2);
  assign select      = ISB > 0 ? block[S_AT] : 1'b0;
  assign rotation    = RB > 0 ? block[R_AT +: 2] : 2'd0;

  generate
    // Each field is read at its constant offset for every subset, then the texel's subset picked
    // (a select of a variable offset would be a 128-bit shifter per field).
    for (genvar e = 0; e < 2; e++) begin : g_endpoint
      logic [2:0]  pbits;  // per subset
      logic        pbit;
      logic [31:0] rgba;
      for (genvar s = 0; s < 3; s++) begin : g_pbit
        if (s >= NS) begin : g_absent
          assign pbits[s] = 1'b0;
        end else if (EPB > 0) begin : g_own
          assign pbits[s] = block[EP_AT + 2 * s + e];
        end else if (SPB > 0) begin : g_shared
          assign pbits[s] = block[SP_AT + s];
        end else begin : g_none
          assign pbits[s] = 1'b0;
        end
      end
      assign pbit = pbits[subset];
      for (genvar c = 0; c < 4; c++) begin : g_channel
        localparam int STORED = c < 3 ? CB : AB;
        localparam int NB     = c < 3 ? NBC : NBA;
        localparam int SW     = STORED > 0 ? STORED : 1;
        logic [3*SW-1:0] fields;  // subset s at [s * SW +: SW]
        logic [SW-1:0]   raw;
        logic [7:0]      value, top;
        for (genvar s = 0; s < 3; s++) begin : g_subset
          if (s >= NS) begin : g_absent
            assign fields[s * SW +: SW] = '0;
          end else if (c < 3) begin : g_colour
            assign fields[s * SW +: SW] = block[C_AT + ((c * NS + s) * 2 + e) * CB +: SW];
          end else begin : g_alpha
            assign fields[s * SW +: SW] = block[A_AT + (s * 2 + e) * ABW +: SW];
          end
        end
        assign raw = fields[32'(subset) * SW +: SW];
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

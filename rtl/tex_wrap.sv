// tex_wrap: the model's `wrap` stage (docs/numerics.md stage 3): the address mode of one integer
// texel index, n = 2^log2_n, given as its mask n - 1.
//   repeat: i & (n-1)   clamp: min(max(i, 0), n-1)   mirror: m = i & (2n-1); m < n ? m : 2n-1-m
//   border: i & (n-1), and border = (i < 0 || i >= n): the tap takes the border colour
//   mirror-clamp: min(i < 0 ? -1-i : i, n-1) (mirrored once about 0, then clamped)
//   (the unused codes 5..7 give 0). n = 1 maps every index to 0 (border: every index but 0 is
//   the border). No carry chain: the mask comes registered (tex_front, clock 4), n is one bit past
//   it, -1-i is ~i.
// Handshake: none (combinational; tex_unit clock 5). Latency: 0. Throughput: 1 per clock.
// Ports:
//   i      : signed IW bits, unwrapped integer texel index
//   mask   : unsigned IW bits, n - 1 (ones below bit log2_n; n must fit OUT_W bits)
//   mode   : tex_pkg::WRAP_*
//   o      : unsigned OUT_W bits, wrapped index in [0, n)
//   border : 1 bit, the tap is outside the level in mode border (o is then the repeat index, a
//            word the memories hold, never read as a texel)
module tex_wrap #(
  parameter int OUT_W = tex_pkg::COORD_W,
  parameter int IW    = tex_pkg::INDEX_W   // from tex_address
) (
  input  logic signed [IW-1:0]               i,
  input  logic [IW-1:0]                      mask,
  input  logic [tex_pkg::WRAP_W-1:0]         mode,
  output logic [OUT_W-1:0]                   o,
  output logic                               border
);
  logic [IW-1:0]    n;                // 2^log2_n: the lowest bit that is not in the mask
  logic [IW-1:0]    folded;           // i, or -1-i = ~i below 0 (mirror clamp)
  logic [OUT_W-1:0] mask_o, low;      // n - 1 and i & (n - 1), in the output width
  logic             negative, beyond, odd_period, folded_beyond;
  assign n             = ~mask & {mask[IW-2:0], 1'b1};
  assign mask_o        = OUT_W'(mask);
  assign low           = OUT_W'(i) & mask_o;
  assign negative      = i[IW-1];
  assign beyond        = |(i & ~mask);         // i >= n, for non-negative i
  assign odd_period    = |(i & n);             // m >= n: the mirrored half of the period 2n
  assign folded        = negative ? ~i : i;
  assign folded_beyond = |(folded & ~mask);
  always_comb begin
    border = 1'b0;
    case (mode)
      tex_pkg::WRAP_REPEAT:       o = low;
      tex_pkg::WRAP_CLAMP:        o = negative ? '0 : (beyond ? mask_o : low);
      tex_pkg::WRAP_MIRROR:       o = odd_period ? (~low & mask_o) : low;  // 2n-1-m = ~m in lw bits
      tex_pkg::WRAP_BORDER: begin
        o      = low;
        border = negative || beyond;
      end
      tex_pkg::WRAP_MIRROR_CLAMP: o = folded_beyond ? mask_o : OUT_W'(folded);
      default:                    o = '0;
    endcase
  end
endmodule

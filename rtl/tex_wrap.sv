// tex_wrap: the model's `wrap` stage (docs/numerics.md stage 3): the address mode of one integer
// texel index on a side of n texels (any size 1..2^ML), for an index of a reduced coordinate
// (tex_reduce: repeat indices lie in [-1, n], mirror in [-1, 2n], the clamping modes in
// [-2n-1, 2n]), so compares replace the modulo:
//   repeat: i < 0 ? n-1 : i; the second tap (SECOND = 1) of the seam, i = 0 or n: 0 on a
//           power-of-two side (pow2), else n (texel 0's copy stored after the last texel, so that
//           the pair n-1, copy sits in two parity banks)
//   clamp: min(max(i, 0), n-1)      mirror: m = i < 0 ? -1-i : i; m < n ? m : max(2n-1-m, 0)
//   border: min(max(i, 0), n-1), and border = (i < 0 || i >= n): the tap takes the border colour
//   mirror-clamp: min(i < 0 ? -1-i : i, n-1)     (the unused code 7 gives 0)
//   skirt (internal: a cube face, stored with a one-texel skirt, face texel i at i + 1; the model's
//          stage::cube_taps): the first tap min(i, n-1) + 1 (a linear filter's i in -1..n-1, a
//          nearest filter's in 0..n clamped to the face), the second i + 1 (0..n+1); skirt-border
//          (a cube face's texel fetch): border's, then + 1
// Handshake: none (combinational; tex_unit clock 5). Latency: 0. Throughput: 1 per clock.
// Ports:
//   i      : signed IW bits, unwrapped integer texel index (tex_address)
//   n      : unsigned NB bits, the level's side, 1..2^(NB-1) (registered, tex_front clock 4)
//   pow2   : the side has no seam copy: n is a power of two (and the cached unit's block footprint
//            asks none; tex_front, registered beside n)
//   mode   : tex_pkg::WRAP_*
//   o      : unsigned OUT_W bits, the wrapped index: [0, n), or n at a repeat seam (skirt: 0..n+1)
//   border : 1 bit, the tap is outside the level in mode border (o is then a don't-care index
//            inside the level, never read as a texel)
module tex_wrap #(
  parameter int OUT_W  = tex_pkg::COORD_W,
  parameter int IW     = tex_pkg::MAX_LOG2_SIZE + 4,  // from tex_address
  parameter int NB     = tex_pkg::SIZE_W,             // bits of a size: the unit's largest log2 + 1
  parameter bit SECOND = 1'b0                         // the second tap of a pair (i0 + 1)
) (
  input  logic signed [IW-1:0]               i,
  input  logic [NB-1:0]                      n,
  input  logic                               pow2,
  input  logic [tex_pkg::WRAP_W-1:0]         mode,
  output logic [OUT_W-1:0]                   o,
  output logic                               border
);
  localparam int XW = IW + 1;  // signed room for n, 2n and 2n-1-m
  logic signed [XW-1:0] ix, nx, folded, mirrored;
  logic                 negative, beyond, folded_beyond;
  assign ix            = XW'(i);
  assign nx            = XW'($signed({1'b0, n}));
  assign negative      = i[IW-1];
  assign beyond        = ix >= nx;                     // i >= n
  assign folded        = negative ? ~ix : ix;          // -1-i below 0
  assign folded_beyond = folded >= nx;
  assign mirrored      = folded_beyond ? (nx + nx - XW'(1) - folded) : folded;
  always_comb begin
    border = 1'b0;
    case (mode)
      tex_pkg::WRAP_REPEAT:
        if (SECOND) o = (i == '0 || beyond) ? (pow2 ? '0 : OUT_W'(n)) : OUT_W'(i);
        else        o = negative ? OUT_W'(n - 1'b1) : OUT_W'(i);
      tex_pkg::WRAP_CLAMP:        o = negative ? '0 : (beyond ? OUT_W'(n - 1'b1) : OUT_W'(i));
      tex_pkg::WRAP_MIRROR:       o = mirrored[XW-1] ? '0 : OUT_W'(mirrored);
      tex_pkg::WRAP_BORDER: begin
        o      = negative ? '0 : (beyond ? OUT_W'(n - 1'b1) : OUT_W'(i));
        border = negative || beyond;
      end
      tex_pkg::WRAP_MIRROR_CLAMP: o = folded_beyond ? OUT_W'(n - 1'b1) : OUT_W'(folded);
      tex_pkg::WRAP_SKIRT:
        if (SECOND) o = OUT_W'(ix + XW'(1));
        else        o = beyond ? OUT_W'(n) : OUT_W'(ix + XW'(1));
      tex_pkg::WRAP_SKIRT_BORDER: begin
        o      = negative ? OUT_W'(1) : (beyond ? OUT_W'(n) : OUT_W'(ix + XW'(1)));
        border = negative || beyond;
      end
      default:                    o = '0;
    endcase
  end
endmodule

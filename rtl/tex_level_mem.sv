// tex_level_mem: stage 4 of docs/numerics.md: the memory of one mip level, split into 4 banks by
// texel parity, bank b = (y & 1) * 2 + (x & 1), word (y >> 1) * 2^(XB-1) + (x >> 1) (fixed stride
// of the largest texture this level can hold: 2^XB x 2^YB texels). A 2x2 footprint after wrap has
// x taps that are equal or of different parity (likewise y), so each bank serves at most one word:
// the whole footprint is read in one clock.
// Handshake: none. Write: one texel per clock when we (ignored outside 2^XB x 2^YB).
//   Read: the 4 banks read at the clock edge when re is high and hold their data otherwise.
// Latency: 1 clock (x0..y1 -> rdata). Throughput: one 2x2 footprint per clock, plus 1 write.
// Ports:
//   wx, wy        : unsigned COORD_W bits, texel coordinate of the write in this level
//   wdata         : 4*CW bits, texel {A, B, G, R}
//   x0, x1, y0, y1: unsigned, wrapped texel indices of the footprint (x1 = x0 or other parity)
//   rdata         : 4 texels, bank b in [b*DW +: DW]; banks outside the level read as 0
module tex_level_mem #(
  parameter int XB = 4,  // log2 of the largest width at this level (0: one texel wide)
  parameter int YB = 4,
  parameter int DW = 32,
  parameter int XO = (XB > 0) ? XB : 1,  // read-port widths (a 1-texel side still has bit 0);
  parameter int YO = (YB > 0) ? YB : 1   // derived, do not override
) (
  input  logic                         clk,
  input  logic                         we,
  input  logic [tex_pkg::COORD_W-1:0]  wx,
  input  logic [tex_pkg::COORD_W-1:0]  wy,
  input  logic [DW-1:0]                wdata,
  input  logic                         re,
  input  logic [XO-1:0]                x0,
  input  logic [XO-1:0]                x1,
  input  logic [YO-1:0]                y0,
  input  logic [YO-1:0]                y1,
  output logic [4*DW-1:0]              rdata
);
  localparam int BX = (XB > 1) ? XB - 1 : 0;  // word-address bits from x >> 1
  localparam int BY = (YB > 1) ? YB - 1 : 0;
  localparam int AW = (BX + BY > 0) ? BX + BY : 1;
  localparam int DEPTH = 1 << (BX + BY);

  logic in_range;
  assign in_range = ((wx >> XB) == '0) && ((wy >> YB) == '0);

  // Word address of texel (x, y) in its bank: {y >> 1, x >> 1}.

  genvar b;
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_bank
      localparam logic PX = b[0];
      localparam logic PY = b[1];
      if ((PX && XB == 0) || (PY && YB == 0)) begin : g_absent
        // A 1-texel side has no odd texels: this bank would never be written.
        assign rdata[b*DW +: DW] = '0;
      end else begin : g_present
        logic [XO-1:0] xs;  // the tap whose x parity is PX (either tap if both are equal)
        logic [YO-1:0] ys;
        logic [AW-1:0] raddr_b, waddr_b;
        assign xs = (x0[0] == PX) ? x0 : x1;
        assign ys = (y0[0] == PY) ? y0 : y1;
        // Bit 0 is the bank's parity: it steers (above) but is not part of the word address.
        logic parity_bits_unused;
        assign parity_bits_unused = ^{xs[0], ys[0]};
        if (BX > 0 && BY > 0) begin : g_xy
          assign raddr_b = {ys[YO-1:1], xs[XO-1:1]};
          assign waddr_b = {wy[YB-1:1], wx[XB-1:1]};
        end else if (BX > 0) begin : g_x
          assign raddr_b = xs[XO-1:1];
          assign waddr_b = wx[XB-1:1];
        end else if (BY > 0) begin : g_y
          assign raddr_b = ys[YO-1:1];
          assign waddr_b = wy[YB-1:1];
        end else begin : g_one
          assign raddr_b = '0;
          assign waddr_b = '0;
        end
        tex_bank #(.AW(AW), .DEPTH(DEPTH), .DW(DW)) u_bank (
          .clk  (clk),
          .we   (we && in_range && wx[0] == PX && wy[0] == PY),
          .waddr(waddr_b),
          .wdata(wdata),
          .re   (re),
          .raddr(raddr_b),
          .rdata(rdata[b*DW +: DW])
        );
      end
    end
  endgenerate
endmodule

// tex_bank: one parity bank of one level memory (part of the model's `fetch` stage): the texels
// (x, y) of mip level LEVEL with (y & 1) * 2 + (x & 1) = PARITY, of a level at most 2^XB x 2^YB
// texels, in a simple dual-port RAM with a synchronous read (BRAM style).
// Layout: texel (x, y) is word (y >> 1) * 2^(XB-1) + (x >> 1) of the unpacked array `mem`
// (stride 1 when XB <= 1), a fixed stride of the largest texture the level can hold; a smaller
// runtime texture uses the low corner. `mem`, LEVEL and PARITY are public in Verilator
// (rtl/tex_unit.vlt) for the C++ backdoor load.
// Handshake: none. Write: at the clock edge when we (the write strobe, shared by every bank) and
//   the texel (wx, wy) of level wlevel belongs here (wlevel = LEVEL, parity = PARITY, inside
//   2^XB x 2^YB); the decode is inside this process so that Verilator tests the strobe once for
//   all banks and decodes only on a write. Read: rdata <= mem[raddr] at the clock edge when re
//   (the read strobe: the pipeline enable, shared by every bank) and rsel (this bank's level is
//   read), held otherwise (a stalled pipeline keeps its read data); again two ports, so that the
//   strobe is tested once in Verilator's C++. A read of the word written at the same edge returns
//   the old data.
// Latency: 1 clock (raddr -> rdata). Throughput: 1 read and 1 write per clock.
// Ports:
//   wlevel         : integer, the level of the written texel
//   wx, wy         : unsigned COORD_W bits, the written texel's coordinate in its level
//   wdata, rdata   : DW bits, a texel {A, B, G, R} (opaque here)
//   raddr          : AW-bit word address, AW = max(XB - 1, 0) + max(YB - 1, 0) (at least 1)
module tex_bank #(
  parameter int LEVEL  = 0,   // mip level of the texels held (0 = largest)
  parameter int PARITY = 0,   // (y & 1) * 2 + (x & 1) of the texels held
  parameter int XB     = 1,   // log2 of the level's largest width (0: one texel wide)
  parameter int YB     = 1,
  parameter int DW     = 32,
  parameter int AW     = (((XB > 1) ? XB - 1 : 0) + ((YB > 1) ? YB - 1 : 0) > 0)
                         ? ((XB > 1) ? XB - 1 : 0) + ((YB > 1) ? YB - 1 : 0) : 1  // derived
) (
  input  logic                         clk,
  input  logic                         we,
  input  logic [tex_pkg::LEVEL_W-1:0]  wlevel,
  input  logic [tex_pkg::COORD_W-1:0]  wx,
  input  logic [tex_pkg::COORD_W-1:0]  wy,
  input  logic [DW-1:0]                wdata,
  input  logic                         re,
  input  logic                         rsel,
  input  logic [AW-1:0]                raddr,
  output logic [DW-1:0]                rdata
);
  localparam int CB = tex_pkg::COORD_W;
  localparam int BX = (XB > 1) ? XB - 1 : 0;  // word-address bits from x >> 1
  localparam int BY = (YB > 1) ? YB - 1 : 0;
  localparam int DEPTH = 1 << (BX + BY);
  localparam logic [CB-1:0] OUTSIDE_X = ~(CB'((1 << XB) - 1));  // coordinate bits beyond the level (brackets: Yosys 0.23 drops a unary ~ right before a size cast)
  localparam logic [CB-1:0] OUTSIDE_Y = ~(CB'((1 << YB) - 1));
  localparam logic [1:0]    PAR = 2'(PARITY);
  localparam int            WW = 2 * CB;  // room for the write address arithmetic

  // Read index: raddr, or 0 in a one-word bank (whose 1-bit address is always 0).
  logic [AW-1:0] ridx;
  generate
    if (DEPTH > 1) begin : g_words
      assign ridx = raddr;
    end else begin : g_one_word
      logic raddr_unused;
      assign raddr_unused = raddr[0];
      assign ridx = '0;
    end
  endgenerate

  logic [DW-1:0] mem [0:DEPTH-1];
  always_ff @(posedge clk) begin
    if (re) begin
      if (rsel) rdata <= mem[ridx];  // first: a read of the word being written gets the old data
    end
    // Blocking write: mem is private to this process (and the backdoor), so this is the same
    // RAM; Verilator then needs no delayed-write shadow per bank (waiver in rtl/tex_unit.vlt).
    // The decode and the word index {y >> 1, x >> 1} (which fits AW bits for a texel inside the
    // level) are written out here, not as continuous assignments, so that Verilator evaluates
    // them only on a write.
    if (we) begin
      if (wlevel == tex_pkg::LEVEL_W'(LEVEL) && {wy[0], wx[0]} == PAR
          && (wx & OUTSIDE_X) == '0 && (wy & OUTSIDE_Y) == '0) begin
        mem[(DEPTH > 1) ? AW'(((WW'(wy) >> 1) << BX) | (WW'(wx) >> 1)) : '0] = wdata;
      end
    end
  end
endmodule

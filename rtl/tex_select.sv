// tex_select: picks the bank words of levels d and d1 out of all level memories (only those two
// read the sample's footprint; the others hold old words) and routes the 4 banks of each level
// to the footprint taps
//   a = T(x0,y0), b = T(x1,y0), c = T(x0,y1), e = T(x1,y1),  tap bank = (y&1)*2 + (x&1).
// Handshake: stall-enable; the registers load when en is high.
// Latency: 1 clock. Throughput: 1 per clock.
// Ports:
//   rdata     : NL levels x 4 banks x DW bits; level k bank b at [(k*4+b)*DW +: DW]
//   d, d1     : level indices 0..NL-1
//   par_d     : parities of level d's footprint {y1&1, y0&1, x1&1, x0&1}; par_d1 likewise
//   taps_d    : {e, c, b, a} of level d, DW bits each (a in the low bits); taps_d1 likewise
module tex_select #(
  parameter int NL = 5,
  parameter int DW = 32
) (
  input  logic                 clk,
  input  logic                 en,
  input  logic [NL*4*DW-1:0]   rdata,
  input  logic [3:0]           d,
  input  logic [3:0]           d1,
  input  logic [3:0]           par_d,
  input  logic [3:0]           par_d1,
  output logic [4*DW-1:0]      taps_d,
  output logic [4*DW-1:0]      taps_d1
);
  logic [4*DW-1:0] banks_d, banks_d1;  // the 4 bank words of levels d and d1
  tex_level_mux #(.NL(NL), .W(4*DW)) u_mux_d  (.entries(rdata), .sel(d),  .out(banks_d));
  tex_level_mux #(.NL(NL), .W(4*DW)) u_mux_d1 (.entries(rdata), .sel(d1), .out(banks_d1));

  // Bank of tap t = (ty, tx): {y parity, x parity} of that tap.
  logic [1:0] bank_a, bank_b, bank_c, bank_e, bank_a1, bank_b1, bank_c1, bank_e1;
  assign bank_a  = {par_d[2], par_d[0]};
  assign bank_b  = {par_d[2], par_d[1]};
  assign bank_c  = {par_d[3], par_d[0]};
  assign bank_e  = {par_d[3], par_d[1]};
  assign bank_a1 = {par_d1[2], par_d1[0]};
  assign bank_b1 = {par_d1[2], par_d1[1]};
  assign bank_c1 = {par_d1[3], par_d1[0]};
  assign bank_e1 = {par_d1[3], par_d1[1]};

  always_ff @(posedge clk) begin
    if (en) begin
      taps_d  <= {banks_d[bank_e*DW +: DW], banks_d[bank_c*DW +: DW],
                  banks_d[bank_b*DW +: DW], banks_d[bank_a*DW +: DW]};
      taps_d1 <= {banks_d1[bank_e1*DW +: DW], banks_d1[bank_c1*DW +: DW],
                  banks_d1[bank_b1*DW +: DW], banks_d1[bank_a1*DW +: DW]};
    end
  end
endmodule

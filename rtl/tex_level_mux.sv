// tex_level_mux: picks entry sel out of NL entries of W bits .
// Handshake: none (combinational). Latency: 0. Throughput: 1 per clock.
// Ports: entries: NL x W bits, entry k at [k*W +: W], opaque; sel: integer 0..NL-1 (others give 0);
//        out: W bits.
module tex_level_mux #(
  parameter int NL = 5,
  parameter int W  = 8
) (
  input  logic [NL*W-1:0] entries,
  input  logic [3:0]      sel,
  output logic [W-1:0]    out
);
  always_comb begin
    out = '0;
    for (int k = 0; k < NL; k = k + 1) if (sel == 4'(k)) out = entries[k*W +: W];
  end
endmodule

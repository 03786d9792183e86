// tex_filter: stage 5 of docs/numerics.md, all 4 channels: two bilinears and the level blend,
// 7 one-multiply lerps per channel, exact until the single final rounding.
//   clock 1: top = lerp(a, b, fx), bot = lerp(c, e, fx)   per level          CW.8
//   clock 2: bil = lerp(top, bot, fy)                      per level          CW.16
//   clock 3: tri = lerp(bil_d, bil_d1, f); out = (tri + 2^23) >> 24           CW.24 -> CW
// Point sampling is the same datapath with fx = fy = 0 and f = 0 (out = a).
// Handshake: stall-enable; every register loads when en is high.
// Latency: 3 clocks. Throughput: 1 per clock.
// Ports:
//   taps_d, taps_d1 : {e, c, b, a} texels of levels d and d1, each {A, B, G, R} of CW-bit
//                     unsigned channels
//   fx_d, fy_d, fx_d1, fy_d1 : unsigned 8 bits, weights of the +1 taps in 1/256
//   f      : unsigned 8 bits, weight of level d1 in 1/256
//   rgba   : {A, B, G, R}, CW-bit unsigned channels, rounded half up
module tex_filter #(
  parameter int CW = 8
) (
  input  logic              clk,
  input  logic              en,
  input  logic [16*CW-1:0]  taps_d,
  input  logic [16*CW-1:0]  taps_d1,
  input  logic [7:0]        fx_d,
  input  logic [7:0]        fy_d,
  input  logic [7:0]        fx_d1,
  input  logic [7:0]        fy_d1,
  input  logic [7:0]        f,
  output logic [4*CW-1:0]   rgba
);
  // Weights delayed to the clock that uses them.
  logic [7:0] fy_d_q, fy_d1_q, f_q, f_qq;
  always_ff @(posedge clk) begin
    if (en) begin
      fy_d_q  <= fy_d;
      fy_d1_q <= fy_d1;
      f_q     <= f;
      f_qq    <= f_q;
    end
  end

  genvar ch;
  generate
    for (ch = 0; ch < 4; ch = ch + 1) begin : g_channel
      // Channel ch of tap t (0 a, 1 b, 2 c, 3 e) is taps[(t*4 + ch)*CW +: CW].
      logic [CW+7:0]  top_d_n, bot_d_n, top_d1_n, bot_d1_n, top_d, bot_d, top_d1, bot_d1;
      logic [CW+15:0] bil_d_n, bil_d1_n, bil_d, bil_d1;
      logic [CW+23:0] tri_n;
      logic [22:0]    tri_fraction_unused;  // below the rounding bit

      tex_lerp #(.IN_W(CW)) u_top_d  (.a(taps_d[(0*4+ch)*CW +: CW]),  .b(taps_d[(1*4+ch)*CW +: CW]),
                                      .w(fx_d),  .y(top_d_n));
      tex_lerp #(.IN_W(CW)) u_bot_d  (.a(taps_d[(2*4+ch)*CW +: CW]),  .b(taps_d[(3*4+ch)*CW +: CW]),
                                      .w(fx_d),  .y(bot_d_n));
      tex_lerp #(.IN_W(CW)) u_top_d1 (.a(taps_d1[(0*4+ch)*CW +: CW]), .b(taps_d1[(1*4+ch)*CW +: CW]),
                                      .w(fx_d1), .y(top_d1_n));
      tex_lerp #(.IN_W(CW)) u_bot_d1 (.a(taps_d1[(2*4+ch)*CW +: CW]), .b(taps_d1[(3*4+ch)*CW +: CW]),
                                      .w(fx_d1), .y(bot_d1_n));
      always_ff @(posedge clk) begin
        if (en) begin
          top_d  <= top_d_n;
          bot_d  <= bot_d_n;
          top_d1 <= top_d1_n;
          bot_d1 <= bot_d1_n;
        end
      end

      tex_lerp #(.IN_W(CW+8)) u_bil_d  (.a(top_d),  .b(bot_d),  .w(fy_d_q),  .y(bil_d_n));
      tex_lerp #(.IN_W(CW+8)) u_bil_d1 (.a(top_d1), .b(bot_d1), .w(fy_d1_q), .y(bil_d1_n));
      always_ff @(posedge clk) begin
        if (en) begin
          bil_d  <= bil_d_n;
          bil_d1 <= bil_d1_n;
        end
      end

      tex_lerp #(.IN_W(CW+16)) u_tri (.a(bil_d), .b(bil_d1), .w(f_qq), .y(tri_n));
      // (tri + 2^23) >> 24 == tri[CW+23:24] + tri[23]; cannot overflow CW bits (tri <= (2^CW-1)*2^24).
      assign tri_fraction_unused = tri_n[22:0];
      always_ff @(posedge clk) begin
        if (en) rgba[ch*CW +: CW] <= tri_n[CW+23:24] + CW'(tri_n[23]);
      end
    end
  endgenerate
endmodule

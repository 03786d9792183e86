// tex_accum: the mean of a sample's probes and its one rounding, bit for bit the model's
// average_and_round (docs/numerics.md stage 6): round half up of sum / (N * 2^24), computed as
// floor(X * ceil(2^25 / N) / 2^25) with X = floor((sum + N * 2^23) / 2^24) (exact for every X
// below 2^21, tests/model/test_aniso.cpp). With N = 1 it is the trilinear rounding.
// A min or max reduction (in_reduction) keeps the min or max of the probes instead of their sum,
// and its mean of 1: each probe's blend is a texel value * 2^24, returned exactly.
//   clock 1: acc = first ? blend : acc + blend (min, max)  per channel, CW.24 (+ 4 bits for 16 probes)
//   clock 2: rgba = the rounded mean of acc; out_valid only for the sample's last probe
// Handshake: stall-enable; the registers load when en is high, the data registers only with a
//   valid probe (clock 1) or a sample's last probe (clock 2): rgba and out_side hold the last
//   sample while out_valid is low. The valid bits are reset.
// Latency: 2 clocks. Throughput: 1 probe per clock (a sample leaves with its last probe).
// Ports:
//   blend        : channel c at [c*(CW+24) +: CW+24], unsigned CW.24 (tex_filter's)
//   in_first, in_last, in_n : the probe's place in its sample and the sample's probes (1..16)
//   in_reduction : tex_pkg::REDUCE_*, the probe's sampler's reduction mode (code 3 as min)
//   in_zero      : the probe counts as 0 (a texel fetch outside the texture: tex_front's zero)
//   in_side    : SIDE_W bits carried along (the tag)
//   rgba       : {A, B, G, R}, CW-bit unsigned channels
`include "tex_param_error.svh"
module tex_accum #(
  parameter int CW     = 8,
  parameter int SIDE_W = 1
) (
  input  logic                  clk,
  input  logic                  rst,
  input  logic                  en,
  input  logic                  in_valid,
  input  logic                  in_first,
  input  logic                  in_last,
  input  logic [4:0]            in_n,
  input  logic [tex_pkg::REDUCTION_W-1:0] in_reduction,
  input  logic                  in_zero,
  input  logic [4*(CW+24)-1:0]  blend,
  input  logic [SIDE_W-1:0]     in_side,
  output logic                  out_valid,
  output logic [4*CW-1:0]       rgba,
  output logic [SIDE_W-1:0]     out_side,
  output logic                  held      // clock 1 holds a sample's last probe
`ifdef FORMAL
  , output logic                f_valid_s1
  , output logic [SIDE_W-1:0]   f_side_s1
`endif
);
  localparam int TW = CW + 24;  // one probe's channel
  localparam int AW = TW + 4;   // the sum of up to 16

  // ---------------------------------------------------------------- clock 1: accumulate
  logic              valid_s1, last_s1;
  logic [4:0]        n_s1;
  logic [SIDE_W-1:0] side_s1;
  always_ff @(posedge clk) begin
    if (rst) valid_s1 <= 1'b0;
    else if (en) valid_s1 <= in_valid;
    if (en && in_valid) begin
      last_s1 <= in_last;
      n_s1    <= (in_reduction != tex_pkg::REDUCE_AVERAGE) ? 5'd1 : in_n;
      side_s1 <= in_side;
    end
  end
  // The channels' sums and means: g_channel below (one register per channel).

  // ---------------------------------------------------------------- clock 2: mean, round
  // ceil(2^25 / n), n = 1..16.
  function automatic logic [25:0] reciprocal(input logic [4:0] n);
    case (n)
      5'd2: reciprocal = 26'd16777216;  5'd3: reciprocal = 26'd11184811;  5'd4: reciprocal = 26'd8388608;
      5'd5: reciprocal = 26'd6710887;   5'd6: reciprocal = 26'd5592406;   5'd7: reciprocal = 26'd4793491;
      5'd8: reciprocal = 26'd4194304;   5'd9: reciprocal = 26'd3728271;   5'd10: reciprocal = 26'd3355444;
      5'd11: reciprocal = 26'd3050403;  5'd12: reciprocal = 26'd2796203;  5'd13: reciprocal = 26'd2581111;
      5'd14: reciprocal = 26'd2396746;  5'd15: reciprocal = 26'd2236963;  5'd16: reciprocal = 26'd2097152;
      default: reciprocal = 26'd33554432;
    endcase
  endfunction
  // floor(X * ceil(2^25 / n) / 2^25) with X = floor((sum + n * 2^23) / 2^24) < 2^21; the product
  // is below 2^(CW+30). A function called inside the enable: evaluated only for a last probe.
  function automatic logic [CW-1:0] mean_of(input logic [AW-1:0] sum, input logic [4:0] n);
    logic [CW+4:0] x;
    x = (CW+5)'(({1'b0, sum} + ((AW+1)'(n) << 23)) >> 24);
    mean_of = CW'(((CW+31)'(x) * (CW+31)'(reciprocal(n))) >> 25);
  endfunction
  always_ff @(posedge clk) begin
    if (rst) out_valid <= 1'b0;
    else if (en) out_valid <= valid_s1 && last_s1;
    if (en && valid_s1 && last_s1) out_side <= side_s1;
  end

  // Per channel: clock 1's sum, clock 2's mean. A register per channel, not one wide vector,
  // which Verilator would copy into a delayed-write shadow in every clock.
  genvar c;
  generate
    for (c = 0; c < 4; c = c + 1) begin : g_channel
      logic [AW-1:0] acc, probe;
      assign probe = in_zero ? '0 : {4'd0, blend[c*TW +: TW]};
      always_ff @(posedge clk) begin
        if (en && in_valid)
          if (in_reduction == tex_pkg::REDUCE_AVERAGE) acc <= (in_first ? '0 : acc) + probe;
          // (a min/max probe is a texel * 2^24: its integer part alone is compared)
          else acc <= (in_first || ((probe[AW-1:24] > acc[AW-1:24]) == (in_reduction == tex_pkg::REDUCE_MAX))) ? probe : acc;
        if (en && valid_s1 && last_s1) rgba[c*CW +: CW] <= mean_of(acc, n_s1);
      end
    end
  endgenerate

  assign held = valid_s1 && last_s1;
`ifdef FORMAL
  assign f_valid_s1 = valid_s1;
  assign f_side_s1  = side_s1;
`endif

  generate
    if (CW < 1 || CW > tex_pkg::MAX_CW) begin : g_bad_cw
      `TEX_PARAM_ERROR("tex_accum: CW must be in 1..16")
    end
  endgenerate
endmodule

// tex_lod: the model's `lod` stage (docs/numerics.md stage 1): bias, clamp and level select from
// an explicit lambda.
// Handshake: stall-enable; every register loads when en is high (no valid bits inside).
// Latency: 2 clocks: tex_unit clock 2 (lambda_s2, the clamped lambda) and clock 3 (level, f).
// Throughput: 1 per clock.
// Ports:
//   lod, bias, min_lod, max_lod : signed Q8.8 (LOD_W bits)
//   mip_mode   : tex_pkg::MIP_* (3 is treated like MIP_LINEAR, as the model's else branch does)
//   last_level : q = max(log2_w0, log2_h0), integer 0..11
//   level      : 2 slots of LEVEL_W bits, slot s at [s*LEVEL_W +: LEVEL_W]: slot 0 = d,
//                slot 1 = d1 = min(d + 1, q); integers 0..q
//   f          : unsigned WEIGHT_BITS, weight of level d1 in 1/256 (0 unless linear mip below q)
//   minify     : lambda' > 0 (clock 3, beside level): the minification filter's texel filter applies,
//                else the magnification filter's (the model's LevelSelect::magnify, inverted)
module tex_lod (
  input  logic                                 clk,
  input  logic                                 en,
  input  logic signed [tex_pkg::LOD_W-1:0]     lod,
  input  logic signed [tex_pkg::LOD_W:0]       bias,       // the sampler's plus the request's: LOD_W+1 bits
  input  logic signed [tex_pkg::LOD_W-1:0]     min_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]     max_lod,
  input  logic [tex_pkg::MIP_W-1:0]            mip_mode,
  input  logic [tex_pkg::LEVEL_W-1:0]          last_level,
  output logic [2*tex_pkg::LEVEL_W-1:0]        level,
  output logic [tex_pkg::WEIGHT_BITS-1:0]      f,
  output logic                                 minify
);
  localparam int LW    = tex_pkg::LOD_W;
  localparam int LF    = tex_pkg::LOD_FRAC;
  localparam int IW    = LW - LF;            // integer bits of lambda (sign included): 8
  localparam int VW    = tex_pkg::LEVEL_W;
  localparam int WB    = tex_pkg::WEIGHT_BITS;

  // ---- clock 2: lambda' = clamp(lambda + bias, min, max) (GL order; exact LW+2-bit sum)
  logic signed [LW+1:0] lod_x, bias_x, min_x, max_x, biased;  // size casts sign-extend
  logic signed [LW-1:0] lambda_next, lambda_s2;
  assign lod_x  = (LW+2)'(lod);
  assign bias_x = (LW+2)'(bias);
  assign min_x  = (LW+2)'(min_lod);
  assign max_x  = (LW+2)'(max_lod);
  assign biased = lod_x + bias_x;
  always_comb begin
    // Same order as std::clamp: below min wins, then above max.
    if (biased < min_x) lambda_next = min_lod;
    else if (max_x < biased) lambda_next = max_lod;
    else lambda_next = biased[LW-1:0];
  end
  always_ff @(posedge clk) if (en) lambda_s2 <= lambda_next;

  // ---- clock 3: level select
  logic          minify_next;     // lambda' > 0
  logic [IW-1:0] floor_level;     // lambda' >> 8 (lambda' > 0, so at most 127)
  logic [IW-1:0] nearest_level;   // (lambda' + 127) >> 8, at most 128
  logic [IW-1:0] last_wide;
  logic [VW-1:0] d_next;          // slot 0's level
  logic [WB-1:0] f_next;
  assign minify_next   = !lambda_s2[LW-1] && (lambda_s2 != '0);
  assign floor_level   = IW'(lambda_s2[LW-2:0] >> LF);
  assign nearest_level = IW'(({1'b0, lambda_s2[LW-2:0]} + LW'((1 << (LF - 1)) - 1)) >> LF);
  assign last_wide     = IW'(last_level);
  always_comb begin
    d_next = '0;
    f_next = '0;
    if (mip_mode != tex_pkg::MIP_NONE && minify_next) begin
      if (mip_mode == tex_pkg::MIP_NEAREST) begin
        d_next = (nearest_level < last_wide) ? nearest_level[VW-1:0] : last_level;
      end else if (floor_level < last_wide) begin  // MIP_LINEAR (and the unused code 3)
        d_next = floor_level[VW-1:0];
        f_next = WB'(lambda_s2[LF-1:0]);  // the fraction of lambda'
      end else begin
        d_next = last_level;  // at the last level there is nothing to blend with
      end
    end
  end
  always_ff @(posedge clk) begin
    if (en) begin
      level  <= {(d_next == last_level) ? last_level : d_next + VW'(1), d_next};
      f      <= f_next;
      minify <= minify_next;
    end
  end
endmodule

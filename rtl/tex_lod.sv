// tex_lod: stage 1 of docs/numerics.md: bias, clamp, and level select from an explicit lambda.
// Handshake: stall-enable; every register loads when en is high (no valid bits inside).
// Latency: 2 clocks (clamp register, then level-select register). Throughput: 1 per clock.
// Ports:
//   lod, bias, min_lod, max_lod : signed Q8.8
//   mip_mode   : tex_pkg::MIP_* (3 is treated like MIP_LINEAR, as the model's else branch does)
//   last_level : q = max(log2_w0, log2_h0), integer 0..11
//   d, d1      : integer level indices 0..q (d1 = min(d + 1, q))
//   f          : unsigned 8 bits, weight of level d1 in 1/256 (0 unless linear mip below q)
module tex_lod (
  input  logic               clk,
  input  logic               en,
  input  logic signed [15:0] lod,
  input  logic signed [15:0] bias,
  input  logic signed [15:0] min_lod,
  input  logic signed [15:0] max_lod,
  input  logic [1:0]         mip_mode,
  input  logic [3:0]         last_level,
  output logic [3:0]         d,
  output logic [3:0]         d1,
  output logic [7:0]         f
);
  // ---- clock 1: lambda' = clamp(lambda + bias, min, max) (GL order; exact 17-bit sum)
  logic signed [16:0] lod17, bias17, min17, max17, biased;  // size casts sign-extend
  logic signed [15:0] clamped_next, clamped;
  assign lod17  = 17'(lod);
  assign bias17 = 17'(bias);
  assign min17  = 17'(min_lod);
  assign max17  = 17'(max_lod);
  assign biased = lod17 + bias17;
  always_comb begin
    // Same order as std::clamp: below min wins, then above max.
    if (biased < min17) clamped_next = min_lod;
    else if (max17 < biased) clamped_next = max_lod;
    else clamped_next = biased[15:0];
  end
  always_ff @(posedge clk) if (en) clamped <= clamped_next;

  // ---- clock 2: level select
  logic       minify;          // lambda' > 0
  logic [7:0] floor_level;     // lambda' >> 8 (lambda' > 0, so at most 127)
  logic [7:0] nearest_level;   // (lambda' + 127) >> 8, at most 128
  logic [7:0] q8;
  logic [3:0] d_next;
  logic [7:0] f_next;
  assign minify        = !clamped[15] && (clamped != 16'sd0);
  assign floor_level   = 8'(clamped[14:0] >> tex_pkg::LOD_FRAC);
  assign nearest_level = 8'(({1'b0, clamped[14:0]} + 16'd127) >> tex_pkg::LOD_FRAC);
  assign q8            = {4'b0, last_level};
  always_comb begin
    d_next = 4'd0;
    f_next = 8'd0;
    if (mip_mode != tex_pkg::MIP_NONE && minify) begin
      if (mip_mode == tex_pkg::MIP_NEAREST) begin
        d_next = (nearest_level < q8) ? nearest_level[3:0] : last_level;
      end else if (floor_level < q8) begin  // MIP_LINEAR (and the unused code 3)
        d_next = floor_level[3:0];
        f_next = clamped[7:0];
      end else begin
        d_next = last_level;  // at the last level there is nothing to blend with
      end
    end
  end
  always_ff @(posedge clk) begin
    if (en) begin
      d  <= d_next;
      d1 <= (d_next == last_level) ? last_level : d_next + 4'd1;
      f  <= f_next;
    end
  end
endmodule

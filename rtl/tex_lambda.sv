// tex_lambda: the LOD unit, lambda from the four derivatives of (u, v) per screen pixel. Bit for
// bit the model's tex_lambda (model/lod.cpp, docs/numerics.md stage 1b): block normalization of
// the texel-space magnitudes to 16 bits, exact squares, rho^2 = max(|d/dx|^2, |d/dy|^2), log2 by
// the leading one and a 33-entry table with linear interpolation, rounded to Q8.8.
// Part of tex_aniso (the request's LOD and probe setup), which also takes the clock-1 squares.
// Handshake: stall-enable; every register loads when en is high (no valid bits inside).
// Latency: 2 clocks (clock 1: normalize and square; clock 2: log2 and round). Throughput: 1 per clock.
// Ports:
//   dudx, dvdx, dudy, dvdy : signed Q8.24 texture widths (heights) per pixel (REQ_COORD_W bits)
//   log2_w, log2_h         : log2 of the level-0 size, integers 0..MAX_LOG2_SIZE (LEVEL_W bits)
//   lambda                 : signed Q8.8 (LOD_W bits); all derivatives 0 gives -128.0
//   px_s1, py_s1           : the clock-1 squared lengths (33 bits, unsigned, the block's scale)
module tex_lambda (
  input  logic                                  clk,
  input  logic                                  en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdy,
  input  logic [tex_pkg::LEVEL_W-1:0]            log2_w,
  input  logic [tex_pkg::LEVEL_W-1:0]            log2_h,
  output logic signed [tex_pkg::LOD_W-1:0]       lambda,
  output logic [2*16:0]                          px_s1,   // clock 1: |d(u,v)/dx|^2, normalized
  output logic [2*16:0]                          py_s1    //          |d(u,v)/dy|^2 (same scale)
);
  localparam int DW = tex_pkg::REQ_COORD_W;             // 32
  localparam int TW = DW + tex_pkg::MAX_LOG2_SIZE;      // texel-space magnitude: < 2^44, 45 bits
  localparam int NW = 16;                               // normalized magnitude
  localparam int PW = 2 * NW + 1;                       // a sum of two squares: 33 bits
  localparam int SW = 6;                                // shift s = 0..29
  localparam int FRAC = tex_pkg::COORD_FRAC;            // 24

  // ------------------------------------------------------------ clock 1: normalize, square
  logic [TW-1:0] mag [4];
  logic [TW-1:0] largest;
  logic [SW-1:0] shift;
  logic [TW-1:0] scaled [4];
  logic [NW-1:0] norm [4];
  logic [PW-1:0] square [4];
  logic [PW-1:0] px, py;

  logic signed [DW-1:0] deriv [4];
  logic [tex_pkg::LEVEL_W-1:0] log2_size [4];
  logic [DW-1:0] absolute [4];

  always_comb begin
    deriv[0] = dudx; log2_size[0] = log2_w;
    deriv[1] = dvdx; log2_size[1] = log2_h;
    deriv[2] = dudy; log2_size[2] = log2_w;
    deriv[3] = dvdy; log2_size[3] = log2_h;
    for (int i = 0; i < 4; i++) begin
      absolute[i] = deriv[i][DW-1] ? -deriv[i] : deriv[i];  // |INT32_MIN| = 2^31 fits unsigned
      mag[i] = {{(TW - DW){1'b0}}, absolute[i]} << log2_size[i];
    end
    largest = mag[0];
    for (int i = 1; i < 4; i++) if (mag[i] > largest) largest = mag[i];
    // s = max(0, msb(largest) - 15): the largest keeps 16 bits.
    shift = '0;
    for (int b = NW; b < TW; b++) if (largest[b]) shift = 6'(b - NW + 1);
    for (int i = 0; i < 4; i++) begin
      scaled[i] = mag[i] >> shift;  // the top bits are zero: the largest now has 16
      norm[i] = scaled[i][NW-1:0];
      square[i] = {{(PW - NW){1'b0}}, norm[i]} * {{(PW - NW){1'b0}}, norm[i]};
    end
    px = square[0] + square[1];
    py = square[2] + square[3];
  end

  logic [PW-1:0] p_s1;
  assign p_s1 = px_s1 > py_s1 ? px_s1 : py_s1;
  logic [SW-1:0] shift_s1;
  always_ff @(posedge clk) begin
    if (en) begin
      px_s1    <= px;
      py_s1    <= py;
      shift_s1 <= shift;
    end
  end

  // ------------------------------------------------------------ clock 2: log2, round
  // log2(1 + j/32) in Q.16, rounded (the model's kLog2Table).
  function automatic logic [16:0] log2_table(input logic [5:0] j);
    log2_table = 17'd65536;
    case (j)
      6'd0: log2_table = 17'd0;      6'd1: log2_table = 17'd2909;   6'd2: log2_table = 17'd5732;   6'd3: log2_table = 17'd8473;
      6'd4: log2_table = 17'd11136;  6'd5: log2_table = 17'd13727;  6'd6: log2_table = 17'd16248;  6'd7: log2_table = 17'd18704;
      6'd8: log2_table = 17'd21098;  6'd9: log2_table = 17'd23433;  6'd10: log2_table = 17'd25711; 6'd11: log2_table = 17'd27936;
      6'd12: log2_table = 17'd30109; 6'd13: log2_table = 17'd32234; 6'd14: log2_table = 17'd34312; 6'd15: log2_table = 17'd36346;
      6'd16: log2_table = 17'd38336; 6'd17: log2_table = 17'd40286; 6'd18: log2_table = 17'd42196; 6'd19: log2_table = 17'd44068;
      6'd20: log2_table = 17'd45904; 6'd21: log2_table = 17'd47705; 6'd22: log2_table = 17'd49472; 6'd23: log2_table = 17'd51207;
      6'd24: log2_table = 17'd52911; 6'd25: log2_table = 17'd54584; 6'd26: log2_table = 17'd56229; 6'd27: log2_table = 17'd57845;
      6'd28: log2_table = 17'd59434; 6'd29: log2_table = 17'd60997; 6'd30: log2_table = 17'd62534; 6'd31: log2_table = 17'd64047;
      default: ;
    endcase
  endfunction

  logic [5:0]  lead;       // k: position of the leading one of p (0..32)
  logic [20:0] mantissa;   // bits 31..11 of the 32 below it: 5 index the table, 16 interpolate
  logic [16:0] lo, hi, step;
  logic [15:0] t;
  logic [22:0] log2_p;     // Q6.16, k <= 32
  logic signed [24:0] lambda_q16;

  always_comb begin
    lead = '0;
    for (int b = 1; b < PW; b++) if (p_s1[b]) lead = 6'(b);
    // p < 2^33, so k <= 32 and the bits below the leading one are a left shift by 32 - k.
    mantissa = 21'(({31'd0, p_s1} << (6'd32 - lead)) >> 11);
    lo = log2_table({1'b0, mantissa[20:16]});
    hi = log2_table({1'b0, mantissa[20:16]} + 6'd1);
    t = mantissa[15:0];
    step = hi - lo;
    log2_p = {lead[5:0], 16'd0} + 23'(lo) + 23'((33'(step) * 33'(t)) >> 16);
    // lambda = log2(p) / 2 + s - 24 (Q.16), then round half up to Q8.8.
    lambda_q16 = 25'($signed({2'b0, log2_p} >>> 1)) + ($signed({13'd0, shift_s1, 6'd0} <<< 10)) -
                 25'(FRAC <<< 16);
  end

  always_ff @(posedge clk) begin
    // Round half up to Q8.8 (|lambda| < 24 levels: the 16-bit result holds it).
    if (en) lambda <= p_s1 == '0 ? {1'b1, {(tex_pkg::LOD_W - 1){1'b0}}} : 16'((lambda_q16 + 25'sd128) >>> 8);
  end

  generate
    if (tex_pkg::LOD_W != 16) begin : g_bad_lod_w
`ifdef __ICARUS__
      initial $fatal(1, "tex_lambda: lambda is built for a 16-bit Q8.8 port (tex_pkg::LOD_W)");  // Icarus 11: no elaboration-time $error
`else
      $error("tex_lambda: lambda is built for a 16-bit Q8.8 port (tex_pkg::LOD_W)");
`endif
    end
  endgenerate
endmodule

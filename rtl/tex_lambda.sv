// tex_lambda: the LOD unit, lambda from the four derivatives of (u, v) per screen pixel. Bit for
// bit the model's tex_lambda (model/lod.cpp, docs/numerics.md stage 1b): block normalization of
// the texel-space magnitudes to 16 bits, exact squares, rho^2 = max(|d/dx|^2, |d/dy|^2), log2 by
// the leading one and a 33-entry table with linear interpolation, rounded to Q8.8.
// Part of tex_aniso (the request's LOD and probe setup), which also takes the clock-1 squares.
// Handshake: stall-enable; every register loads when en is high (no valid bits inside).
// Latency: 2 clocks (clock 1: normalize and square; clock 2: log2 and round). Throughput: 1 per clock.
// Ports:
//   dudx, dvdx, dudy, dvdy : signed Q8.24 texture widths (heights) per pixel (REQ_COORD_W bits)
//   w, h                   : the level-0 size, unsigned SIZE_W bits, 1..2^MAX_LOG2_SIZE (any value)
//   lambda                 : signed Q8.8 (LOD_W bits); all derivatives 0 gives -128.0
//   px_s1, py_s1           : the clock-1 squared lengths (33 bits, unsigned, the block's scale)
`include "tex_param_error.svh"
module tex_lambda (
  input  logic                                  clk,
  input  logic                                  en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdy,
  input  logic [tex_pkg::SIZE_W-1:0]             w,
  input  logic [tex_pkg::SIZE_W-1:0]             h,
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
  // Each clock's logic sits inside its register enable: the hardware is the same as combinational
  // logic in front of enabled registers, and Verilator evaluates it only in a clock with en high
  // (tex_aniso's en is low unless a derivative request is in it).
  // {px, py, s}: the texel-space magnitudes |d| * size (the paper's shift |d| << log2 size where
  // the size is a power of two; a 32 x 14-bit multiply), shifted right by s so that the
  // largest keeps 16 bits, squared and summed per screen axis. Written out, not a function: an
  // inlined function's wide temporaries are cleared in every clock by Verilator, called or not.
  logic [PW-1:0] p_s1;
  assign p_s1 = px_s1 > py_s1 ? px_s1 : py_s1;
  logic [SW-1:0] shift_s1;
  always_ff @(posedge clk) begin
    if (en) begin
      logic [4*TW-1:0] mag;
      logic [4*PW-1:0] square;
      logic [TW-1:0]   largest;
      logic [DW-1:0]   value;
      logic [tex_pkg::SIZE_W-1:0] size;
      logic [SW-1:0]   shift;
      for (int i = 0; i < 4; i++) begin
        value = (i == 0) ? dudx : (i == 1) ? dvdx : (i == 2) ? dudy : dvdy;
        if (value[DW-1]) value = -value;  // |INT32_MIN| = 2^31 fits unsigned
        size  = (i % 2 == 0) ? w : h;
        mag[i*TW +: TW] = TW'(value) * TW'(size);  // < 2^31 * 2^13
      end
      largest = mag[0 +: TW];
      for (int i = 1; i < 4; i++) if (mag[i*TW +: TW] > largest) largest = mag[i*TW +: TW];
      // s = max(0, msb(largest) - 15): the largest keeps 16 bits.
      shift = '0;
      for (int b = NW; b < TW; b++) if (largest[b]) shift = 6'(b - NW + 1);
      for (int i = 0; i < 4; i++)  // the largest now has 16 bits, the bits above are zero
        square[i*PW +: PW] = PW'(NW'(mag[i*TW +: TW] >> shift)) * PW'(NW'(mag[i*TW +: TW] >> shift));
      px_s1    <= square[0 +: PW] + square[PW +: PW];
      py_s1    <= square[2*PW +: PW] + square[3*PW +: PW];
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

  // lambda = log2(p) / 2 + s - 24, rounded half up to Q8.8 (|lambda| < 24 levels: 16 bits hold
  // it); p = 0 (no footprint) gives -128.0.
  function automatic logic signed [tex_pkg::LOD_W-1:0] lambda_of(input logic [PW-1:0] p,
                                                                 input logic [SW-1:0] s);
    logic [5:0]  lead;       // k: position of the leading one of p (0..32)
    logic [20:0] mantissa;   // bits 31..11 of the 32 below it: 5 index the table, 16 interpolate
    logic [16:0] lo, hi, step;
    logic [22:0] log2_p;     // Q6.16, k <= 32
    logic signed [24:0] lambda_q16;
    lead = '0;
    for (int b = 1; b < PW; b++) if (p[b]) lead = 6'(b);
    // p < 2^33, so k <= 32 and the bits below the leading one are a left shift by 32 - k.
    mantissa = 21'(({31'd0, p} << (6'd32 - lead)) >> 11);
    lo = log2_table({1'b0, mantissa[20:16]});
    hi = log2_table({1'b0, mantissa[20:16]} + 6'd1);
    step = hi - lo;
    log2_p = {lead[5:0], 16'd0} + 23'(lo) + 23'((33'(step) * 33'(mantissa[15:0])) >> 16);
    lambda_q16 = 25'($signed({2'b0, log2_p} >>> 1)) + ($signed({13'd0, s, 6'd0} <<< 10)) -
                 25'(FRAC <<< 16);
    lambda_of = p == '0 ? {1'b1, {(tex_pkg::LOD_W - 1){1'b0}}} : 16'((lambda_q16 + 25'sd128) >>> 8);
  endfunction

  always_ff @(posedge clk) if (en) lambda <= lambda_of(p_s1, shift_s1);

  generate
    if (tex_pkg::LOD_W != 16) begin : g_bad_lod_w
      `TEX_PARAM_ERROR("tex_lambda: lambda is built for a 16-bit Q8.8 port (tex_pkg::LOD_W)")
    end
  endgenerate
endmodule

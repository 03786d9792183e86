// tex_aniso: a request's LOD and probe setup from its four derivatives, bit for bit the model's
// tex_aniso (model/lod.cpp, docs/numerics.md stage 1c): tex_lambda's lambda and squared lengths
// Px^2, Py^2; the probe count N = least n (1..cap) with n^2 Pmin^2 >= Pmax^2 - Pmax^2/64 (powers of
// two only when pow2), else the cap; lambda' = lambda - round(256 log2 N); the probe spacing
// along the major axis (the x derivatives when Px^2 >= Py^2), axis * round(2^16 / N) / 2^16.
// Handshake: stall-enable; every register loads when en is high (no valid bits inside).
// Latency: 3 clocks (1: tex_lambda's squares; 2: tex_lambda's log2, N, major axis; 3: lambda',
//   steps). Throughput: 1 per clock.
// Ports:
//   dudx, dvdx, dudy, dvdy : signed Q8.24 texture widths (heights) per pixel; must be registers
//                            (tex_lambda's first clock is combinational on them)
//   w, h                   : the level-0 size, unsigned SIZE_W bits, 1..2^MAX_LOG2_SIZE
//   max_aniso_m1           : the cap less one, unsigned 0..15 (cap 1..16)
//   pow2                   : probe counts are powers of two (the cap rounds down to one)
//   n                      : probes, unsigned 1..16 (5 bits)
//   lambda                 : lambda' in signed Q8.8 (LOD_W bits), before bias and clamp
//   step_u, step_v         : signed Q8.24 (REQ_COORD_W bits), the spacing of the probes
`include "tex_param_error.svh"
module tex_aniso (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] dvdy,
  input  logic [tex_pkg::SIZE_W-1:0]             w,
  input  logic [tex_pkg::SIZE_W-1:0]             h,
  input  logic [3:0]                             max_aniso_m1,
  input  logic                                   pow2,
  output logic [4:0]                             n,
  output logic signed [tex_pkg::LOD_W-1:0]       lambda,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] step_u,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] step_v
`ifdef FORMAL
  , output logic [4:0]                           f_n_s2  // the clock-2 probe count
`endif
);
  localparam int DW = tex_pkg::REQ_COORD_W;
  localparam int PW = 33;  // tex_lambda's squared lengths

  // ---------------------------------------------------------------- clock 1 (tex_lambda's squares)
  logic signed [tex_pkg::LOD_W-1:0] lambda_s2;
  logic [PW-1:0] px_s1, py_s1;
  tex_lambda u_lambda (
    .clk(clk), .en(en), .dudx(dudx), .dvdx(dvdx), .dudy(dudy), .dvdy(dvdy), .w(w),
    .h(h), .lambda(lambda_s2), .px_s1(px_s1), .py_s1(py_s1)
  );
  logic signed [DW-1:0] dudx_s1, dvdx_s1, dudy_s1, dvdy_s1;
  logic [3:0]           cap_m1_s1;
  logic                 pow2_s1;
  always_ff @(posedge clk) begin
    if (en) begin
      dudx_s1   <= dudx;
      dvdx_s1   <= dvdx;
      dudy_s1   <= dudy;
      dvdy_s1   <= dvdy;
      cap_m1_s1 <= max_aniso_m1;
      pow2_s1   <= pow2;
    end
  end

  // ---------------------------------------------------------------- clock 2: N, the major axis
  // reaches[k]: k^2 Pmin^2 >= Pmax^2 - Pmax^2/64, k = 1..15 (Pmax, Pmin: px_s1, py_s1 sorted)
  function automatic logic [15:1] reaches_of(input logic [PW-1:0] px, input logic [PW-1:0] py);
    logic [PW-1:0] pmax, pmin, target;
    pmax = px >= py ? px : py;
    pmin = px >= py ? py : px;
    target = pmax - (pmax >> 6);
    for (int k = 1; k <= 15; k++) reaches_of[k] = 41'(k * k) * 41'(pmin) >= 41'(target);
  endfunction
  // N: the least k below the cap (powers of two only when pow2) that reaches the target, else the
  // cap (rounded down to a power of two when pow2)
  function automatic logic [4:0] count_of(input logic [15:1] reaches, input logic [3:0] cap_m1,
                                          input logic pow2_only);
    logic [4:0] cap;
    cap = {1'b0, cap_m1} + 5'd1;
    if (pow2_only) cap = cap[4] ? 5'd16 : cap[3] ? 5'd8 : cap[2] ? 5'd4 : cap[1] ? 5'd2 : 5'd1;
    count_of = cap;  // searched from the top down: the least k wins
    for (int k = 15; k >= 1; k--)
      if (5'(k) < cap && (!pow2_only || (k & (k - 1)) == 0) && reaches[k]) count_of = 5'(k);
  endfunction
  // The comparisons are a named signal only for the formal proof, which cuts it
  // (scripts/formal.sh); elsewhere they are evaluated inside the enable, like the rest.
`ifdef FORMAL
  logic [15:1] reaches;
  always_comb reaches = reaches_of(px_s1, py_s1);
`endif
  logic                 major_x;
  logic [4:0]           n_s2;
  logic signed [DW-1:0] axis_u_s2, axis_v_s2;
  assign major_x = px_s1 >= py_s1;
  always_ff @(posedge clk) begin
    if (en) begin
`ifdef FORMAL
      n_s2      <= count_of(reaches, cap_m1_s1, pow2_s1);
`else
      n_s2      <= count_of(reaches_of(px_s1, py_s1), cap_m1_s1, pow2_s1);
`endif
      axis_u_s2 <= major_x ? dudx_s1 : dudy_s1;
      axis_v_s2 <= major_x ? dvdx_s1 : dvdy_s1;
    end
  end

  // ---------------------------------------------------------------- clock 3: lambda', steps
  // round(256 log2 k) and round(2^16 / k), k = 1..16 (the model's aniso_log2_q8, aniso_reciprocal).
  function automatic logic [10:0] log2_q8(input logic [4:0] k);
    case (k)
      5'd2: log2_q8 = 11'd256;   5'd3: log2_q8 = 11'd406;   5'd4: log2_q8 = 11'd512;
      5'd5: log2_q8 = 11'd594;   5'd6: log2_q8 = 11'd662;   5'd7: log2_q8 = 11'd719;
      5'd8: log2_q8 = 11'd768;   5'd9: log2_q8 = 11'd812;   5'd10: log2_q8 = 11'd850;
      5'd11: log2_q8 = 11'd886;  5'd12: log2_q8 = 11'd918;  5'd13: log2_q8 = 11'd947;
      5'd14: log2_q8 = 11'd975;  5'd15: log2_q8 = 11'd1000; 5'd16: log2_q8 = 11'd1024;
      default: log2_q8 = 11'd0;
    endcase
  endfunction
  function automatic logic [16:0] reciprocal(input logic [4:0] k);
    case (k)
      5'd2: reciprocal = 17'd32768;  5'd3: reciprocal = 17'd21845;  5'd4: reciprocal = 17'd16384;
      5'd5: reciprocal = 17'd13107;  5'd6: reciprocal = 17'd10923;  5'd7: reciprocal = 17'd9362;
      5'd8: reciprocal = 17'd8192;   5'd9: reciprocal = 17'd7282;   5'd10: reciprocal = 17'd6554;
      5'd11: reciprocal = 17'd5958;  5'd12: reciprocal = 17'd5461;  5'd13: reciprocal = 17'd5041;
      5'd14: reciprocal = 17'd4681;  5'd15: reciprocal = 17'd4369;  5'd16: reciprocal = 17'd4096;
      default: reciprocal = 17'd65536;
    endcase
  endfunction
  // axis * round(2^16 / k) / 2^16 (a function called inside the enable, like tex_lambda's: a
  // simulator evaluates it only when a derivative request moves)
  function automatic logic signed [DW-1:0] step_of(input logic signed [DW-1:0] axis,
                                                  input logic [4:0] k);
    logic signed [DW+17:0] product;  // 32 x 17 bits, signed
    product = 50'(axis) * $signed({1'b0, reciprocal(k)});
    step_of = 32'(product >>> 16);   // |step| <= |axis|: fits
  endfunction
  always_ff @(posedge clk) begin
    if (en) begin
      n      <= n_s2;
      lambda <= lambda_s2 - $signed({5'd0, log2_q8(n_s2)});
      step_u <= step_of(axis_u_s2, n_s2);
      step_v <= step_of(axis_v_s2, n_s2);
    end
  end

`ifdef FORMAL
  assign f_n_s2 = n_s2;
`endif

  generate
    if (tex_pkg::LOD_W != 16 || tex_pkg::REQ_COORD_W != 32) begin : g_bad_formats
      `TEX_PARAM_ERROR("tex_aniso: built for 16-bit Q8.8 lambda and 32-bit Q8.24 derivatives (tex_pkg)")
    end
  endgenerate
endmodule

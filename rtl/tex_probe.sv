// tex_probe: the request port and the probe sequencer, bit for bit the model's tex_probe
// (model/sampler.cpp, docs/numerics.md stage 1c). A request carries lambda (req_deriv = 0: one
// probe at (u, v, lambda)) or four derivatives (req_deriv = 1: tex_aniso gives lambda', N and the
// spacing; N probes along the major axis, probe i at coord + floor((2i + 1 - N) * step / 2),
// saturated to Q8.24). It issues one probe per clock; a request with N probes holds the request
// port for N - 1 extra clocks, an isotropic one (N = 1) takes 1.
//   clock 1 capture   2-4 tex_aniso (clock 4: the sequencer register, which holds while it issues)
// Handshake: req_valid/req_ready (valid/ready); req_ready = en && !hold is a function of registers
//   only. Downstream stall-enable: the probe on the outputs is taken at every clock edge with en
//   high (probe_valid says whether there is one).
// Latency: 4 clocks from the request handshake edge to its first probe on the outputs (the
//   outputs are combinational on the clock-4 registers). Throughput: 1 probe per clock.
// Ports:
//   req_u, req_v     : signed Q8.24; req_lod: signed Q8.8 (req_deriv = 0)
//   req_bias         : signed Q8.8, the request's own LOD bias (GLSL texture(s, uv, bias)); every
//                      probe of the request carries it (probe_bias), for tex_lod
//   req_dudx .. dvdy : signed Q8.24 texture widths (heights) per pixel (req_deriv = 1)
//   req_w, req_h     : the request's texture's level-0 size (unsigned SIZE_W bits, 1..8192), taken with the request
//   req_max_aniso_m1 : the request's sampler: probes at most less one (0..15); req_aniso_pow2:
//                      probe counts rounded up to powers of two. Taken with the request.
//   probe_u, probe_v : signed Q8.24; probe_lod: signed Q8.8 (lambda', before bias and clamp)
//   probe_first, probe_last : the request's first / last probe; probe_n: its probes, 1..16
module tex_probe #(
  parameter int TAG_W = 16
) (
  input  logic                                   clk,
  input  logic                                   rst,
  input  logic                                   en,
  input  logic                                   req_valid,
  output logic                                   req_ready,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_v,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_bias,
  input  logic                                   req_deriv,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdy,
  input  logic [tex_pkg::SIZE_W-1:0]             req_w,
  input  logic [tex_pkg::SIZE_W-1:0]             req_h,
  input  logic [3:0]                             req_max_aniso_m1,
  input  logic                                   req_aniso_pow2,
  input  logic [TAG_W-1:0]                       req_tag,
  output logic                                   probe_valid,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] probe_u,
  output logic signed [tex_pkg::REQ_COORD_W-1:0] probe_v,
  output logic signed [tex_pkg::LOD_W-1:0]       probe_lod,
  output logic signed [tex_pkg::LOD_W-1:0]       probe_bias,
  output logic                                   probe_first,
  output logic                                   probe_last,
  output logic [4:0]                             probe_n,
  output logic [TAG_W-1:0]                       probe_tag,
  output logic [2:0]                             held       // requests in clocks 1-4 (0..4)
`ifdef FORMAL
  , output logic [4:1]         f_valid                     // the clock-k registers' valid bits
  , output logic [4*TAG_W-1:0] f_tags                      // clock k's tag at [(k-1)*TAG_W +: TAG_W]
`endif
);
  localparam int DW = tex_pkg::REQ_COORD_W;

  logic en_up;  // clocks 1-4 advance: the sequencer issues its request's last probe (or is empty)
  logic hold;   // the sequencer register has probes after this one
  assign en_up = en && !hold;
  assign req_ready = en_up;

  // ---------------------------------------------------------------- clocks 1-4: request registers
  // Clock 1 captures the pins; u, v, lod, the mode and the tag ride along while tex_aniso works.
  logic [4:1]                       valid;
  // One register per clock and field, g_req[k] for clock k (a packed shift register wider than 64
  // bits, or an unpacked array, would cost Verilator a wide copy or a delayed-write shadow in every
  // clock).
  localparam int LW = tex_pkg::LOD_W;
  logic [4:1]                       deriv_q;
  logic signed [DW-1:0]             dudx_s1, dvdx_s1, dudy_s1, dvdy_s1;
  logic [tex_pkg::SIZE_W-1:0]       w_s1, h_s1;            // the texture's size, for tex_aniso's clock 1
  logic [3:0]                       max_aniso_m1_s1;       // and the sampler's cap
  logic                             pow2_s1;
  always_ff @(posedge clk) begin
    if (rst) valid <= '0;
    else if (en_up) valid <= {valid[3:1], req_valid};
    if (en_up) begin
      deriv_q    <= {deriv_q[3:1], req_deriv};
      dudx_s1    <= req_dudx;
      dvdx_s1    <= req_dvdx;
      dudy_s1    <= req_dudy;
      dvdy_s1    <= req_dvdy;
      w_s1       <= req_w;
      h_s1       <= req_h;
      max_aniso_m1_s1 <= req_max_aniso_m1;
      pow2_s1    <= req_aniso_pow2;
    end
  end
  genvar k;
  generate
    for (k = 1; k <= 4; k = k + 1) begin : g_req
      logic signed [DW-1:0] u, v;
      logic signed [LW-1:0] lod, bias;
      logic [TAG_W-1:0]     tag;
      if (k == 1) begin : g_capture
        always_ff @(posedge clk)
          if (en_up) begin
            u    <= req_u;
            v    <= req_v;
            lod  <= req_lod;
            bias <= req_bias;
            tag  <= req_tag;
          end
      end else begin : g_shift
        always_ff @(posedge clk)
          if (en_up) begin
            u    <= g_req[k-1].u;
            v    <= g_req[k-1].v;
            lod  <= g_req[k-1].lod;
            bias <= g_req[k-1].bias;
            tag  <= g_req[k-1].tag;
          end
      end
    end
  endgenerate

  logic [4:0]           aniso_n;
  logic                 aniso_en;  // tex_aniso advances only with a derivative request in it: its
  assign aniso_en = en_up && (deriv_q[1] || deriv_q[2] || deriv_q[3]);  // logic then rests
`ifdef FORMAL
  logic [4:0]           f_aniso_n_s2;
`endif
  logic signed [15:0]   aniso_lambda;
  logic signed [DW-1:0] step_u, step_v;
  tex_aniso u_aniso (
    .clk(clk), .en(aniso_en), .dudx(dudx_s1), .dvdx(dvdx_s1), .dudy(dudy_s1), .dvdy(dvdy_s1),
    .w(w_s1), .h(h_s1), .max_aniso_m1(max_aniso_m1_s1), .pow2(pow2_s1),
    .n(aniso_n), .lambda(aniso_lambda), .step_u(step_u), .step_v(step_v)
`ifdef FORMAL
    , .f_n_s2(f_aniso_n_s2)
`endif
  );

  // ---------------------------------------------------------------- the sequencer (clock 4)
  logic [3:0] index;  // the probe on the outputs, 0..n - 1
  logic [4:0] n;
  assign n = deriv_q[4] ? aniso_n : 5'd1;
  assign hold = valid[4] && {1'b0, index} != n - 5'd1;
  always_ff @(posedge clk) begin
    if (rst) index <= '0;
    else if (en_up) index <= '0;
    else if (en) index <= index + 4'd1;
  end

  // Probe index: coord + floor((2i + 1 - n) * step / 2), saturated to the Q8.24 range.
  logic signed [5:0]    position;  // 2i + 1 - n: -15..15
  logic signed [DW+5:0] offset_u, offset_v;
  logic signed [DW+6:0] sum_u, sum_v;
  function automatic logic signed [DW-1:0] saturate(input logic signed [DW+6:0] x);
    if (x > 39'sh007FFFFFFF) saturate = 32'sh7FFFFFFF;
    else if (x < -39'sh0080000000) saturate = -32'sh80000000;
    else saturate = x[DW-1:0];
  endfunction
  // Only a derivative request has offsets (a lambda request's probe is its coordinates; its
  // derivative pins, and so the steps, are don't-care): a simulator skips the multiplies otherwise.
  always_comb begin
    {position, offset_u, offset_v, sum_u, sum_v} = '0;
    probe_u = g_req[4].u;
    probe_v = g_req[4].v;
    if (deriv_q[4]) begin
      position = $signed({1'b0, index, 1'b1}) - $signed({1'b0, n});
      offset_u = (38'(position) * 38'(step_u)) >>> 1;
      offset_v = (38'(position) * 38'(step_v)) >>> 1;
      sum_u    = 39'($signed(g_req[4].u)) + 39'(offset_u);
      sum_v    = 39'($signed(g_req[4].v)) + 39'(offset_v);
      probe_u  = saturate(sum_u);
      probe_v  = saturate(sum_v);
    end
  end
  assign probe_valid = valid[4];
  assign probe_lod   = deriv_q[4] ? aniso_lambda : g_req[4].lod;
  assign probe_bias  = g_req[4].bias;
  assign probe_first = index == 4'd0;
  assign probe_last  = !hold;
  assign probe_n     = n;
  assign probe_tag   = g_req[4].tag;
  assign held        = 3'(valid[1]) + 3'(valid[2]) + 3'(valid[3]) + 3'(valid[4]);

`ifdef FORMAL
  assign f_valid = valid;
  assign f_tags  = {g_req[4].tag, g_req[3].tag, g_req[2].tag, g_req[1].tag};
  // The probe index is 0 except while a request with derivatives issues its probes.
  logic f_reset_done = 1'b0;
  always_ff @(posedge clk) if (rst) f_reset_done <= 1'b1;
  // A derivative request's probe count is 1..16 from tex_aniso's clock 2 on, and the sequencer's
  // index stays below it (the sequencer neither wraps nor restarts a request).
  always_comb
    if (f_reset_done) begin
      assert (index == 4'd0 || (valid[4] && deriv_q[4]));
      if (valid[3] && deriv_q[3]) assert (f_aniso_n_s2 >= 5'd1 && f_aniso_n_s2 <= 5'd16);
      if (valid[4] && deriv_q[4]) assert (aniso_n >= 5'd1 && aniso_n <= 5'd16 && 5'(index) < aniso_n);
    end
`endif
endmodule

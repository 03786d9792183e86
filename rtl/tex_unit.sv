// tex_unit: the mip-mapping texture unit (Williams 1983), bit-exact to docs/numerics.md.
// Interface contract: docs/rtl-interface.md. Architecture and resources: docs/rtl.md.
//
// Handshake: req and rsp are valid/ready. req_ready is a register output (the skid buffer's
//   !full): it never depends combinationally on rsp_ready or req_valid. Responses come in request
//   order with their tag; nothing is lost or duplicated. Writes (wr_*) are always accepted.
// Latency: LATENCY = 16 clocks (16 registers): a request accepted in cycle t (req_valid &&
//   req_ready at the rising edge ending cycle t) has rsp_valid high in cycle t + 16 if the output
//   was not stalled and the request has one probe; each further probe adds a clock. Stall-enable
//   pipeline: every stage advances together when the skid buffer can take an item (clocks 1-4
//   also wait while tex_probe issues a request's probes); only the valid bits are reset.
// Throughput: 1 probe per clock sustained (8 texel reads per clock: a 2x2 footprint in each of
//   levels d and d1): 1 sample per clock for lambda requests and isotropic footprints, 1 per N
//   clocks for an anisotropic sample of N probes; under backpressure the unit adds no bubbles.
// Ports (see docs/rtl-interface.md): req_u, req_v signed Q8.24; req_lod, req_bias (the request's
//   own LOD bias, added to the sampler's: GLSL texture(s, uv, bias)), cfg_smp_lod_bias,
//   req_op what the request asks (tex_pkg::OP_*): OP_SAMPLE a filtered sample, OP_FETCH texelFetch
//   (req_u, req_v, req_lod the signed integers i, j and level; req_deriv 0; the texel, or 0 where
//   there is none: tex_front), OP_GATHER textureGather (req_component 0..3 of the four texels a
//   linear filter weighs at level 0, in GL's order as R, G, B, A: tex_front, tex_filter),
//   OP_COMPARE a depth compare (each texel's R tested `req_ref OP R` by cfg_smp_compare_op, then
//   filtered: tex_compare_ref, tex_filter); req_ref signed Q8.24 (1.0 = 2^24);
//   cfg_smp_min_lod, cfg_smp_max_lod signed Q8.8; req_deriv selects req_lod (0) or the derivatives
//   req_dudx, req_dvdx, req_dudy, req_dvdy (1, signed Q8.24 texture widths per pixel);
//   cfg_smp_max_aniso_m1 the probes per sample at most less one (0..15; 0 = trilinear),
//   cfg_smp_aniso_pow2 probe counts rounded up to powers of two; cfg_smp_min_linear the minification
//   filter's texel filter, cfg_smp_mag_linear the magnification filter (where lambda' <= 0);
//   cfg_smp_unnormalized req_u, req_v are signed Q16.16 texels of level 0 (Vulkan's
//   unnormalizedCoordinates; with clamp-to-edge or -border modes, one texel filter, no
//   anisotropy, the base level only: the driver checks);
//   cfg_smp_reduction how the filter combines its taps (tex_pkg::REDUCE_*: the weighted average,
//   or the component-wise min or max of the taps it weighs above 0, both levels and every probe);
//   cfg_smp_border_rgba the border colour of address mode border, {A, B, G, R} unorm16; wr_data, rsp_rgba {A, B, G, R} CW-bit unsigned;
//   cfg_w, cfg_h the texture's size, unsigned SIZE_W bits, 1..2^MAX_LOG2_W (2^MAX_LOG2_H), any
//   value (GL's level sizes; a side that is not a power of two is loaded with its repeat seam's
//   copy of texel column (row) 0 at index w (h) of every level: docs/numerics.md stage 3);
//   cfg_last_level the texture's last level (its level count - 1; a chain may stop before 1x1:
//   a view's max level), unsigned LEVEL_W bits;
//   wr_level, wr_x, wr_y unsigned integers.
// Inputs are only ever registered: no logic depends combinationally on an input pin.
//   cfg_* are taken with each request (in tex_probe and tex_front; the border colour and the
//   reduction registered every clock) and must be static while requests are in flight. The cfg_smp_* pins are the
//   unit's one sampler: the fields of an entry of tex_unit_cached's sampler table.
//   wr_* are registered (wr_*_q) and written one clock later: a texel on the write pins in cycle
//   t is in its memory from cycle t + 2 on, and is seen by every request accepted in cycle t - 6
//   or later (the memories are read in a probe's clock 5, the request's clock 9 for its first).
//
// Pipeline (register at the end of each clock; names carry _s<clock> counted from a probe's
// capture in tex_front, docs/rtl.md):
//   request 1-4 tex_probe (capture, tex_aniso: lambda, N, steps; the sequencer issues probes)
//   probe   1 capture (u_s1, v_s1, lod_s1)  2 tex_lod clamp, tex_reduce  3 tex_lod level select
//   (slots: 0 = level d, 1 = level d1)  4 tex_scale and tex_address per slot and axis  5 tex_wrap
//   (combinational); tex_fetch: the memories of levels d and d1 read (4 banks each)
//   6 tex_fetch: bank words -> 8 taps  7 top/bot lerps  8 bilinear lerps  9 level blend
//   10 tex_accum: sum of the probes  11 mean and rounding  12 tex_skid (output register)
`include "tex_param_error.svh"
module tex_unit #(
  parameter int MAX_LOG2_W = 10,  // largest texture: 2^MAX_LOG2_W x 2^MAX_LOG2_H (any size up to it), each 0..11
  parameter int MAX_LOG2_H = 10,
  parameter int CW         = 8,   // bits per channel, 1..16
  parameter int TAG_W      = 16   // >= 1
) (
  input  logic                                   clk,
  input  logic                                   rst,

  input  logic [tex_pkg::SIZE_W-1:0]             cfg_w,
  input  logic [tex_pkg::SIZE_W-1:0]             cfg_h,
  input  logic [tex_pkg::LEVEL_W-1:0]            cfg_last_level,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_smp_wrap_u,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_smp_wrap_v,
  input  logic                                   cfg_smp_min_linear,
  input  logic                                   cfg_smp_mag_linear,
  input  logic [tex_pkg::MIP_W-1:0]              cfg_smp_mip_mode,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_lod_bias,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_min_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_max_lod,
  input  logic [3:0]                             cfg_smp_max_aniso_m1,
  input  logic                                   cfg_smp_aniso_pow2,
  input  logic [63:0]                            cfg_smp_border_rgba,
  input  logic                                   cfg_smp_unnormalized,
  input  logic [tex_pkg::REDUCTION_W-1:0]        cfg_smp_reduction,
  input  logic [tex_pkg::COMPARE_W-1:0]          cfg_smp_compare_op,

  input  logic                                   wr_en,
  input  logic [tex_pkg::LEVEL_W-1:0]            wr_level,
  input  logic [tex_pkg::COORD_W-1:0]            wr_x,
  input  logic [tex_pkg::COORD_W-1:0]            wr_y,
  input  logic [4*CW-1:0]                        wr_data,

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
  input  logic [tex_pkg::OP_W-1:0]               req_op,
  input  logic [1:0]                             req_component,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_ref,
  input  logic [TAG_W-1:0]                       req_tag,

  output logic                                   rsp_valid,
  input  logic                                   rsp_ready,
  output logic [4*CW-1:0]                        rsp_rgba,
  output logic [TAG_W-1:0]                       rsp_tag
);
  localparam int LATENCY = 16;     // request handshake edge to response (one probe)
  localparam int NSTAGE  = 9;      // probe pipeline registers from tex_front to tex_filter
  localparam int PRE     = 4;      // tex_probe's request registers
  localparam int POST    = 2;      // tex_accum's registers
  localparam int VW = tex_pkg::LEVEL_W;
  localparam int WB = tex_pkg::WEIGHT_BITS;

  // ---------------------------------------------------------------- parameter checks
  // (The datapath is elaborated with the parameters clamped into range, so that a bad value stops
  // the tools with the message below, not with an error deep inside the datapath.)
  localparam int MLW = (MAX_LOG2_W < 0) ? 0 : (MAX_LOG2_W > tex_pkg::MAX_LOG2_ONCHIP)
                       ? tex_pkg::MAX_LOG2_ONCHIP : MAX_LOG2_W;
  localparam int MLH = (MAX_LOG2_H < 0) ? 0 : (MAX_LOG2_H > tex_pkg::MAX_LOG2_ONCHIP)
                       ? tex_pkg::MAX_LOG2_ONCHIP : MAX_LOG2_H;
  localparam int CWD = (CW < 1) ? 1 : (CW > tex_pkg::MAX_CW) ? tex_pkg::MAX_CW : CW;
  localparam int TGW = (TAG_W < 1) ? 1 : TAG_W;
  localparam int XW  = (MLW > 0) ? MLW : 1;  // wrapped index bits (level 0's)
  localparam int YW  = (MLH > 0) ? MLH : 1;
  generate
    if (MAX_LOG2_W < 0 || MAX_LOG2_W > tex_pkg::MAX_LOG2_ONCHIP) begin : g_bad_max_log2_w
      `TEX_PARAM_ERROR("tex_unit: parameter MAX_LOG2_W must be in 0..11 (tex_pkg::MAX_LOG2_ONCHIP)")
    end
    if (MAX_LOG2_H < 0 || MAX_LOG2_H > tex_pkg::MAX_LOG2_ONCHIP) begin : g_bad_max_log2_h
      `TEX_PARAM_ERROR("tex_unit: parameter MAX_LOG2_H must be in 0..11 (tex_pkg::MAX_LOG2_ONCHIP)")
    end
    if (CW < 1 || CW > tex_pkg::MAX_CW) begin : g_bad_cw
      `TEX_PARAM_ERROR("tex_unit: parameter CW must be in 1..16 (tex_pkg::MAX_CW)")
    end
    if (TAG_W < 1) begin : g_bad_tag_w
      `TEX_PARAM_ERROR("tex_unit: parameter TAG_W must be at least 1")
    end
    if (LATENCY != PRE + NSTAGE + POST + 1) begin : g_bad_latency  // (the header's figure)
      `TEX_PARAM_ERROR("tex_unit: LATENCY is not the registers a one-probe request passes")
    end
  endgenerate

  // ---------------------------------------------------------------- control: valid bits, enable
  logic en;                        // every stage advances (the skid buffer has room)
  logic [NSTAGE:1] valid;          // valid[n]: the clock-n register holds a probe

  // ---------------------------------------------------------------- requests 1-4: tex_probe
  logic                                   probe_valid, probe_first, probe_last;
  logic [4:0]                             probe_n;
  logic signed [tex_pkg::REQ_COORD_W-1:0] probe_u, probe_v;
  logic signed [tex_pkg::LOD_W-1:0]       probe_lod, probe_bias;
  logic [TGW-1:0]                         probe_tag;
  logic [tex_pkg::OP_W-1:0]               probe_op;    // (ride in tex_probe's tag, above req_tag)
  logic [1:0]                             probe_component;
  logic [CWD-1:0]                         probe_ref;   // a depth compare's reference code
  logic [2:0]                             probe_held;  // requests in tex_probe
  localparam int PTW = TGW + tex_pkg::OP_W + 2 + CWD;
  logic [CWD-1:0] req_ref_code;  // (at the port: CW bits ride where the 32-bit reference would)
  tex_compare_ref #(.CW(CWD)) u_compare_ref (.dref(req_ref), .code(req_ref_code));
`ifdef FORMAL
  logic [4:1]                             f_probe_valid;
  logic [4*PTW-1:0]                       f_probe_tags;
`endif
  tex_probe #(.TAG_W(PTW)) u_probe (
    .clk(clk), .rst(rst), .en(en),
    .req_valid(req_valid), .req_ready(req_ready), .req_u(req_u), .req_v(req_v), .req_lod(req_lod),
    .req_bias(req_bias),
    .req_deriv(req_deriv), .req_dudx(req_dudx), .req_dvdx(req_dvdx), .req_dudy(req_dudy),
    .req_dvdy(req_dvdy), .req_w(cfg_w), .req_h(cfg_h),
    .req_max_aniso_m1(cfg_smp_max_aniso_m1), .req_aniso_pow2(cfg_smp_aniso_pow2), .req_tag({req_ref_code, req_component, req_op, req_tag}),
    .probe_valid(probe_valid), .probe_u(probe_u), .probe_v(probe_v), .probe_lod(probe_lod), .probe_bias(probe_bias),
    .probe_first(probe_first), .probe_last(probe_last), .probe_n(probe_n), .probe_tag({probe_ref, probe_component, probe_op, probe_tag}),
    .held(probe_held)
`ifdef FORMAL
    , .f_valid(f_probe_valid), .f_tags(f_probe_tags)
`endif
  );

  always_ff @(posedge clk) begin
    if (rst) valid <= '0;
    else if (en) valid <= {valid[NSTAGE-1:1], probe_valid};
  end

  // g_tag[n].tag: the tag of the probe in the clock-n register, with its place in the sample
  // {n, last, first} and, above, whether it is a gather and of which component, whether a depth
  // compare and its reference code (for tex_filter) (it rides along, not reset).
  localparam int SW = TGW + 11 + CWD;
  logic [NSTAGE:1] last;           // last[n]: the clock-n probe is its sample's last
  genvar n;
  generate
    for (n = 1; n <= NSTAGE; n = n + 1) begin : g_tag
      logic [SW-1:0] tag;
      assign last[n] = tag[TGW+1];
      if (n == 1) begin : g_capture
        always_ff @(posedge clk)
          if (en) tag <= {probe_ref, probe_op == tex_pkg::OP_COMPARE, probe_component, probe_op == tex_pkg::OP_GATHER,
                          probe_n, probe_last, probe_first, probe_tag};
      end else begin : g_shift
        always_ff @(posedge clk) if (en) tag <= g_tag[n-1].tag;
      end
    end
  endgenerate

  // ---------------------------------------------------------------- input registers
  // wr_*: tex_fetch writes the memories from these copies, one clock later. The texel and its
  // coordinates are loaded only with a write (wr_en_q says whether they are one).
  logic                         wr_en_q;
  logic [VW-1:0]                wr_level_q;
  logic [tex_pkg::COORD_W-1:0]  wr_x_q, wr_y_q;
  logic [4*CWD-1:0]             wr_data_q;
  always_ff @(posedge clk) begin
    wr_en_q <= wr_en;
    if (wr_en) begin
      wr_level_q <= wr_level;
      wr_x_q     <= wr_x;
      wr_y_q     <= wr_y;
      wr_data_q  <= wr_data;
    end
  end

  // ---------------------------------------------------------------- clocks 1-4: tex_front
  // lod, scale, address (clock-4 registers) and wrap (combinational, into tex_fetch).
  logic [2*VW-1:0] level_s4;           // slot s at [s*VW +: VW]: slot 0 = d, slot 1 = d1
  logic [WB-1:0]   f_s4, f_s5, f_s6;
  logic [4*WB-1:0] w_s4, w_s5, w_s6;   // slot s axis a weight at [(s*2 + a)*WB +: WB]
  logic [4*tex_pkg::SIZE_W-1:0] size_s4;  // (the level memories have fixed strides: unused)
  logic [4*XW-1:0] x;                  // wrapped x taps: slot s tap j at [(s*2 + j)*XW +: XW]
  logic [4*YW-1:0] y;
  logic [3:0]      border_x, border_y;  // slot s tap j at [s*2 + j]: outside the level (border)
  logic [3:0]      border_x_s5, border_y_s5, border_x_s6, border_y_s6;
  logic            zero_s4;            // a texel fetch that reads nothing: its blend is 0
  logic [9:5]      zero_q;             // zero_s4 at clocks 5..9
  tex_front #(.XW(XW), .YW(YW)) u_front (
    .clk(clk), .en(en), .req_u(probe_u), .req_v(probe_v), .req_lod(probe_lod), .req_bias(probe_bias),
    .req_w(cfg_w), .req_h(cfg_h), .req_last_level(cfg_last_level), .req_wrap_u(cfg_smp_wrap_u),
    .req_wrap_v(cfg_smp_wrap_v), .req_min_linear(cfg_smp_min_linear), .req_mag_linear(cfg_smp_mag_linear),
    .req_mip_mode(cfg_smp_mip_mode), .req_lod_bias(cfg_smp_lod_bias), .req_min_lod(cfg_smp_min_lod),
    .req_max_lod(cfg_smp_max_lod), .req_unnormalized(cfg_smp_unnormalized),
    .req_fetch(probe_op == tex_pkg::OP_FETCH), .req_gather(probe_op == tex_pkg::OP_GATHER), .req_footprint(8'h11), .req_cube(1'b0),
    .level(level_s4), .f(f_s4), .w(w_s4), .size(size_s4), .x(x), .y(y),
    .border_x(border_x), .border_y(border_y), .zero(zero_s4)
  );
  logic [4*tex_pkg::SIZE_W-1:0] size_unused;
  assign size_unused = size_s4;  // (*_unused: likewise)

  always_ff @(posedge clk) begin
    if (en) begin
      f_s5 <= f_s4;
      w_s5 <= w_s4;
      f_s6 <= f_s5;
      w_s6 <= w_s5;
      border_x_s5 <= border_x;
      border_y_s5 <= border_y;
      border_x_s6 <= border_x_s5;
      border_y_s6 <= border_y_s5;
      zero_q      <= {zero_q[8:5], zero_s4};
    end
  end

  // ---------------------------------------------------------------- clocks 5-6: fetch
  logic [32*CWD-1:0] taps_s6;  // slot s tap t at [(s*4 + t)*4*CW +: 4*CW]
  tex_fetch #(.MAX_LOG2_W(MLW), .MAX_LOG2_H(MLH), .CW(CWD)) u_fetch (
    .clk(clk), .en(en),
    .wr_en(wr_en_q), .wr_level(wr_level_q), .wr_x(wr_x_q), .wr_y(wr_y_q), .wr_data(wr_data_q),
    .level(level_s4), .x(x), .y(y), .taps(taps_s6)
  );

  // Address mode border: a tap outside its level takes the border colour, before the filter
  // (model BankedMipMemory::fetch). Tap t of a slot is (x_(t & 1), y_(t >> 1)).
  // The colour is static: the pin is registered, converted, and the result registered again, so
  // that the conversion's adders are not in front of the filter in one clock (Fmax).
  logic [63:0]       cfg_border_q;
  logic [4*CWD-1:0]  border_next, border_rgba;  // in the filter's channel width (tex_border)
  logic [32*CWD-1:0] taps_b_s6;
  tex_border #(.CW(CWD)) u_border (.rgba16(cfg_border_q), .rgba(border_next));
  logic [tex_pkg::REDUCTION_W-1:0] cfg_reduction_q;  // (the filter's and tex_accum's)
  logic [tex_pkg::COMPARE_W-1:0]   cfg_compare_q;    // (the filter's)
  always_ff @(posedge clk) begin
    cfg_border_q    <= cfg_smp_border_rgba;
    border_rgba     <= border_next;
    cfg_reduction_q <= cfg_smp_reduction;
    cfg_compare_q   <= cfg_smp_compare_op;
  end
  always_comb begin
    for (int t = 0; t < 8; t++) begin
      if (border_x_s6[(t / 4) * 2 + (t % 2)] || border_y_s6[(t / 4) * 2 + (t % 4) / 2])
        taps_b_s6[t*4*CWD +: 4*CWD] = border_rgba;
      else
        taps_b_s6[t*4*CWD +: 4*CWD] = taps_s6[t*4*CWD +: 4*CWD];
    end
  end

  // ---------------------------------------------------------------- clocks 7-9: filter
  logic [4*(CWD+24)-1:0] blend_s9;
  tex_filter #(.CW(CWD)) u_filter (
    .clk(clk), .en(en), .taps(taps_b_s6), .w(w_s6), .f(f_s6), .reduction(cfg_reduction_q),
    .gather(g_tag[6].tag[TGW+7]), .component(g_tag[6].tag[TGW+8 +: 2]), .depth_test(g_tag[6].tag[TGW+10]),
    .compare_op(cfg_compare_q), .dref(g_tag[6].tag[TGW+11 +: CWD]), .blend(blend_s9)
  );

  // ---------------------------------------------------------------- clocks 10-11: tex_accum
  logic             sample_valid;
  logic [4*CWD-1:0] rgba_s11;
  logic [TGW-1:0]   tag_s11;
  logic             accum_held;  // tex_accum's clock 1 holds a sample's last probe
`ifdef FORMAL
  logic             f_accum_valid;
  logic [TGW-1:0]   f_accum_tag;
`endif
  tex_accum #(.CW(CWD), .SIDE_W(TGW)) u_accum (
    .clk(clk), .rst(rst), .en(en), .in_valid(valid[NSTAGE]),
    .in_first(g_tag[NSTAGE].tag[TGW]), .in_last(g_tag[NSTAGE].tag[TGW+1]),
    .in_n(g_tag[NSTAGE].tag[TGW+2 +: 5]), .in_reduction(cfg_reduction_q), .in_zero(zero_q[9]), .blend(blend_s9), .in_side(g_tag[NSTAGE].tag[TGW-1:0]),
    .out_valid(sample_valid), .rgba(rgba_s11), .out_side(tag_s11), .held(accum_held)
`ifdef FORMAL
    , .f_valid_s1(f_accum_valid), .f_side_s1(f_accum_tag)
`endif
  );

  // ---------------------------------------------------------------- clock 12: skid buffer
`ifdef FORMAL
  logic [TGW+4*CWD-1:0] f_skid_data;  // the skid entry {tag, rgba} (formal properties, below)
`endif
  tex_skid #(.W(TGW + 4*CWD)) u_skid (
    .clk(clk), .rst(rst),
    .in_valid(sample_valid), .in_ready(en), .in_data({tag_s11, rgba_s11}),
    .out_valid(rsp_valid), .out_ready(rsp_ready), .out_data({rsp_tag, rsp_rgba})
`ifdef FORMAL
    , .f_skid_data(f_skid_data)
`endif
  );

`ifndef SYNTHESIS
  // ---------------------------------------------------------------- simulation checks
  // (Verilator --assert; a failure stops the simulation.)
  // Requests in flight = accepted minus answered (reset empties the unit). rsp_valid is low
  // whenever nothing is in flight, so the count never goes below 0 (no response without a
  // request); it never exceeds the 4 request registers, 9 + 2 probe registers and 2 skid
  // entries; and it always equals the requests the unit holds (tex_probe's valid bits, the probe
  // registers holding a sample's last probe, output register, skid entry = !en): nothing is lost
  // or duplicated.
  localparam int CAPACITY = PRE + NSTAGE + POST + 2;
  localparam int FW = $clog2(CAPACITY + 2);
  // (Everything below reads the input pins only at the clock edge: no combinational logic on them.)
  logic [FW-1:0] in_flight, held;
  logic [NSTAGE:1] chain_last;  // the probe registers holding a sample's last probe
  assign chain_last = valid & last;
  always_comb begin
    // (a loop, not $countones: Icarus 11 leaves a system function's arguments out of an
    // always_comb's sensitivity, and `held` went stale)
    held = FW'(probe_held) + FW'(accum_held) + FW'(sample_valid) + FW'(rsp_valid) + FW'(!en);
    for (int i = 1; i <= NSTAGE; i++) held = held + FW'(chain_last[i]);
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      in_flight <= '0;
    end else begin
      assert (in_flight != '0 || !rsp_valid)
        else $error("tex_unit: rsp_valid high with no request in flight");
      assert (in_flight <= FW'(CAPACITY))
        else $error("tex_unit: more requests in flight than the pipeline and skid buffer hold");
      assert (in_flight == held)
        else $error("tex_unit: requests in flight differ from the requests the pipeline holds");
      in_flight <= in_flight + FW'(req_valid && req_ready) - FW'(rsp_valid && rsp_ready);
    end
  end

  // Handshake rules: a valid is held until ready, and the payload is stable meanwhile, on both
  // channels.
  logic                                   req_stalled_q, rsp_stalled_q;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u_q, req_v_q;
  logic signed [tex_pkg::LOD_W-1:0]       req_lod_q, req_bias_q;
  logic [4*tex_pkg::REQ_COORD_W:0]        req_deriv_q;  // {req_deriv, dudx, dvdx, dudy, dvdy}
  logic [TAG_W-1:0]                       req_tag_q, rsp_tag_q;
  logic [tex_pkg::OP_W-1:0]               req_op_q;
  logic [1:0]                             req_component_q;
  logic [tex_pkg::REQ_COORD_W-1:0]        req_ref_q;
  logic [4*CW-1:0]                        rsp_rgba_q;
  // (The payload copies are taken only in a stalled cycle, the only time they are compared.)
  always_ff @(posedge clk) begin
    req_stalled_q <= !rst && req_valid && !req_ready;
    rsp_stalled_q <= !rst && rsp_valid && !rsp_ready;
    if (req_valid && !req_ready) begin
      req_u_q   <= req_u;
      req_v_q   <= req_v;
      req_lod_q <= req_lod;
      req_bias_q <= req_bias;
      req_tag_q <= req_tag;
      req_op_q  <= req_op;
      req_component_q <= req_component;
      req_ref_q <= req_ref;
      req_deriv_q <= {req_deriv, req_dudx, req_dvdx, req_dudy, req_dvdy};
    end
    if (rsp_valid && !rsp_ready) begin
      rsp_tag_q  <= rsp_tag;
      rsp_rgba_q <= rsp_rgba;
    end
    if (!rst && req_stalled_q) begin
      assert (req_valid && req_u == req_u_q && req_v == req_v_q && req_lod == req_lod_q && req_bias == req_bias_q
              && req_tag == req_tag_q && req_op == req_op_q && req_component === req_component_q  // (don't-care but with a gather)
              && req_ref === req_ref_q  // (don't-care but with a compare)
              // (=== : a lambda request's derivative pins are don't-care, X in the 4-state run)
              && {req_deriv, req_dudx, req_dvdx, req_dudy, req_dvdy} === req_deriv_q)
        else $error("tex_unit: req_valid dropped or request changed while req_ready was low");
    end
    if (!rst && rsp_stalled_q) begin
      assert (rsp_valid && rsp_tag == rsp_tag_q && rsp_rgba == rsp_rgba_q)
        else $error("tex_unit: rsp_valid dropped or response changed while rsp_ready was low");
    end
    if (!rst && req_valid)
      assert (req_op == tex_pkg::OP_SAMPLE || req_op == tex_pkg::OP_COMPARE
              || ((req_op == tex_pkg::OP_FETCH || req_op == tex_pkg::OP_GATHER) && !req_deriv))
        else $error("tex_unit: req_op %0d with req_deriv %0d is not an operation of this unit", req_op, req_deriv);
  end
`endif

`ifdef FORMAL
  // ---------------------------------------------------------------- formal properties
  // Proven by scripts/formal.sh (k-induction, Yosys) in a small configuration; the handshake
  // logic is the same in all. They hold from the first reset on, for any inputs (rsp_ready, the
  // request, configuration and write pins free in every clock), also with a reset in mid-traffic.
  // Items in flight, oldest first: the output register (rsp_valid), the skid entry (!en), then
  // the pipeline registers valid[NSTAGE] down to valid[1]. The tracked request: the f_pick-th
  // accepted (mod 32; f_pick any constant), its tag taken when it is accepted.
  localparam int F_CAPACITY = LATENCY + 1;  // 4 + 9 + 2 registers + the 2 skid entries
  localparam int FN = 5;                    // counter bits: 2^FN > F_CAPACITY + 1

  function automatic logic [FN-1:0] f_count(input logic [NSTAGE:1] v);  // bits set
    f_count = '0;
    for (int i = 1; i <= NSTAGE; i++) f_count = f_count + FN'(v[i]);
  endfunction

  logic          f_reset_done = 1'b0;  // a reset has been applied (the valid bits are defined)
  logic [FN-1:0] f_held;               // requests accepted minus responses emitted since reset
  logic [FN-1:0] f_emitted;            // responses emitted since the reset, mod 2^FN
  (* anyconst *) logic [FN-1:0] f_pick;
  logic [TGW-1:0] f_pick_tag;
  logic [FN-1:0] f_pos;                // the tracked request's place in the order above
  logic          f_stalled_q;          // rsp_valid && !rsp_ready in the previous cycle, no reset
  logic [TGW-1:0] f_tag_q;
  logic [4*CW-1:0] f_rgba_q;
  logic          f_in_take, f_out_take;
  logic [FN-1:0] f_after_accum;        // requests ahead of tex_accum's clock-1 register
  logic [FN-1:0] f_after_chain;        // requests ahead of tex_probe's clock-4 register

  assign f_in_take  = req_valid && req_ready;
  assign f_out_take = rsp_valid && rsp_ready;
  assign f_pos      = f_pick - f_emitted;
  assign f_after_accum = FN'(rsp_valid) + FN'(!en) + FN'(sample_valid);
  assign f_after_chain = f_after_accum + FN'(accum_held) + f_count(valid & last);
  always_ff @(posedge clk) begin
    f_stalled_q <= !rst && rsp_valid && !rsp_ready;
    f_tag_q     <= rsp_tag;
    f_rgba_q    <= rsp_rgba;
    // (a request accepted now is number f_emitted + f_held: it is f_pick when f_pos == f_held)
    if (f_in_take && f_pos == f_held) f_pick_tag <= req_tag;
    if (rst) begin
      f_reset_done <= 1'b1;
      f_held       <= '0;
      f_emitted    <= '0;
    end else begin
      f_held    <= f_held + FN'(f_in_take) - FN'(f_out_take);
      f_emitted <= f_emitted + FN'(f_out_take);
    end
  end

  always_comb begin
    if (f_reset_done) begin
      // capacity: in flight = the requests the unit holds, at most F_CAPACITY
      assert (f_held == f_after_chain + FN'(probe_held));
      assert (en || rsp_valid);
      assert (f_held <= FN'(F_CAPACITY));
      // order: the tracked request is answered as the f_pick-th response, with its tag (none
      // lost, duplicated or reordered); until then its tag is in the register at place f_pos
      // (every probe of a request carries its tag)
      if (rsp_valid && f_pos == FN'(0)) assert (rsp_tag == f_pick_tag);
      if (!en && f_pos == FN'(1)) assert (f_skid_data[4*CWD +: TGW] == f_pick_tag);
      if (sample_valid && f_pos == FN'(rsp_valid) + FN'(!en)) assert (tag_s11 == f_pick_tag);
      if (f_accum_valid && f_pos == f_after_accum) assert (f_accum_tag == f_pick_tag);
      // (the probes after a partial sum, and after the sequencer's first probe: see g_f_stage)
      if (f_accum_valid && !accum_held)
        assert (valid[NSTAGE] && !g_tag[NSTAGE].tag[TGW] && g_tag[NSTAGE].tag[TGW-1:0] == f_accum_tag);
      if (probe_valid && !probe_first)
        assert (valid[1] && !last[1] && g_tag[1].tag[TGW-1:0] == probe_tag);
      // hold: a stalled response stays valid with the same tag and texel
      if (f_stalled_q) assert (rsp_valid && rsp_tag == f_tag_q && rsp_rgba == f_rgba_q);
    end
  end
  generate
    for (n = 1; n <= NSTAGE; n = n + 1) begin : g_f_stage
      // requests ahead of the probe in the clock-n register: tex_accum on, later registers'
      // last probes (a request's earlier probes belong to it)
      logic [FN-1:0] ahead;
      assign ahead = f_after_accum + FN'(accum_held) + f_count((valid & last) >> n);
      always_comb
        if (f_reset_done && valid[n] && f_pos == ahead) assert (g_tag[n].tag[TGW-1:0] == f_pick_tag);
      // a sample's probes are contiguous: one that is not its sample's last has the next probe
      // of the same request one register behind it, one that is not its first the previous one
      // ahead of it (in tex_accum's clock-1 register after the last stage)
      logic           behind_valid, behind_first, ahead_valid, ahead_last;
      logic [TGW-1:0] behind_tag, ahead_tag;
      if (n == 1) begin : g_behind_probe
        assign {behind_valid, behind_first, behind_tag} = {probe_valid, probe_first, probe_tag};
      end else begin : g_behind_stage
        assign {behind_valid, behind_first, behind_tag} =
          {valid[n-1], g_tag[n-1].tag[TGW], g_tag[n-1].tag[TGW-1:0]};
      end
      if (n == NSTAGE) begin : g_ahead_accum
        assign {ahead_valid, ahead_last, ahead_tag} = {f_accum_valid, accum_held, f_accum_tag};
      end else begin : g_ahead_stage
        assign {ahead_valid, ahead_last, ahead_tag} =
          {valid[n+1], last[n+1], g_tag[n+1].tag[TGW-1:0]};
      end
      always_comb
        if (f_reset_done && valid[n]) begin
          if (!last[n])
            assert (behind_valid && !behind_first && behind_tag == g_tag[n].tag[TGW-1:0]);
          if (!g_tag[n].tag[TGW])
            assert (ahead_valid && !ahead_last && ahead_tag == g_tag[n].tag[TGW-1:0]);
        end
    end
    for (n = 1; n <= PRE; n = n + 1) begin : g_f_request
      logic [FN-1:0] ahead;
      logic [PRE:1] later;  // the valid bits of the clock-k registers, k > n
      assign later = f_probe_valid >> n;
      assign ahead = f_after_chain + FN'(later[1]) + FN'(later[2]) + FN'(later[3]);
      always_comb
        if (f_reset_done && f_probe_valid[n] && f_pos == ahead)
          assert (f_probe_tags[(n-1)*PTW +: TGW] == f_pick_tag);
    end
  endgenerate
`endif
endmodule

// tex_unit: the mip-mapping texture unit (Williams 1983), bit-exact to docs/numerics.md.
// Interface contract: docs/rtl-interface.md. Architecture and resources: docs/rtl.md.
//
// Handshake: req and rsp are valid/ready. req_ready is a register output (the skid buffer's
//   !full): it never depends combinationally on rsp_ready or req_valid. Responses come in request
//   order with their tag; nothing is lost or duplicated. Writes (wr_*) are always accepted.
// Latency: LATENCY = 10 clocks (10 registers): a request accepted in cycle t (req_valid &&
//   req_ready at the rising edge ending cycle t) has rsp_valid high in cycle t + 10 if the output
//   was not stalled. Stall-enable pipeline: every stage advances together
//   when the skid buffer can take an item; only the valid bits are reset.
// Throughput: 1 sample per clock sustained (8 texel reads per clock: a 2x2 footprint in each of
//   levels d and d1); under backpressure the unit adds no bubbles of its own.
// Ports (see docs/rtl-interface.md): req_u, req_v signed Q8.24; req_lod, cfg_lod_bias,
//   cfg_min_lod, cfg_max_lod signed Q8.8; wr_data, rsp_rgba {A, B, G, R} CW-bit unsigned;
//   cfg_log2_w/h integer <= MAX_LOG2_W/H; cfg_* static while requests are in flight (they are
//   registered every clock: a request uses the values present in the cycle it is accepted).
//
// Pipeline (register at the end of each clock):
//   1 capture  2 bias+clamp, coordinate scale  3 level select (d, d1)
//   4 texel coordinates at levels d and d1  5 wrap; the memories of levels d and d1 read
//   (4 banks each; the others hold)  6 select levels d, d1 -> 8 taps
//   7 top/bot lerps  8 bilinear lerps  9 level blend + round  10 skid buffer (output register)
module tex_unit #(
  parameter int MAX_LOG2_W = 10,  // largest texture: 2^MAX_LOG2_W x 2^MAX_LOG2_H, each 0..11
  parameter int MAX_LOG2_H = 10,
  parameter int CW         = 8,   // bits per channel, 1..16
  parameter int TAG_W      = 16
) (
  input  logic                    clk,
  input  logic                    rst,

  input  logic [3:0]              cfg_log2_w,
  input  logic [3:0]              cfg_log2_h,
  input  logic [1:0]              cfg_wrap_u,
  input  logic [1:0]              cfg_wrap_v,
  input  logic                    cfg_texel_linear,
  input  logic [1:0]              cfg_mip_mode,
  input  logic signed [15:0]      cfg_lod_bias,
  input  logic signed [15:0]      cfg_min_lod,
  input  logic signed [15:0]      cfg_max_lod,

  input  logic                    wr_en,
  input  logic [3:0]              wr_level,
  input  logic [10:0]             wr_x,
  input  logic [10:0]             wr_y,
  input  logic [4*CW-1:0]         wr_data,

  input  logic                    req_valid,
  output logic                    req_ready,
  input  logic signed [31:0]      req_u,
  input  logic signed [31:0]      req_v,
  input  logic signed [15:0]      req_lod,
  input  logic [TAG_W-1:0]        req_tag,

  output logic                    rsp_valid,
  input  logic                    rsp_ready,
  output logic [4*CW-1:0]         rsp_rgba,
  output logic [TAG_W-1:0]        rsp_tag
);
  localparam int LATENCY = 10;
  localparam int NL = ((MAX_LOG2_W > MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H) + 1;  // level memories
  localparam int DW = 4 * CW;      // one texel
  localparam int NSTAGE = 9;       // pipeline registers before the skid buffer

  // ---------------------------------------------------------------- control: valid bits, enable
  logic en;                        // every stage advances (the skid buffer has room)
  logic [NSTAGE:1] valid;          // valid[s]: stage s register holds a request
  logic [NSTAGE*TAG_W-1:0] tags;   // tag of stage s at [(s-1)*TAG_W +: TAG_W]

  assign req_ready = en;

  always_ff @(posedge clk) begin
    if (rst) valid <= '0;
    else if (en) valid <= {valid[NSTAGE-1:1], req_valid};
  end
  always_ff @(posedge clk) begin
    if (en) tags <= {tags[(NSTAGE-1)*TAG_W-1:0], req_tag};
  end

  // ---------------------------------------------------------------- configuration register
  // The cfg_* pins are registered every clock and only these copies are used: no request-path
  // logic depends combinationally on an input pin (for Verilator that logic is then evaluated
  // once per clock, not on every eval of the inputs). A request uses the cfg_* of the cycle in
  // which it is accepted and of the next two, which the contract keeps static anyway.
  logic [3:0]         cfg_log2_w_q, cfg_log2_h_q;
  logic [1:0]         cfg_wrap_u_q, cfg_wrap_v_q, cfg_mip_mode_q;
  logic               cfg_texel_linear_q;
  logic signed [15:0] cfg_lod_bias_q, cfg_min_lod_q, cfg_max_lod_q;
  always_ff @(posedge clk) begin
    cfg_log2_w_q       <= cfg_log2_w;
    cfg_log2_h_q       <= cfg_log2_h;
    cfg_wrap_u_q       <= cfg_wrap_u;
    cfg_wrap_v_q       <= cfg_wrap_v;
    cfg_texel_linear_q <= cfg_texel_linear;
    cfg_mip_mode_q     <= cfg_mip_mode;
    cfg_lod_bias_q     <= cfg_lod_bias;
    cfg_min_lod_q      <= cfg_min_lod;
    cfg_max_lod_q      <= cfg_max_lod;
  end

  // ---------------------------------------------------------------- clock 1: capture
  logic signed [31:0] u1, v1;
  logic signed [15:0] lod1;
  always_ff @(posedge clk) begin
    if (en) begin
      u1   <= req_u;
      v1   <= req_v;
      lod1 <= req_lod;
    end
  end

  // ---------------------------------------------------------------- clocks 2-3: LOD, scale
  logic [3:0] last_level;
  assign last_level = (cfg_log2_w_q > cfg_log2_h_q) ? cfg_log2_w_q : cfg_log2_h_q;

  logic [3:0] d3, d1_3;
  logic [7:0] f3;
  tex_lod u_lod (
    .clk(clk), .en(en), .lod(lod1), .bias(cfg_lod_bias_q), .min_lod(cfg_min_lod_q),
    .max_lod(cfg_max_lod_q), .mip_mode(cfg_mip_mode_q), .last_level(last_level),
    .d(d3), .d1(d1_3), .f(f3)
  );

  logic signed [tex_pkg::SCALED_W-1:0] su2, sv2;
  tex_scale u_scale_u (.clk(clk), .en(en), .coord(u1), .log2_size0(cfg_log2_w_q), .scaled(su2));
  tex_scale u_scale_v (.clk(clk), .en(en), .coord(v1), .log2_size0(cfg_log2_h_q), .scaled(sv2));

  // ---------------------------------------------------------------- clock 3: wait for d, d1
  logic signed [tex_pkg::SCALED_W-1:0] su3, sv3;
  always_ff @(posedge clk) begin
    if (en) begin
      su3 <= su2;
      sv3 <= sv2;
    end
  end

  // ---------------------------------------------------------------- clock 4: coordinates at d, d1
  // Only the two levels the sample uses are addressed: t9 = s >>> d (and >>> d1).
  logic signed [tex_pkg::INDEX_W-1:0] i0_u_d4, i0_v_d4, i0_u_d1_4, i0_v_d1_4;
  logic [7:0] fx_d4, fy_d4, fx_d1_4, fy_d1_4;
  tex_addr u_addr_u_d  (.clk(clk), .en(en), .scaled(su3), .level(d3),   .linear(cfg_texel_linear_q),
                        .i0(i0_u_d4),   .w(fx_d4));
  tex_addr u_addr_v_d  (.clk(clk), .en(en), .scaled(sv3), .level(d3),   .linear(cfg_texel_linear_q),
                        .i0(i0_v_d4),   .w(fy_d4));
  tex_addr u_addr_u_d1 (.clk(clk), .en(en), .scaled(su3), .level(d1_3), .linear(cfg_texel_linear_q),
                        .i0(i0_u_d1_4), .w(fx_d1_4));
  tex_addr u_addr_v_d1 (.clk(clk), .en(en), .scaled(sv3), .level(d1_3), .linear(cfg_texel_linear_q),
                        .i0(i0_v_d1_4), .w(fy_d1_4));

  // Runtime sizes of levels d and d1: a side that reaches 1 texel stays 1.
  logic [3:0] lw_d3, lh_d3, lw_d1_3, lh_d1_3;
  assign lw_d3   = (cfg_log2_w_q > d3)   ? cfg_log2_w_q - d3   : 4'd0;
  assign lh_d3   = (cfg_log2_h_q > d3)   ? cfg_log2_h_q - d3   : 4'd0;
  assign lw_d1_3 = (cfg_log2_w_q > d1_3) ? cfg_log2_w_q - d1_3 : 4'd0;
  assign lh_d1_3 = (cfg_log2_h_q > d1_3) ? cfg_log2_h_q - d1_3 : 4'd0;

  logic [3:0] d4, d1_4, lw_d4, lh_d4, lw_d1_4, lh_d1_4;
  logic [7:0] f4;
  always_ff @(posedge clk) begin
    if (en) begin
      d4      <= d3;
      d1_4    <= d1_3;
      f4      <= f3;
      lw_d4   <= lw_d3;
      lh_d4   <= lh_d3;
      lw_d1_4 <= lw_d1_3;
      lh_d1_4 <= lh_d1_3;
    end
  end

  // ---------------------------------------------------------------- clock 5: wrap, read d and d1
  localparam int XW0 = (MAX_LOG2_W > 0) ? MAX_LOG2_W : 1;  // wrapped index bits (level 0's)
  localparam int YW0 = (MAX_LOG2_H > 0) ? MAX_LOG2_H : 1;
  logic [XW0-1:0] x0_d, x1_d, x0_d1, x1_d1;
  logic [YW0-1:0] y0_d, y1_d, y0_d1, y1_d1;
  tex_wrap #(.OUT_W(XW0)) u_wrap_x0_d  (.i(i0_u_d4),                           .log2_n(lw_d4),
                                        .mode(cfg_wrap_u_q), .o(x0_d));
  tex_wrap #(.OUT_W(XW0)) u_wrap_x1_d  (.i(i0_u_d4 + tex_pkg::INDEX_W'(1)),    .log2_n(lw_d4),
                                        .mode(cfg_wrap_u_q), .o(x1_d));
  tex_wrap #(.OUT_W(YW0)) u_wrap_y0_d  (.i(i0_v_d4),                           .log2_n(lh_d4),
                                        .mode(cfg_wrap_v_q), .o(y0_d));
  tex_wrap #(.OUT_W(YW0)) u_wrap_y1_d  (.i(i0_v_d4 + tex_pkg::INDEX_W'(1)),    .log2_n(lh_d4),
                                        .mode(cfg_wrap_v_q), .o(y1_d));
  tex_wrap #(.OUT_W(XW0)) u_wrap_x0_d1 (.i(i0_u_d1_4),                         .log2_n(lw_d1_4),
                                        .mode(cfg_wrap_u_q), .o(x0_d1));
  tex_wrap #(.OUT_W(XW0)) u_wrap_x1_d1 (.i(i0_u_d1_4 + tex_pkg::INDEX_W'(1)),  .log2_n(lw_d1_4),
                                        .mode(cfg_wrap_u_q), .o(x1_d1));
  tex_wrap #(.OUT_W(YW0)) u_wrap_y0_d1 (.i(i0_v_d1_4),                         .log2_n(lh_d1_4),
                                        .mode(cfg_wrap_v_q), .o(y0_d1));
  tex_wrap #(.OUT_W(YW0)) u_wrap_y1_d1 (.i(i0_v_d1_4 + tex_pkg::INDEX_W'(1)),  .log2_n(lh_d1_4),
                                        .mode(cfg_wrap_v_q), .o(y1_d1));

  // Footprint parities {y1, y0, x1, x0} & 1 of levels d and d1 (they route banks to taps).
  logic [3:0] par_d4, par_d1_4;
  assign par_d4   = {y1_d[0],  y0_d[0],  x1_d[0],  x0_d[0]};
  assign par_d1_4 = {y1_d1[0], y0_d1[0], x1_d1[0], x0_d1[0]};

  // Level memory k reads level d's footprint if k = d, level d1's if k = d1, nothing otherwise
  // (it holds its words; tex_select ignores them). A wrapped index of level k fits its memory.
  logic [NL*4*DW-1:0] rdata5;  // per-level bank words (clock 5)
  genvar k;
  generate
    for (k = 0; k < NL; k = k + 1) begin : g_level
      localparam int XB = (MAX_LOG2_W > k) ? MAX_LOG2_W - k : 0;  // level k's largest log2 width
      localparam int YB = (MAX_LOG2_H > k) ? MAX_LOG2_H - k : 0;
      localparam int XO = (XB > 0) ? XB : 1;
      localparam int YO = (YB > 0) ? YB : 1;
      logic          is_d;  // level k is level d of the sample
      logic          re;
      logic [XO-1:0] x0, x1;
      logic [YO-1:0] y0, y1;
      assign is_d = d4 == 4'(k);
      assign re   = en && (is_d || d1_4 == 4'(k));
      assign x0   = is_d ? x0_d[XO-1:0] : x0_d1[XO-1:0];
      assign x1   = is_d ? x1_d[XO-1:0] : x1_d1[XO-1:0];
      assign y0   = is_d ? y0_d[YO-1:0] : y0_d1[YO-1:0];
      assign y1   = is_d ? y1_d[YO-1:0] : y1_d1[YO-1:0];
      tex_level_mem #(.XB(XB), .YB(YB), .DW(DW)) u_mem (
        .clk(clk),
        .we(wr_en && wr_level == 4'(k)), .wx(wr_x), .wy(wr_y), .wdata(wr_data),
        .re(re), .x0(x0), .x1(x1), .y0(y0), .y1(y1),
        .rdata(rdata5[k*4*DW +: 4*DW])
      );
    end
  endgenerate

  logic [3:0] d5, d1_5, par_d5, par_d1_5;
  logic [7:0] f5, fx_d5, fy_d5, fx_d1_5, fy_d1_5;
  always_ff @(posedge clk) begin
    if (en) begin
      d5       <= d4;
      d1_5     <= d1_4;
      par_d5   <= par_d4;
      par_d1_5 <= par_d1_4;
      f5       <= f4;
      fx_d5    <= fx_d4;
      fy_d5    <= fy_d4;
      fx_d1_5  <= fx_d1_4;
      fy_d1_5  <= fy_d1_4;
    end
  end

  // ---------------------------------------------------------------- clock 6: 8 taps
  logic [4*DW-1:0] taps_d6, taps_d1_6;
  tex_select #(.NL(NL), .DW(DW)) u_select (
    .clk(clk), .en(en), .rdata(rdata5), .d(d5), .d1(d1_5), .par_d(par_d5), .par_d1(par_d1_5),
    .taps_d(taps_d6), .taps_d1(taps_d1_6)
  );
  logic [7:0] f6, fx_d6, fy_d6, fx_d1_6, fy_d1_6;
  always_ff @(posedge clk) begin
    if (en) begin
      f6      <= f5;
      fx_d6   <= fx_d5;
      fy_d6   <= fy_d5;
      fx_d1_6 <= fx_d1_5;
      fy_d1_6 <= fy_d1_5;
    end
  end

  // ---------------------------------------------------------------- clocks 7-9: filter
  logic [4*CW-1:0] rgba9;
  tex_filter #(.CW(CW)) u_filter (
    .clk(clk), .en(en), .taps_d(taps_d6), .taps_d1(taps_d1_6),
    .fx_d(fx_d6), .fy_d(fy_d6), .fx_d1(fx_d1_6), .fy_d1(fy_d1_6), .f(f6), .rgba(rgba9)
  );

  // ---------------------------------------------------------------- clock 10: skid buffer
  tex_skid #(.W(TAG_W + 4*CW)) u_skid (
    .clk(clk), .rst(rst),
    .in_valid(valid[NSTAGE]), .in_ready(en), .in_data({tags[(NSTAGE-1)*TAG_W +: TAG_W], rgba9}),
    .out_valid(rsp_valid), .out_ready(rsp_ready), .out_data({rsp_tag, rsp_rgba})
  );

`ifndef SYNTHESIS
  initial assert (LATENCY == NSTAGE + 1) else $error("tex_unit: LATENCY must match the stages");
  // Handshake rules, checked in simulation (Verilator --assert): a valid is held until ready,
  // and the payload is stable meanwhile, on both channels.
  logic req_stalled_q, rsp_stalled_q;
  logic [31:0] req_u_q, req_v_q;
  logic [15:0] req_lod_q;
  logic [TAG_W-1:0] req_tag_q, rsp_tag_q;
  logic [4*CW-1:0] rsp_rgba_q;
  always_ff @(posedge clk) begin
    req_stalled_q <= !rst && req_valid && !req_ready;
    rsp_stalled_q <= !rst && rsp_valid && !rsp_ready;
    req_u_q <= req_u;
    req_v_q <= req_v;
    req_lod_q <= req_lod;
    req_tag_q <= req_tag;
    rsp_tag_q <= rsp_tag;
    rsp_rgba_q <= rsp_rgba;
    if (!rst && req_stalled_q) begin
      assert (req_valid && req_u == req_u_q && req_v == req_v_q && req_lod == req_lod_q
              && req_tag == req_tag_q)
        else $error("tex_unit: req_valid dropped or request changed while req_ready was low");
    end
    if (!rst && rsp_stalled_q) begin
      assert (rsp_valid && rsp_tag == rsp_tag_q && rsp_rgba == rsp_rgba_q)
        else $error("tex_unit: rsp_valid dropped or response changed while rsp_ready was low");
    end
  end
`endif
endmodule

// tex_unit: the mip-mapping texture unit (Williams 1983), bit-exact to docs/numerics.md.
// Interface contract: docs/rtl-interface.md. Architecture and resources: docs/rtl.md.
//
// Handshake: req and rsp are valid/ready. req_ready is a register output (the skid buffer's
//   !full): it never depends combinationally on rsp_ready or req_valid. Responses come in request
//   order with their tag; nothing is lost or duplicated. Writes (wr_*) are always accepted.
// Latency: LATENCY = 10 clocks (10 registers): a request accepted in cycle t (req_valid &&
//   req_ready at the rising edge ending cycle t) has rsp_valid high in cycle t + 10 if the output
//   was not stalled. Stall-enable pipeline: every stage advances together when the skid buffer
//   can take an item; only the valid bits are reset.
// Throughput: 1 sample per clock sustained (8 texel reads per clock: a 2x2 footprint in each of
//   levels d and d1); under backpressure the unit adds no bubbles of its own.
// Ports (see docs/rtl-interface.md): req_u, req_v signed Q8.24; req_lod, cfg_lod_bias,
//   cfg_min_lod, cfg_max_lod signed Q8.8; wr_data, rsp_rgba {A, B, G, R} CW-bit unsigned;
//   cfg_log2_w/h integer <= MAX_LOG2_W/H; wr_level, wr_x, wr_y unsigned integers.
// Inputs are only ever registered: no logic depends combinationally on an input pin.
//   cfg_* are registered every clock (in tex_front); a request accepted in cycle t uses the
//   cfg_* pins of cycles t to t + 3 (clock 2: bias, clamp, sizes; clock 3: mip mode, last level; clock 4:
//   texel filter, level sizes; clock 5: wrap modes), which the contract keeps static anyway.
//   wr_* are registered (wr_*_q) and written one clock later: a texel on the write pins in cycle
//   t is in its memory from cycle t + 2 on, and is seen by every request accepted in cycle t - 2
//   or later (the memories are read in a request's clock 5).
//
// Pipeline (register at the end of each clock; names carry _s<clock>, docs/rtl.md):
//   1 capture (u_s1, v_s1, lod_s1)  2 tex_lod clamp, tex_scale  3 tex_lod level select (slots:
//   0 = level d, 1 = level d1)  4 tex_address per slot and axis  5 tex_wrap (combinational);
//   tex_fetch: the memories of levels d and d1 read (4 banks each; the others hold)
//   6 tex_fetch: bank words -> 8 taps  7 top/bot lerps  8 bilinear lerps  9 level blend + round
//   10 tex_skid (output register)
module tex_unit #(
  parameter int MAX_LOG2_W = 10,  // largest texture: 2^MAX_LOG2_W x 2^MAX_LOG2_H, each 0..11
  parameter int MAX_LOG2_H = 10,
  parameter int CW         = 8,   // bits per channel, 1..16
  parameter int TAG_W      = 16   // >= 1
) (
  input  logic                                   clk,
  input  logic                                   rst,

  input  logic [tex_pkg::LEVEL_W-1:0]            cfg_log2_w,
  input  logic [tex_pkg::LEVEL_W-1:0]            cfg_log2_h,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_wrap_u,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_wrap_v,
  input  logic                                   cfg_texel_linear,
  input  logic [tex_pkg::MIP_W-1:0]              cfg_mip_mode,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_lod_bias,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_min_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_max_lod,

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
  input  logic [TAG_W-1:0]                       req_tag,

  output logic                                   rsp_valid,
  input  logic                                   rsp_ready,
  output logic [4*CW-1:0]                        rsp_rgba,
  output logic [TAG_W-1:0]                       rsp_tag
);
  localparam int LATENCY = 10;     // request handshake edge to response handshake edge
  localparam int NSTAGE  = LATENCY - 1;  // pipeline registers before the skid buffer
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
`ifdef __ICARUS__
  `define TEX_PARAM_ERROR(msg) initial $fatal(1, msg);  // Icarus 11: no elaboration-time $error
`else
  `define TEX_PARAM_ERROR(msg) $error(msg);
`endif
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
  endgenerate
`undef TEX_PARAM_ERROR

  // ---------------------------------------------------------------- control: valid bits, enable
  logic en;                        // every stage advances (the skid buffer has room)
  logic [NSTAGE:1] valid;          // valid[n]: the clock-n register holds a request

  assign req_ready = en;

  always_ff @(posedge clk) begin
    if (rst) valid <= '0;
    else if (en) valid <= {valid[NSTAGE-1:1], req_valid};
  end

  // g_tag[n].tag: the tag of the request in the clock-n register (it rides along, not reset).
  genvar n;
  generate
    for (n = 1; n <= NSTAGE; n = n + 1) begin : g_tag
      logic [TGW-1:0] tag;
      if (n == 1) begin : g_capture
        always_ff @(posedge clk) if (en) tag <= req_tag;
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
  logic [4*VW-1:0] log2_size_s4;       // (the level memories have fixed sizes: unused)
  logic [VW-1:0]   log2_w0_unused, log2_h0_unused;
  logic [4*XW-1:0] x;                  // wrapped x taps: slot s tap j at [(s*2 + j)*XW +: XW]
  logic [4*YW-1:0] y;
  tex_front #(.XW(XW), .YW(YW)) u_front (
    .clk(clk), .en(en), .req_u(req_u), .req_v(req_v), .req_lod(req_lod),
    .cfg_log2_w(cfg_log2_w), .cfg_log2_h(cfg_log2_h), .cfg_wrap_u(cfg_wrap_u),
    .cfg_wrap_v(cfg_wrap_v), .cfg_texel_linear(cfg_texel_linear), .cfg_mip_mode(cfg_mip_mode),
    .cfg_lod_bias(cfg_lod_bias), .cfg_min_lod(cfg_min_lod), .cfg_max_lod(cfg_max_lod),
    .log2_w0(log2_w0_unused), .log2_h0(log2_h0_unused), .level(level_s4), .f(f_s4), .w(w_s4), .log2_size(log2_size_s4), .x(x), .y(y)
  );
  logic [4*VW-1:0] log2_size_unused;
  assign log2_size_unused = log2_size_s4;  // (log2_*_unused: likewise)

  always_ff @(posedge clk) begin
    if (en) begin
      f_s5 <= f_s4;
      w_s5 <= w_s4;
      f_s6 <= f_s5;
      w_s6 <= w_s5;
    end
  end

  // ---------------------------------------------------------------- clocks 5-6: fetch
  logic [32*CWD-1:0] taps_s6;  // slot s tap t at [(s*4 + t)*4*CW +: 4*CW]
  tex_fetch #(.MAX_LOG2_W(MLW), .MAX_LOG2_H(MLH), .CW(CWD)) u_fetch (
    .clk(clk), .en(en),
    .wr_en(wr_en_q), .wr_level(wr_level_q), .wr_x(wr_x_q), .wr_y(wr_y_q), .wr_data(wr_data_q),
    .level(level_s4), .x(x), .y(y), .taps(taps_s6)
  );

  // ---------------------------------------------------------------- clocks 7-9: filter
  logic [4*CWD-1:0] rgba_s9;
  tex_filter #(.CW(CWD)) u_filter (
    .clk(clk), .en(en), .taps(taps_s6), .w(w_s6), .f(f_s6), .rgba(rgba_s9)
  );

  // ---------------------------------------------------------------- clock 10: skid buffer
`ifdef FORMAL
  logic [TGW+4*CWD-1:0] f_skid_data;  // the skid entry {tag, rgba} (formal properties, below)
`endif
  tex_skid #(.W(TGW + 4*CWD)) u_skid (
    .clk(clk), .rst(rst),
    .in_valid(valid[NSTAGE]), .in_ready(en), .in_data({g_tag[NSTAGE].tag, rgba_s9}),
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
  // request); it never exceeds the 9 pipeline registers plus the 2 skid entries; and it always
  // equals the items the unit holds (valid bits, output register, skid entry = !en): nothing is
  // lost or duplicated.
  localparam int CAPACITY = NSTAGE + 2;
  localparam int FW = $clog2(CAPACITY + 2);
  // (Everything below reads the input pins only at the clock edge: no combinational logic on them.)
  logic [FW-1:0] in_flight;
  always_ff @(posedge clk) begin
    if (rst) begin
      in_flight <= '0;
    end else begin
      assert (in_flight != '0 || !rsp_valid)
        else $error("tex_unit: rsp_valid high with no request in flight");
      assert (in_flight <= FW'(CAPACITY))
        else $error("tex_unit: more requests in flight than the pipeline and skid buffer hold");
      assert (in_flight == FW'($countones(valid)) + FW'(rsp_valid) + FW'(!en))
        else $error("tex_unit: requests in flight differ from the items the pipeline holds");
      in_flight <= in_flight + FW'(req_valid && req_ready) - FW'(rsp_valid && rsp_ready);
    end
  end

  // Handshake rules: a valid is held until ready, and the payload is stable meanwhile, on both
  // channels.
  logic                                   req_stalled_q, rsp_stalled_q;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u_q, req_v_q;
  logic signed [tex_pkg::LOD_W-1:0]       req_lod_q;
  logic [TAG_W-1:0]                       req_tag_q, rsp_tag_q;
  logic [4*CW-1:0]                        rsp_rgba_q;
  // (The payload copies are taken only in a stalled cycle, the only time they are compared.)
  always_ff @(posedge clk) begin
    req_stalled_q <= !rst && req_valid && !req_ready;
    rsp_stalled_q <= !rst && rsp_valid && !rsp_ready;
    if (req_valid && !req_ready) begin
      req_u_q   <= req_u;
      req_v_q   <= req_v;
      req_lod_q <= req_lod;
      req_tag_q <= req_tag;
    end
    if (rsp_valid && !rsp_ready) begin
      rsp_tag_q  <= rsp_tag;
      rsp_rgba_q <= rsp_rgba;
    end
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

`ifdef FORMAL
  // ---------------------------------------------------------------- formal properties
  // Proven by scripts/formal.sh (k-induction, Yosys) in a small configuration; the handshake
  // logic is the same in all. They hold from the first reset on, for any inputs (rsp_ready, the
  // request, configuration and write pins free in every clock), also with a reset in mid-traffic.
  // Items in flight, oldest first: the output register (rsp_valid), the skid entry (!en), then
  // the pipeline registers valid[NSTAGE] down to valid[1]. The tracked request: the f_pick-th
  // accepted (mod 32; f_pick any constant), its tag taken when it is accepted.
  localparam int F_CAPACITY = LATENCY + 1;  // LATENCY - 1 pipeline registers + 2 skid entries
  localparam int FN = 5;                    // counter bits: 2^FN > F_CAPACITY + 1

  function automatic logic [FN-1:0] f_count(input logic [NSTAGE:1] v);  // valid bits set
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

  assign f_in_take  = req_valid && req_ready;
  assign f_out_take = rsp_valid && rsp_ready;
  assign f_pos      = f_pick - f_emitted;
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
      // capacity: in flight = the items the unit holds, at most F_CAPACITY
      assert (f_held == f_count(valid) + FN'(rsp_valid) + FN'(!en));
      assert (en || rsp_valid);
      assert (f_held <= FN'(F_CAPACITY));
      // order: the tracked request is answered as the f_pick-th response, with its tag (none
      // lost, duplicated or reordered); until then its tag is in the register at place f_pos
      if (rsp_valid && f_pos == FN'(0)) assert (rsp_tag == f_pick_tag);
      if (!en && f_pos == FN'(1)) assert (f_skid_data[4*CWD +: TGW] == f_pick_tag);
      // hold: a stalled response stays valid with the same tag and texel
      if (f_stalled_q) assert (rsp_valid && rsp_tag == f_tag_q && rsp_rgba == f_rgba_q);
    end
  end
  generate
    for (n = 1; n <= NSTAGE; n = n + 1) begin : g_f_stage
      // requests ahead of the one in the clock-n register: output, skid entry, later registers
      logic [FN-1:0] ahead;
      assign ahead = FN'(rsp_valid) + FN'(!en) + f_count(valid >> n);
      always_comb
        if (f_reset_done && valid[n] && f_pos == ahead) assert (g_tag[n].tag == f_pick_tag);
    end
  endgenerate
`endif
endmodule

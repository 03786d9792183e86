// tb_tex_unit: 4-state X-propagation bench of tex_unit for Icarus Verilog 11 (iverilog -g2012;
// run by scripts/xprop.sh, described in docs/verification.md).
//
// Registers without reset start as X (Icarus's 4-state default; checked at the first clock). The
// bench replays the vectors of tests/xprop/xprop_vectors.cpp (directory: +vectors=DIR): texture
// loads through the write port, cfg pins, requests offered until taken (input gaps between them),
// rsp_ready from a per-clock schedule (output stalls), resets with requests in flight, drains. Every
// don't-care input is X: req_u/v/lod/tag while req_valid is low, wr_level/x/y/data while wr_en is
// low, the cfg pins until the first configuration.
//
// Fails ($fatal, exit code 1, a line "xprop: FAIL ...") if
//   - req_ready or rsp_valid is X/Z in any clock after the first reset is released;
//   - any bit of rsp_tag or rsp_rgba is X/Z while rsp_valid is high;
//   - a response differs from the golden model's (rgba; and the tag, in request order: the
//     requests in flight at a reset are dropped, the next response is the first request after it);
//   - a response is missing (a drain times out), extra (rsp_valid with nothing in flight, or
//     during a reset), changes or disappears while stalled, or a request is never taken;
//   - the stimulus is off: bad header, a reset that hit nothing in flight, expected values left.
// Sampling: inputs change 1 ns after the rising edge; outputs are sampled at the falling edge,
// and a handshake fires at the next rising edge when valid && ready (the driver's convention).
// On success it prints one line "xprop: PASS ..." and calls $finish.
`timescale 1ns / 1ps
module tb_tex_unit #(
  parameter int MAX_LOG2_W = 3,
  parameter int MAX_LOG2_H = 3,
  parameter int CW         = 8,
  parameter int TAG_W      = 16
);
  localparam int MAX_ERRORS = 10;    // stop after this many
  localparam int READY_MAX  = 65536; // longest rsp_ready schedule
  localparam int TIMEOUT    = 2000;  // clocks to wait for a drain or for a request to be taken
  localparam int RESET_CLOCKS0 = 4;  // the first reset

  logic clk = 1'b0;
  logic rst = 1'b1;
  logic [tex_pkg::SIZE_W-1:0]             cfg_w = 'x, cfg_h = 'x;
  logic [tex_pkg::LEVEL_W-1:0]            cfg_last_level = 'x;
  logic [tex_pkg::WRAP_W-1:0]             cfg_smp_wrap_u = 'x, cfg_smp_wrap_v = 'x;
  logic                                   cfg_smp_min_linear = 'x;
  logic                                   cfg_smp_mag_linear = 'x;
  logic [tex_pkg::MIP_W-1:0]              cfg_smp_mip_mode = 'x;
  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_lod_bias = 'x, cfg_smp_min_lod = 'x, cfg_smp_max_lod = 'x;
  logic                                   wr_en = 1'b0;
  logic [tex_pkg::LEVEL_W-1:0]            wr_level = 'x;
  logic [tex_pkg::COORD_W-1:0]            wr_x = 'x, wr_y = 'x;
  logic [4*CW-1:0]                        wr_data = 'x;
  logic                                   req_valid = 1'b0;
  logic                                   req_ready;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u = 'x, req_v = 'x;
  logic signed [tex_pkg::LOD_W-1:0]       req_lod = 'x;
  logic signed [tex_pkg::LOD_W-1:0]       req_bias = 'x;
  // Lambda requests: req_deriv = 0 with every derivative pin X (don't-care), also the anisotropy
  // configuration (used by derivative requests only).
  logic                                   req_deriv = 'x;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudx = 'x, req_dvdx = 'x, req_dudy = 'x, req_dvdy = 'x;
  logic [3:0]                             cfg_smp_max_aniso_m1 = 'x;
  logic                                   cfg_smp_aniso_pow2 = 'x;
  logic [63:0]                            cfg_smp_border_rgba = 'x;
  logic                                   cfg_smp_unnormalized = 1'b0;  // (the vectors' samplers are normalized)
  logic [tex_pkg::REDUCTION_W-1:0]        cfg_smp_reduction = 'x;
  logic [tex_pkg::COMPARE_W-1:0]          cfg_smp_compare_op = 'x;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_ref = 'x;
  logic [TAG_W-1:0]                       req_tag = 'x;
  logic [tex_pkg::OP_W-1:0]               req_op = 'x;
  logic [1:0]                             req_component = 'x;
  logic                                   rsp_valid;
  logic                                   rsp_ready = 1'b0;
  logic [4*CW-1:0]                        rsp_rgba;
  logic [TAG_W-1:0]                       rsp_tag;

  tex_unit #(.MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W)) dut (.*);

  always #5 clk = !clk;

  // ---------------------------------------------------------------- state
  string  dir;
  integer stim_fd, exp_fd, r;
  bit     ready_sched [0:READY_MAX-1];
  int     ready_len = 1;
  longint requests = 0;              // from the header
  longint cycle = 0;                 // clocks since time 0
  bit     released = 0;              // the first reset is over: every check is live
  bit     first_sample = 1;
  bit     hold_ready_low = 0;        // rsp_ready low whatever the schedule (before a reset)
  int     reset_clock = 0;           // clocks of the current reset sampled so far
  longint accepted = 0, answered = 0, dropped = 0, exp_read = 0;
  bit     took;                      // the request offered in the last clock was taken
  bit     stalled_q = 0;             // the last clock had rsp_valid && !rsp_ready
  logic [TAG_W-1:0] stalled_tag;
  logic [4*CW-1:0]  stalled_rgba;
  int     errors = 0, x_errors = 0, value_errors = 0, protocol_errors = 0;
  longint x_bits = 0;                // X/Z bits seen where they are not allowed
  longint resets = 0, configs = 0, writes = 0, rewrites = 0;
  longint idle_x_clocks = 0;         // rsp_valid low and rsp_rgba has X: X is in the datapath
  longint req_x_clocks = 0, wr_x_clocks = 0, stall_clocks = 0, backpressure_clocks = 0;
  string  first_error = "";

  // ---------------------------------------------------------------- reporting
  task automatic summary_fail;
    $display("xprop: FAIL %0d errors (X/Z %0d, value %0d, protocol %0d), %0d X/Z bits; %0d responses, clock %0d; first: %s",
             errors, x_errors, value_errors, protocol_errors, x_bits, answered - dropped, cycle, first_error);
    $fatal(1, "xprop: FAILED");
  endtask

  // kind: 0 X/Z, 1 value, 2 protocol or stimulus
  task automatic fail(input int kind, input string msg);
    errors++;
    if (kind == 0) x_errors++;
    else if (kind == 1) value_errors++;
    else protocol_errors++;
    if (errors == 1) first_error = msg;
    $display("xprop: error at clock %0d (%0t): %s", cycle, $time, msg);
    if (errors >= MAX_ERRORS) summary_fail();
  endtask

  // ---------------------------------------------------------------- one clock
  // The caller has set every input but rsp_ready; this sets rsp_ready, checks the outputs just
  // before the rising edge, counts the handshakes, and returns 1 ns after the edge.
  task automatic check_outputs;
    int nx;
    logic [TAG_W-1:0] etag;
    logic [4*CW-1:0] ergba;
    took = 0;
    if (first_sample) begin
      first_sample = 0;
      if (!$isunknown(rsp_rgba) || !$isunknown(rsp_tag))
        fail(2, "rsp_rgba/rsp_tag are not X before the first reset: the simulation does not start unreset registers at X");
    end
    if (!released) begin
      // before the first reset is released nothing is checked
    end else if ($isunknown(req_ready) || $isunknown(rsp_valid)) begin
      x_bits += $countbits(req_ready, 1'bx, 1'bz) + $countbits(rsp_valid, 1'bx, 1'bz);
      fail(0, $sformatf("X/Z on req_ready=%b rsp_valid=%b", req_ready, rsp_valid));
    end else if (rst) begin
      if (reset_clock > 0 && rsp_valid)
        fail(2, $sformatf("rsp_valid high in clock %0d of a reset (tag %h)", reset_clock, rsp_tag));
      reset_clock++;
      stalled_q = 0;
    end else begin
      if (!rsp_valid && $isunknown(rsp_rgba)) idle_x_clocks++;
      if (rsp_valid) begin
        nx = $countbits(rsp_rgba, 1'bx, 1'bz) + $countbits(rsp_tag, 1'bx, 1'bz);
        if (nx != 0) begin
          x_bits += nx;
          fail(0, $sformatf("%0d X/Z bits in a valid response: tag %h rgba %h", nx, rsp_tag, rsp_rgba));
        end
        if (answered == accepted) begin
          fail(2, $sformatf("extra response (nothing in flight): tag %h rgba %h", rsp_tag, rsp_rgba));
        end else begin
          if (stalled_q && (rsp_tag !== stalled_tag || rsp_rgba !== stalled_rgba))
            fail(2, $sformatf("response changed while rsp_ready was low: tag %h rgba %h, was tag %h rgba %h",
                              rsp_tag, rsp_rgba, stalled_tag, stalled_rgba));
          if (rsp_ready) begin
            r = $fscanf(exp_fd, "%h %h\n", etag, ergba);
            if (r != 2) begin
              fail(2, "expected.txt ends before the responses");
            end else begin
              exp_read++;
              if (rsp_tag !== etag)
                fail(2, $sformatf("response #%0d has tag %h, expected %h (lost, duplicated or reordered): rgba %h, expected %h",
                                  answered, rsp_tag, etag, rsp_rgba, ergba));
              else if (rsp_rgba !== ergba)
                fail(1, $sformatf("response #%0d (tag %h) differs from the model: rgba %h, expected %h",
                                  answered, rsp_tag, rsp_rgba, ergba));
            end
            answered++;
          end
        end
      end else if (stalled_q) begin
        fail(2, $sformatf("rsp_valid dropped while rsp_ready was low (tag %h)", stalled_tag));
      end
      stalled_q    = rsp_valid && !rsp_ready;
      stalled_tag  = rsp_tag;
      stalled_rgba = rsp_rgba;
      if (rsp_valid && !rsp_ready) stall_clocks++;
      if (req_valid && !req_ready) backpressure_clocks++;
      if (req_valid && req_ready) begin
        took = 1;
        accepted++;
      end
    end
  endtask

  task automatic step;
    if (rst || hold_ready_low) rsp_ready = 1'b0;
    else rsp_ready = ready_sched[cycle % ready_len];
    if (!req_valid) req_x_clocks++;
    if (!wr_en) wr_x_clocks++;
    @(negedge clk);
    check_outputs();
    @(posedge clk);
    #1;
    cycle++;
  endtask

  // ---------------------------------------------------------------- pins
  task automatic idle_request_pins;
    req_valid = 1'b0;
    req_u = 'x;
    req_v = 'x;
    req_lod = 'x;
    req_bias = 'x;
    req_deriv = 'x;
    req_tag = 'x;
    req_op = 'x;
    req_component = 'x;
    req_ref = 'x;
  endtask

  task automatic idle_write_pins;
    wr_en = 1'b0;
    wr_level = 'x;
    wr_x = 'x;
    wr_y = 'x;
    wr_data = 'x;
  endtask

  task automatic set_write(input int level, input int x, input int y, input logic [63:0] data);
    wr_en = 1'b1;
    wr_level = level;
    wr_x = x;
    wr_y = y;
    wr_data = data[4*CW-1:0];
  endtask

  // ---------------------------------------------------------------- commands
  task automatic drain;
    int waited;
    idle_request_pins();
    waited = 0;
    while (answered < accepted && waited < TIMEOUT) begin
      step();
      waited++;
    end
    if (answered < accepted)
      fail(2, $sformatf("missing responses: %0d of %0d accepted requests unanswered after %0d clocks",
                        accepted - answered, accepted, TIMEOUT));
    repeat (16) step();  // anything that comes out now is extra
  endtask

  task automatic do_reset(input int hold, input int clocks);
    longint n;
    logic [TAG_W-1:0] etag;
    logic [4*CW-1:0] ergba;
    idle_request_pins();
    hold_ready_low = 1;  // the output stalls: the skid buffer may fill
    repeat (hold) step();
    hold_ready_low = 0;
    if (accepted == answered) fail(2, "stimulus: a reset with no request in flight");
    n = accepted - answered;
    dropped += n;
    repeat (n) begin  // the requests in flight are dropped: skip their expected responses
      r = $fscanf(exp_fd, "%h %h\n", etag, ergba);
      exp_read++;
    end
    answered = accepted;
    resets++;
    rst = 1'b1;
    reset_clock = 0;
    repeat (clocks) step();
    rst = 1'b0;
  endtask

  task automatic request(input int gap, input logic signed [31:0] u, input logic signed [31:0] v,
                         input int lod, input logic [TAG_W-1:0] tag, input int wr, input int wl,
                         input int wx, input int wy, input logic [63:0] wd, input int op, input int component,
                         input logic signed [31:0] dref);
    int waited;
    idle_request_pins();
    if (wr != 0) begin
      set_write(wl, wx, wy, wd);
      rewrites++;
    end
    repeat (gap) begin
      step();
      idle_write_pins();
    end
    req_valid = 1'b1;
    req_u = u;
    req_v = v;
    req_lod = lod;
    req_bias = '0;  // (the vectors' requests have no bias of their own)
    req_deriv = 1'b0;
    req_tag = tag;
    req_op = op[tex_pkg::OP_W-1:0];
    req_component = (op == 1) ? component[1:0] : 'x;  // (don't-care but with a gather, OP_GATHER)
    req_ref = (op == 2) ? dref : 'x;                   // (don't-care but with a compare, OP_COMPARE)
    step();
    idle_write_pins();
    waited = 0;
    while (!took && waited < TIMEOUT) begin
      step();
      waited++;
    end
    if (!took) fail(2, $sformatf("request tag %h not taken in %0d clocks", tag, TIMEOUT));
    idle_request_pins();
  endtask

  // ---------------------------------------------------------------- main
  initial begin : main
    byte op;
    int a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12;
    logic [63:0] h0, h1;
    logic signed [31:0] s0, s1, s2;
    bit done;

    if (!$value$plusargs("vectors=%s", dir)) dir = ".";
    stim_fd = $fopen({dir, "/stimulus.txt"}, "r");
    exp_fd = $fopen({dir, "/expected.txt"}, "r");
    if (stim_fd == 0 || exp_fd == 0) $fatal(1, "xprop: FAIL cannot open %s/stimulus.txt or expected.txt", dir);
    r = $fscanf(stim_fd, " %c %d %d %d %d %d %d", op, a0, a1, a2, a3, a4, a5);
    if (r != 7 || op != "H" || a0 != MAX_LOG2_W || a1 != MAX_LOG2_H || a2 != CW || a3 != TAG_W ||
        a5 < 1 || a5 > READY_MAX)
      $fatal(1, "xprop: FAIL stimulus header '%c %0d %0d %0d %0d %0d %0d' does not match the bench (MAX_LOG2_W %0d MAX_LOG2_H %0d CW %0d TAG_W %0d)",
             op, a0, a1, a2, a3, a4, a5, MAX_LOG2_W, MAX_LOG2_H, CW, TAG_W);
    requests = a4;
    ready_len = a5;
    $readmemb({dir, "/ready.txt"}, ready_sched, 0, ready_len - 1);

    // The first reset, from time 0: every unreset register is X until the pipeline loads it.
    rst = 1'b1;
    repeat (RESET_CLOCKS0) step();
    rst = 1'b0;
    released = 1;

    done = 0;
    while (!done) begin
      r = $fscanf(stim_fd, " %c", op);
      if (r != 1) begin
        fail(2, "stimulus.txt ends without E");
        done = 1;
      end else if (op == "C") begin
        r = $fscanf(stim_fd, "%d %d %d %d %d %d %d %d %d %d %d %h %d %d", a0, a1, a10, a2, a3, a4, a5, a6, a7, a8, a9, h0, a11, a12);
        if (accepted != answered) fail(2, "stimulus: cfg changed with requests in flight");
        cfg_w = a0;
        cfg_h = a1;
        cfg_last_level = a10;
        cfg_smp_wrap_u = a2;
        cfg_smp_wrap_v = a3;
        cfg_smp_min_linear = a4[0];
        cfg_smp_mip_mode = a5;
        cfg_smp_lod_bias = a6;
        cfg_smp_min_lod = a7;
        cfg_smp_max_lod = a8;
        cfg_smp_mag_linear = a9[0];
        cfg_smp_border_rgba = h0;
        cfg_smp_reduction = a11[1:0];
        cfg_smp_compare_op = a12[2:0];
        configs++;
      end else if (op == "W") begin
        r = $fscanf(stim_fd, "%d %d %d %h", a0, a1, a2, h0);
        idle_request_pins();
        set_write(a0, a1, a2, h0);
        step();
        idle_write_pins();
        writes++;
      end else if (op == "I") begin
        r = $fscanf(stim_fd, "%d", a0);
        idle_request_pins();
        repeat (a0) step();
      end else if (op == "R") begin
        r = $fscanf(stim_fd, "%d %d %d %d %h %d %d %d %d %h %d %d %d", a0, s0, s1, a1, h0, a2, a3, a4, a5, h1, a11, a6, s2);
        if (r != 13) $fatal(1, "xprop: FAIL bad R line in stimulus.txt (%0d fields)", r);
        request(a0, s0, s1, a1, h0[TAG_W-1:0], a2, a3, a4, a5, h1, a11, a6, s2);
      end else if (op == "Z") begin
        r = $fscanf(stim_fd, "%d %d", a0, a1);
        do_reset(a0, a1);
      end else if (op == "D") begin
        drain();
      end else if (op == "E") begin
        done = 1;
      end else begin
        $fatal(1, "xprop: FAIL unknown command '%c' in stimulus.txt", op);
      end
    end

    drain();
    if (accepted != requests)
      fail(2, $sformatf("stimulus: %0d requests offered, the header says %0d", accepted, requests));
    if (answered != accepted) fail(2, "missing responses at the end");
    if (exp_read != requests || $fscanf(exp_fd, "%h %h\n", h0, h1) == 2)
      fail(2, $sformatf("expected.txt: %0d lines used, %0d requests", exp_read, requests));
    if (resets > 0 && dropped == 0) fail(2, "stimulus: no reset had a request in flight");
    if (errors != 0) summary_fail();
    $display("xprop: PASS %0d requests: %0d responses equal to the model, %0d dropped in flight by %0d resets; 0 X/Z bits on req_ready, rsp_valid or a valid response; %0d configurations, %0d texel writes + %0d rewrites; don't-care pins X: request %0d clocks, write %0d clocks; X on rsp_rgba while rsp_valid low: %0d clocks; output stalled %0d clocks, input backpressure %0d clocks; %0d clocks",
             requests, answered - dropped, dropped, resets, configs, writes, rewrites, req_x_clocks, wr_x_clocks,
             idle_x_clocks, stall_clocks, backpressure_clocks, cycle);
    $finish;
  end
endmodule

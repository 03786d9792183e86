// 4-state X-propagation bench of tex_unit for Icarus Verilog (scripts/xprop.sh).
// Registers without reset start as X. The bench loads a random 4x4 texture through the write
// port, then offers random requests (every filter and wrap, lambda across all levels) with random
// input gaps and output stalls, resets once with requests in flight, and drives every don't-care
// input to X: the request pins while req_valid is low, the write pins while wr_en is low.
// It fails if, after the first reset, req_ready or rsp_valid is ever X/Z, or any bit of rsp_tag or
// rsp_rgba is X/Z while rsp_valid is high, or the responses' tags are not 0, 1, 2, ... in order.
`timescale 1ns / 1ps
module tb_tex_unit;
  localparam int LW = 2, LH = 2, CW = 8, TAG_W = 16, REQUESTS = 3000;
  logic clk = 0, rst = 1;
  logic [tex_pkg::LEVEL_W-1:0] cfg_log2_w = LW, cfg_log2_h = LH;
  logic [tex_pkg::WRAP_W-1:0] cfg_wrap_u = 0, cfg_wrap_v = 0;
  logic cfg_texel_linear = 1;
  logic [tex_pkg::MIP_W-1:0] cfg_mip_mode = 0;
  logic signed [tex_pkg::LOD_W-1:0] cfg_lod_bias = 0, cfg_min_lod = -16'sd32768, cfg_max_lod = 16'sd32767;
  logic wr_en = 0;
  logic [tex_pkg::LEVEL_W-1:0] wr_level;
  logic [tex_pkg::COORD_W-1:0] wr_x, wr_y;
  logic [4*CW-1:0] wr_data;
  logic req_valid = 0, req_ready;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u, req_v;
  logic signed [tex_pkg::LOD_W-1:0] req_lod;
  logic [TAG_W-1:0] req_tag;
  logic rsp_valid, rsp_ready = 0;
  logic [4*CW-1:0] rsp_rgba;
  logic [TAG_W-1:0] rsp_tag;

  tex_unit #(.MAX_LOG2_W(LW), .MAX_LOG2_H(LH), .CW(CW), .TAG_W(TAG_W)) dut (.*);

  always #5 clk = !clk;

  int errors = 0, responses = 0, resets = 0;
  logic [TAG_W-1:0] sent = 0, expected = 0;
  bit checking = 0, taken;

  // Checks just before each rising edge (inputs set after the previous edge).
  always @(negedge clk) if (checking && !rst) begin
    if ($isunknown(req_ready) || $isunknown(rsp_valid)) begin
      errors++;
      if (errors < 5) $display("xprop: X/Z on req_ready=%b or rsp_valid=%b at %0t", req_ready, rsp_valid, $time);
    end else if (rsp_valid && ($isunknown(rsp_rgba) || $isunknown(rsp_tag))) begin
      errors++;
      if (errors < 5) $display("xprop: X/Z in a valid response: tag %h rgba %h at %0t", rsp_tag, rsp_rgba, $time);
    end else if (rsp_valid && rsp_ready) begin
      if (rsp_tag !== expected) begin
        errors++;
        if (errors < 5) $display("xprop: response tag %0d, expected %0d at %0t", rsp_tag, expected, $time);
      end
      expected++;
      responses++;
    end
  end

  task automatic load_texture;
    for (int level = 0; level <= (LW > LH ? LW : LH); level++)
      for (int y = 0; y < (1 << (LH - level < 0 ? 0 : LH - level)); y++)
        for (int x = 0; x < (1 << (LW - level < 0 ? 0 : LW - level)); x++) begin
          wr_en = 1; wr_level = level; wr_x = x; wr_y = y; wr_data = $urandom;
          @(posedge clk); #1;
        end
    wr_en = 0; wr_level = 'x; wr_x = 'x; wr_y = 'x; wr_data = 'x;
    repeat (3) @(posedge clk);
    #1;
  endtask

  task automatic reset(int clocks);
    rst = 1; req_valid = 0; rsp_ready = 0;
    req_u = 'x; req_v = 'x; req_lod = 'x; req_tag = 'x;
    repeat (clocks) @(posedge clk);
    #1 rst = 0; sent = 0; expected = 0; resets++;
  endtask

  initial begin
    wr_level = 'x; wr_x = 'x; wr_y = 'x; wr_data = 'x;
    reset(4);
    checking = 1;
    load_texture();
    for (int part = 0; part < 2; part++) begin
      for (int i = 0; i < REQUESTS; i++) begin
        if (i % 300 == 0) begin  // another filter and wrap pair, held while nothing is in flight
          req_valid = 0; rsp_ready = 1; req_u = 'x; req_v = 'x; req_lod = 'x; req_tag = 'x;
          repeat (16) @(posedge clk);
          #1;
          cfg_texel_linear = $urandom; cfg_mip_mode = $urandom % 3;
          cfg_wrap_u = $urandom % 3; cfg_wrap_v = $urandom % 3;
          repeat (4) @(posedge clk);
          #1;
        end
        while ($urandom % 4 == 0) begin  // input gap: the request pins are X
          req_valid = 0; req_u = 'x; req_v = 'x; req_lod = 'x; req_tag = 'x;
          rsp_ready = $urandom % 3 != 0;
          @(posedge clk); #1;
        end
        req_valid = 1; req_tag = sent;
        req_u = $signed($urandom) >>> 6; req_v = $signed($urandom) >>> 6;  // about +-32 textures
        req_lod = $signed(($urandom % 1536)) - 256;                         // -1 .. 5 levels
        taken = 0;
        while (!taken) begin  // offered until taken
          rsp_ready = $urandom % 3 != 0;
          @(negedge clk);
          taken = req_ready;
          @(posedge clk); #1;
        end
        sent++;
        if (part == 0 && i == REQUESTS / 2) reset(2);  // reset with requests in flight
      end
      req_valid = 0; req_u = 'x; req_v = 'x; req_lod = 'x; req_tag = 'x; rsp_ready = 1;
      repeat (40) @(posedge clk);
      #1;
      if (expected != sent) begin
        errors++;
        $display("xprop: %0d requests sent, %0d answered", sent, expected);
      end
    end
    if (errors == 0 && responses > 0)
      $display("xprop: PASS %0d responses, no X or Z on valid outputs, tags in order, %0d resets", responses, resets);
    else
      $display("xprop: FAIL %0d errors, %0d responses", errors, responses);
    $finish;
  end
endmodule

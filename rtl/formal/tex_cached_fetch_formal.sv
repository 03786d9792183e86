// Formal environment of tex_cached_fetch's memory read port (scripts/formal.sh): a reset in the
// first clock, then every input free in every clock (the front's samples and their level entries,
// both stall enables, the cache pins, the AR ready and the R channel within the rule the unit assumes,
// further resets). scripts/formal.sh cuts the cache tags' answers, the line addresses and the data
// banks' words to free values: every pattern of hits and misses is reachable. The properties are
// tex_cached_fetch's own, under `ifdef FORMAL in rtl/tex_cached_fetch.sv.
module tex_cached_fetch_formal #(
  parameter int MAX_LOG2_W = 2,
  parameter int MAX_LOG2_H = 2,
  parameter int CW         = 1,
  parameter int TAG_W      = 2,
  parameter int BW         = 2,
  parameter int BH         = 2,
  parameter int LINES      = 16,
  parameter int MAX_WAYS   = 1,
  parameter int FIFO_DEPTH = 2,
  parameter int MISS_DEPTH = 16,
  parameter int FILL_DEPTH = 1,
  parameter int MEM_W      = 64,
  parameter int SAMPLERS   = 1,
  parameter int XW         = MAX_LOG2_W,
  parameter int YW         = MAX_LOG2_H,
  parameter int SXW        = 1,
  parameter int PTW        = MAX_LOG2_W + 1,
  parameter int LNW        = tex_pkg::MEM_ADDR_W - 4
) (
  input  logic                              clk,
  input  logic                              rst,
  input  logic                              en_back,
  input  logic                              front_valid,
  input  logic [TAG_W-1:0]                  front_tag,
  input  logic [SXW-1:0]                    front_smp,
  input  logic                              level_odd,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]   f,
  input  logic [4*tex_pkg::WEIGHT_BITS-1:0] w,
  input  logic [4*tex_pkg::SIZE_W-1:0]      size,
  input  logic [4*XW-1:0]                   x,
  input  logic [4*YW-1:0]                   y,
  input  logic [3:0]                        border_x,
  input  logic [3:0]                        border_y,
  input  logic                              smp_we,
  input  logic [SXW-1:0]                    smp_index,
  input  logic [63:0]                       smp_border_rgba,
  input  logic [2*LNW-1:0]                  front_line,
  input  logic [2*PTW-1:0]                  front_pitch,
  input  logic [2*tex_pkg::LEVEL_W-1:0]     front_square,
  input  logic [tex_pkg::FORMAT_W-1:0]      front_format,
  input  logic                              front_srgb,
  input  logic [tex_pkg::LEVEL_W-1:0]       front_log2_lw,
  input  logic [tex_pkg::LEVEL_W-1:0]       front_log2_lh,
  input  logic                              cfg_block_morton,
  input  logic [tex_pkg::LOG2_SETS_W-1:0]   cfg_log2_sets,
  input  logic [tex_pkg::LOG2_WAYS_W-1:0]   cfg_log2_ways,
  input  logic [$clog2(FIFO_DEPTH+1)-1:0]   cfg_fifo_limit,
  input  logic                              mem_req_ready,
  input  logic                              mem_rsp_valid,
  input  logic [MEM_W-1:0]                  mem_rsp_data,
  input  logic                              mem_rsp_error
);
  logic                              en_front, mem_req_valid, mem_rsp_ready, out_valid, out_error, stat_mem_wait;
  logic [tex_pkg::MEM_ADDR_W-1:0]    mem_req_addr;
  logic [TAG_W-1:0]                  out_tag;
  logic [32*CW-1:0]                  taps;
  logic [4*tex_pkg::WEIGHT_BITS-1:0] out_w;
  logic [tex_pkg::WEIGHT_BITS-1:0]   out_f;
  logic [3:0]                        stat_lookups, stat_misses;

  tex_cached_fetch #(
    .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W), .BW(BW), .BH(BH), .LINES(LINES),
    .MAX_WAYS(MAX_WAYS), .FIFO_DEPTH(FIFO_DEPTH), .MISS_DEPTH(MISS_DEPTH), .FILL_DEPTH(FILL_DEPTH), .MEM_W(MEM_W),
    .SAMPLERS(SAMPLERS)
  ) dut (.*);

  always_comb if ($initstate) assume (rst);
endmodule

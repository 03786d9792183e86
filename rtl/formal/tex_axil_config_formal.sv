// Formal environment of tex_axil_config (scripts/formal.sh): a reset in the first clock, then every
// input free in every clock (further resets, BREADY, RREADY, the counters' events, the unit's
// cfg_desc_ready) except that the
// AXI4-Lite master keeps the protocol's rules (AMBA AXI A3.2.1): AWVALID, WVALID and ARVALID,
// once high, stay high with their payload unchanged until the handshake (a reset releases them).
// The properties are tex_axil_config's own, under `ifdef FORMAL in rtl/tex_axil_config.sv.
module tex_axil_config_formal #(
  parameter int ADDR_W = 8
) (
  input logic              clk,
  input logic              rst,
  input logic              s_axi_awvalid,
  input logic [ADDR_W-1:0] s_axi_awaddr,
  input logic [2:0]        s_axi_awprot,
  input logic              s_axi_wvalid,
  input logic [31:0]       s_axi_wdata,
  input logic [3:0]        s_axi_wstrb,
  input logic              s_axi_bready,
  input logic              s_axi_arvalid,
  input logic [ADDR_W-1:0] s_axi_araddr,
  input logic [2:0]        s_axi_arprot,
  input logic              s_axi_rready,
  input logic              stat_sample,
  input logic              stat_sample_error,
  input logic [3:0]        stat_lookups,
  input logic [3:0]        stat_misses,
  input logic              stat_mem_beat,
  input logic              stat_out_stall,
  input logic              stat_mem_wait,
  input logic              stat_req_stall,
  input logic              cfg_desc_ready
);
  logic s_axi_awready, s_axi_wready, s_axi_bvalid, s_axi_arready, s_axi_rvalid;
  logic [1:0] s_axi_bresp, s_axi_rresp;
  logic [31:0] s_axi_rdata;

  // A small unit: 4 textures, 4 samplers, 16 lines of at most 2 ways, a 4-sample FIFO.
  tex_axil_config #(
    .ADDR_W(ADDR_W), .MAX_LOG2_W(3), .MAX_LOG2_H(2), .LINES(16), .MAX_WAYS(2), .FIFO_DEPTH(4),
    .TEXTURES(4), .SAMPLERS(4), .BLOCK_FORMATS(1), .SRGB(1), .LINE_BYTES(64), .BEAT_BYTES(16)
  ) dut (
    .clk, .rst,
    .s_axi_awvalid, .s_axi_awready, .s_axi_awaddr, .s_axi_awprot,
    .s_axi_wvalid, .s_axi_wready, .s_axi_wdata, .s_axi_wstrb,
    .s_axi_bvalid, .s_axi_bready, .s_axi_bresp,
    .s_axi_arvalid, .s_axi_arready, .s_axi_araddr, .s_axi_arprot,
    .s_axi_rvalid, .s_axi_rready, .s_axi_rdata, .s_axi_rresp,
    .unit_rst(), .cfg_desc_we(), .cfg_desc_index(), .cfg_desc_base(), .cfg_desc_w(),
    .cfg_desc_h(), .cfg_desc_last_level(), .cfg_desc_ready(cfg_desc_ready), .cfg_desc_format(), .cfg_desc_srgb(), .cfg_smp_we(), .cfg_smp_index(),
    .cfg_smp_wrap_u(), .cfg_smp_wrap_v(), .cfg_smp_min_linear(), .cfg_smp_mag_linear(), .cfg_smp_mip_mode(),
    .cfg_smp_lod_bias(), .cfg_smp_min_lod(), .cfg_smp_max_lod(), .cfg_smp_max_aniso_m1(), .cfg_smp_aniso_pow2(),
    .cfg_smp_border_rgba(), .cfg_smp_unnormalized(), .cfg_smp_reduction(), .cfg_block_morton(),
    .cfg_log2_sets(), .cfg_log2_ways(), .cfg_fifo_limit(),
    .stat_sample, .stat_sample_error, .stat_lookups, .stat_misses, .stat_mem_beat,
    .stat_out_stall, .stat_mem_wait, .stat_req_stall
  );

  // The master's side: a valid not taken last clock (and no reset now) is still there, unchanged.
  logic              aw_wait_q, w_wait_q, ar_wait_q;
  logic [ADDR_W+2:0] aw_q, ar_q;
  logic [35:0]       w_q;
  always_ff @(posedge clk) begin
    aw_wait_q <= !rst && s_axi_awvalid && !s_axi_awready;
    w_wait_q  <= !rst && s_axi_wvalid && !s_axi_wready;
    ar_wait_q <= !rst && s_axi_arvalid && !s_axi_arready;
    aw_q      <= {s_axi_awprot, s_axi_awaddr};
    w_q       <= {s_axi_wstrb, s_axi_wdata};
    ar_q      <= {s_axi_arprot, s_axi_araddr};
  end
  always_comb begin
    if ($initstate) assume (rst);
    if (!rst) begin
      if (aw_wait_q) assume (s_axi_awvalid && {s_axi_awprot, s_axi_awaddr} == aw_q);
      if (w_wait_q)  assume (s_axi_wvalid && {s_axi_wstrb, s_axi_wdata} == w_q);
      if (ar_wait_q) assume (s_axi_arvalid && {s_axi_arprot, s_axi_araddr} == ar_q);
    end
  end
endmodule

// tex_unit_axi: tex_unit_cached for an FPGA or SoC: its configuration and performance counters
// behind an AXI4-Lite slave (tex_axil_config), its pyramid behind its AXI4 read master, the
// sample request and response ports as they are. Interface and register map:
// docs/rtl-interface.md, "AXI4-Lite configuration (tex_unit_axi)".
// Handshake: req, rsp valid/ready (tex_unit_cached's); s_axi_* AXI4-Lite (tex_axil_config's: one
//   write and one read at a time, AW and W in either order); m_axi_* an AXI4 read master
//   (tex_unit_cached's: one INCR burst per cache line, ID 0, in order). rst is synchronous and
//   active high (an AXI system's !ARESETN, synchronised); it resets the slave, which then holds
//   the unit in reset (CONTROL.unit_reset = 1) until software releases it.
// Latency: tex_unit_cached's (19 clocks request to response when every line hits); a
//   configuration write reaches the unit's pins 1 clock after the write's edge (BVALID with it).
// Throughput: tex_unit_cached's (1 probe per clock while lines hit).
// Ports: req_* / rsp_* as tex_unit_cached (req_u, req_v, req_w, req_dudx .. req_dwdy signed Q8.24;
//   req_lod, req_bias signed Q8.8; req_layer signed Q16.16; req_ref signed Q8.24; req_tex a descriptor entry, req_sampler a sampler entry; rsp_rgba {A, B, G, R} CW-bit unsigned;
//   rsp_error: the sample read a line the memory answered with an error, rsp_rgba 0);
//   s_axi_* 32-bit data, ADDR_W-bit byte addresses; m_axi_* MEM_W-bit data,
//   tex_pkg::MEM_ADDR_W-bit byte addresses, AXI_ID_W-bit IDs.
module tex_unit_axi #(
  parameter int MAX_LOG2_W    = 10,   // tex_unit_cached's parameters (same ranges and checks)
  parameter int MAX_LOG2_H    = 10,
  parameter int CW            = 8,
  parameter int TAG_W         = 16,
  parameter int BLOCK_W       = 4,
  parameter int BLOCK_H       = 4,
  parameter int LINES         = 256,
  parameter int MAX_WAYS      = 4,
  parameter int FIFO_DEPTH    = 256,
  parameter int MISS_DEPTH    = 64,
  parameter int FILL_DEPTH    = 4,
  parameter int MEM_W         = 128,  // AXI4 read data width, 32..256
  parameter int AXI_ID_W      = 1,
  parameter int TEXTURES      = 16,
  parameter int SAMPLERS      = 16,
  parameter int BLOCK_FORMATS = 1,
  parameter int SRGB          = 0,
  parameter int CUBE_MAPS     = 1,
  parameter int ADDR_W        = 12    // AXI4-Lite byte address bits, 8..32 (tex_axil_config)
) (
  input  logic                                   clk,
  input  logic                                   rst,

  // AXI4-Lite slave: configuration and counters
  input  logic                                   s_axi_awvalid,
  output logic                                   s_axi_awready,
  input  logic [ADDR_W-1:0]                      s_axi_awaddr,
  input  logic [2:0]                             s_axi_awprot,
  input  logic                                   s_axi_wvalid,
  output logic                                   s_axi_wready,
  input  logic [31:0]                            s_axi_wdata,
  input  logic [3:0]                             s_axi_wstrb,
  output logic                                   s_axi_bvalid,
  input  logic                                   s_axi_bready,
  output logic [1:0]                             s_axi_bresp,
  input  logic                                   s_axi_arvalid,
  output logic                                   s_axi_arready,
  input  logic [ADDR_W-1:0]                      s_axi_araddr,
  input  logic [2:0]                             s_axi_arprot,
  output logic                                   s_axi_rvalid,
  input  logic                                   s_axi_rready,
  output logic [31:0]                            s_axi_rdata,
  output logic [1:0]                             s_axi_rresp,

  // sample requests and responses
  input  logic                                   req_valid,
  output logic                                   req_ready,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_v,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_w,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_bias,
  input  logic                                   req_deriv,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dwdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dwdy,
  input  logic [tex_pkg::TEX_ID_W-1:0]           req_tex,
  input  logic [tex_pkg::SMP_ID_W-1:0]           req_sampler,
  input  logic [tex_pkg::OP_W-1:0]               req_op,
  input  logic [1:0]                             req_component,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_layer,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_ref,
  input  logic [TAG_W-1:0]                       req_tag,
  output logic                                   rsp_valid,
  input  logic                                   rsp_ready,
  output logic [4*CW-1:0]                        rsp_rgba,
  output logic [TAG_W-1:0]                       rsp_tag,
  output logic                                   rsp_error,

  // AXI4 read master: the texture pyramid
  output logic                                   m_axi_arvalid,
  input  logic                                   m_axi_arready,
  output logic [tex_pkg::MEM_ADDR_W-1:0]         m_axi_araddr,
  output logic [7:0]                             m_axi_arlen,
  output logic [2:0]                             m_axi_arsize,
  output logic [1:0]                             m_axi_arburst,
  output logic [AXI_ID_W-1:0]                    m_axi_arid,
  output logic [3:0]                             m_axi_arcache,
  output logic [2:0]                             m_axi_arprot,
  input  logic                                   m_axi_rvalid,
  output logic                                   m_axi_rready,
  input  logic [MEM_W-1:0]                       m_axi_rdata,
  input  logic [1:0]                             m_axi_rresp,
  input  logic                                   m_axi_rlast,
  input  logic [AXI_ID_W-1:0]                    m_axi_rid
);
  // A cache line's bytes (tex_unit_cached's LINE_BITS / 8): 4 bytes a texel, 8 for CW > 8
  // without SRGB; descriptor bases must be multiples of it.
  localparam int LINE_BYTES = BLOCK_W * BLOCK_H * ((CW > 8 && SRGB == 0) ? 8 : 4);

  logic                              unit_rst;
  logic                              cfg_desc_we, cfg_desc_srgb, cfg_smp_min_linear, cfg_smp_mag_linear, cfg_smp_aniso_pow2;
  logic                              cfg_smp_unnormalized;
  logic [tex_pkg::REDUCTION_W-1:0]   cfg_smp_reduction;
  logic [tex_pkg::COMPARE_W-1:0]     cfg_smp_compare_op;
  logic [tex_pkg::TEX_ID_W-1:0]      cfg_desc_index;
  logic [tex_pkg::MEM_ADDR_W-1:0]    cfg_desc_base;
  logic [tex_pkg::SIZE_W-1:0]        cfg_desc_w, cfg_desc_h;
  logic [tex_pkg::LEVEL_W-1:0]       cfg_desc_last_level;
  logic [tex_pkg::LAYER_W-1:0]       cfg_desc_layers_m1;
  logic                              cfg_desc_cube;
  logic                              cfg_desc_ready;
  logic                              cfg_smp_we;
  logic [tex_pkg::SMP_ID_W-1:0]      cfg_smp_index;
  logic [tex_pkg::WRAP_W-1:0]        cfg_smp_wrap_u, cfg_smp_wrap_v;
  logic [tex_pkg::FORMAT_W-1:0]      cfg_desc_format;
  logic [tex_pkg::MIP_W-1:0]         cfg_smp_mip_mode;
  logic signed [tex_pkg::LOD_W-1:0]  cfg_smp_lod_bias, cfg_smp_min_lod, cfg_smp_max_lod;
  logic [3:0]                        cfg_smp_max_aniso_m1;
  logic [63:0]                       cfg_smp_border_rgba;
  logic                              cfg_block_morton;
  logic [tex_pkg::LOG2_SETS_W-1:0]   cfg_log2_sets;
  logic [tex_pkg::LOG2_WAYS_W-1:0]   cfg_log2_ways;
  logic [$clog2(FIFO_DEPTH+1)-1:0]   cfg_fifo_limit;
  logic [3:0]                        stat_lookups, stat_misses;
  logic                              stat_mem_wait;

  tex_axil_config #(
    .ADDR_W(ADDR_W), .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .LINES(LINES),
    .MAX_WAYS(MAX_WAYS), .FIFO_DEPTH(FIFO_DEPTH), .TEXTURES(TEXTURES), .SAMPLERS(SAMPLERS),
    .BLOCK_FORMATS(BLOCK_FORMATS), .SRGB(SRGB), .CUBE_MAPS(CUBE_MAPS), .LINE_BYTES(LINE_BYTES), .BEAT_BYTES(MEM_W / 8)
  ) u_config (
    .clk(clk), .rst(rst),
    .s_axi_awvalid(s_axi_awvalid), .s_axi_awready(s_axi_awready), .s_axi_awaddr(s_axi_awaddr),
    .s_axi_awprot(s_axi_awprot), .s_axi_wvalid(s_axi_wvalid), .s_axi_wready(s_axi_wready),
    .s_axi_wdata(s_axi_wdata), .s_axi_wstrb(s_axi_wstrb), .s_axi_bvalid(s_axi_bvalid),
    .s_axi_bready(s_axi_bready), .s_axi_bresp(s_axi_bresp), .s_axi_arvalid(s_axi_arvalid),
    .s_axi_arready(s_axi_arready), .s_axi_araddr(s_axi_araddr), .s_axi_arprot(s_axi_arprot),
    .s_axi_rvalid(s_axi_rvalid), .s_axi_rready(s_axi_rready), .s_axi_rdata(s_axi_rdata),
    .s_axi_rresp(s_axi_rresp),
    .unit_rst(unit_rst),
    .cfg_desc_we(cfg_desc_we), .cfg_desc_index(cfg_desc_index), .cfg_desc_base(cfg_desc_base),
    .cfg_desc_w(cfg_desc_w), .cfg_desc_h(cfg_desc_h), .cfg_desc_ready(cfg_desc_ready),
    .cfg_desc_last_level(cfg_desc_last_level),
    .cfg_smp_we(cfg_smp_we), .cfg_smp_index(cfg_smp_index),
    .cfg_smp_wrap_u(cfg_smp_wrap_u), .cfg_smp_wrap_v(cfg_smp_wrap_v),
    .cfg_desc_format(cfg_desc_format), .cfg_desc_srgb(cfg_desc_srgb), .cfg_desc_layers_m1(cfg_desc_layers_m1), .cfg_desc_cube(cfg_desc_cube),
    .cfg_smp_min_linear(cfg_smp_min_linear), .cfg_smp_mag_linear(cfg_smp_mag_linear), .cfg_smp_mip_mode(cfg_smp_mip_mode),
    .cfg_smp_lod_bias(cfg_smp_lod_bias), .cfg_smp_min_lod(cfg_smp_min_lod), .cfg_smp_max_lod(cfg_smp_max_lod),
    .cfg_smp_max_aniso_m1(cfg_smp_max_aniso_m1), .cfg_smp_aniso_pow2(cfg_smp_aniso_pow2), .cfg_smp_border_rgba(cfg_smp_border_rgba),
    .cfg_smp_unnormalized(cfg_smp_unnormalized), .cfg_smp_reduction(cfg_smp_reduction),
    .cfg_smp_compare_op(cfg_smp_compare_op),
    .cfg_block_morton(cfg_block_morton), .cfg_log2_sets(cfg_log2_sets),
    .cfg_log2_ways(cfg_log2_ways), .cfg_fifo_limit(cfg_fifo_limit),
    // the counters' events, at the unit's ports
    .stat_sample(rsp_valid && rsp_ready), .stat_sample_error(rsp_valid && rsp_ready && rsp_error),
    .stat_lookups(stat_lookups), .stat_misses(stat_misses),
    .stat_mem_beat(m_axi_rvalid && m_axi_rready), .stat_out_stall(rsp_valid && !rsp_ready),
    .stat_mem_wait(stat_mem_wait), .stat_req_stall(req_valid && !req_ready)
  );

  tex_unit_cached #(
    .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W),
    .BLOCK_W(BLOCK_W), .BLOCK_H(BLOCK_H), .LINES(LINES), .MAX_WAYS(MAX_WAYS),
    .FIFO_DEPTH(FIFO_DEPTH), .MISS_DEPTH(MISS_DEPTH), .FILL_DEPTH(FILL_DEPTH), .MEM_W(MEM_W),
    .AXI_ID_W(AXI_ID_W), .TEXTURES(TEXTURES), .SAMPLERS(SAMPLERS), .BLOCK_FORMATS(BLOCK_FORMATS), .SRGB(SRGB),
    .CUBE_MAPS(CUBE_MAPS)
  ) u_unit (
    .clk(clk), .rst(rst || unit_rst),  // (rst too: unit_rst is a register, random in the first clock)
    .cfg_desc_we(cfg_desc_we), .cfg_desc_index(cfg_desc_index), .cfg_desc_base(cfg_desc_base),
    .cfg_desc_w(cfg_desc_w), .cfg_desc_h(cfg_desc_h), .cfg_desc_ready(cfg_desc_ready),
    .cfg_desc_last_level(cfg_desc_last_level),
    .cfg_smp_we(cfg_smp_we), .cfg_smp_index(cfg_smp_index),
    .cfg_smp_wrap_u(cfg_smp_wrap_u), .cfg_smp_wrap_v(cfg_smp_wrap_v),
    .cfg_desc_format(cfg_desc_format), .cfg_desc_srgb(cfg_desc_srgb), .cfg_desc_layers_m1(cfg_desc_layers_m1), .cfg_desc_cube(cfg_desc_cube),
    .cfg_smp_min_linear(cfg_smp_min_linear), .cfg_smp_mag_linear(cfg_smp_mag_linear), .cfg_smp_mip_mode(cfg_smp_mip_mode),
    .cfg_smp_lod_bias(cfg_smp_lod_bias), .cfg_smp_min_lod(cfg_smp_min_lod), .cfg_smp_max_lod(cfg_smp_max_lod),
    .cfg_smp_max_aniso_m1(cfg_smp_max_aniso_m1), .cfg_smp_aniso_pow2(cfg_smp_aniso_pow2), .cfg_smp_border_rgba(cfg_smp_border_rgba),
    .cfg_smp_unnormalized(cfg_smp_unnormalized), .cfg_smp_reduction(cfg_smp_reduction),
    .cfg_smp_compare_op(cfg_smp_compare_op),
    .cfg_block_morton(cfg_block_morton), .cfg_log2_sets(cfg_log2_sets),
    .cfg_log2_ways(cfg_log2_ways), .cfg_fifo_limit(cfg_fifo_limit),
    .req_valid(req_valid), .req_ready(req_ready), .req_u(req_u), .req_v(req_v), .req_w(req_w),
    .req_lod(req_lod), .req_bias(req_bias), .req_deriv(req_deriv), .req_dudx(req_dudx), .req_dvdx(req_dvdx),
    .req_dudy(req_dudy), .req_dvdy(req_dvdy), .req_dwdx(req_dwdx), .req_dwdy(req_dwdy), .req_tex(req_tex), .req_sampler(req_sampler), .req_op(req_op), .req_component(req_component),
    .req_layer(req_layer), .req_ref(req_ref), .req_tag(req_tag),
    .rsp_valid(rsp_valid), .rsp_ready(rsp_ready), .rsp_rgba(rsp_rgba), .rsp_tag(rsp_tag),
    .rsp_error(rsp_error),
    .m_axi_arvalid(m_axi_arvalid), .m_axi_arready(m_axi_arready), .m_axi_araddr(m_axi_araddr),
    .m_axi_arlen(m_axi_arlen), .m_axi_arsize(m_axi_arsize), .m_axi_arburst(m_axi_arburst),
    .m_axi_arid(m_axi_arid), .m_axi_arcache(m_axi_arcache), .m_axi_arprot(m_axi_arprot),
    .m_axi_rvalid(m_axi_rvalid), .m_axi_rready(m_axi_rready), .m_axi_rdata(m_axi_rdata),
    .m_axi_rresp(m_axi_rresp), .m_axi_rlast(m_axi_rlast), .m_axi_rid(m_axi_rid),
    .stat_lookups(stat_lookups), .stat_misses(stat_misses), .stat_mem_wait(stat_mem_wait)
  );
endmodule

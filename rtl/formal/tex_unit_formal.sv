// Formal environment of tex_unit (scripts/formal.sh): a reset in the first clock, then every
// input free in every clock: requests (valid, tag, coordinates, lambda or derivatives),
// rsp_ready, configuration, texel writes, and further resets. scripts/formal.sh cuts the probe
// count N out of tex_aniso (a free value), so a derivative request issues any number of probes. The properties are tex_unit's own, under `ifdef FORMAL in
// rtl/tex_unit.sv (and tex_skid's, in rtl/tex_skid.sv). Parameters from scripts/formal.sh.
module tex_unit_formal #(
  parameter int MAX_LOG2_W = 1,
  parameter int MAX_LOG2_H = 1,
  parameter int CW         = 1,
  parameter int TAG_W      = 2
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
  input  logic                                   wr_en,
  input  logic [tex_pkg::LEVEL_W-1:0]            wr_level,
  input  logic [tex_pkg::COORD_W-1:0]            wr_x,
  input  logic [tex_pkg::COORD_W-1:0]            wr_y,
  input  logic [4*CW-1:0]                        wr_data,
  input  logic                                   req_valid,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_v,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_bias,
  input  logic                                   req_deriv,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdx,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dudy,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_dvdy,
  input  logic [3:0]                             cfg_smp_max_aniso_m1,
  input  logic                                   cfg_smp_aniso_pow2,
  input  logic [63:0]                            cfg_smp_border_rgba,
  input  logic                                   cfg_smp_unnormalized,
  input  logic [tex_pkg::REDUCTION_W-1:0]        cfg_smp_reduction,
  input  logic [tex_pkg::OP_W-1:0]               req_op,
  input  logic [1:0]                             req_component,
  input  logic [tex_pkg::COMPARE_W-1:0]          cfg_smp_compare_op,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_ref,
  input  logic [TAG_W-1:0]                       req_tag,
  input  logic                                   rsp_ready
);
  logic              req_ready, rsp_valid;
  logic [4*CW-1:0]   rsp_rgba;
  logic [TAG_W-1:0]  rsp_tag;

  tex_unit #(.MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W)) dut (.*);

  always_comb if ($initstate) assume (rst);
endmodule

// tex_ice40_cached_top: synthesis and place-and-route harness only (scripts/synth.sh), not part
// of the design. tex_unit_cached's ports (about 400 with a 128-bit memory beat) exceed an HX8K
// package's pins: every input is fed from one shift register loaded through pin `sin`, and the
// outputs are folded to one pin by XOR, so no logic of tex_unit_cached is optimized away and its
// timing is measured register to register.
// Parameters come from macros (yosys read_verilog -D...), not chparam: Yosys 0.23 fails an
// internal assertion (`modules_.count(module->name) == 0`) when it re-derives a parameterized
// tex_unit_cached, whose ports' widths depend on its parameters.
// Handshake: none of its own (a measurement wrapper). Latency: that of tex_unit_cached plus the
//   shift-in. Ports: clk, rst, sin (serial input bit), req_ready, rsp_valid, sout (XOR of every
//   other output).
`ifndef TEX_SYN_LOG2
`define TEX_SYN_LOG2 4
`endif
`ifndef TEX_SYN_CW
`define TEX_SYN_CW 8
`endif
`ifndef TEX_SYN_LINES
`define TEX_SYN_LINES 16
`endif
`ifndef TEX_SYN_FIFO
`define TEX_SYN_FIFO 16
`endif
`ifndef TEX_SYN_MISS
`define TEX_SYN_MISS 16
`endif
`ifndef TEX_SYN_MEM_W
`define TEX_SYN_MEM_W 32
`endif
`ifndef TEX_SYN_TEXTURES
`define TEX_SYN_TEXTURES 16
`endif
`ifndef TEX_SYN_FORMATS
`define TEX_SYN_FORMATS 0
`endif
module tex_ice40_cached_top #(
  parameter int MAX_LOG2_W = `TEX_SYN_LOG2,
  parameter int MAX_LOG2_H = `TEX_SYN_LOG2,
  parameter int CW         = `TEX_SYN_CW,
  parameter int TAG_W      = 4,
  parameter int LINES      = `TEX_SYN_LINES,
  parameter int FIFO_DEPTH = `TEX_SYN_FIFO,
  parameter int MISS_DEPTH = `TEX_SYN_MISS,
  parameter int MEM_W      = `TEX_SYN_MEM_W,
  parameter int TEXTURES   = `TEX_SYN_TEXTURES,
  parameter int FORMATS    = `TEX_SYN_FORMATS  // 1: the block decoders and sRGB tables (CW 16)
) (
  input  logic clk,
  input  logic rst,
  input  logic sin,
  output logic req_ready,
  output logic rsp_valid,
  output logic sout
);
  localparam int NW = tex_pkg::SIZE_W;
  localparam int WW = tex_pkg::WRAP_W;
  localparam int MW = tex_pkg::MIP_W;
  localparam int LW = tex_pkg::LOD_W;
  localparam int UW = tex_pkg::REQ_COORD_W;
  localparam int AW = tex_pkg::MEM_ADDR_W;
  localparam int SW = tex_pkg::LOG2_SETS_W;
  localparam int YW = tex_pkg::LOG2_WAYS_W;
  localparam int FW = $clog2(FIFO_DEPTH + 1);
  localparam int XW = tex_pkg::TEX_ID_W;
  // Field offsets in the input shift register, in port order.
  localparam int O_DWE     = 0;
  localparam int O_DINDEX  = O_DWE + 1;
  localparam int O_DESC_W  = O_DINDEX + XW;
  localparam int O_DESC_H  = O_DESC_W + NW;
  localparam int O_LAST    = O_DESC_H + NW;
  localparam int O_FORMAT  = O_LAST + tex_pkg::LEVEL_W;
  localparam int O_SRGB    = O_FORMAT + tex_pkg::FORMAT_W;
  localparam int O_SWE     = O_SRGB + 1;
  localparam int O_SINDEX  = O_SWE + 1;
  localparam int O_WRAP_U  = O_SINDEX + tex_pkg::SMP_ID_W;
  localparam int O_WRAP_V  = O_WRAP_U + WW;
  localparam int O_LINEAR  = O_WRAP_V + WW;
  localparam int O_MAG     = O_LINEAR + 1;
  localparam int O_MIP     = O_MAG + 1;
  localparam int O_BIAS    = O_MIP + MW;
  localparam int O_MIN_LOD = O_BIAS + LW;
  localparam int O_MAX_LOD = O_MIN_LOD + LW;
  localparam int O_BASE    = O_MAX_LOD + LW;
  localparam int O_MORTON  = O_BASE + AW;
  localparam int O_TEX     = O_MORTON + 1;
  localparam int O_SMP     = O_TEX + XW;
  localparam int O_BORDER  = O_SMP + tex_pkg::SMP_ID_W;
  localparam int O_SETS    = O_BORDER + 64;
  localparam int O_WAYS    = O_SETS + SW;
  localparam int O_FIFO    = O_WAYS + YW;
  localparam int O_VALID   = O_FIFO + FW;
  localparam int O_U       = O_VALID + 1;
  localparam int O_V       = O_U + UW;
  localparam int O_LOD     = O_V + UW;
  localparam int O_TAG     = O_LOD + LW;
  localparam int O_READY   = O_TAG + TAG_W;
  localparam int O_MREADY  = O_READY + 1;
  localparam int O_MVALID  = O_MREADY + 1;
  localparam int O_MDATA   = O_MVALID + 1;
  localparam int O_MRESP   = O_MDATA + MEM_W;
  localparam int O_MLAST   = O_MRESP + 2;
  localparam int O_OP      = O_MLAST + 1;       // req_op
  localparam int O_COMP    = O_OP + tex_pkg::OP_W;  // req_component
  localparam int O_UNNORM  = O_COMP + 2;        // cfg_smp_unnormalized
  localparam int O_REDUCE  = O_UNNORM + 1;      // cfg_smp_reduction
  localparam int O_LAYER   = O_REDUCE + tex_pkg::REDUCTION_W;  // req_layer
  localparam int O_LAYERS  = O_LAYER + UW;      // cfg_desc_layers_m1
  localparam int O_CMP     = O_LAYERS + tex_pkg::LAYER_W;  // cfg_smp_compare_op
  localparam int O_REF     = O_CMP + tex_pkg::COMPARE_W;   // req_ref
  localparam int NIN       = O_REF + UW;

  logic [NIN-1:0] in_bits;
  always_ff @(posedge clk) in_bits <= {in_bits[NIN-2:0], sin};

  logic [4*CW-1:0]  rsp_rgba;
  logic [TAG_W-1:0] rsp_tag;
  logic             arvalid, rready, rsp_error, stat_mem_wait, arid, desc_ready;
  logic [AW-1:0]    araddr;
  logic [7:0]       arlen;
  logic [2:0]       arsize, arprot;
  logic [1:0]       arburst;
  logic [3:0]       arcache, stat_lookups, stat_misses;
  tex_unit_cached #(
    .MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W), .LINES(LINES),
    .FIFO_DEPTH(FIFO_DEPTH), .MISS_DEPTH(MISS_DEPTH), .MEM_W(MEM_W), .TEXTURES(TEXTURES),
    .BLOCK_FORMATS(FORMATS), .SRGB(FORMATS)
  ) u_unit (
    .clk(clk), .rst(rst),
    .cfg_desc_we(in_bits[O_DWE]), .cfg_desc_index(in_bits[O_DINDEX +: XW]),
    .cfg_desc_w(in_bits[O_DESC_W +: NW]), .cfg_desc_h(in_bits[O_DESC_H +: NW]), .cfg_desc_ready(desc_ready),
    .cfg_desc_last_level(in_bits[O_LAST +: tex_pkg::LEVEL_W]),
    .cfg_desc_format(in_bits[O_FORMAT +: tex_pkg::FORMAT_W]), .cfg_desc_srgb(in_bits[O_SRGB]),
    .cfg_desc_base(in_bits[O_BASE +: AW]), .req_tex(in_bits[O_TEX +: XW]),
    .req_sampler(in_bits[O_SMP +: tex_pkg::SMP_ID_W]),
    .cfg_smp_we(in_bits[O_SWE]), .cfg_smp_index(in_bits[O_SINDEX +: tex_pkg::SMP_ID_W]),
    .cfg_smp_wrap_u(in_bits[O_WRAP_U +: WW]), .cfg_smp_wrap_v(in_bits[O_WRAP_V +: WW]),
    .cfg_smp_border_rgba(in_bits[O_BORDER +: 64]),
    .cfg_smp_min_linear(in_bits[O_LINEAR]), .cfg_smp_mag_linear(in_bits[O_MAG]),
    .cfg_smp_mip_mode(in_bits[O_MIP +: MW]),
    .cfg_smp_lod_bias(in_bits[O_BIAS +: LW]), .cfg_smp_min_lod(in_bits[O_MIN_LOD +: LW]),
    .cfg_smp_max_lod(in_bits[O_MAX_LOD +: LW]),
    .cfg_smp_unnormalized(in_bits[O_UNNORM]), .cfg_smp_reduction(in_bits[O_REDUCE +: tex_pkg::REDUCTION_W]),
    .cfg_block_morton(in_bits[O_MORTON]),
    .cfg_log2_sets(in_bits[O_SETS +: SW]), .cfg_log2_ways(in_bits[O_WAYS +: YW]),
    .cfg_fifo_limit(in_bits[O_FIFO +: FW]),
    .req_valid(in_bits[O_VALID]), .req_ready(req_ready), .req_u(in_bits[O_U +: UW]),
    .req_v(in_bits[O_V +: UW]), .req_lod(in_bits[O_LOD +: LW]), .req_tag(in_bits[O_TAG +: TAG_W]),
    .req_op(in_bits[O_OP +: tex_pkg::OP_W]), .req_component(in_bits[O_COMP +: 2]),
    .req_layer(in_bits[O_LAYER +: UW]), .cfg_desc_layers_m1(in_bits[O_LAYERS +: tex_pkg::LAYER_W]),
    .cfg_smp_compare_op(in_bits[O_CMP +: tex_pkg::COMPARE_W]), .req_ref(in_bits[O_REF +: UW]),
    .req_bias('0),  // lambda requests (textureLod) have no bias of their own
    // Lambda requests only (the LOD / anisotropy unit is tied off and optimized away: a fit
    // of the probe datapath on the HX8K is not measured here).
    .req_deriv(1'b0), .req_dudx('0), .req_dvdx('0), .req_dudy('0), .req_dvdy('0),
    .cfg_smp_max_aniso_m1(4'd0), .cfg_smp_aniso_pow2(1'b0),
    .rsp_valid(rsp_valid), .rsp_ready(in_bits[O_READY]), .rsp_rgba(rsp_rgba), .rsp_tag(rsp_tag),
    .rsp_error(rsp_error),
    .m_axi_arvalid(arvalid), .m_axi_arready(in_bits[O_MREADY]), .m_axi_araddr(araddr),
    .m_axi_arlen(arlen), .m_axi_arsize(arsize), .m_axi_arburst(arburst), .m_axi_arid(arid),
    .m_axi_arcache(arcache), .m_axi_arprot(arprot),
    .m_axi_rvalid(in_bits[O_MVALID]), .m_axi_rready(rready), .m_axi_rdata(in_bits[O_MDATA +: MEM_W]),
    .m_axi_rresp(in_bits[O_MRESP +: 2]), .m_axi_rlast(in_bits[O_MLAST]), .m_axi_rid(1'b0),
    .stat_lookups(stat_lookups), .stat_misses(stat_misses), .stat_mem_wait(stat_mem_wait)
  );
  always_ff @(posedge clk)
    sout <= ^{rsp_rgba, rsp_tag, rsp_error, arvalid, rready, araddr, arlen, arsize, arburst, arid, arcache,
              arprot, stat_lookups, stat_misses, stat_mem_wait, desc_ready};
endmodule

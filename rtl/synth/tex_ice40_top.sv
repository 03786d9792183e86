// tex_ice40_top: place-and-route harness only (scripts/synth.sh), not part of the design.
// tex_unit has about 240 ports, more than an HX8K package's pins: every input is fed from one
// shift register loaded through pin `sin`, and the response is folded to one pin by XOR, so no
// logic of tex_unit is optimized away and its timing is measured register to register.
// DERIV = 1 (default) feeds the derivative request and the anisotropy configuration from the
// shift register too: the whole tex_unit, as compiled (scripts/synth.sh places a compiled
// configuration this way when an iCE40 part holds it), and the operation, the reduction and the
// unnormalized flag. DERIV = 0 ties them all to 0: λ sample requests only (weighted average,
// normalized coordinates), the LOD/anisotropy unit, the min/max, texel fetch and gather logic
// optimized away (scripts/synth.sh's reduced iCE40 reference, the same unit as before those).
// Handshake: none of its own (a measurement wrapper). Latency: that of tex_unit plus the
//   shift-in. Ports: clk, rst, sin (serial input bit), req_ready, rsp_valid, sout (XOR of the
//   response data and tag).
module tex_ice40_top #(
  parameter int MAX_LOG2_W = 4,
  parameter int MAX_LOG2_H = 4,
  parameter int CW         = 8,
  parameter int TAG_W      = 16,
  parameter int DERIV      = 1
) (
  input  logic clk,
  input  logic rst,
  input  logic sin,
  output logic req_ready,
  output logic rsp_valid,
  output logic sout
);
  localparam int VW = tex_pkg::LEVEL_W;
  localparam int WW = tex_pkg::WRAP_W;
  localparam int MW = tex_pkg::MIP_W;
  localparam int LW = tex_pkg::LOD_W;
  localparam int XW = tex_pkg::COORD_W;
  localparam int UW = tex_pkg::REQ_COORD_W;
  // Field offsets in the input shift register, in port order.
  localparam int NW = tex_pkg::SIZE_W;
  localparam int O_SIZE_W  = 0;
  localparam int O_SIZE_H  = O_SIZE_W + NW;
  localparam int O_LAST    = O_SIZE_H + NW;
  localparam int O_WRAP_U  = O_LAST + tex_pkg::LEVEL_W;
  localparam int O_WRAP_V  = O_WRAP_U + WW;
  localparam int O_LINEAR  = O_WRAP_V + WW;
  localparam int O_MAG     = O_LINEAR + 1;
  localparam int O_MIP     = O_MAG + 1;
  localparam int O_BIAS    = O_MIP + MW;
  localparam int O_MIN_LOD = O_BIAS + LW;
  localparam int O_MAX_LOD = O_MIN_LOD + LW;
  localparam int O_WR_EN   = O_MAX_LOD + LW;
  localparam int O_WR_LVL  = O_WR_EN + 1;
  localparam int O_WR_X    = O_WR_LVL + VW;
  localparam int O_WR_Y    = O_WR_X + XW;
  localparam int O_WR_DATA = O_WR_Y + XW;
  localparam int O_VALID   = O_WR_DATA + 4*CW;
  localparam int O_U       = O_VALID + 1;
  localparam int O_V       = O_U + UW;
  localparam int O_LOD     = O_V + UW;
  localparam int O_TAG     = O_LOD + LW;
  localparam int O_READY   = O_TAG + TAG_W;
  localparam int O_BORDER  = O_READY + 1;      // cfg_smp_border_rgba
  localparam int O_DERIV   = O_BORDER + 64;    // with DERIV only: req_deriv, the 4 derivatives,
  localparam int O_DUDX    = O_DERIV + 1;      // cfg_smp_max_aniso_m1, cfg_smp_aniso_pow2, req_op,
  localparam int O_DVDX    = O_DUDX + UW;      // req_component, cfg_smp_unnormalized, cfg_smp_reduction,
                                               // cfg_smp_compare_op, req_ref
  localparam int O_DUDY    = O_DVDX + UW;
  localparam int O_DVDY    = O_DUDY + UW;
  localparam int O_ANISO   = O_DVDY + UW;
  localparam int O_POW2    = O_ANISO + 4;
  localparam int O_OP      = O_POW2 + 1;
  localparam int O_COMP    = O_OP + tex_pkg::OP_W;
  localparam int O_UNNORM  = O_COMP + 2;
  localparam int O_REDUCE  = O_UNNORM + 1;
  localparam int O_CMP     = O_REDUCE + tex_pkg::REDUCTION_W;
  localparam int O_REF     = O_CMP + tex_pkg::COMPARE_W;
  localparam int NIN       = DERIV != 0 ? O_REF + UW : O_DERIV;

  logic [NIN-1:0] in_bits;
  always_ff @(posedge clk) in_bits <= {in_bits[NIN-2:0], sin};

  logic [4*CW-1:0]  rsp_rgba;
  logic [TAG_W-1:0] rsp_tag;
  logic             req_deriv, cfg_smp_aniso_pow2;
  logic [UW-1:0]    req_dudx, req_dvdx, req_dudy, req_dvdy;
  logic [3:0]       cfg_smp_max_aniso_m1;
  logic [tex_pkg::OP_W-1:0]        req_op;
  logic [1:0]                      req_component;
  logic                            cfg_smp_unnormalized;
  logic [tex_pkg::REDUCTION_W-1:0] cfg_smp_reduction;
  logic [tex_pkg::COMPARE_W-1:0]   cfg_smp_compare_op;
  logic [UW-1:0]                   req_ref;
  if (DERIV != 0) begin : g_deriv
    assign req_deriv        = in_bits[O_DERIV];
    assign req_dudx         = in_bits[O_DUDX +: UW];
    assign req_dvdx         = in_bits[O_DVDX +: UW];
    assign req_dudy         = in_bits[O_DUDY +: UW];
    assign req_dvdy         = in_bits[O_DVDY +: UW];
    assign cfg_smp_max_aniso_m1 = in_bits[O_ANISO +: 4];
    assign cfg_smp_aniso_pow2   = in_bits[O_POW2];
    assign req_op               = in_bits[O_OP +: tex_pkg::OP_W];
    assign req_component        = in_bits[O_COMP +: 2];
    assign cfg_smp_unnormalized = in_bits[O_UNNORM];
    assign cfg_smp_reduction    = in_bits[O_REDUCE +: tex_pkg::REDUCTION_W];
    assign cfg_smp_compare_op   = in_bits[O_CMP +: tex_pkg::COMPARE_W];
    assign req_ref              = in_bits[O_REF +: UW];
  end else begin : g_no_deriv
    // λ sample requests only: the LOD / anisotropy unit, and the min/max, fetch, gather and
    // compare logic, are optimized away.
    assign req_deriv        = 1'b0;
    assign {req_dudx, req_dvdx, req_dudy, req_dvdy} = '0;
    assign cfg_smp_max_aniso_m1 = 4'd0;
    assign req_op               = tex_pkg::OP_SAMPLE;
    assign req_component        = 2'd0;
    assign cfg_smp_unnormalized = 1'b0;
    assign cfg_smp_reduction    = tex_pkg::REDUCE_AVERAGE;
    assign cfg_smp_compare_op   = tex_pkg::CMP_ALWAYS;
    assign req_ref              = '0;
    assign cfg_smp_aniso_pow2   = 1'b0;
  end
  tex_unit #(.MAX_LOG2_W(MAX_LOG2_W), .MAX_LOG2_H(MAX_LOG2_H), .CW(CW), .TAG_W(TAG_W)) u_unit (
    .clk(clk), .rst(rst),
    .cfg_w(in_bits[O_SIZE_W +: NW]), .cfg_h(in_bits[O_SIZE_H +: NW]), .cfg_last_level(in_bits[O_LAST +: tex_pkg::LEVEL_W]),
    .cfg_smp_wrap_u(in_bits[O_WRAP_U +: WW]), .cfg_smp_wrap_v(in_bits[O_WRAP_V +: WW]),
    .cfg_smp_min_linear(in_bits[O_LINEAR]), .cfg_smp_mag_linear(in_bits[O_MAG]),
    .cfg_smp_mip_mode(in_bits[O_MIP +: MW]),
    .cfg_smp_lod_bias(in_bits[O_BIAS +: LW]), .cfg_smp_min_lod(in_bits[O_MIN_LOD +: LW]),
    .cfg_smp_max_lod(in_bits[O_MAX_LOD +: LW]),
    .wr_en(in_bits[O_WR_EN]), .wr_level(in_bits[O_WR_LVL +: VW]), .wr_x(in_bits[O_WR_X +: XW]),
    .wr_y(in_bits[O_WR_Y +: XW]), .wr_data(in_bits[O_WR_DATA +: 4*CW]),
    .req_valid(in_bits[O_VALID]), .req_ready(req_ready), .req_u(in_bits[O_U +: UW]),
    .req_v(in_bits[O_V +: UW]), .req_lod(in_bits[O_LOD +: LW]), .req_tag(in_bits[O_TAG +: TAG_W]),
    .req_bias('0),  // lambda requests (textureLod) have no bias of their own
    .req_deriv(req_deriv), .req_dudx(req_dudx), .req_dvdx(req_dvdx), .req_dudy(req_dudy),
    .req_dvdy(req_dvdy), .cfg_smp_max_aniso_m1(cfg_smp_max_aniso_m1), .cfg_smp_aniso_pow2(cfg_smp_aniso_pow2),
    .cfg_smp_border_rgba(in_bits[O_BORDER +: 64]),
    .req_op(req_op), .req_component(req_component), .cfg_smp_unnormalized(cfg_smp_unnormalized),
    .cfg_smp_reduction(cfg_smp_reduction), .cfg_smp_compare_op(cfg_smp_compare_op), .req_ref(req_ref),
    .rsp_valid(rsp_valid), .rsp_ready(in_bits[O_READY]), .rsp_rgba(rsp_rgba), .rsp_tag(rsp_tag)
  );
  always_ff @(posedge clk) sout <= ^{rsp_rgba, rsp_tag};
endmodule

// tex_filter: the model's `filter_unrounded` stage (docs/numerics.md stage 5), all 4 channels: a
// bilinear in each slot (level d, level d1) and the level blend, 7 one-multiply tex_lerps per
// channel, exact (the one rounding is tex_accum's, after the probes of a sample are summed).
//   clock 1: top = lerp(a, b, fx), bot = lerp(c, e, fx)   per slot            CW.8
//   clock 2: bil = lerp(top, bot, fy)                      per slot            CW.16
//   clock 3: blend = lerp(bil[0], bil[1], f)                                   CW.24
// Point sampling is the same datapath with fx = fy = 0 and f = 0 (blend = a of slot 0, * 2^24).
// A min or max reduction (the model's reduce_taps) compares instead of weighing, in the same
// registers: clock 1 the min/max of the taps a slot weighs with a weight above 0 (a; b if fx > 0;
// c if fy > 0; e if both), clock 2 passes it, clock 3 takes slot 1's too if f > 0; blend is that
// texel value * 2^24 (exact: tex_accum's rounding returns it).
// A gather (the model's stage::gather) takes the same path with channel c of clock 1 holding
// component `component` of slot 0's tap c, e, b, a for c = R, G, B, A (f is 0).
// A depth compare (the model's stage::compare_taps; percentage-closer filtering) tests each tap's
// R, its depth code, in clock 1: `dref OP R`, the tap then (1, 0, 0, 1) where it passes and
// (0, 0, 0, 1) where not, and the lerps weigh those as any taps: clock 1's lerps of two such taps
// are written as their closed form, one * ((256 - w) * pass0 + w * pass1) with one = 2^DW - 1 (DW:
// the bits of the depth codes in the CW-bit channels: 8 in a unit whose memory holds 8-bit
// channels filtered at CW = 16, where an 8-bit texel stays an 8-bit value).
// Handshake: stall-enable; every register loads when en is high.
// Latency: 3 clocks. Throughput: 1 per clock.
// Ports:
//   taps : slot s tap t (0 a, 1 b, 2 c, 3 e) at [(s*4 + t)*4*CW +: 4*CW], each {A, B, G, R} of
//          CW-bit unsigned channels
//   w    : slot s axis a (0 fx, 1 fy) at [(s*2 + a)*WEIGHT_BITS +: WEIGHT_BITS], unsigned, the
//          weight of the +1 tap in 1/256
//   f    : unsigned WEIGHT_BITS, weight of slot 1 (level d1) in 1/256
//   reduction : tex_pkg::REDUCE_*, with the taps (the sampler's reduction mode; code 3 as min)
//   gather, component : with the taps: a gather of channel `component` (0 R .. 3 A)
//   depth_test, compare_op, dref : with the taps: a depth compare, its tex_pkg::CMP_* operator and
//          its reference as a DW-bit code (tex_compare_ref)
//   blend: channel c at [c*(CW+24) +: CW+24] (R, G, B, A), unsigned CW.24, exact
`include "tex_param_error.svh"
module tex_filter #(
  parameter int CW = 8,
  parameter int DW = CW  // bits of a depth code (<= CW)
) (
  input  logic                                clk,
  input  logic                                en,
  input  logic [32*CW-1:0]                    taps,
  input  logic [4*tex_pkg::WEIGHT_BITS-1:0]   w,
  input  logic [tex_pkg::WEIGHT_BITS-1:0]     f,
  input  logic [tex_pkg::REDUCTION_W-1:0]     reduction,
  input  logic                                gather,
  input  logic [1:0]                          component,
  input  logic                                depth_test,
  input  logic [tex_pkg::COMPARE_W-1:0]       compare_op,
  input  logic [DW-1:0]                       dref,
  output logic [4*(CW+24)-1:0]                blend
);
  localparam int WB = tex_pkg::WEIGHT_BITS;

  // Weights and the reduction delayed to the clock that uses them.
  logic [2*WB-1:0] fy_s7;  // slot s at [s*WB +: WB]
  logic [WB-1:0]   f_s7, f_s8;
  logic            compare, compare_s7, compare_s8;  // a min or max reduction
  logic            take_max, take_max_s7, take_max_s8;
  assign compare  = reduction != tex_pkg::REDUCE_AVERAGE || gather;
  assign take_max = reduction == tex_pkg::REDUCE_MAX;
  always_ff @(posedge clk) begin
    if (en) begin
      fy_s7 <= {w[3*WB +: WB], w[1*WB +: WB]};
      f_s7  <= f;
      f_s8  <= f_s7;
      {compare_s7, take_max_s7} <= {compare, take_max};
      {compare_s8, take_max_s8} <= {compare_s7, take_max_s7};
    end
  end

  // `dref OP depth` (tex_pkg::CMP_*: Vulkan's VkCompareOp). Called only in the branches of a depth
  // test, so a simulator evaluates it only then.
  function automatic logic passes(input logic [tex_pkg::COMPARE_W-1:0] op, input logic [DW-1:0] r,
                                  input logic [CW-1:0] d);
    case (op)
      tex_pkg::CMP_NEVER:   passes = 1'b0;
      tex_pkg::CMP_LESS:    passes = CW'(r) < d;
      tex_pkg::CMP_EQUAL:   passes = CW'(r) == d;
      tex_pkg::CMP_LEQUAL:  passes = CW'(r) <= d;
      tex_pkg::CMP_GREATER: passes = CW'(r) > d;
      tex_pkg::CMP_NEQUAL:  passes = CW'(r) != d;
      tex_pkg::CMP_GEQUAL:  passes = CW'(r) >= d;
      tex_pkg::CMP_ALWAYS:  passes = 1'b1;
      default:              passes = 1'b1;
    endcase
  endfunction
  // The lerp of two tested taps of channel c: R one * ((256 - w) * p0 + w * p1), G = B = 0, A one * 256 (CW.8).
  function automatic logic [CW+WB-1:0] tested_lerp(input int c, input logic p0, input logic p1, input logic [WB-1:0] wt);
    logic [WB:0] k;  // (256 - wt) * p0 + wt * p1, 0..256
    k = (p0 ? (WB+1)'(1 << WB) - (WB+1)'(wt) : '0) + (p1 ? (WB+1)'(wt) : '0);
    if (c == 0) tested_lerp = ((CW+WB)'(k) << DW) - (CW+WB)'(k);
    else if (c == 3) tested_lerp = (CW+WB)'({{DW{1'b1}}, WB'(0)});
    else tested_lerp = '0;
  endfunction

  genvar c, s;
  generate
    for (c = 0; c < 4; c = c + 1) begin : g_channel
      for (s = 0; s < 2; s = s + 1) begin : g_slot
        // Channel c of the taps a, b, c, e of slot s.
        logic [CW-1:0]      ta, tb, tc, te;
        logic [CW+WB-1:0]   top_next, bot_next, top_s7, bot_s7;  // CW.8
        logic [CW+2*WB-1:0] bil_next, bil_s8;                    // CW.16
        assign ta = taps[((s*4 + 0)*4 + c)*CW +: CW];
        assign tb = taps[((s*4 + 1)*4 + c)*CW +: CW];
        assign tc = taps[((s*4 + 2)*4 + c)*CW +: CW];
        assign te = taps[((s*4 + 3)*4 + c)*CW +: CW];
        tex_lerp #(.IN_W(CW)) u_top (.a(ta), .b(tb), .w(w[(s*2)*WB +: WB]), .y(top_next));
        tex_lerp #(.IN_W(CW)) u_bot (.a(tc), .b(te), .w(w[(s*2)*WB +: WB]), .y(bot_next));
        // A min or max: the taps of weight 0 replaced by a (which is always weighed), then the min
        // or max of the four. A gather: channel c holds component `component` of tap c, e, b, a of
        // slot 0 (slot 1 takes none: f is 0). Written as statements in the enable's branches, not
        // as continuous logic or functions, so that the simulation computes them only for a min/max
        // or a gather (a function's arguments are evaluated in every clock).
        localparam int GT = (c == 0) ? 2 : (c == 1) ? 3 : (c == 2) ? 1 : 0;
        logic wx, wy;
        assign wx = w[(s*2)*WB +: WB] != '0;
        assign wy = w[(s*2 + 1)*WB +: WB] != '0;
        always_ff @(posedge clk) begin
          if (en) begin
            if (depth_test) begin : g_test  // each tap's R tested; the lerps' closed form
              logic pa, pb, pc, pe;
              pa = passes(compare_op, dref, taps[((s*4 + 0)*4)*CW +: CW]);
              pb = passes(compare_op, dref, taps[((s*4 + 1)*4)*CW +: CW]);
              pc = passes(compare_op, dref, taps[((s*4 + 2)*4)*CW +: CW]);
              pe = passes(compare_op, dref, taps[((s*4 + 3)*4)*CW +: CW]);
              top_s7 <= tested_lerp(c, pa, pb, w[(s*2)*WB +: WB]);
              bot_s7 <= tested_lerp(c, pc, pe, w[(s*2)*WB +: WB]);
            end else if (s == 0 && gather) begin
              case (component)
                2'd0:    top_s7 <= {taps[(GT*4 + 0)*CW +: CW], WB'(0)};
                2'd1:    top_s7 <= {taps[(GT*4 + 1)*CW +: CW], WB'(0)};
                2'd2:    top_s7 <= {taps[(GT*4 + 2)*CW +: CW], WB'(0)};
                default: top_s7 <= {taps[(GT*4 + 3)*CW +: CW], WB'(0)};
              endcase
            end else if (compare) begin : g_reduce
              logic [CW-1:0] pb, pc, pe, m0, m1;
              pb = wx ? tb : ta;
              pc = wy ? tc : ta;
              pe = (wx && wy) ? te : ta;
              m0 = ((ta > pb) == take_max) ? ta : pb;
              m1 = ((pc > pe) == take_max) ? pc : pe;
              top_s7 <= {((m0 > m1) == take_max) ? m0 : m1, WB'(0)};
            end else begin
              top_s7 <= top_next;
            end
            if (!depth_test) bot_s7 <= bot_next;
          end
        end
        tex_lerp #(.IN_W(CW+WB)) u_bil (.a(top_s7), .b(bot_s7), .w(fy_s7[s*WB +: WB]), .y(bil_next));
        always_ff @(posedge clk) if (en) bil_s8 <= compare_s7 ? {top_s7, WB'(0)} : bil_next;
      end

      logic [CW+3*WB-1:0] tri_next;                              // CW.24
      logic [CW-1:0]      r0, r1;  // the slots' reductions (bil_s8's integer part)
      tex_lerp #(.IN_W(CW+2*WB)) u_tri (.a(g_slot[0].bil_s8), .b(g_slot[1].bil_s8), .w(f_s8),
                                        .y(tri_next));
      assign r0 = g_slot[0].bil_s8[2*WB +: CW];
      assign r1 = g_slot[1].bil_s8[2*WB +: CW];
      always_ff @(posedge clk)
        if (en) begin
          if (compare_s8)  // slot 1's too if f > 0 (a gather's f is 0)
            blend[c*(CW+3*WB) +: CW+3*WB] <= {(f_s8 != '0 && ((r1 > r0) == take_max_s8)) ? r1 : r0, (3*WB)'(0)};
          else
            blend[c*(CW+3*WB) +: CW+3*WB] <= tri_next;
        end
    end
  endgenerate

  generate
    if (DW < 1 || DW > CW) begin : g_bad_dw
      `TEX_PARAM_ERROR("tex_filter: DW must be in 1..CW")
    end
    if (3 * WB != 24) begin : g_bad_weights
      `TEX_PARAM_ERROR("tex_filter: blend is CW.24 (tex_pkg::WEIGHT_BITS = 8)")
    end
  endgenerate
endmodule

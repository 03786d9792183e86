// tex_front: the model's stages lod, reduce, scale, address and wrap (docs/numerics.md stages 1-3)
// for both levels a sample reads (slot 0 = level d, slot 1 = level d1): everything before the
// texel fetch, shared by tex_unit (on-chip level memories) and tex_unit_cached (texture caches).
//   clock 1 capture (u_s1, v_s1, lod_s1)  2 tex_lod clamp, tex_reduce  3 tex_lod level select
//   4 per slot and axis: the level's size, tex_scale (u' * size) and tex_address; then tex_wrap,
//   combinational on the clock-4 registers
// A texel fetch (req_fetch; the model's stage::fetch_inside) takes the same path as a point sample
// of an unnormalized sampler in clamp-to-border mode: level k = req_lod in both slots, f = 0, the
// nearest texel of (i + 1/2, j + 1/2) texels; every tap is a border tap when i, j or k lies
// outside every level (clock 2) or k beyond the texture's last level (clock 3), and `zero` says
// the fetch reads nothing (the top answers 0).
// A gather (req_gather; the model's stage::gather) takes level 0 in both slots, f = 0 and the linear
// filter's taps; its weights leave as 1/256 where they are 0, so that every tap is read (the
// filter does not weigh a gather's taps).
// A cube face (req_cube; the model's stage::cube_taps): req_u, req_v are the face's s, t in [0, 1]
// (tex_cube's), reduced as in clamp-to-edge (unchanged) and wrapped in the internal skirt mode:
// the face's texel i is stored at i + 1, its neighbours' edge texels at 0 and n + 1; a texel fetch
// of a cube face reads texel (i + 1, j + 1) of the layer (face) it names.
// Handshake: stall-enable; every register loads when en is high (the valid bits and tags are
//   the top's). The texture's size (req_w, req_h) and the sampler's fields (req_wrap_*, req_min_linear
//   .. req_max_lod: the request's sampler-table entry, or the on-chip unit's one sampler) are the
//   request's, taken with it at clock 1 and carried to the clock that uses them. The datapath
//   reads only registers: no logic depends combinationally on a pin.
// Latency: 4 clocks from the request pins to the clock-4 registers; x, y are combinational on
//   them. Throughput: 1 per clock.
// Ports:
//   req_u, req_v          : signed Q8.24 (an unnormalized sampler's: signed Q16.16 texels of
//                           level 0); req_lod: signed Q8.8 (before bias and clamp); req_bias:
//                           signed Q8.8, the request's own LOD bias (added to the sampler's)
//   req_fetch             : a texel fetch: req_u, req_v, req_lod are the signed integers i, j, k
//   req_gather            : a gather (req_lod, req_bias and the sampler's filters and LOD fields unused)
//   req_cube              : the texture is a cube map (its faces stored with their skirts)
//   req_footprint         : the texture's block footprint {h, w}, 4 bits each (tex_pkg::footprint;
//                           1 x 1 for texels): a power-of-two side longer than a footprint side
//                           that is not a power of two (ASTC 5, 6, 10, 12) has a repeat-seam copy
//   req_w, req_h          : unsigned SIZE_W bits, level 0's size of the request's texture, each
//                           1..2^max(XW, YW) (any value: GL's sizes)
//   req_last_level        : unsigned LEVEL_W bits, the texture's last level (its level count - 1:
//                           a chain may stop before 1x1); tex_lod takes the smaller of it and
//                           floor(log2 max(w, h))
//   req_wrap_u .. req_max_lod: the request's sampler, as tex_unit's cfg_smp_* pins: wrap modes
//                           (tex_pkg::WRAP_*), req_min_linear the minification filter's texel
//                           filter, req_mag_linear the magnification filter (where lambda' <= 0),
//                           req_mip_mode (tex_pkg::MIP_*), req_lod_bias, req_min_lod, req_max_lod
//                           signed Q8.8, req_unnormalized the coordinates are texels (tex_reduce)
//   level                 : slot s at [s*LEVEL_W +: LEVEL_W], integer level (clock 4)
//   f                     : unsigned WEIGHT_BITS, weight of slot 1 in 1/256 (clock 4)
//   w                     : slot s axis a (0 x, 1 y) at [(s*2 + a)*WEIGHT_BITS +: WEIGHT_BITS],
//                           weight of the +1 tap in 1/256 (clock 4)
//   size                  : slot s axis a at [(s*2 + a)*SIZE_W +: SIZE_W], the slot's level size
//                           along the axis, max(1, size0 >> level) (clock 4)
//   x, y                  : wrapped texel indices, unsigned XW (YW) bits; slot s tap j (0: i0,
//                           1: i0 + 1) at [(s*2 + j)*XW +: XW]; each inside its level, or the
//                           repeat seam's index = size (texel 0's copy, a side that is not a
//                           power of two or that the footprint asks one for; docs/numerics.md
//                           stage 3, docs/memory.md §1)
//   border_x, border_y    : slot s tap j at [s*2 + j]: the tap is outside its level in address
//                           mode border (tex_wrap's border; x, y are then don't-care indices)
//   zero                  : a texel fetch outside the texture (no texel read; clock 4)
module tex_front #(
  parameter int XW = 10,  // bits of a wrapped x index: max(MAX_LOG2_W, 1)
  parameter int YW = 10,  // (sizes up to 2^XW x 2^YW)
  parameter int CUBE_MAPS = 0  // 1: req_cube is used (tex_unit_cached's CUBE_MAPS), else ignored
) (
  input  logic                                   clk,
  input  logic                                   en,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u,
  input  logic signed [tex_pkg::REQ_COORD_W-1:0] req_v,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_bias,
  input  logic [tex_pkg::SIZE_W-1:0]             req_w,
  input  logic [tex_pkg::SIZE_W-1:0]             req_h,
  input  logic [tex_pkg::LEVEL_W-1:0]            req_last_level,
  input  logic [tex_pkg::WRAP_W-1:0]             req_wrap_u,
  input  logic [tex_pkg::WRAP_W-1:0]             req_wrap_v,
  input  logic                                   req_min_linear,
  input  logic                                   req_mag_linear,
  input  logic [tex_pkg::MIP_W-1:0]              req_mip_mode,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_lod_bias,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_min_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       req_max_lod,
  input  logic                                   req_unnormalized,
  input  logic                                   req_fetch,
  input  logic                                   req_gather,
  input  logic                                   req_cube,
  input  logic [7:0]                             req_footprint,
  output logic [2*tex_pkg::LEVEL_W-1:0]          level,
  output logic [tex_pkg::WEIGHT_BITS-1:0]        f,
  output logic [4*tex_pkg::WEIGHT_BITS-1:0]      w,
  output logic [4*tex_pkg::SIZE_W-1:0]           size,
  output logic [4*XW-1:0]                        x,
  output logic [4*YW-1:0]                        y,
  output logic [3:0]                             border_x,
  output logic [3:0]                             border_y,
  output logic                                   zero
);
  localparam int VW = tex_pkg::LEVEL_W;
  localparam int WB = tex_pkg::WEIGHT_BITS;
  localparam int NW = tex_pkg::SIZE_W;
  // Widths for this unit's largest texture.
  localparam int ML = (XW > YW) ? XW : YW;   // >= the largest log2 size on either axis
  localparam int RW = tex_pkg::COORD_FRAC + 3;  // tex_reduce's result
  localparam int TW = ML + 12;               // tex_scale's
  localparam int IW = ML + 4;                // tex_address's unwrapped index: [-2n-1, 2n]
  // A size, 1..2^ML: NB bits (of the pins' SIZE_W: the unit's sizes are at most 2^ML, the
  // driver and the configuration port check), the multipliers' and compares' width.
  localparam int NB = ML + 1;

  // ---------------------------------------------------------------- clock 1: capture
  // The texture's {h, w}, the sampler's {wrap v, wrap u} and its filters ride along, clock k's at
  // [(k-1)*width +: width]: tex_reduce reads clock 1's wrap modes, tex_lod the LOD fields of
  // clock 1 and the mip mode and level-select size of clock 2, the level sizes and texel filters
  // clock 3's; tex_wrap clock 4's wrap modes.
  localparam int ZW = 2 * NB, MW = 2 * tex_pkg::WRAP_W, LW = tex_pkg::LOD_W, PW = tex_pkg::MIP_W;
  logic signed [tex_pkg::REQ_COORD_W-1:0] u_s1, v_s1;
  logic signed [LW-1:0]                   lod_s1, min_lod_s1, max_lod_s1;
  logic signed [LW:0]                     lod_bias_s1;  // the sampler's + the request's, exact
  logic [3*ZW-1:0]                        size_q;
  logic [VW-1:0]                          last_s1;   // req_last_level at clock 1
  logic [4*MW-1:0]                        wrap_q;
  logic [2*PW-1:0]                        mip_q;     // clocks 1, 2
  logic [3*2-1:0]                         linear_q;  // {mag, min} at clocks 1..3
  logic [2:0]                             unnorm_q;  // req_unnormalized at clocks 1..3
  logic [3:0]                             fetch_q;   // req_fetch at clocks 1..4
  logic [3:0]                             gather_q;  // req_gather at clocks 1..4
  logic [3:0]                             cube_q;    // req_cube at clocks 1..4 (CUBE_MAPS; else 0)
  logic [3*8-1:0]                         foot_q;    // req_footprint at clocks 1..3
  always_ff @(posedge clk) begin
    if (en) begin
      u_s1        <= req_u;
      v_s1        <= req_v;
      lod_s1      <= req_lod;
      lod_bias_s1 <= (LW+1)'(req_lod_bias) + (LW+1)'(req_bias);
      min_lod_s1  <= req_min_lod;
      max_lod_s1  <= req_max_lod;
      size_q   <= {size_q[0 +: 2*ZW], NB'(req_h), NB'(req_w)};  // (at most 2^ML: NB bits)
      last_s1  <= req_last_level;
      wrap_q   <= {wrap_q[0 +: 3*MW], req_wrap_v, req_wrap_u};
      mip_q    <= {mip_q[0 +: PW], req_mip_mode};
      linear_q <= {linear_q[0 +: 2*2], req_mag_linear, req_min_linear};
      unnorm_q <= {unnorm_q[1:0], req_unnormalized};
      fetch_q  <= {fetch_q[2:0], req_fetch};
      gather_q <= {gather_q[2:0], req_gather};
      foot_q   <= {foot_q[0 +: 2*8], req_footprint};
    end
  end
  generate
    if (CUBE_MAPS != 0) begin : g_cube
      always_ff @(posedge clk) if (en) cube_q <= {cube_q[2:0], req_cube};
    end else begin : g_no_cube
      assign cube_q = '0;
      logic unused_cube;
      assign unused_cube = ^{req_cube, cube_q[2:1]};
    end
    if (NB < NW) begin : g_size_high  // zero for every size this unit takes (1..2^ML)
      logic unused_size_high;
      assign unused_size_high = ^{req_w[NW-1:NB], req_h[NW-1:NB]};
    end
  endgenerate
  logic [ZW-1:0]              size_s3;  // {h0, w0} at clock 3
  logic [tex_pkg::WRAP_W-1:0] wrap_u_s1, wrap_v_s1, wrap_u_s4, wrap_v_s4;
  assign size_s3 = size_q[2*ZW +: ZW];
  assign {wrap_v_s1, wrap_u_s1} = wrap_q[0*MW +: MW];
  assign {wrap_v_s4, wrap_u_s4} = wrap_q[3*MW +: MW];

  // ---------------------------------------------------------------- clocks 2-3: lod, scale
  // The last level, floor(log2 max(w0, h0)) = the larger of the sides' leading ones, or the
  // texture's own last level if its chain stops earlier, from clock 1's size and registered in
  // clock 2 (tex_lod selects the levels in clock 3: the leading-one detectors stay out of that
  // clock).
  logic [VW-1:0] last_level;
  always_ff @(posedge clk) begin
    if (en) begin
      logic [VW-1:0] lead_w, lead_h;
      lead_w = '0;
      lead_h = '0;
      for (int b = 1; b < NB; b++) begin
        if (size_q[b]) lead_w = VW'(b);
        if (size_q[NB + b]) lead_h = VW'(b);
      end
      lead_w = (lead_w > lead_h) ? lead_w : lead_h;
      last_level <= (last_s1 < lead_w) ? last_s1 : lead_w;
    end
  end

  logic [2*VW-1:0] level_s3;       // slot s at [s*VW +: VW]: slot 0 = d, slot 1 = d1
  logic [WB-1:0]   f_s3;
  logic            minify_s3;      // lambda' > 0: the minification filter, else the magnification
  tex_lod u_lod (
    .clk(clk), .en(en), .lod(lod_s1), .bias(lod_bias_s1), .min_lod(min_lod_s1),
    .max_lod(max_lod_s1), .mip_mode(mip_q[PW +: PW]), .last_level(last_level),
    .level(level_s3), .f(f_s3), .minify(minify_s3)
  );
  logic linear_s3;  // the sample's texel filter (the model's stage::texel_filter; a fetch: nearest, a gather linear)
  assign linear_s3 = gather_q[2] || (!fetch_q[2] && (minify_s3 ? linear_q[2*2] : linear_q[2*2 + 1]));

  // A texel fetch: whether its i, j or k lies outside every level this unit holds (clock 2), or k
  // beyond the texture's last level (clock 3); k itself replaces tex_lod's levels in clock 3.
  localparam logic signed [tex_pkg::REQ_COORD_W-1:0] SIDE_MAX = tex_pkg::REQ_COORD_W'(1) <<< ML;
  logic          outside_s2, outside_s3, outside_s4;
  logic [VW-1:0] fetch_level_s2, fetch_level_s3;
  always_ff @(posedge clk) begin
    if (en) begin
      // (if statements rather than logic: the simulation checks only a fetch's indices)
      if (fetch_q[0])
        outside_s2 <= u_s1 < 0 || u_s1 >= SIDE_MAX || v_s1 < 0 || v_s1 >= SIDE_MAX || lod_s1 < 0
                      || lod_s1 > LW'((1 << VW) - 1);
      else
        outside_s2 <= 1'b0;
      fetch_level_s2 <= lod_s1[VW-1:0];
      if (fetch_q[1]) outside_s3 <= outside_s2 || fetch_level_s2 > last_level;
      else outside_s3 <= 1'b0;
      fetch_level_s3 <= fetch_level_s2;
      outside_s4     <= outside_s3;
    end
  end
  logic [2*VW-1:0] level_sel;      // clock 3's levels: tex_lod's, a fetch's k or a gather's 0
  assign level_sel = fetch_q[2] ? {fetch_level_s3, fetch_level_s3} : gather_q[2] ? '0 : level_s3;

  // Per axis a (0 = u / x / width, 1 = v / y / height; part a of these vectors): the reduced
  // coordinate, held one clock while tex_lod selects the levels. A fetch's integer index is the
  // texel centre i + 1/2 in Q16.16 texels (0 <= i < 2^ML where it reads a texel), reduced and
  // scaled as an unnormalized sampler's coordinate.
  logic [2*RW-1:0] reduced_s2, reduced_s3;
  genvar a, s;
  generate
    for (a = 0; a < 2; a = a + 1) begin : g_axis
      logic signed [tex_pkg::REQ_COORD_W-1:0] coord, centre;
      logic [ML-1:0]                          index;  // (its low bits: 0..2^ML - 1 where it reads a texel)
      assign index  = (a == 0) ? u_s1[ML-1:0] : v_s1[ML-1:0];
      assign centre = (tex_pkg::REQ_COORD_W'(index) <<< tex_pkg::TEXEL_COORD_FRAC)
                      | (tex_pkg::REQ_COORD_W'(1) <<< (tex_pkg::TEXEL_COORD_FRAC - 1));
      assign coord = fetch_q[0] ? centre : (a == 0) ? u_s1 : v_s1;
      tex_reduce #(.ML(ML)) u_reduce (.clk(clk), .en(en), .coord(coord),
                                      .mode(cube_q[0] ? tex_pkg::WRAP_CLAMP : (a == 0) ? wrap_u_s1 : wrap_v_s1),
                                      .unnormalized(unnorm_q[0] || fetch_q[0]),
                                      .reduced(reduced_s2[a*RW +: RW]));
    end
  endgenerate
  always_ff @(posedge clk) if (en) reduced_s3 <= reduced_s2;

  // ---------------------------------------------------------------- clock 4: per slot
  // Slot s = level d (s = 0) or d1 (s = 1): the texel coordinates of both axes at that level
  // (clock 4), then their wrap (combinational, into the fetch).
  always_ff @(posedge clk) begin
    if (en) begin
      level <= level_sel;
      f     <= (fetch_q[2] || gather_q[2]) ? '0 : f_s3;
    end
  end
  generate
    for (s = 0; s < 2; s = s + 1) begin : g_slot
      for (a = 0; a < 2; a = a + 1) begin : g_axis
        localparam int OW = (a == 0) ? XW : YW;
        logic signed [IW-1:0] i0_s4, i1_s4;  // the taps, unwrapped
        logic [NB-1:0]        n_s3, n_s4;    // the slot's level size along the axis
        logic                 pow2_s4;       // it has no seam copy: a power of two (not one the footprint asks a copy for)
        logic [3:0]           fp;            // the footprint's side along the axis
        logic signed [TW-1:0] t9_s3;
        logic [OW-1:0]        t0, t1;        // wrapped taps i0, i0 + 1
        logic                 b0, b1;        // their border flags
        // max(1, size0 >> level): a side that reaches 1 texel stays 1 (GL's level sizes).
        logic [NB-1:0] shifted;
        assign shifted = size_s3[a*NB +: NB] >> level_sel[s*VW +: VW];
        assign n_s3    = (shifted == '0) ? NB'(1) : shifted;
        tex_scale #(.ML(ML), .RW(RW)) u_scale (.reduced(reduced_s3[a*RW +: RW]), .n(n_s3),
                                               .unnormalized(unnorm_q[2] || fetch_q[2]), .t9(t9_s3));
        logic [WB-1:0] w_s4;
        tex_address #(.TW(TW), .IW(IW)) u_address (
          .clk(clk), .en(en), .t9(t9_s3), .linear(linear_s3), .i0(i0_s4), .i1(i1_s4), .w(w_s4)
        );
        assign w[(s*2 + a)*WB +: WB] = (gather_q[3] && w_s4 == '0) ? WB'(1) : w_s4;
        // The size and its power-of-two flag are registered here rather than made in clock 5.
        always_ff @(posedge clk) begin
          if (en) begin
            n_s4    <= n_s3;
            pow2_s4 <= !tex_pkg::seam_copy(16'(n_s3), fp);
          end
        end
        assign fp = foot_q[2*8 + a*4 +: 4];
        assign size[(s*2 + a)*NW +: NW] = NW'(n_s4);
        logic [tex_pkg::WRAP_W-1:0] mode;  // the sampler's, a fetch's clamp to border, a cube face's skirt
        assign mode = fetch_q[3] ? (cube_q[3] ? tex_pkg::WRAP_SKIRT_BORDER : tex_pkg::WRAP_BORDER)
                    : cube_q[3] ? tex_pkg::WRAP_SKIRT : (a == 0) ? wrap_u_s4 : wrap_v_s4;
        tex_wrap #(.OUT_W(OW), .IW(IW), .NB(NB), .SECOND(1'b0)) u_wrap0 (.i(i0_s4), .n(n_s4), .pow2(pow2_s4),
                                        .mode(mode), .o(t0), .border(b0));
        tex_wrap #(.OUT_W(OW), .IW(IW), .NB(NB), .SECOND(1'b1)) u_wrap1 (.i(i1_s4), .n(n_s4), .pow2(pow2_s4),
                                        .mode(mode), .o(t1), .border(b1));
        if (a == 0) begin : g_x
          assign x[(s*2 + 0)*XW +: XW] = t0;
          assign x[(s*2 + 1)*XW +: XW] = t1;
          assign border_x[s*2 +: 2]    = {b1, b0} | {2{outside_s4}};
        end else begin : g_y
          assign y[(s*2 + 0)*YW +: YW] = t0;
          assign y[(s*2 + 1)*YW +: YW] = t1;
          assign border_y[s*2 +: 2]    = {b1, b0} | {2{outside_s4}};
        end
      end
    end
  endgenerate
  assign zero = fetch_q[3] && (border_x[0] || border_y[0]);  // (outside_s4 is only ever a fetch's)
endmodule

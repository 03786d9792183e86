// tex_desc_table: tex_unit_cached's texture descriptor table and its set-up. A descriptor names a
// pyramid in external memory; the set-up turns it into what a lookup needs per level: the level's
// first line, the pitch of its block grid and its Morton square (the layout of docs/memory.md §1,
// model/memory_layout.cpp, bit for bit).
//   write    desc_we registers the descriptor (clock 0); in clock 1 its size, last level, format
//            and sRGB flag are written and the set-up starts;
//   set-up   then one level per clock, all 2^LEVEL_W level slots (those past the chain's last
//            level are never read): level k's grid NBX x NBY lines of the format covering its
//            max(1, w >> k) x max(1, h >> k) texels, in units of the format's block (a texel for
//            RGBA8, 4 x 4 texels, or an ASTC footprint: ceil(n_k / F) units a side) and, on a side
//            that is not a power of two or that an ASTC footprint F does not divide (n_k > F),
//            the repeat seam's copy of unit column (row) 0; its first line = the last
//            one's + NBX * NBY (row-major) or + 2^(ceil log2 NBX + ceil log2 NBY) (Morton). One
//            multiplier, used once per level, where one per level in a single clock would be 16.
//            A cube map's faces (desc_cube) are stored with a one-texel skirt and no seam copy:
//            a side spans n_k + 2 texels (model MemoryLayout, TextureKind::Cube).
//            At the chain's last level (the smaller of desc_last_level and floor(log2 max(w, h)))
//            the lines so far are the layer stride: an array's layers are whole pyramids one after
//            another (layer l at the base + l x stride lines; model MemoryLayout::layer_bytes).
// Handshake: busy (a register output) is high from the clock after desc_we until the set-up has
//   written the last level, 1 + 2^LEVEL_W clocks; desc_we must stay low while busy is high, and
//   tex_unit_cached takes no request meanwhile. The table is not reset (an entry is valid once
//   written).
// Latency: reads are combinational (the size at the request port and the probe's clock 1, the
//   level entries and format at the tag stage). Throughput: one descriptor per 2 + 2^LEVEL_W clocks.
// Ports:
//   desc_*            : a descriptor write (tex_unit_cached's cfg_desc_* pins): entry desc_index is
//                       the pyramid at byte address desc_base (line aligned) of desc_w x desc_h
//                       texels (1..2^MAX_LOG2_W, 1..2^MAX_LOG2_H; unsigned SIZE_W bits), levels
//                       0..desc_last_level (LEVEL_W bits; the set-up walks all 16 slots anyway),
//                       format desc_format (tex_pkg::FMT_*), sRGB if desc_srgb, desc_layers_m1 + 1
//                       layers (unsigned LAYER_W bits), a cube map (or cube array) if desc_cube:
//                       6 layers a cube, +X .. -Z, square RGBA faces (CUBE_MAPS only)
//   block_morton      : the block order of every level (a registered cfg pin; set under reset)
//   size_tex_a/_b     : two entries whose size is read: size_a, size_b = {h, w}, SIZE_W bits each;
//                       last_b: entry b's last level; footprint_b: entry b's block footprint {h, w}
//                       (4 bits each: tex_pkg::footprint; the repeat seam's rule); layers_a: entry a's layer count - 1,
//                       cubes_a its cube count - 1 (a cube map's: the clamp of its cube index);
//                       cube_b: entry b is a cube map
//   cube_tex_c, cube_c : an entry and whether it is a cube map (read at the request port)
//   stride_tex, stride : an entry and its layer stride, in lines (LNW bits)
//   tag_tex, tag_level: the tag stage's entry and its two slots' levels ({d1, d}, LEVEL_W each);
//   tag_line          : per slot, the level's first line (a line number, MEM_ADDR_W - log2 line bytes)
//   tag_pitch         : per slot, NBX (row-major: the block row's pitch), PTW bits unsigned
//   tag_square        : per slot, min(ceil log2 NBX, ceil log2 NBY) (Morton: the interleaved square)
//   tag_format, tag_srgb, tag_log2_lw, tag_log2_lh : the entry's format, sRGB flag and line shape
//                       (log2 units across and down a line: the BW x BH texels, or a block format's
//                       blocks, 2^a x 2^b of them in the line's bytes, a = b or b + 1)
`include "tex_param_error.svh"
module tex_desc_table #(
  parameter int MAX_LOG2_W    = 10,
  parameter int MAX_LOG2_H    = 10,
  parameter int TEXTURES      = 16,  // power of two, 1..16
  parameter int BW            = 4,   // texels per line of RGBA8: BW x BH (2, 4, 8)
  parameter int BH            = 4,
  parameter int LINE_BYTES    = 64,
  parameter int BLOCK_FORMATS = 0,
  parameter int SRGB          = 0,
  parameter int CUBE_MAPS     = 0,
  parameter int TXW = (TEXTURES > 1) ? $clog2(TEXTURES) : 1,  // derived, do not override
  parameter int PTW = ((MAX_LOG2_W > MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H) + 1,
  parameter int LNW = tex_pkg::MEM_ADDR_W - $clog2(LINE_BYTES)
) (
  input  logic                            clk,
  input  logic                            rst,
  input  logic                            desc_we,
  input  logic [TXW-1:0]                  desc_index,
  input  logic [tex_pkg::MEM_ADDR_W-1:0]  desc_base,
  input  logic [tex_pkg::SIZE_W-1:0]      desc_w,
  input  logic [tex_pkg::SIZE_W-1:0]      desc_h,
  input  logic [tex_pkg::LEVEL_W-1:0]     desc_last_level,
  input  logic [tex_pkg::FORMAT_W-1:0]    desc_format,
  input  logic                            desc_srgb,
  input  logic [tex_pkg::LAYER_W-1:0]     desc_layers_m1,
  input  logic                            desc_cube,
  input  logic                            block_morton,
  output logic                            busy,

  input  logic [TXW-1:0]                  size_tex_a,
  output logic [2*tex_pkg::SIZE_W-1:0]    size_a,
  output logic [tex_pkg::LAYER_W-1:0]     layers_a,
  output logic [tex_pkg::LAYER_W-1:0]     cubes_a,
  input  logic [TXW-1:0]                  size_tex_b,
  output logic [2*tex_pkg::SIZE_W-1:0]    size_b,
  output logic [tex_pkg::LEVEL_W-1:0]     last_b,
  output logic [7:0]                      footprint_b,
  output logic                            cube_b,
  input  logic [TXW-1:0]                  cube_tex_c,
  output logic                            cube_c,
  input  logic [TXW-1:0]                  stride_tex,
  output logic [LNW-1:0]                  stride,

  input  logic [TXW-1:0]                  tag_tex,
  input  logic [2*tex_pkg::LEVEL_W-1:0]   tag_level,
  output logic [2*LNW-1:0]                tag_line,
  output logic [2*PTW-1:0]                tag_pitch,
  output logic [2*tex_pkg::LEVEL_W-1:0]   tag_square,
  output logic [tex_pkg::FORMAT_W-1:0]    tag_format,
  output logic                            tag_srgb,
  output logic [tex_pkg::LEVEL_W-1:0]     tag_log2_lw,
  output logic [tex_pkg::LEVEL_W-1:0]     tag_log2_lh
);
  localparam int VW      = tex_pkg::LEVEL_W;
  localparam int NW      = tex_pkg::SIZE_W;
  localparam int FW      = tex_pkg::FORMAT_W;
  localparam int YL      = tex_pkg::LAYER_W;
  localparam int LOG2_LB = $clog2(LINE_BYTES);
  localparam int LEVELS  = 1 << VW;
  localparam int EW      = LNW + PTW + VW;  // a level entry: {first line, pitch, square}

  generate  // (tex_unit_cached checks its own parameters, from which these come)
    if ((TEXTURES & (TEXTURES - 1)) != 0 || TEXTURES < 1 || TEXTURES > 16 || (BW != 2 && BW != 4 && BW != 8)
        || (BH != 2 && BH != 4 && BH != 8) || (LINE_BYTES & (LINE_BYTES - 1)) != 0 || LINE_BYTES < 16)
    begin : g_bad_params
      `TEX_PARAM_ERROR("tex_desc_table: TEXTURES must be a power of two 1..16, BW and BH 2, 4 or 8, LINE_BYTES a power of two >= 16")
    end
  endgenerate

  // ---------------------------------------------------------------- the write, registered
  logic                   we_q;
  logic [TXW-1:0]         index_q;
  logic [LNW-1:0]         base_q;
  logic [NW-1:0]          w_q, h_q;
  logic [VW-1:0]          last_q;
  logic [FW-1:0]          format_q;
  logic                   srgb_q;
  logic [YL-1:0]          layers_q;
  logic                   cube_q;
  always_ff @(posedge clk) begin
    we_q <= !rst && desc_we;
    if (desc_we) begin  // (held through the set-up: no write while busy)
      index_q  <= desc_index;
      base_q   <= LNW'(desc_base >> LOG2_LB);
      w_q      <= desc_w;
      h_q      <= desc_h;
      last_q   <= desc_last_level;
      format_q <= (BLOCK_FORMATS != 0) ? desc_format : tex_pkg::FMT_RGBA8;
      srgb_q   <= (SRGB != 0) && desc_srgb;
      layers_q <= desc_layers_m1;
      cube_q   <= (CUBE_MAPS != 0) && desc_cube;
    end
  end

  // A cube array's cubes - 1: (layers_q + 1) / 6 - 1 (layers a multiple of 6, at most 252).
  logic [YL-1:0] cubes_m1;
  assign cubes_m1 = YL'((YL+1)'(layers_q) / (YL+1)'(6));

  // A format's line, in units (texels, or blocks): log2 across and down.
  function automatic logic [2*VW-1:0] line_shape(input logic [FW-1:0] fmt);
    int lb;  // log2 of the line's blocks
    lb = tex_pkg::line_kind(fmt) == tex_pkg::LINE_BLOCKS8 ? LOG2_LB - 3 : LOG2_LB - 4;  // 8- or 16-byte blocks
    if (fmt == tex_pkg::FMT_RGBA8) line_shape = {VW'($clog2(BH)), VW'($clog2(BW))};
    else line_shape = {VW'(lb / 2), VW'((lb + 1) / 2)};
  endfunction
  // The lines across one side of level k: the side max(1, n >> k) in units of the footprint side
  // f (ceil(n_k / f)) and the repeat seam's copy of unit column 0 where the side has one (not a
  // power of two, or longer than an f that is not: ASTC 5, 6, 10, 12), in lines of 2^lb units; a
  // cube face's n_k and its skirt's two.
  function automatic logic [PTW-1:0] side_blocks(input logic [NW-1:0] n, input logic [VW-1:0] k,
                                                 input logic [VW-1:0] lb, input logic [3:0] f, input logic cube);
    logic [NW+2:0] nk, units;
    logic [15:0]   whole;  // ceil(n_k / f)
    logic          seam;
    nk = (NW+3)'(n) >> k;
    if (nk == '0) nk = (NW+3)'(1);
    seam = tex_pkg::seam_copy(16'(nk), f);
    whole = tex_pkg::div_footprint(16'(nk + (NW+3)'(f) - (NW+3)'(1)), f);
    if (cube) units = nk + (NW+3)'(2);
    else units = (NW+3)'(whole) + (NW+3)'(seam);
    side_blocks = PTW'((units + (NW+3)'((1 << lb) - 1)) >> lb);
  endfunction
  function automatic logic [VW-1:0] log2_ceil(input logic [PTW-1:0] v);
    log2_ceil = '0;
    for (int i = 0; i < PTW; i++) if ((PTW+1)'(v) > ((PTW+1)'(1) << i)) log2_ceil = VW'(i + 1);
  endfunction

  // ---------------------------------------------------------------- set-up: a level per clock
  logic          walking;
  logic [VW-1:0] lev;       // the level this clock writes
  logic [LNW-1:0] acc;      // its first line
  logic [VW-1:0] lw, lh;    // the format's line shape
  logic [PTW-1:0] nbx, nby;
  logic [VW-1:0] lbx, lby;
  logic [LNW-1:0] lines;    // the level's lines in memory
  logic [7:0]    foot_q;    // the format's footprint {h, w}
  assign {lh, lw} = line_shape(format_q);
  assign foot_q   = tex_pkg::footprint(format_q);
  always_comb begin
    nbx   = side_blocks(w_q, lev, lw, foot_q[3:0], cube_q);
    nby   = side_blocks(h_q, lev, lh, foot_q[7:4], cube_q);
    lbx   = log2_ceil(nbx);
    lby   = log2_ceil(nby);
    lines = block_morton ? LNW'(1) << (5'(lbx) + 5'(lby)) : LNW'(nbx) * LNW'(nby);
  end
  assign busy = we_q || walking;
  // The chain's last level: desc_last_level, or floor(log2 max(w, h)) if the chain reaches 1x1 first.
  logic [VW-1:0] chain_last;
  always_comb begin
    logic [VW-1:0] lead;
    lead = '0;
    for (int b = 1; b < NW; b++) if (w_q[b] || h_q[b]) lead = VW'(b);
    chain_last = (last_q < lead) ? last_q : lead;
  end

  logic [NW-1:0]  size_w [TEXTURES];
  logic [NW-1:0]  size_h [TEXTURES];
  logic [VW-1:0]  last   [TEXTURES];
  logic [FW-1:0]  format [TEXTURES];
  logic           srgb   [TEXTURES];
  logic [YL-1:0]  layers [TEXTURES];
  logic [YL-1:0]  cubes  [TEXTURES];
  logic           cube   [TEXTURES];
  logic [LNW-1:0] strides [TEXTURES];
  logic [EW-1:0]  level  [TEXTURES * LEVELS];  // entry t, level k at t * LEVELS + k
  always_ff @(posedge clk) begin
    if (we_q) begin
      size_w[index_q] <= w_q;
      size_h[index_q] <= h_q;
      last[index_q]   <= last_q;
      format[index_q] <= format_q;
      srgb[index_q]   <= srgb_q;
      layers[index_q] <= layers_q;
      cubes[index_q]  <= cubes_m1;
      cube[index_q]   <= cube_q;
    end
    if (walking)
      level[(32'(index_q) << VW) + 32'(lev)] <= {acc, nbx, (lbx < lby) ? lbx : lby};
    if (walking && lev == chain_last)
      strides[index_q] <= acc + lines - base_q;
  end
  always_ff @(posedge clk) begin
    if (rst) begin
      walking <= 1'b0;
    end else if (we_q) begin
      walking <= 1'b1;
    end else if (walking && lev == VW'(LEVELS - 1)) begin
      walking <= 1'b0;
    end
    if (we_q) begin
      lev <= '0;
      acc <= base_q;
    end else if (walking) begin
      lev <= lev + 1'b1;
      acc <= acc + lines;
    end
  end

  // ---------------------------------------------------------------- reads
  assign size_a = {size_h[size_tex_a], size_w[size_tex_a]};
  assign size_b = {size_h[size_tex_b], size_w[size_tex_b]};
  assign last_b = last[size_tex_b];
  assign footprint_b = tex_pkg::footprint(format[size_tex_b]);
  assign layers_a = layers[size_tex_a];
  assign cubes_a  = cubes[size_tex_a];
  assign cube_b   = cube[size_tex_b];
  assign cube_c   = cube[cube_tex_c];
  assign stride   = strides[stride_tex];
  generate
    for (genvar s = 0; s < 2; s++) begin : g_slot
      logic [EW-1:0] e;
      assign e = level[(32'(tag_tex) << VW) + 32'(tag_level[s*VW +: VW])];
      assign tag_line[s*LNW +: LNW]   = e[PTW + VW +: LNW];
      assign tag_pitch[s*PTW +: PTW]  = e[VW +: PTW];
      assign tag_square[s*VW +: VW]   = e[0 +: VW];
    end
  endgenerate
  assign tag_format = format[tag_tex];
  assign tag_srgb   = srgb[tag_tex];
  assign {tag_log2_lh, tag_log2_lw} = line_shape(tag_format);
endmodule

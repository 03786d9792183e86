// tex_unit_cached: the texture unit with the pyramid in external memory behind two texture caches
// (even and odd levels) and a latency-hiding sample FIFO (docs/memory.md). Same numerics, request
// and response ports as tex_unit (bit-identical responses); the level memories and their write
// port are replaced by an AXI4 read master. Interface contract: docs/rtl-interface.md.
//
// Handshake: req and rsp are valid/ready. req_ready is a register output (tex_cached_fetch's
//   en_front: room in the sample FIFO and the miss ring). Responses come in request order with
//   their tag, with full backpressure.
// AXI4 read master (AMBA AXI4 names): one INCR burst per cache line, LINE_BITS / MEM_W beats of
//   MEM_W bits (ARLEN = beats - 1, ARSIZE = log2 of the beat's bytes), a single ID (ARID = 0) and
//   so responses in order, at most MISS_DEPTH reads outstanding (the miss ring), ARVALID and
//   ARADDR functions of registers only, RREADY of registers only. A beat with RRESP SLVERR or
//   DECERR marks its line: every sample that looks the line up while it is cached comes out with
//   rsp_error set and rsp_rgba 0 (the unit keeps running; docs/memory.md §3). RLAST and RID are
//   checked in simulation only (tex_axi_read counts the beats of a line).
// Latency: 19 clocks from the request handshake edge to rsp_valid when every line hits, the
//   request has one probe and the output is not stalled, 29 with CUBE_MAPS (6 clocks of tex_cube
//   for every request first, 4 of tex_cube_seam for every probe after tex_probe; otherwise
//   requests 1-4 tex_probe; probes 1-4
//   tex_front, 5 tag stage and FIFO push, 6 head, 7 data read, 8 taps, 9-11 tex_filter, 12-13
//   tex_accum, 14 tex_skid); a miss adds the memory's latency, each further probe a clock.
// Throughput: 1 probe per clock while lines hit (1 sample per clock for lambda requests and
//   isotropic footprints); the FIFO (FIFO_DEPTH probes) keeps requests flowing while misses are
//   outstanding. Memory traffic is a function of the requests and the
//   cache configuration alone (docs/memory.md §2).
// Ports: as tex_unit (req_u, req_v signed Q8.24; req_lod signed Q8.8; req_deriv, req_dudx ..
//   req_dvdy; rsp_rgba {A, B, G, R} CW-bit unsigned) but for the texture and the sampler, which a
//   request names (tables, as Vulkan and D3D12 keep image views and samplers apart), plus
//   req_tex          : the request's texture descriptor-table entry, 0..TEXTURES-1
//   req_sampler      : the request's sampler-table entry, 0..SAMPLERS-1
//   req_op, req_component : as tex_unit's (a sample, a gather or a texel fetch of the request's texture)
//   req_ref          : a depth compare's reference (req_op OP_COMPARE), signed Q8.24: each texel's R,
//                      its depth, tested `ref OP R` by the request's sampler's cfg_smp_compare_op, then
//                      filtered (tex_compare_ref, tex_filter; the depth codes are the memory's
//                      channel width: 8 bits with SRGB)
//   req_w, req_dwdx, req_dwdy : a cube map's direction is (req_u, req_v, req_w), signed Q8.24 of any
//                      length, its derivatives (req_dudx, req_dvdx, req_dwdx) and (.. req_dwdy);
//                      tex_cube makes them the face's s, t and theirs (CUBE_MAPS; a texel fetch
//                      of a cube names the face as its layer, 6 a cube); an anisotropic probe
//                      beyond its face moves onto the face it lies over (tex_cube_seam)
//   req_layer        : the layer of an array texture, signed Q16.16 layers (rounded to the nearest,
//                      a tie to the even, clamped to the texture's layers: tex_layer); a texel
//                      fetch's: a signed integer (outside the layers: the fetch answers 0)
//   cfg_smp_*        : a sampler write (cfg_smp_we high for one clock): entry cfg_smp_index gets
//                      the fields of tex_unit's cfg_smp_* pins (filters, mip mode, LOD bias and
//                      clamp signed Q8.8, anisotropy cap, wrap modes, reduction, compare op, border colour
//                      {A, B, G, R} unorm16). Written before the requests that name the entry; requests of
//                      different samplers interleave freely (no flush: the fields ride with
//                      each request).
//   cfg_desc_*       : a descriptor write (cfg_desc_we high for one clock, while cfg_desc_ready):
//                      entry cfg_desc_index is the pyramid at byte address cfg_desc_base
//                      (MEM_ADDR_W bits, line aligned) of cfg_desc_w x cfg_desc_h texels (1 to
//                      2^MAX_LOG2_W x 2^MAX_LOG2_H, any size; a chain of levels of GL's sizes
//                      from 0 to cfg_desc_last_level, or to 1x1 if that comes first: docs/memory.md §1) in format cfg_desc_format (tex_pkg::FMT_*: RGBA, or with BLOCK_FORMATS a
//                      block format, decoded after the cache to unorm8 texels, EAC's to 16-bit
//                      channels (SRGB only; signed ones in offset binary); docs/memory.md §1),
//                      its R, G, B sRGB-encoded if cfg_desc_srgb (SRGB only; not BC4, BC5, EAC); an
//                      array of cfg_desc_layers_m1 + 1 such pyramids one after another (1..256
//                      layers; each layer's first line a whole number of lines after the last's);
//                      a cube map or cube array if cfg_desc_cube (CUBE_MAPS): 6 layers a cube
//                      (+X, -X, +Y, -Y, +Z, -Z), square RGBA faces of n x n texels, n + 2 at most
//                      the configuration's smaller side, each level stored with its one-texel skirt
//                      (n_k + 2 texels a side, no seam copies; docs/memory.md §1).
//                      Written before the requests that name the entry (and rewritten between
//                      frames, with no request of that entry in flight); the caches need no flush
//                      (they are tagged by address). The unit then sets the entry up (its levels'
//                      first lines and pitches, tex_desc_table): cfg_desc_ready (a register
//                      output) is low and req_ready is low for 1 + 2^LEVEL_W clocks.
//   cfg_block_morton : 0 row-major, 1 Morton order of a level's blocks
//   cfg_log2_sets, cfg_log2_ways : geometry of each cache (sets >= 4, sets * ways <= LINES)
//   cfg_fifo_limit   : samples the FIFO holds at most, 1..FIFO_DEPTH (0 or more: FIFO_DEPTH), to
//                      measure a shallower FIFO without rebuilding; unsigned $clog2(FIFO_DEPTH+1) bits
//   m_axi_araddr     : byte address of a line (line aligned); m_axi_rdata: one MEM_W-bit beat
//                      of it, bytes [i*MEM_W/8 +: MEM_W/8] of the line in beat i
//   rsp_error        : the sample read a line the memory answered with an error; rsp_rgba is 0
//   stat_lookups, stat_misses : lines looked up in this clock (0..8) and of those missing, unsigned
//   stat_mem_wait    : the FIFO's head waits for memory in this clock (for counters)
// cfg_* are registered every clock; a descriptor or sampler entry must not be rewritten while a
//   request that names it is in flight; cfg_log2_sets, cfg_log2_ways, cfg_block_morton change only under reset (the caches are
//   emptied by rst), a texture in memory only with its descriptor (and no request of it in flight).
`include "tex_param_error.svh"
module tex_unit_cached #(
  parameter int MAX_LOG2_W = 10,   // largest texture: 2^MAX_LOG2_W x 2^MAX_LOG2_H, each 0..13
  parameter int MAX_LOG2_H = 10,
  parameter int CW         = 8,    // bits per channel, 1..16
  parameter int TAG_W      = 16,   // >= 1
  parameter int BLOCK_W    = 4,    // texels per cache line: BLOCK_W x BLOCK_H, each 2, 4 or 8
  parameter int BLOCK_H    = 4,
  parameter int LINES      = 256,  // lines per cache at most (power of two, >= 16)
  parameter int MAX_WAYS   = 4,    // 1, 2 or 4
  parameter int FIFO_DEPTH = 256,  // samples waiting for memory (power of two, >= 2)
  parameter int MISS_DEPTH = 64,   // misses in flight (power of two, >= 16)
  parameter int FILL_DEPTH = 4,    // received lines not yet written (power of two)
  parameter int MEM_W      = 128,  // AXI data width: bits of a beat (32..256, divides the line)
  parameter int AXI_ID_W   = 1,    // AXI ID width (1..16; the unit uses ID 0)
  parameter int TEXTURES   = 16,   // texture descriptor-table entries (power of two, 1..16)
  parameter int SAMPLERS   = 16,   // sampler-table entries (power of two, 1..16)
  parameter int BLOCK_FORMATS = 1, // 1: BC1-BC5 and BC7 textures too, 8 decoders after the cache
                                   // (needs 8-bit memory channels and lines of at least 64 bytes)
  parameter int SRGB       = 0,    // 1: sRGB textures too: memory holds 8-bit channels, CW = 16;
                                   // an sRGB texture's R, G, B decoded to linear unorm16 by a table
                                   // before the filter, a linear texture filtered as 8-bit values
  parameter int CUBE_MAPS  = 1     // 1: cube maps and cube arrays too (tex_cube ahead of tex_probe,
                                   // tex_cube_seam after it: every request's latency 10 clocks longer)
) (
  input  logic                                   clk,
  input  logic                                   rst,

  input  logic                                   cfg_desc_we,
  input  logic [tex_pkg::TEX_ID_W-1:0]           cfg_desc_index,
  input  logic [tex_pkg::MEM_ADDR_W-1:0]         cfg_desc_base,
  input  logic [tex_pkg::SIZE_W-1:0]             cfg_desc_w,
  input  logic [tex_pkg::SIZE_W-1:0]             cfg_desc_h,
  input  logic [tex_pkg::LEVEL_W-1:0]            cfg_desc_last_level,
  input  logic [tex_pkg::FORMAT_W-1:0]           cfg_desc_format,
  input  logic                                   cfg_desc_srgb,
  input  logic [tex_pkg::LAYER_W-1:0]            cfg_desc_layers_m1,
  input  logic                                   cfg_desc_cube,
  output logic                                   cfg_desc_ready,
  input  logic                                   cfg_smp_we,
  input  logic [tex_pkg::SMP_ID_W-1:0]           cfg_smp_index,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_smp_wrap_u,
  input  logic [tex_pkg::WRAP_W-1:0]             cfg_smp_wrap_v,
  input  logic                                   cfg_smp_min_linear,
  input  logic                                   cfg_smp_mag_linear,
  input  logic [tex_pkg::MIP_W-1:0]              cfg_smp_mip_mode,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_lod_bias,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_min_lod,
  input  logic signed [tex_pkg::LOD_W-1:0]       cfg_smp_max_lod,
  input  logic [3:0]                             cfg_smp_max_aniso_m1,
  input  logic                                   cfg_smp_aniso_pow2,
  input  logic [63:0]                            cfg_smp_border_rgba,
  input  logic                                   cfg_smp_unnormalized,
  input  logic [tex_pkg::REDUCTION_W-1:0]        cfg_smp_reduction,
  input  logic [tex_pkg::COMPARE_W-1:0]          cfg_smp_compare_op,
  input  logic                                   cfg_block_morton,
  input  logic [tex_pkg::LOG2_SETS_W-1:0]        cfg_log2_sets,
  input  logic [tex_pkg::LOG2_WAYS_W-1:0]        cfg_log2_ways,
  input  logic [$clog2(FIFO_DEPTH+1)-1:0]        cfg_fifo_limit,

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
  input  logic [AXI_ID_W-1:0]                    m_axi_rid,

  output logic [3:0]                             stat_lookups,
  output logic [3:0]                             stat_misses,
  output logic                                   stat_mem_wait
);
  localparam int VW = tex_pkg::LEVEL_W;
  localparam int WB = tex_pkg::WEIGHT_BITS;

  // ---------------------------------------------------------------- parameter checks
  localparam int MLW = (MAX_LOG2_W < 0) ? 0 : (MAX_LOG2_W > tex_pkg::MAX_LOG2_SIZE)
                       ? tex_pkg::MAX_LOG2_SIZE : MAX_LOG2_W;
  localparam int MLH = (MAX_LOG2_H < 0) ? 0 : (MAX_LOG2_H > tex_pkg::MAX_LOG2_SIZE)
                       ? tex_pkg::MAX_LOG2_SIZE : MAX_LOG2_H;
  localparam int CWD = (CW < 1) ? 1 : (CW > tex_pkg::MAX_CW) ? tex_pkg::MAX_CW : CW;
  localparam int TGW = (TAG_W < 1) ? 1 : TAG_W;
  localparam int XW  = (MLW > 0) ? MLW : 1;
  localparam int YW  = (MLH > 0) ? MLH : 1;
  localparam int LINE_BITS = BLOCK_W * BLOCK_H * ((CW > 8 && SRGB == 0) ? 64 : 32);
  generate
    if (MAX_LOG2_W < 0 || MAX_LOG2_W > tex_pkg::MAX_LOG2_SIZE) begin : g_bad_max_log2_w
      `TEX_PARAM_ERROR("tex_unit_cached: parameter MAX_LOG2_W must be in 0..13 (tex_pkg::MAX_LOG2_SIZE)")
    end
    if (MAX_LOG2_H < 0 || MAX_LOG2_H > tex_pkg::MAX_LOG2_SIZE) begin : g_bad_max_log2_h
      `TEX_PARAM_ERROR("tex_unit_cached: parameter MAX_LOG2_H must be in 0..13 (tex_pkg::MAX_LOG2_SIZE)")
    end
    if (CW < 1 || CW > tex_pkg::MAX_CW) begin : g_bad_cw
      `TEX_PARAM_ERROR("tex_unit_cached: parameter CW must be in 1..16 (tex_pkg::MAX_CW)")
    end
    if (TAG_W < 1) begin : g_bad_tag_w
      `TEX_PARAM_ERROR("tex_unit_cached: parameter TAG_W must be at least 1")
    end
    if (!(BLOCK_W == 2 || BLOCK_W == 4 || BLOCK_W == 8)) begin : g_bad_block_w
      `TEX_PARAM_ERROR("tex_unit_cached: parameter BLOCK_W must be 2, 4 or 8")
    end
    if (!(BLOCK_H == 2 || BLOCK_H == 4 || BLOCK_H == 8)) begin : g_bad_block_h
      `TEX_PARAM_ERROR("tex_unit_cached: parameter BLOCK_H must be 2, 4 or 8")
    end
    if (!(MAX_WAYS == 1 || MAX_WAYS == 2 || MAX_WAYS == 4)) begin : g_bad_ways
      `TEX_PARAM_ERROR("tex_unit_cached: parameter MAX_WAYS must be 1, 2 or 4")
    end
    if (LINES < 16 || (LINES & (LINES - 1)) != 0) begin : g_bad_lines
      `TEX_PARAM_ERROR("tex_unit_cached: parameter LINES must be a power of two, at least 16")
    end
    if (FIFO_DEPTH < 2 || (FIFO_DEPTH & (FIFO_DEPTH - 1)) != 0) begin : g_bad_fifo
      `TEX_PARAM_ERROR("tex_unit_cached: parameter FIFO_DEPTH must be a power of two, at least 2")
    end
    if (MISS_DEPTH < 16 || (MISS_DEPTH & (MISS_DEPTH - 1)) != 0) begin : g_bad_miss
      `TEX_PARAM_ERROR("tex_unit_cached: parameter MISS_DEPTH must be a power of two, at least 16")
    end
    if (FILL_DEPTH < 1 || (FILL_DEPTH & (FILL_DEPTH - 1)) != 0) begin : g_bad_fill
      `TEX_PARAM_ERROR("tex_unit_cached: parameter FILL_DEPTH must be a power of two")
    end
    if (MEM_W < 32 || MEM_W > 256 || (MEM_W & (MEM_W - 1)) != 0 || MEM_W > LINE_BITS) begin : g_bad_mem_w
      `TEX_PARAM_ERROR("tex_unit_cached: parameter MEM_W must be a power of two from 32 to 256 that divides the line's bits (the AXI data width)")
    end
    if (AXI_ID_W < 1 || AXI_ID_W > 16) begin : g_bad_axi_id_w
      `TEX_PARAM_ERROR("tex_unit_cached: parameter AXI_ID_W must be in 1..16")
    end
    if (TEXTURES < 1 || TEXTURES > (1 << tex_pkg::TEX_ID_W) || (TEXTURES & (TEXTURES - 1)) != 0) begin : g_bad_textures
      `TEX_PARAM_ERROR("tex_unit_cached: parameter TEXTURES must be a power of two from 1 to 16 (tex_pkg::TEX_ID_W)")
    end
    if (SAMPLERS < 1 || SAMPLERS > (1 << tex_pkg::SMP_ID_W) || (SAMPLERS & (SAMPLERS - 1)) != 0) begin : g_bad_samplers
      `TEX_PARAM_ERROR("tex_unit_cached: parameter SAMPLERS must be a power of two from 1 to 16 (tex_pkg::SMP_ID_W)")
    end
    if (!(SRGB == 0 || (SRGB == 1 && CW == 16))) begin : g_bad_srgb
      `TEX_PARAM_ERROR("tex_unit_cached: parameter SRGB must be 0, or 1 with CW = 16")
    end
    if (!(BLOCK_FORMATS == 0 || (BLOCK_FORMATS == 1 && (CW == 8 || SRGB == 1) && LINE_BITS >= 512))) begin : g_bad_block_formats
      `TEX_PARAM_ERROR("tex_unit_cached: parameter BLOCK_FORMATS must be 0, or 1 with 8-bit memory channels (CW = 8, or SRGB) and lines of at least 64 bytes (BLOCK_W * BLOCK_H >= 16)")
    end
    if (!(CUBE_MAPS == 0 || CUBE_MAPS == 1)) begin : g_bad_cube_maps
      `TEX_PARAM_ERROR("tex_unit_cached: parameter CUBE_MAPS must be 0 or 1")
    end
  endgenerate

  // ---------------------------------------------------------------- input registers
  // (the descriptor and sampler writes are registered with their tables below; these here)
  logic                               cfg_block_morton_q;
  logic [tex_pkg::LOG2_SETS_W-1:0]    cfg_log2_sets_q;
  logic [tex_pkg::LOG2_WAYS_W-1:0]    cfg_log2_ways_q;
  logic [$clog2(FIFO_DEPTH+1)-1:0]    cfg_fifo_limit_q;
  always_ff @(posedge clk) begin
    cfg_fifo_limit_q   <= cfg_fifo_limit;
    cfg_block_morton_q <= cfg_block_morton;
    cfg_log2_sets_q    <= cfg_log2_sets;
    cfg_log2_ways_q    <= cfg_log2_ways;
  end

  // ---------------------------------------------------------------- texture descriptors
  // The table and its set-up (tex_desc_table): sizes read at the request port and by the front,
  // level entries and format by the tag stage. While a descriptor is set up, no request is taken.
  localparam int TXW = (TEXTURES > 1) ? $clog2(TEXTURES) : 1;
  localparam int NW  = tex_pkg::SIZE_W;
  localparam int ZW  = 2*NW;
  localparam int PTW = ((MLW > MLH) ? MLW : MLH) + 1;
  localparam int LNW = tex_pkg::MEM_ADDR_W - $clog2(LINE_BITS / 8);
  logic            desc_busy;
  logic [ZW-1:0]   req_size, probe_size;     // {h, w}
  logic [VW-1:0]   probe_last_level;              // the probe's texture's last level
  logic [TXW-1:0]  probe_tex, tex_s4;        // the probe's texture; the tag stage's
  logic [2*VW-1:0] level_s4;
  logic [2*LNW-1:0] line_s4;
  logic [2*PTW-1:0] pitch_s4;
  logic [2*VW-1:0] square_s4;
  logic [tex_pkg::FORMAT_W-1:0] format_s4;
  logic            srgb_s4;
  logic [VW-1:0]   log2_lw_s4, log2_lh_s4;
  localparam int YL = tex_pkg::LAYER_W;
  logic [YL-1:0]   req_layers_m1;            // the request's texture's layer count - 1 (at tex_probe's port)
  logic            probe_cube;               // the probe's texture is a cube map
  logic [7:0]      probe_footprint;          // and its block footprint {h, w} (the repeat seam's rule)
  logic [TXW-1:0]  stride_tex;               // the front's clock-3 texture
  logic [LNW-1:0]  stride;                   // and its layer stride, in lines
  tex_desc_table #(
    .MAX_LOG2_W(MLW), .MAX_LOG2_H(MLH), .TEXTURES(TEXTURES), .BW(BLOCK_W), .BH(BLOCK_H),
    .LINE_BYTES(LINE_BITS / 8), .BLOCK_FORMATS(BLOCK_FORMATS), .SRGB(SRGB), .CUBE_MAPS(CUBE_MAPS)
  ) u_desc (
    .clk(clk), .rst(rst), .desc_we(cfg_desc_we), .desc_index(TXW'(cfg_desc_index)),
    .desc_base(cfg_desc_base), .desc_w(cfg_desc_w), .desc_h(cfg_desc_h),
    .desc_last_level(cfg_desc_last_level), .desc_format(cfg_desc_format), .desc_srgb(cfg_desc_srgb),
    .desc_layers_m1(cfg_desc_layers_m1), .desc_cube(cfg_desc_cube), .block_morton(cfg_block_morton_q),
    .busy(desc_busy),
    .size_tex_a(line_tex), .size_a(req_size), .layers_a(req_layers_m1), .cubes_a(line_cubes_m1),
    .size_tex_b(probe_tex), .size_b(probe_size), .last_b(probe_last_level), .footprint_b(probe_footprint),
    .cube_b(probe_cube),
    .cube_tex_c(TXW'(req_tex)), .cube_c(req_cube_tex), .stride_tex(stride_tex), .stride(stride),
    .tag_tex(tex_s4), .tag_level(level_s4), .tag_line(line_s4), .tag_pitch(pitch_s4),
    .tag_square(square_s4), .tag_format(format_s4), .tag_srgb(srgb_s4),
    .tag_log2_lw(log2_lw_s4), .tag_log2_lh(log2_lh_s4)
  );
  assign cfg_desc_ready = !desc_busy;

  // ---------------------------------------------------------------- sampler table
  // A sampler write is registered, then written, in three parts by the clock that reads them:
  // the anisotropy cap at the request port (tex_probe), the filters, LOD fields and wrap modes at
  // the front's clock 1 (tex_front; the reduction there too, carried in the probe's tag to the
  // filter and tex_accum), the border colour after the FIFO (tex_cached_fetch's table).
  localparam int SXW = (SAMPLERS > 1) ? $clog2(SAMPLERS) : 1;
  localparam int LW  = tex_pkg::LOD_W, PW = tex_pkg::MIP_W, WW = tex_pkg::WRAP_W;
  localparam int FRW = 2*WW + 2 + PW + 3*LW + 1;  // the front's fields
  localparam int RDW = tex_pkg::REDUCTION_W;
  localparam int CPW = tex_pkg::COMPARE_W;
  logic            smp_we_q;
  logic [SXW-1:0]  smp_index_q;
  logic [4:0]      smp_aniso_q;    // {pow2, max_aniso_m1}
  logic [FRW-1:0]  smp_front_q;    // {unnormalized, max, min, bias, mip mode, mag linear, min linear, wrap v, wrap u}
  logic [RDW-1:0]  smp_reduction_q;
  logic [CPW-1:0]  smp_compare_q;
  logic [63:0]     smp_border_q;
  logic [4:0]      smp_aniso [SAMPLERS];
  logic [FRW-1:0]  smp_front [SAMPLERS];
  logic [RDW-1:0]  smp_reduction [SAMPLERS];
  logic [CPW-1:0]  smp_compare [SAMPLERS];
  always_ff @(posedge clk) begin
    smp_we_q     <= !rst && cfg_smp_we;
    smp_index_q  <= SXW'(cfg_smp_index);
    smp_aniso_q  <= {cfg_smp_aniso_pow2, cfg_smp_max_aniso_m1};
    smp_front_q  <= {cfg_smp_unnormalized, cfg_smp_max_lod, cfg_smp_min_lod, cfg_smp_lod_bias, cfg_smp_mip_mode, cfg_smp_mag_linear,
                     cfg_smp_min_linear, cfg_smp_wrap_v, cfg_smp_wrap_u};
    smp_reduction_q <= cfg_smp_reduction;
    smp_compare_q <= cfg_smp_compare_op;
    smp_border_q <= cfg_smp_border_rgba;
    if (smp_we_q) begin
      smp_aniso[smp_index_q] <= smp_aniso_q;
      smp_front[smp_index_q] <= smp_front_q;
      smp_reduction[smp_index_q] <= smp_reduction_q;
      smp_compare[smp_index_q] <= smp_compare_q;
    end
  end
  // ---------------------------------------------------------------- a compare's reference
  // In the depth's codes at the port (DW bits ride in the tags where the 32-bit reference would):
  // the memory's channel width (with SRGB an 8-bit texel stays an 8-bit value in the filter).
  localparam int DW = (SRGB != 0) ? 8 : CWD;
  logic [DW-1:0] req_ref_code;
  tex_compare_ref #(.CW(DW)) u_compare_ref (.dref(req_ref), .code(req_ref_code));

  // ---------------------------------------------------------------- cube: tex_cube (CUBE_MAPS)
  // A lookup of a cube map (not a texel fetch) goes through tex_cube: its face, the face's s, t and
  // their derivatives become a 2D request of the face's layer. Every request waits the same 6
  // clocks beside it (a line advancing with tex_probe's req_ready), so that they stay in order;
  // the line's end is the request tex_probe takes ("line_*"). Without CUBE_MAPS the line is wires.
  localparam int RW = 2*LW + 1 + TXW + SXW + tex_pkg::OP_W + 2 + DW + TGW;  // the fields beside the coordinates
  localparam int CC = tex_pkg::REQ_COORD_W;
  logic               probe_ready;  // tex_probe takes a request
  logic               line_valid, line_cube;
  logic signed [CC-1:0] line_u, line_v, line_dudx, line_dvdx, line_dudy, line_dvdy, line_layer;
  logic [RW-1:0]      line_rest;    // {lod, bias, deriv, tex, sampler, op, component, ref code, tag}
  logic [2:0]         line_face;
  logic [RW-1:0]      req_rest;
  assign req_rest = {req_lod, req_bias, req_deriv, TXW'(req_tex), SXW'(req_sampler), req_op, req_component,
                     req_ref_code, req_tag};
  logic               req_cube_tex;  // the request's texture is a cube map
  generate
    if (CUBE_MAPS != 0) begin : g_cube
      localparam int LINE_W = 1 + 7*CC + RW;  // {cube, u, v, derivatives, layer, rest}
      logic req_cube;
      assign req_cube = req_valid && !desc_busy && req_cube_tex && req_op != tex_pkg::OP_FETCH;
      logic [LINE_W-1:0] line_out;
      tex_delay #(.W(LINE_W), .DEPTH(6)) u_line (
        .clk(clk), .rst(rst), .en(probe_ready), .in_valid(req_valid && !desc_busy),
        .in_data({req_cube, req_u, req_v, req_dudx, req_dvdx, req_dudy, req_dvdy, req_layer, req_rest}),
        .out_valid(line_valid), .out_data(line_out)
      );
      logic signed [CC-1:0] s, t, dsdx, dtdx, dsdy, dtdy;
      tex_cube u_cube (
        .clk(clk), .en(probe_ready), .cube(req_cube), .rx(req_u), .ry(req_v), .rz(req_w),
        .dxdx(req_dudx), .dydx(req_dvdx), .dzdx(req_dwdx), .dxdy(req_dudy), .dydy(req_dvdy), .dzdy(req_dwdy),
        .face(line_face), .s(s), .t(t), .dsdx(dsdx), .dtdx(dtdx), .dsdy(dsdy), .dtdy(dtdy)
      );
      logic signed [CC-1:0] u5, v5, dudx5, dvdx5, dudy5, dvdy5;
      assign {line_cube, u5, v5, dudx5, dvdx5, dudy5, dvdy5, line_layer, line_rest} = line_out;
      assign line_u    = line_cube ? s : u5;
      assign line_v    = line_cube ? t : v5;
      assign line_dudx = line_cube ? dsdx : dudx5;
      assign line_dvdx = line_cube ? dtdx : dvdx5;
      assign line_dudy = line_cube ? dsdy : dudy5;
      assign line_dvdy = line_cube ? dtdy : dvdy5;
    end else begin : g_no_cube
      assign {line_valid, line_cube, line_u, line_v, line_dudx, line_dvdx, line_dudy, line_dvdy, line_layer, line_rest} =
             {req_valid && !desc_busy, 1'b0, req_u, req_v, req_dudx, req_dvdx, req_dudy, req_dvdy, req_layer, req_rest};
      assign line_face = '0;
      logic unused_cube;
      assign unused_cube = ^{req_w, req_dwdx, req_dwdy, req_cube_tex};
    end
  endgenerate
  logic signed [LW-1:0] line_lod, line_bias;
  logic                 line_deriv;
  logic [TXW-1:0]       line_tex;
  logic [SXW-1:0]       line_smp;
  logic [tex_pkg::OP_W-1:0] line_op;
  logic [1:0]           line_component;
  logic [DW-1:0]        line_ref_code;
  logic [TGW-1:0]       line_tag;
  assign {line_lod, line_bias, line_deriv, line_tex, line_smp, line_op, line_component, line_ref_code, line_tag} = line_rest;
  logic [4:0] line_aniso;  // the request's sampler's cap, taken with the request
  assign line_aniso = smp_aniso[line_smp];

  // ---------------------------------------------------------------- the request's layer
  // Resolved where tex_probe takes the request (the texture's layer count is read there as its
  // size is) and carried in tex_probe's tag: 9 bits where the coordinate would be 32. A cube map's
  // lookup: the cube the layer picks (clamped to the cubes) times 6 plus the face tex_cube selected.
  logic [YL-1:0] line_layer_index, line_cubes_m1;
  logic          line_layer_outside;
  tex_layer u_layer (.coord(line_layer), .fetch(line_op == tex_pkg::OP_FETCH),
                     .layers_m1(line_cube ? line_cubes_m1 : req_layers_m1),
                     .layer(line_layer_index), .outside(line_layer_outside));
  logic [YL-1:0] line_layer_base;  // the layer the request reads (a cube's: its first, +X; tex_cube_seam adds the face)
  assign line_layer_base = line_cube ? YL'(line_layer_index * YL'(6)) : line_layer_index;

  // ---------------------------------------------------------------- requests 1-4: tex_probe
  logic en_front, en_back;
  assign req_ready = probe_ready && !desc_busy;
  // tex_probe's probe (tp_*), then (CUBE_MAPS) tex_cube_seam's: the probe the front takes (probe_*).
  localparam int PTGW = 4 + DW + YL + 3 + tex_pkg::OP_W + SXW + TXW + TGW;  // tex_probe's tag
  logic                                   tp_valid, tp_first, tp_last;
  logic [4:0]                             tp_n;
  logic signed [tex_pkg::REQ_COORD_W-1:0] tp_u, tp_v;
  logic signed [tex_pkg::LOD_W-1:0]       tp_lod, tp_bias;
  logic [PTGW-1:0]                        tp_tag;
  logic                                   probe_valid, probe_first, probe_last;
  logic [4:0]                             probe_n;
  logic signed [tex_pkg::REQ_COORD_W-1:0] probe_u, probe_v;
  logic signed [tex_pkg::LOD_W-1:0]       probe_lod, probe_bias;
  logic [TGW-1:0]                         probe_tag;
  logic [SXW-1:0]                         probe_smp;   // and its sampler
  logic [tex_pkg::OP_W-1:0]               probe_op;    // and its operation
  logic [1:0]                             probe_component;
  logic [YL:0]                            probe_layer;  // {a fetch outside the layers, the layer}
  logic [DW-1:0]                          probe_ref;    // a compare's reference code
  logic [2:0]                             probe_held;  // requests in tex_probe
  tex_probe #(.TAG_W(PTGW)) u_probe (
    .clk(clk), .rst(rst), .en(en_front),
    .req_valid(line_valid), .req_ready(probe_ready), .req_u(line_u), .req_v(line_v), .req_lod(line_lod),
    .req_bias(line_bias),
    .req_deriv(line_deriv), .req_dudx(line_dudx), .req_dvdx(line_dvdx), .req_dudy(line_dudy),
    .req_dvdy(line_dvdy), .req_w(req_size[0 +: NW]), .req_h(req_size[NW +: NW]),
    .req_max_aniso_m1(line_aniso[3:0]), .req_aniso_pow2(line_aniso[4]),
    .req_tag({line_cube, line_face, line_ref_code, line_layer_outside, line_layer_base, line_component, line_op,
              line_smp, line_tex, line_tag}),
    .probe_valid(tp_valid), .probe_u(tp_u), .probe_v(tp_v), .probe_lod(tp_lod), .probe_bias(tp_bias),
    .probe_first(tp_first), .probe_last(tp_last), .probe_n(tp_n), .probe_tag(tp_tag),
    .held(probe_held)  // (its formal-only ports are for tex_unit's proof: unconnected here)
  );

  // ---------------------------------------------------------------- probes: tex_cube_seam (CUBE_MAPS)
  // A cube lookup's probe beyond its face (anisotropic, near a seam) moves onto the face it lies
  // over; every probe waits the same 4 clocks beside it. The probe's layer is then its cube's first
  // plus its face.
  localparam int SDW = 1 + 2*LW + 2 + 5 + PTGW - 4;  // {cube, lod, bias, first, last, n, tag but cube and face}
  logic           seam_cube;
  logic [2:0]     seam_face;
  logic [YL-1:0]  probe_layer_base;
  logic           probe_layer_outside;
  generate
    if (CUBE_MAPS != 0) begin : g_seam
      tex_cube_seam #(.SIDE_W(SDW)) u_seam (
        .clk(clk), .rst(rst), .en(en_front), .in_valid(tp_valid), .in_cube(tp_tag[PTGW-1]), .in_u(tp_u), .in_v(tp_v),
        .in_face(tp_tag[PTGW-2 -: 3]),
        .in_side({tp_tag[PTGW-1], tp_lod, tp_bias, tp_first, tp_last, tp_n, tp_tag[PTGW-5:0]}),
        .out_valid(probe_valid), .out_u(probe_u), .out_v(probe_v), .out_face(seam_face),
        .out_side({seam_cube, probe_lod, probe_bias, probe_first, probe_last, probe_n, probe_ref,
                   probe_layer_outside, probe_layer_base, probe_component, probe_op, probe_smp, probe_tex, probe_tag})
      );
    end else begin : g_no_seam
      assign {probe_valid, probe_u, probe_v, probe_lod, probe_bias, probe_first, probe_last, probe_n} =
             {tp_valid, tp_u, tp_v, tp_lod, tp_bias, tp_first, tp_last, tp_n};
      assign {probe_ref, probe_layer_outside, probe_layer_base, probe_component, probe_op, probe_smp, probe_tex,
              probe_tag} = tp_tag[PTGW-5:0];
      assign {seam_cube, seam_face} = '0;
      logic unused_seam;
      assign unused_seam = ^tp_tag[PTGW-1 -: 4];
    end
  endgenerate
  assign probe_layer = {probe_layer_outside, seam_cube ? YL'(probe_layer_base + YL'(seam_face)) : probe_layer_base};
  // The probe's sampler's fields for the front (taken at its clock 1; its texture's size likewise).
  logic [FRW-1:0] probe_smp_front;
  assign probe_smp_front = smp_front[probe_smp];

  // ---------------------------------------------------------------- front: probe clocks 1-4
  // A probe's tag carries its place in the sample, its sampler's reduction, whether it is a
  // gather and of which component, and whether a depth compare with its sampler's operator and
  // its reference code, through the front: {ref, compare op, compare, component, gather,
  // reduction, n, last, first, tag}; from the front's clock 4 on, with tex_front's zero (a texel
  // fetch that reads nothing) above them, through the FIFO.
  localparam int FTW = TGW + 7 + RDW + 3 + 1 + CPW + DW;
  localparam int SW  = FTW + 1;
  // The tags are one register per clock: an unpacked array or a wide packed vector would cost a
  // delayed-write shadow copy in every clock in Verilator, a narrow register does not.
  logic [4:1] valid_f;             // the front's clock-n register holds a probe
  logic [FTW-1:0] tag_f1, tag_f2, tag_f3, tag_f4;  // clock n's probe
  logic [4*TXW-1:0] tex_f;         // clock n's texture at [(n-1)*TXW +: TXW] (for the level entries)
  logic [4*SXW-1:0] smp_f;         // and its sampler (for the border colour)
  always_ff @(posedge clk) begin
    if (rst) valid_f <= '0;
    else if (en_front) valid_f <= {valid_f[3:1], probe_valid};
    if (en_front) begin
      tag_f1 <= {probe_ref, smp_compare[probe_smp], probe_op == tex_pkg::OP_COMPARE, probe_component,
                 probe_op == tex_pkg::OP_GATHER, smp_reduction[probe_smp], probe_n, probe_last, probe_first, probe_tag};
      tag_f2 <= tag_f1;
      tag_f3 <= tag_f2;
      tag_f4 <= tag_f3;
      tex_f  <= {tex_f[0 +: 3*TXW], probe_tex};
      smp_f  <= {smp_f[0 +: 3*SXW], probe_smp};
    end
  end

  assign tex_s4 = tex_f[3*TXW +: TXW];

  // The layer: its first line's offset, layer x stride, made in clock 3 from the texture's stride
  // (one multiplier) and registered for the tag stage, which adds it to both slots' level lines;
  // a fetch outside the layers makes every tap a border tap and the fetch zero, as tex_front's
  // fetch outside the texture does.
  logic [YL:0]    layer_f1, layer_f2, layer_f3;
  logic [LNW-1:0] layer_offset_s4;
  logic           layer_outside_s4;
  assign stride_tex = tex_f[2*TXW +: TXW];
  always_ff @(posedge clk) begin
    if (en_front) begin
      layer_f1 <= probe_layer;
      layer_f2 <= layer_f1;
      layer_f3 <= layer_f2;
      layer_offset_s4  <= LNW'(layer_f3[YL-1:0]) * stride;
      layer_outside_s4 <= layer_f3[YL];
    end
  end
  logic [WB-1:0]   f_s4;
  logic [4*WB-1:0] w_s4;
  logic [4*NW-1:0] size_s4;       // the slots' level sizes
  logic [4*XW-1:0] x;
  logic [4*YW-1:0] y;
  logic [3:0]      border_x, border_y;  // slot s tap j at [s*2 + j]: outside its level (mode border)
  logic            zero_s4;             // a texel fetch that reads nothing (its blend is 0)
  logic [3:0]      border_x_front, border_y_front;  // tex_front's (before a fetch's layer)
  logic            zero_front;
  tex_front #(.XW(XW), .YW(YW), .CUBE_MAPS(CUBE_MAPS)) u_front (
    .clk(clk), .en(en_front), .req_u(probe_u), .req_v(probe_v), .req_lod(probe_lod), .req_bias(probe_bias),
    .req_w(probe_size[0 +: NW]), .req_h(probe_size[NW +: NW]), .req_last_level(probe_last_level),
    .req_wrap_u(probe_smp_front[0 +: WW]), .req_wrap_v(probe_smp_front[WW +: WW]),
    .req_min_linear(probe_smp_front[2*WW]), .req_mag_linear(probe_smp_front[2*WW + 1]),
    .req_mip_mode(probe_smp_front[2*WW + 2 +: PW]), .req_lod_bias(probe_smp_front[2*WW + 2 + PW +: LW]),
    .req_min_lod(probe_smp_front[2*WW + 2 + PW + LW +: LW]),
    .req_max_lod(probe_smp_front[2*WW + 2 + PW + 2*LW +: LW]), .req_unnormalized(probe_smp_front[FRW - 1]),
    .req_fetch(probe_op == tex_pkg::OP_FETCH), .req_gather(probe_op == tex_pkg::OP_GATHER), .req_cube(probe_cube),
    .req_footprint(probe_footprint),
    .level(level_s4), .f(f_s4), .w(w_s4), .size(size_s4), .x(x), .y(y),
    .border_x(border_x_front), .border_y(border_y_front), .zero(zero_front)
  );
  assign border_x = border_x_front | {4{layer_outside_s4}};
  assign border_y = border_y_front | {4{layer_outside_s4}};
  assign zero_s4  = zero_front || layer_outside_s4;
  logic [2*LNW-1:0] layer_line_s4;  // the slots' level lines in the request's layer
  assign layer_line_s4 = {line_s4[LNW +: LNW] + layer_offset_s4, line_s4[0 +: LNW] + layer_offset_s4};

  // ---------------------------------------------------------------- AXI4 read master
  // The miss ring's line reads and the fill FIFO's beats are the AR and R channels: one INCR burst
  // of a whole line per read (tex_axi_read).
  logic                           mem_req_valid, mem_req_ready, mem_rsp_valid, mem_rsp_ready, mem_rsp_error;
  logic [tex_pkg::MEM_ADDR_W-1:0] mem_req_addr;
  logic [MEM_W-1:0]               mem_rsp_data;
  tex_axi_read #(.MEM_W(MEM_W), .LINE_BITS(LINE_BITS), .AXI_ID_W(AXI_ID_W)) u_axi_read (
    .clk(clk), .rst(rst), .mem_req_valid(mem_req_valid), .mem_req_ready(mem_req_ready),
    .mem_req_addr(mem_req_addr), .mem_rsp_valid(mem_rsp_valid), .mem_rsp_ready(mem_rsp_ready),
    .mem_rsp_data(mem_rsp_data), .mem_rsp_error(mem_rsp_error), .m_axi_arvalid(m_axi_arvalid),
    .m_axi_arready(m_axi_arready), .m_axi_araddr(m_axi_araddr), .m_axi_arlen(m_axi_arlen),
    .m_axi_arsize(m_axi_arsize), .m_axi_arburst(m_axi_arburst), .m_axi_arid(m_axi_arid),
    .m_axi_arcache(m_axi_arcache), .m_axi_arprot(m_axi_arprot), .m_axi_rvalid(m_axi_rvalid),
    .m_axi_rready(m_axi_rready), .m_axi_rdata(m_axi_rdata), .m_axi_rresp(m_axi_rresp),
    .m_axi_rlast(m_axi_rlast), .m_axi_rid(m_axi_rid)
  );

  // ---------------------------------------------------------------- cached fetch: clocks 5-8
  logic              fetch_valid, fetch_error;
  logic [SW-1:0]     fetch_tag;
  logic [32*CWD-1:0] taps;
  logic [4*WB-1:0]   fetch_w;
  logic [WB-1:0]     fetch_f;
  tex_cached_fetch #(
    .MAX_LOG2_W(MLW), .MAX_LOG2_H(MLH), .CW(CWD), .TAG_W(SW), .BW(BLOCK_W), .BH(BLOCK_H),
    .LINES(LINES), .MAX_WAYS(MAX_WAYS), .FIFO_DEPTH(FIFO_DEPTH), .MISS_DEPTH(MISS_DEPTH),
    .FILL_DEPTH(FILL_DEPTH), .MEM_W(MEM_W), .SAMPLERS(SAMPLERS),
    .BLOCK_FORMATS(BLOCK_FORMATS),
    .SRGB(SRGB)
  ) u_fetch (
    .clk(clk), .rst(rst), .en_front(en_front), .en_back(en_back),
    .front_valid(valid_f[4]), .front_tag({zero_s4, tag_f4}), .front_smp(smp_f[3*SXW +: SXW]), .level_odd(level_s4[0]),
    .f(f_s4), .w(w_s4), .size(size_s4), .x(x), .y(y),
    .front_line(layer_line_s4), .front_pitch(pitch_s4), .front_square(square_s4), .front_format(format_s4),
    .front_srgb(srgb_s4), .front_log2_lw(log2_lw_s4), .front_log2_lh(log2_lh_s4),
    .border_x(border_x), .border_y(border_y),
    .smp_we(smp_we_q), .smp_index(smp_index_q), .smp_border_rgba(smp_border_q),
    .cfg_block_morton(cfg_block_morton_q), .cfg_log2_sets(cfg_log2_sets_q),
    .cfg_log2_ways(cfg_log2_ways_q), .cfg_fifo_limit(cfg_fifo_limit_q),
    .mem_req_valid(mem_req_valid), .mem_req_ready(mem_req_ready), .mem_req_addr(mem_req_addr),
    .mem_rsp_valid(mem_rsp_valid), .mem_rsp_ready(mem_rsp_ready), .mem_rsp_data(mem_rsp_data),
    .mem_rsp_error(mem_rsp_error),
    .out_valid(fetch_valid), .out_tag(fetch_tag), .taps(taps), .out_w(fetch_w),
    .out_f(fetch_f), .out_error(fetch_error),
    .stat_lookups(stat_lookups), .stat_misses(stat_misses), .stat_mem_wait(stat_mem_wait)
  );

  // ---------------------------------------------------------------- filter: clocks 9-11
  // The filter's registers load only while a sample is in its clocks (its data registers then
  // hold their last values): a simulator skips the filter while the unit waits for memory.
  logic [3:1]      valid_b;
  logic [SW-1:0]   tag_b1, tag_b2, tag_b3;  // the filter's clock n (one register each, as tag_f)
  logic [3:1]      err_b;                   // and its probe's memory error
  logic            filter_en;      // a sample enters one of the filter's clocks
  assign filter_en = en_back && (fetch_valid || valid_b[1] || valid_b[2]);
  always_ff @(posedge clk) begin
    if (rst) valid_b <= '0;
    else if (en_back) valid_b <= {valid_b[2:1], fetch_valid};
    if (filter_en) begin
      tag_b1 <= fetch_tag;
      tag_b2 <= tag_b1;
      tag_b3 <= tag_b2;
      err_b  <= {err_b[2:1], fetch_error};
    end
  end
  logic [4*(CWD+24)-1:0] blend;
  tex_filter #(.CW(CWD), .DW(DW)) u_filter (
    .clk(clk), .en(filter_en), .taps(taps), .w(fetch_w), .f(fetch_f), .reduction(fetch_tag[TGW+7 +: RDW]),
    .gather(fetch_tag[TGW+7+RDW]), .component(fetch_tag[TGW+8+RDW +: 2]), .depth_test(fetch_tag[TGW+10+RDW]),
    .compare_op(fetch_tag[TGW+11+RDW +: CPW]), .dref(fetch_tag[TGW+11+RDW+CPW +: DW]), .blend(blend)
  );

  // ---------------------------------------------------------------- clocks 12-13: tex_accum
  // A sample's memory error: any of its probes' (the side data of its last probe carries the OR).
  logic             err_run;        // the probes of the sample so far, before this one
  logic             probe_err;      // with this one
  assign probe_err = err_b[3] || (!tag_b3[TGW] && err_run);
  always_ff @(posedge clk)
    if (en_back && valid_b[3]) err_run <= probe_err;
  logic             sample_valid, sample_error;
  logic [4*CWD-1:0] rgba;
  logic [TGW-1:0]   sample_tag;
  logic             accum_held_unused;  // (in-flight accounting: tex_unit's checks)

  logic [2:0]       probe_held_unused;
  assign probe_held_unused = probe_held;
  tex_accum #(.CW(CWD), .SIDE_W(TGW + 1)) u_accum (
    .clk(clk), .rst(rst), .en(en_back), .in_valid(valid_b[3]), .in_first(tag_b3[TGW]),
    .in_last(tag_b3[TGW+1]), .in_n(tag_b3[TGW+2 +: 5]), .in_reduction(tag_b3[TGW+7 +: RDW]),
    .in_zero(tag_b3[SW-1]), .blend(blend),
    .in_side({probe_err, tag_b3[TGW-1:0]}), .out_valid(sample_valid), .rgba(rgba),
    .out_side({sample_error, sample_tag}),
    .held(accum_held_unused)
  );

  // ---------------------------------------------------------------- clock 14: skid buffer
  // A sample with a memory error leaves as 0 (its texels are not what memory holds).
  tex_skid #(.W(1 + TGW + 4*CWD)) u_skid (
    .clk(clk), .rst(rst),
    .in_valid(sample_valid), .in_ready(en_back), .in_data({sample_error, sample_tag, sample_error ? '0 : rgba}),
    .out_valid(rsp_valid), .out_ready(rsp_ready), .out_data({rsp_error, rsp_tag, rsp_rgba})
  );

`ifndef SYNTHESIS
  // ---------------------------------------------------------------- simulation checks
  // Requests in flight never go below 0 (no response without a request); handshake rules of the
  // request and response channels: a valid is held until ready, with a stable payload (the AXI
  // read channels' own rules: tex_axi_read).
  logic [31:0] in_flight;
  logic        req_stalled_q, rsp_stalled_q;
  logic signed [tex_pkg::REQ_COORD_W-1:0] req_u_q, req_v_q;
  logic signed [tex_pkg::LOD_W-1:0]       req_lod_q, req_bias_q;
  logic [4*tex_pkg::REQ_COORD_W:0]        req_deriv_q;  // {req_deriv, dudx, dvdx, dudy, dvdy}
  logic [TAG_W-1:0]                       req_tag_q, rsp_tag_q;
  logic [tex_pkg::OP_W-1:0]               req_op_q;
  logic [1:0]                             req_component_q;
  logic [tex_pkg::REQ_COORD_W-1:0]        req_layer_q, req_ref_q, req_w_q, req_dwdx_q, req_dwdy_q;
  logic [tex_pkg::TEX_ID_W-1:0]           req_tex_q;
  logic [tex_pkg::SMP_ID_W-1:0]           req_sampler_q;
  logic [4*CW-1:0]                        rsp_rgba_q;
  logic                                   rsp_error_q;
  always_ff @(posedge clk) begin
    if (rst) begin
      in_flight <= '0;
    end else begin
      assert (in_flight != '0 || !rsp_valid)
        else $error("tex_unit_cached: rsp_valid high with no request in flight");
      in_flight <= in_flight + 32'(req_valid && req_ready) - 32'(rsp_valid && rsp_ready);
    end
    req_stalled_q  <= !rst && req_valid && !req_ready;
    rsp_stalled_q  <= !rst && rsp_valid && !rsp_ready;
    if (req_valid && !req_ready) begin
      req_u_q   <= req_u;
      req_v_q   <= req_v;
      req_lod_q <= req_lod;
      req_bias_q <= req_bias;
      req_tag_q <= req_tag;
      req_op_q  <= req_op;
      req_component_q <= req_component;
      req_layer_q <= req_layer;
      req_ref_q <= req_ref;
      req_w_q <= req_w;
      req_dwdx_q <= req_dwdx;
      req_dwdy_q <= req_dwdy;
      req_tex_q <= req_tex;
      req_sampler_q <= req_sampler;
      req_deriv_q <= {req_deriv, req_dudx, req_dvdx, req_dudy, req_dvdy};
    end
    if (rsp_valid && !rsp_ready) begin
      rsp_tag_q  <= rsp_tag;
      rsp_rgba_q <= rsp_rgba;
      rsp_error_q <= rsp_error;
    end
    if (!rst && cfg_desc_we)
      assert (32'(cfg_desc_index) < TEXTURES)
        else $error("tex_unit_cached: cfg_desc_index %0d is beyond the descriptor table (TEXTURES = %0d)",
                    cfg_desc_index, TEXTURES);
    if (!rst && cfg_desc_we)
      assert (cfg_desc_ready)
        else $error("tex_unit_cached: cfg_desc_we while cfg_desc_ready is low (the last descriptor is being set up)");
    if (!rst && cfg_desc_we)
      assert (cfg_desc_w >= 1 && 32'(cfg_desc_w) <= (1 << MLW) && cfg_desc_h >= 1 && 32'(cfg_desc_h) <= (1 << MLH))
        else $error("tex_unit_cached: cfg_desc_w x cfg_desc_h = %0d x %0d is not 1..%0d x 1..%0d",
                    cfg_desc_w, cfg_desc_h, 1 << MLW, 1 << MLH);
    if (!rst && cfg_desc_we)
      assert (cfg_desc_format == tex_pkg::FMT_RGBA8
              || (BLOCK_FORMATS != 0 && tex_pkg::block_format(cfg_desc_format)))
        else $error("tex_unit_cached: cfg_desc_format %0d is not a format of this unit (BLOCK_FORMATS = %0d)",
                    cfg_desc_format, BLOCK_FORMATS);
    if (!rst && cfg_desc_we && tex_pkg::eac(cfg_desc_format))
      assert (SRGB != 0)
        else $error("tex_unit_cached: cfg_desc_format %0d is EAC, whose 16-bit channels need the CW = 16 filter (SRGB = 1)",
                    cfg_desc_format);
    if (!rst && cfg_desc_we && cfg_desc_srgb)
      assert (SRGB != 0 && tex_pkg::srgb_format(cfg_desc_format))
        else $error("tex_unit_cached: cfg_desc_srgb for format %0d (SRGB = %0d; BC4, BC5 and EAC have no sRGB)",
                    cfg_desc_format, SRGB);
    if (!rst && cfg_desc_we && cfg_desc_cube)
      assert (CUBE_MAPS != 0 && cfg_desc_format == tex_pkg::FMT_RGBA8 && cfg_desc_w == cfg_desc_h
              && (32'(cfg_desc_layers_m1) + 1) % 6 == 0 && 32'(cfg_desc_w) + 2 <= (1 << ((MLW < MLH) ? MLW : MLH)))
        else $error("tex_unit_cached: cfg_desc_cube for a %0d x %0d texture of format %0d and %0d layers (CUBE_MAPS = %0d: square RGBA faces of n + 2 <= %0d texels, 6 layers a cube)",
                    cfg_desc_w, cfg_desc_h, cfg_desc_format, 32'(cfg_desc_layers_m1) + 1, CUBE_MAPS,
                    1 << ((MLW < MLH) ? MLW : MLH));
    if (!rst && cfg_smp_we)
      assert (32'(cfg_smp_index) < SAMPLERS)
        else $error("tex_unit_cached: cfg_smp_index %0d is beyond the sampler table (SAMPLERS = %0d)",
                    cfg_smp_index, SAMPLERS);
    if (!rst && req_valid)
      assert (32'(req_sampler) < SAMPLERS)
        else $error("tex_unit_cached: req_sampler %0d is beyond the sampler table (SAMPLERS = %0d)",
                    req_sampler, SAMPLERS);
    if (!rst && req_valid)
      assert (req_op == tex_pkg::OP_SAMPLE || req_op == tex_pkg::OP_COMPARE
              || ((req_op == tex_pkg::OP_FETCH || req_op == tex_pkg::OP_GATHER) && !req_deriv))
        else $error("tex_unit_cached: req_op %0d with req_deriv %0d is not an operation of this unit", req_op, req_deriv);
    if (!rst && req_valid)
      assert (32'(req_tex) < TEXTURES)
        else $error("tex_unit_cached: req_tex %0d is beyond the descriptor table (TEXTURES = %0d)", req_tex, TEXTURES);
    if (!rst && req_stalled_q) begin
      assert (req_valid && req_u == req_u_q && req_v == req_v_q && req_lod == req_lod_q && req_bias == req_bias_q
              && req_tag == req_tag_q && req_op == req_op_q && req_component == req_component_q && req_layer == req_layer_q && req_ref == req_ref_q
              && req_w == req_w_q && req_dwdx == req_dwdx_q && req_dwdy == req_dwdy_q && req_tex == req_tex_q && req_sampler == req_sampler_q && {req_deriv, req_dudx, req_dvdx, req_dudy, req_dvdy} == req_deriv_q)
        else $error("tex_unit_cached: req_valid dropped or request changed while req_ready was low");
    end
    if (!rst && rsp_stalled_q) begin
      assert (rsp_valid && rsp_tag == rsp_tag_q && rsp_rgba == rsp_rgba_q && rsp_error == rsp_error_q)
        else $error("tex_unit_cached: rsp_valid dropped or response changed while rsp_ready was low");
    end
  end
`endif
endmodule

// tex_axil_config: AXI4-Lite slave holding tex_unit_cached's configuration and its performance
// counters (register map, soft reset and descriptor commit: docs/rtl-interface.md, "AXI4-Lite
// configuration (tex_unit_axi)"): a texture descriptor and a sampler are each staged in registers
// and written into tex_unit_cached's tables by a commit naming the entry.
// Handshake: AXI4-Lite, one transaction at a time per direction; reads and writes independent.
//   AW and W are taken in either order or together: AWREADY (WREADY) is a register, high while no
//   address (data) is held and no B response waits. The write happens at the clock edge where
//   both are held (a DESC_COMMIT also waits, held, while tex_unit_cached sets up the last
//   descriptor: cfg_desc_ready low or cfg_desc_we high); BVALID rises at that edge and stays, with
//   BRESP, until BREADY. ARREADY is
//   high while no R response waits; RVALID rises at the AR edge and stays, with RDATA and RRESP,
//   until RREADY. Every output is a register.
// Latency: 1 clock from the edge that takes the later of AW and W to BVALID, and from the AR
//   edge to RVALID. Throughput: one write and one read every 2 clocks (BREADY, RREADY high).
// Errors: SLVERR (2'b10), and the write changes nothing, for a write to an undefined or
//   read-only address, with WSTRB other than 4'b1111 (registers are written whole), to CACHE
//   while the unit runs or with a geometry the caches lack, and a DESC_COMMIT (SMP_COMMIT) of a
//   descriptor (sampler) tex_unit_cached has no use for, or while the unit is in reset (the
//   pulse would be lost).
//   A read of an undefined address: SLVERR with RDATA 0. AWPROT, ARPROT, address bits 1:0 and
//   reserved bits of a register are ignored (reserved bits read 0).
// Counters: 64 bits, unsigned, wrap. An event is registered, then counted one clock later.
//   Reading a counter's LO word latches its HI word, which the next read of that counter's HI
//   word returns (a HI read without that LO read returns the live value).
// Ports:
//   s_axi_*       : AXI4-Lite, 32-bit data, ADDR_W-bit byte addresses (the whole 2^ADDR_W-byte
//                   window is decoded: no register repeats)
//   unit_rst      : tex_unit_cached's rst: CONTROL.unit_reset, a register, 1 from rst on
//   cfg_*         : tex_unit_cached's pins, registers (its formats; lod fields signed Q8.8)
//   cfg_desc_we   : high for the one clock after an accepted DESC_COMMIT write, with
//                   cfg_desc_index and the staging registers (cfg_desc_base .. _srgb) stable
//   cfg_desc_ready: tex_unit_cached takes a descriptor write (it has set up the last one)
//   cfg_smp_we    : likewise after an accepted SMP_COMMIT write, with cfg_smp_index and the
//                   staged sampler (cfg_smp_wrap_u .. cfg_smp_border_rgba)
//   stat_*        : events of this clock: stat_sample (a response handshake), stat_sample_error
//                   (of those, with rsp_error), stat_lookups, stat_misses (unsigned 0..8),
//                   stat_mem_beat (a memory read beat taken: BEAT_BYTES bytes), stat_out_stall
//                   (rsp_valid && !rsp_ready), stat_mem_wait, stat_req_stall (req_valid && !req_ready)
`include "tex_param_error.svh"
module tex_axil_config #(
  parameter int ADDR_W        = 12,   // byte address bits of the register window, 8..32
  // tex_unit_cached's parameters (the checks of CACHE and DESC_COMMIT, the CAPS registers):
  parameter int MAX_LOG2_W    = 10,
  parameter int MAX_LOG2_H    = 10,
  parameter int LINES         = 256,
  parameter int MAX_WAYS      = 4,
  parameter int FIFO_DEPTH    = 256,
  parameter int TEXTURES      = 16,
  parameter int SAMPLERS      = 16,
  parameter int BLOCK_FORMATS = 1,
  parameter int SRGB          = 0,
  parameter int CUBE_MAPS     = 1,
  parameter int LINE_BYTES    = 64,   // bytes of a cache line: descriptor bases are multiples
  parameter int BEAT_BYTES    = 16    // bytes counted per stat_mem_beat (power of two, 1..64)
) (
  input  logic                              clk,
  input  logic                              rst,

  input  logic                              s_axi_awvalid,
  output logic                              s_axi_awready,
  input  logic [ADDR_W-1:0]                 s_axi_awaddr,
  input  logic [2:0]                        s_axi_awprot,
  input  logic                              s_axi_wvalid,
  output logic                              s_axi_wready,
  input  logic [31:0]                       s_axi_wdata,
  input  logic [3:0]                        s_axi_wstrb,
  output logic                              s_axi_bvalid,
  input  logic                              s_axi_bready,
  output logic [1:0]                        s_axi_bresp,
  input  logic                              s_axi_arvalid,
  output logic                              s_axi_arready,
  input  logic [ADDR_W-1:0]                 s_axi_araddr,
  input  logic [2:0]                        s_axi_arprot,
  output logic                              s_axi_rvalid,
  input  logic                              s_axi_rready,
  output logic [31:0]                       s_axi_rdata,
  output logic [1:0]                        s_axi_rresp,

  output logic                              unit_rst,
  output logic                              cfg_desc_we,
  output logic [tex_pkg::TEX_ID_W-1:0]      cfg_desc_index,
  output logic [tex_pkg::MEM_ADDR_W-1:0]    cfg_desc_base,
  output logic [tex_pkg::SIZE_W-1:0]        cfg_desc_w,
  output logic [tex_pkg::SIZE_W-1:0]        cfg_desc_h,
  output logic [tex_pkg::LEVEL_W-1:0]       cfg_desc_last_level,
  output logic [tex_pkg::FORMAT_W-1:0]      cfg_desc_format,
  output logic                              cfg_desc_srgb,
  output logic                              cfg_desc_cube,
  output logic [tex_pkg::LAYER_W-1:0]       cfg_desc_layers_m1,
  input  logic                              cfg_desc_ready,
  output logic                              cfg_smp_we,
  output logic [tex_pkg::SMP_ID_W-1:0]      cfg_smp_index,
  output logic [tex_pkg::WRAP_W-1:0]        cfg_smp_wrap_u,
  output logic [tex_pkg::WRAP_W-1:0]        cfg_smp_wrap_v,
  output logic                              cfg_smp_min_linear,
  output logic                              cfg_smp_mag_linear,
  output logic [tex_pkg::MIP_W-1:0]         cfg_smp_mip_mode,
  output logic signed [tex_pkg::LOD_W-1:0]  cfg_smp_lod_bias,
  output logic signed [tex_pkg::LOD_W-1:0]  cfg_smp_min_lod,
  output logic signed [tex_pkg::LOD_W-1:0]  cfg_smp_max_lod,
  output logic [3:0]                        cfg_smp_max_aniso_m1,
  output logic                              cfg_smp_aniso_pow2,
  output logic [63:0]                       cfg_smp_border_rgba,
  output logic                              cfg_smp_unnormalized,
  output logic [tex_pkg::REDUCTION_W-1:0]   cfg_smp_reduction,
  output logic [tex_pkg::COMPARE_W-1:0]     cfg_smp_compare_op,
  output logic                              cfg_block_morton,
  output logic [tex_pkg::LOG2_SETS_W-1:0]   cfg_log2_sets,
  output logic [tex_pkg::LOG2_WAYS_W-1:0]   cfg_log2_ways,
  output logic [$clog2(FIFO_DEPTH+1)-1:0]   cfg_fifo_limit,

  input  logic                              stat_sample,
  input  logic                              stat_sample_error,
  input  logic [3:0]                        stat_lookups,
  input  logic [3:0]                        stat_misses,
  input  logic                              stat_mem_beat,
  input  logic                              stat_out_stall,
  input  logic                              stat_mem_wait,
  input  logic                              stat_req_stall
);
  // ---------------------------------------------------------------- parameter checks
  generate
    if (ADDR_W < 8 || ADDR_W > 32) begin : g_bad_addr_w
      `TEX_PARAM_ERROR("tex_axil_config: parameter ADDR_W must be in 8..32 (the registers span 256 bytes)")
    end
    if (MAX_LOG2_W < 0 || MAX_LOG2_W > tex_pkg::MAX_LOG2_SIZE) begin : g_bad_max_log2_w
      `TEX_PARAM_ERROR("tex_axil_config: parameter MAX_LOG2_W must be in 0..13 (tex_pkg::MAX_LOG2_SIZE)")
    end
    if (MAX_LOG2_H < 0 || MAX_LOG2_H > tex_pkg::MAX_LOG2_SIZE) begin : g_bad_max_log2_h
      `TEX_PARAM_ERROR("tex_axil_config: parameter MAX_LOG2_H must be in 0..13 (tex_pkg::MAX_LOG2_SIZE)")
    end
    if (LINES < 16 || (LINES & (LINES - 1)) != 0) begin : g_bad_lines
      `TEX_PARAM_ERROR("tex_axil_config: parameter LINES must be a power of two, at least 16")
    end
    if (!(MAX_WAYS == 1 || MAX_WAYS == 2 || MAX_WAYS == 4)) begin : g_bad_ways
      `TEX_PARAM_ERROR("tex_axil_config: parameter MAX_WAYS must be 1, 2 or 4")
    end
    if (FIFO_DEPTH < 2 || (FIFO_DEPTH & (FIFO_DEPTH - 1)) != 0) begin : g_bad_fifo
      `TEX_PARAM_ERROR("tex_axil_config: parameter FIFO_DEPTH must be a power of two, at least 2")
    end
    if (TEXTURES < 1 || TEXTURES > (1 << tex_pkg::TEX_ID_W) || (TEXTURES & (TEXTURES - 1)) != 0) begin : g_bad_textures
      `TEX_PARAM_ERROR("tex_axil_config: parameter TEXTURES must be a power of two from 1 to 16 (tex_pkg::TEX_ID_W)")
    end
    if (SAMPLERS < 1 || SAMPLERS > (1 << tex_pkg::SMP_ID_W) || (SAMPLERS & (SAMPLERS - 1)) != 0) begin : g_bad_samplers
      `TEX_PARAM_ERROR("tex_axil_config: parameter SAMPLERS must be a power of two from 1 to 16 (tex_pkg::SMP_ID_W)")
    end
    if (!(BLOCK_FORMATS == 0 || BLOCK_FORMATS == 1)) begin : g_bad_block_formats
      `TEX_PARAM_ERROR("tex_axil_config: parameter BLOCK_FORMATS must be 0 or 1")
    end
    if (!(SRGB == 0 || SRGB == 1)) begin : g_bad_srgb
      `TEX_PARAM_ERROR("tex_axil_config: parameter SRGB must be 0 or 1")
    end
    if (LINE_BYTES < 1 || LINE_BYTES > 4096 || (LINE_BYTES & (LINE_BYTES - 1)) != 0) begin : g_bad_line_bytes
      `TEX_PARAM_ERROR("tex_axil_config: parameter LINE_BYTES must be a power of two from 1 to 4096")
    end
    if (BEAT_BYTES < 1 || BEAT_BYTES > 64 || (BEAT_BYTES & (BEAT_BYTES - 1)) != 0) begin : g_bad_beat_bytes
      `TEX_PARAM_ERROR("tex_axil_config: parameter BEAT_BYTES must be a power of two from 1 to 64")
    end
  endgenerate

  // ---------------------------------------------------------------- register map
  // Word addresses (byte offset / 4). docs/rtl-interface.md has the fields.
  localparam int WA = ADDR_W - 2;
  localparam logic [WA-1:0] R_ID          = WA'('h000 >> 2);  // RO "TEXU"
  localparam logic [WA-1:0] R_VERSION     = WA'('h004 >> 2);  // RO
  localparam logic [WA-1:0] R_CAPS0       = WA'('h008 >> 2);  // RO texture parameters
  localparam logic [WA-1:0] R_CAPS1       = WA'('h00C >> 2);  // RO cache and memory parameters
  localparam logic [WA-1:0] R_CONTROL     = WA'('h010 >> 2);
  localparam logic [WA-1:0] R_CACHE       = WA'('h020 >> 2);
  localparam logic [WA-1:0] R_FIFO_LIMIT  = WA'('h024 >> 2);
  localparam logic [WA-1:0] R_FILTER      = WA'('h030 >> 2);  // the staged sampler: 0x030 .. 0x03C,
                                                              //   0x050 .. 0x058
  localparam logic [WA-1:0] R_LOD_BIAS    = WA'('h034 >> 2);
  localparam logic [WA-1:0] R_MIN_LOD     = WA'('h038 >> 2);
  localparam logic [WA-1:0] R_MAX_LOD     = WA'('h03C >> 2);
  localparam logic [WA-1:0] R_DESC_BASE   = WA'('h040 >> 2);
  localparam logic [WA-1:0] R_DESC_ATTR   = WA'('h044 >> 2);
  localparam logic [WA-1:0] R_DESC_COMMIT = WA'('h048 >> 2);
  localparam logic [WA-1:0] R_DESC_SIZE   = WA'('h04C >> 2);  // {height, width} texels, 16 bits each
  localparam logic [WA-1:0] R_BORDER_RG   = WA'('h050 >> 2);  // border colour: {G, R} unorm16
  localparam logic [WA-1:0] R_BORDER_BA   = WA'('h054 >> 2);  //                {A, B}
  localparam logic [WA-1:0] R_WRAP        = WA'('h058 >> 2);  // {wrap_v, 0, wrap_u}
  localparam logic [WA-1:0] R_SMP_COMMIT  = WA'('h05C >> 2);
  // Counters: counter i's LO word at 0x080 + 8 i, HI at 0x084 + 8 i (words 0x20 .. 0x3F).
  localparam int NCNT = 9;  // CYCLES, SAMPLES, SAMPLE_ERRORS, LOOKUPS, MISSES, MEM_BYTES,
                            // OUT_STALL, MEM_WAIT, REQ_STALL
  localparam logic [31:0] ID      = 32'h5445_5855;  // "TEXU"
  localparam logic [31:0] VERSION = 32'h0003_0007;  // major 3 (any texture size: DESC_SIZE), minor 7 (EAC: formats 11..14)
                                                    // (FILTER.unnormalized, FILTER.reduction)

  localparam int FLW       = $clog2(FIFO_DEPTH + 1);
  localparam int SETS_W    = tex_pkg::LOG2_SETS_W;
  localparam int WAYS_W    = tex_pkg::LOG2_WAYS_W;
  localparam int LOG2_LINES = $clog2(LINES);
  localparam int LOG2_WAYS  = $clog2(MAX_WAYS);
  localparam logic [1:0] OKAY = 2'b00, SLVERR = 2'b10;
  localparam logic [31:0] CAPS0 = {7'd0, 5'(SAMPLERS), 1'd0, 1'(CUBE_MAPS), 1'(SRGB), 1'(BLOCK_FORMATS), 3'd0,
                                   5'(TEXTURES), 4'(MAX_LOG2_H), 4'(MAX_LOG2_W)};
  localparam logic [31:0] CAPS1 = {4'($clog2(BEAT_BYTES)), 4'($clog2(LINE_BYTES)), 3'd0,
                                   5'($clog2(FIFO_DEPTH)), 5'd0, 3'(MAX_WAYS), 3'd0, 5'(LOG2_LINES)};

  // ---------------------------------------------------------------- write channel
  logic              aw_full, w_full;   // the address / the data of the next write is held
  logic [WA-1:0]     aw_addr_q;
  logic [31:0]       w_data_q;
  logic [3:0]        w_strb_q;
  logic              bvalid;
  logic [1:0]        bresp;
  logic              aw_take, w_take, do_write;
  logic [WA-1:0]     wa;                // the write's word address, data and strobes: held or
  logic [31:0]       wd;                // being taken in this clock
  logic [3:0]        ws;
  assign s_axi_awready = !aw_full && !bvalid;
  assign s_axi_wready  = !w_full && !bvalid;
  assign s_axi_bvalid  = bvalid;
  assign s_axi_bresp   = bresp;
  assign aw_take  = s_axi_awvalid && s_axi_awready;
  assign w_take   = s_axi_wvalid && s_axi_wready;
  logic              desc_wait;         // a DESC_COMMIT waits while the unit sets up a descriptor
  assign wa = aw_full ? aw_addr_q : s_axi_awaddr[ADDR_W-1:2];
  assign desc_wait = wa == R_DESC_COMMIT && (!cfg_desc_ready || cfg_desc_we);
  assign do_write = (aw_full || aw_take) && (w_full || w_take) && !desc_wait;  // (never with bvalid high)
  assign wd = w_full ? w_data_q : s_axi_wdata;
  assign ws = w_full ? w_strb_q : s_axi_wstrb;

  // The registers
  logic                             ctl_unit_reset, ctl_freeze;
  logic                             desc_we;
  logic [tex_pkg::TEX_ID_W-1:0]     desc_index;
  logic [tex_pkg::MEM_ADDR_W-1:0]   desc_base;
  logic [6:0]                       desc_attr;  // {cube, srgb, format} (DESC_ATTR bits 22:16)
  logic [tex_pkg::LEVEL_W-1:0]      desc_last;  // DESC_ATTR bits 11:8
  logic [tex_pkg::LAYER_W-1:0]      desc_layers_m1;  // DESC_ATTR bits 31:24
  logic [tex_pkg::SIZE_W-1:0]       desc_w, desc_h;
  logic                             smp_we;
  logic [tex_pkg::SMP_ID_W-1:0]     smp_index;
  logic [6:0]                       wrap;       // {wrap_v, 0, wrap_u}
  logic [18:0]                      filter;     // {compare_op, reduction, unnormalized, pow2, aniso_m1, 2'b0, mip_mode, 2'b0, mag, linear}
  logic [63:0]                      border;     // {A, B, G, R} unorm16
  logic signed [tex_pkg::LOD_W-1:0] lod_bias, min_lod, max_lod;
  logic                             block_morton;
  logic [SETS_W-1:0]                log2_sets;
  logic [WAYS_W-1:0]                log2_ways;
  logic [FLW-1:0]                   fifo_limit;

  // The staged descriptor as DESC_COMMIT checks it
  logic [tex_pkg::FORMAT_W-1:0] attr_format;
  logic                         attr_srgb;
  assign attr_format = desc_attr[4:0];
  assign attr_srgb   = desc_attr[5];
  logic                         attr_cube;
  assign attr_cube   = desc_attr[6];
  logic [tex_pkg::WRAP_W-1:0] wrap_u, wrap_v;
  assign wrap_u = wrap[2:0];
  assign wrap_v = wrap[6:4];
  // The address modes: repeat, clamp, mirror, border, mirror-clamp (5..7 are no mode).
  function automatic logic wrap_ok(input logic [tex_pkg::WRAP_W-1:0] m);
    wrap_ok = m <= tex_pkg::WRAP_MIRROR_CLAMP;
  endfunction

  // Clamp to edge or to border: the modes of an unnormalized sampler.
  function automatic logic clamping(input logic [tex_pkg::WRAP_W-1:0] m);
    clamping = m == tex_pkg::WRAP_CLAMP || m == tex_pkg::WRAP_BORDER;
  endfunction

  // Write decode: which register, and whether the write is allowed (else SLVERR, no change).
  logic sel_control, sel_cache, sel_fifo, sel_filter, sel_bias, sel_min, sel_max;
  logic sel_base, sel_attr, sel_size, sel_commit, sel_border_rg, sel_border_ba, sel_wrap, sel_smp_commit;
  logic wr_ok, wr_en;
  logic geometry_ok, desc_ok, smp_ok;
  always_comb begin
    // CACHE: ways <= MAX_WAYS, sets >= 4, sets * ways <= LINES (tex_cache_tags)
    geometry_ok = 32'(wd[17:16]) <= LOG2_WAYS && 32'(wd[12:8]) >= 2
                  && 32'(wd[12:8]) + 32'(wd[17:16]) <= LOG2_LINES;
    // DESC_COMMIT: what tex_unit_cached's simulation checks, the sizes and a line-aligned base
    desc_ok = 32'(wd[3:0]) < TEXTURES
              && desc_w != '0 && 32'(desc_w) <= (1 << MAX_LOG2_W)
              && desc_h != '0 && 32'(desc_h) <= (1 << MAX_LOG2_H)
              && (attr_format == tex_pkg::FMT_RGBA8 || (BLOCK_FORMATS != 0 && tex_pkg::block_format(attr_format)))
              && (!attr_srgb || (SRGB != 0 && tex_pkg::srgb_format(attr_format)))
              && (!tex_pkg::eac(attr_format) || SRGB != 0)  // EAC's 16-bit channels: the CW = 16 filter
              && (desc_base & 32'(LINE_BYTES - 1)) == '0
              // a cube map: square RGBA faces of n + 2 <= the smaller side, 6 layers a cube
              && (!attr_cube || (CUBE_MAPS != 0 && attr_format == tex_pkg::FMT_RGBA8 && desc_w == desc_h
                                 && (32'(desc_layers_m1) + 1) % 6 == 0
                                 && 32'(desc_w) + 2 <= (1 << ((MAX_LOG2_W < MAX_LOG2_H) ? MAX_LOG2_W : MAX_LOG2_H))));
    // SMP_COMMIT: an entry of the table, address modes and a mip mode the unit has; unnormalized
    // coordinates only as Vulkan allows them (clamp to edge or border, one texel filter, no
    // anisotropy, the base level only: mip mode none or a max LOD <= 0); a reduction the unit has
    smp_ok = 32'(wd[3:0]) < SAMPLERS && wrap_ok(wrap_u) && wrap_ok(wrap_v) && filter[5:4] != 2'd3
             && filter[15:14] <= tex_pkg::REDUCE_MAX
             && (!filter[13] || (clamping(wrap_u) && clamping(wrap_v) && filter[0] == filter[1]
                                 && filter[11:8] == 4'd0
                                 && (filter[5:4] == tex_pkg::MIP_NONE || max_lod <= 0)));
  end
  always_comb begin
    {sel_control, sel_cache, sel_fifo, sel_filter, sel_bias, sel_min, sel_max} = '0;
    {sel_base, sel_attr, sel_size, sel_commit, sel_border_rg, sel_border_ba, sel_wrap, sel_smp_commit} = '0;
    wr_ok = ws == 4'hF;
    case (wa)
      R_CONTROL:     sel_control = 1'b1;
      R_CACHE:       begin sel_cache = 1'b1; if (!ctl_unit_reset || !geometry_ok) wr_ok = 1'b0; end
      R_FIFO_LIMIT:  sel_fifo = 1'b1;
      R_FILTER:      sel_filter = 1'b1;
      R_LOD_BIAS:    sel_bias = 1'b1;
      R_MIN_LOD:     sel_min = 1'b1;
      R_MAX_LOD:     sel_max = 1'b1;
      R_DESC_BASE:   sel_base = 1'b1;
      R_DESC_ATTR:   sel_attr = 1'b1;
      R_DESC_SIZE:   sel_size = 1'b1;
      R_DESC_COMMIT: begin sel_commit = 1'b1; if (ctl_unit_reset || !desc_ok) wr_ok = 1'b0; end
      R_BORDER_RG:   sel_border_rg = 1'b1;
      R_BORDER_BA:   sel_border_ba = 1'b1;
      R_WRAP:        sel_wrap = 1'b1;
      R_SMP_COMMIT:  begin sel_smp_commit = 1'b1; if (ctl_unit_reset || !smp_ok) wr_ok = 1'b0; end
      default:       wr_ok = 1'b0;  // undefined or read-only
    endcase
  end
  assign wr_en = do_write && wr_ok;

  always_ff @(posedge clk) begin
    if (rst) begin
      aw_full <= 1'b0;
      w_full  <= 1'b0;
      bvalid  <= 1'b0;
    end else begin
      aw_full <= !do_write && (aw_full || aw_take);
      w_full  <= !do_write && (w_full || w_take);
      if (do_write) bvalid <= 1'b1;
      else if (s_axi_bready) bvalid <= 1'b0;
    end
    if (aw_take) aw_addr_q <= s_axi_awaddr[ADDR_W-1:2];
    if (w_take) begin
      w_data_q <= s_axi_wdata;
      w_strb_q <= s_axi_wstrb;
    end
    if (do_write) bresp <= wr_ok ? OKAY : SLVERR;
  end

  // Reset values: the unit held in reset, the largest cache of MAX_WAYS ways, trilinear, no LOD
  // clamp beyond the texture's own levels (min -128.0, max +127.996).
  always_ff @(posedge clk) begin
    if (rst) begin
      ctl_unit_reset <= 1'b1;
      ctl_freeze     <= 1'b0;
      desc_we        <= 1'b0;
      desc_index     <= '0;
      desc_base      <= '0;
      desc_attr      <= '0;
      desc_last      <= '1;  // every level of the chain
      desc_layers_m1 <= '0;  // one layer
      desc_w         <= tex_pkg::SIZE_W'(1);
      desc_h         <= tex_pkg::SIZE_W'(1);
      smp_we         <= 1'b0;
      smp_index      <= '0;
      wrap           <= '0;
      border         <= '0;
      filter         <= 19'h30023;  // linear texels (minification and magnification), MIP_LINEAR, compare LESS_OR_EQUAL
      lod_bias       <= '0;
      min_lod        <= 16'sh8000;
      max_lod        <= 16'sh7FFF;
      block_morton   <= 1'b0;
      log2_ways      <= WAYS_W'(LOG2_WAYS);
      log2_sets      <= SETS_W'(LOG2_LINES - LOG2_WAYS);
      fifo_limit     <= '0;
    end else begin
      desc_we <= wr_en && sel_commit;
      smp_we  <= wr_en && sel_smp_commit;
      if (wr_en && sel_control) {ctl_freeze, ctl_unit_reset} <= wd[1:0];
      if (wr_en && sel_cache) {log2_ways, log2_sets, block_morton} <= {wd[17:16], wd[12:8], wd[0]};
      if (wr_en && sel_fifo)   fifo_limit <= wd[FLW-1:0];
      if (wr_en && sel_filter) filter <= wd[18:0] & 19'h7FF33;
      if (wr_en && sel_bias)   lod_bias <= wd[15:0];
      if (wr_en && sel_min)    min_lod <= wd[15:0];
      if (wr_en && sel_max)    max_lod <= wd[15:0];
      if (wr_en && sel_base)   desc_base <= wd;
      if (wr_en && sel_attr)   {desc_layers_m1, desc_attr, desc_last} <= {wd[31:24], wd[22:16], wd[11:8]};
      if (wr_en && sel_size)   {desc_h, desc_w} <= {wd[16 +: tex_pkg::SIZE_W], wd[0 +: tex_pkg::SIZE_W]};
      if (wr_en && sel_wrap)   wrap <= wd[6:0] & 7'h77;
      if (wr_en && sel_smp_commit) smp_index <= wd[3:0];
      if (wr_en && sel_border_rg) border[31:0]  <= wd;
      if (wr_en && sel_border_ba) border[63:32] <= wd;
      if (wr_en && sel_commit) desc_index <= wd[3:0];
    end
  end

  assign unit_rst         = ctl_unit_reset;
  assign cfg_desc_we      = desc_we;
  assign cfg_desc_index   = desc_index;
  assign cfg_desc_base    = desc_base;
  assign cfg_desc_w       = desc_w;
  assign cfg_desc_h       = desc_h;
  assign cfg_desc_last_level = desc_last;
  assign cfg_desc_format  = attr_format;
  assign cfg_desc_srgb    = attr_srgb;
  assign cfg_desc_cube    = attr_cube;
  assign cfg_desc_layers_m1 = desc_layers_m1;
  assign cfg_smp_we       = smp_we;
  assign cfg_smp_index    = smp_index;
  assign cfg_smp_wrap_u   = wrap_u;
  assign cfg_smp_wrap_v   = wrap_v;
  assign cfg_smp_min_linear = filter[0];
  assign cfg_smp_mag_linear   = filter[1];
  assign cfg_smp_mip_mode     = filter[5:4];
  assign cfg_smp_max_aniso_m1 = filter[11:8];
  assign cfg_smp_aniso_pow2   = filter[12];
  assign cfg_smp_unnormalized = filter[13];
  assign cfg_smp_reduction    = filter[15:14];
  assign cfg_smp_compare_op   = filter[18:16];
  assign cfg_smp_border_rgba  = border;
  assign cfg_smp_lod_bias     = lod_bias;
  assign cfg_smp_min_lod      = min_lod;
  assign cfg_smp_max_lod      = max_lod;
  assign cfg_block_morton = block_morton;
  assign cfg_log2_sets    = log2_sets;
  assign cfg_log2_ways    = log2_ways;
  assign cfg_fifo_limit   = fifo_limit;

  // ---------------------------------------------------------------- counters
  // The events are registered first (the 64-bit adders start at flip-flops).
  localparam int IW = 8;  // bits of one clock's increment (BEAT_BYTES <= 64)
  logic              ev_sample, ev_sample_error, ev_mem_beat, ev_out_stall, ev_mem_wait, ev_req_stall;
  logic [3:0]        ev_lookups, ev_misses;
  logic              cnt_clear;                 // CONTROL write with bit 2 (clear) set
  logic [NCNT*IW-1:0] cnt_inc;                  // counter i's increment at [i*IW +: IW]
  logic [NCNT*64-1:0] cnt;                      // counter i at [i*64 +: 64]
  always_ff @(posedge clk) begin
    ev_sample       <= stat_sample;
    ev_sample_error <= stat_sample_error;
    ev_lookups      <= stat_lookups;
    ev_misses       <= stat_misses;
    ev_mem_beat     <= stat_mem_beat;
    ev_out_stall    <= stat_out_stall;
    ev_mem_wait     <= stat_mem_wait;
    ev_req_stall    <= stat_req_stall;
  end
  assign cnt_clear = wr_en && sel_control && wd[2];
  assign cnt_inc = {IW'(ev_req_stall), IW'(ev_mem_wait), IW'(ev_out_stall),
                    ev_mem_beat ? IW'(BEAT_BYTES) : IW'(0), IW'(ev_misses), IW'(ev_lookups),
                    IW'(ev_sample_error), IW'(ev_sample), IW'(1)};
  generate
    for (genvar i = 0; i < NCNT; i++) begin : g_cnt
      always_ff @(posedge clk) begin
        if (rst || cnt_clear) cnt[i*64 +: 64] <= '0;
        else if (!ctl_freeze) cnt[i*64 +: 64] <= cnt[i*64 +: 64] + 64'(cnt_inc[i*IW +: IW]);
      end
    end
  endgenerate

  // ---------------------------------------------------------------- read channel
  logic          rvalid;
  logic [31:0]   rdata;
  logic [1:0]    rresp;
  logic          ar_take;
  logic [WA-1:0] ra;
  logic          ra_cnt;         // a counter word: 0x080 .. 0x0FF
  logic [3:0]    ra_idx;         // its counter
  logic          snap_valid;     // snap_hi is counter snap_idx's HI word from its last LO read
  logic [3:0]    snap_idx;
  logic [31:0]   snap_hi;
  logic [63:0]   cnt_sel;        // counter ra_idx
  logic [31:0]   rd_data;
  logic          rd_ok;
  assign s_axi_arready = !rvalid;
  assign s_axi_rvalid  = rvalid;
  assign s_axi_rdata   = rdata;
  assign s_axi_rresp   = rresp;
  assign ar_take = s_axi_arvalid && s_axi_arready;
  assign ra      = s_axi_araddr[ADDR_W-1:2];
  assign ra_cnt  = (ra >> 5) == WA'(1);
  assign ra_idx  = ra[4:1];
  always_comb begin
    cnt_sel = '0;
    for (int i = 0; i < NCNT; i++) if (ra_idx == 4'(i)) cnt_sel = cnt[i*64 +: 64];
    rd_ok   = 1'b1;
    rd_data = '0;
    if (ra_cnt) begin
      if (32'(ra_idx) >= NCNT) rd_ok = 1'b0;
      else if (!ra[0]) rd_data = cnt_sel[31:0];
      else rd_data = (snap_valid && snap_idx == ra_idx) ? snap_hi : cnt_sel[63:32];
    end else begin
      case (ra)
        R_ID:          rd_data = ID;
        R_VERSION:     rd_data = VERSION;
        R_CAPS0:       rd_data = CAPS0;
        R_CAPS1:       rd_data = CAPS1;
        R_CONTROL:     rd_data = {30'd0, ctl_freeze, ctl_unit_reset};
        R_CACHE:       rd_data = {14'd0, log2_ways, 3'd0, log2_sets, 7'd0, block_morton};
        R_FIFO_LIMIT:  rd_data = 32'(fifo_limit);
        R_FILTER:      rd_data = 32'(filter);
        R_LOD_BIAS:    rd_data = {16'd0, lod_bias};
        R_MIN_LOD:     rd_data = {16'd0, min_lod};
        R_MAX_LOD:     rd_data = {16'd0, max_lod};
        R_DESC_BASE:   rd_data = desc_base;
        R_DESC_ATTR:   rd_data = {desc_layers_m1, 1'd0, desc_attr, 4'd0, desc_last, 8'd0};
        R_DESC_SIZE:   rd_data = {2'd0, desc_h, 2'd0, desc_w};
        R_DESC_COMMIT: rd_data = {28'd0, desc_index};
        R_BORDER_RG:   rd_data = border[31:0];
        R_BORDER_BA:   rd_data = border[63:32];
        R_WRAP:        rd_data = {25'd0, wrap};
        R_SMP_COMMIT:  rd_data = {28'd0, smp_index};
        default:       rd_ok = 1'b0;
      endcase
    end
  end

  always_ff @(posedge clk) begin
    if (rst) rvalid <= 1'b0;
    else if (ar_take) rvalid <= 1'b1;
    else if (s_axi_rready) rvalid <= 1'b0;
    if (ar_take) begin
      rdata <= rd_ok ? rd_data : '0;
      rresp <= rd_ok ? OKAY : SLVERR;
    end
    // 64-bit reads: a LO read latches the HI word; the HI read that follows uses it up.
    if (rst || cnt_clear) snap_valid <= 1'b0;
    else if (ar_take && ra_cnt && 32'(ra_idx) < NCNT) begin
      if (!ra[0]) snap_valid <= 1'b1;
      else if (snap_idx == ra_idx) snap_valid <= 1'b0;
    end
    if (ar_take && ra_cnt && !ra[0]) begin
      snap_idx <= ra_idx;
      snap_hi  <= cnt_sel[63:32];
    end
  end

  logic unused_ok;  // AWPROT, ARPROT (no protection), byte address bits 1:0, reserved data bits
  assign unused_ok = ^{s_axi_awprot, s_axi_arprot, s_axi_awaddr[1:0], s_axi_araddr[1:0]};

`ifdef FORMAL
  // ---------------------------------------------------------------- formal properties
  // Proven by scripts/formal.sh (BMC from reset, then k-induction) in the environment
  // rtl/formal/tex_axil_config_formal.sv: a reset in the first clock, then every input free but
  // for the master's AXI rules (a valid held until ready, with a stable payload); resets
  // mid-traffic included. The checker counts requests and responses and records the last write's
  // address, data and strobes and the last read's address as the handshakes take them; the
  // register map it checks against is its own list (f_writable, f_readable).
  logic          f_reset_done = 1'b0;    // a reset has been applied
  logic [1:0]    f_aw_open, f_w_open;    // write addresses / data taken minus B responses taken
  logic [1:0]    f_ar_open;              // read addresses taken minus R responses taken
  logic [WA-1:0] f_aw_addr, f_ar_addr;   // the last taken write address and read address
  logic [31:0]   f_w_data;               // the last taken write data and strobes
  logic [3:0]    f_w_strb;
  logic          f_b_stall_q, f_r_stall_q;  // bvalid && !bready (rvalid && !rready), last clock
  logic [1:0]    f_bresp_q;
  logic [33:0]   f_r_q;                  // {rresp, rdata}, last clock
  // wraps, min/mag linear, mip mode, 3 LODs, aniso cap and pow2, border, unnormalized, reduction
  localparam int FSW = 2 * tex_pkg::WRAP_W + 2 + tex_pkg::MIP_W + 3 * tex_pkg::LOD_W + 5 + 64 + 1 + tex_pkg::REDUCTION_W
                       + tex_pkg::COMPARE_W;
  localparam int FCW = 1 + tex_pkg::TEX_ID_W + tex_pkg::SMP_ID_W + tex_pkg::MEM_ADDR_W + 2 * tex_pkg::SIZE_W + tex_pkg::LEVEL_W
                       + tex_pkg::FORMAT_W + tex_pkg::LAYER_W + 3 + SETS_W + WAYS_W + FLW + FSW;
  logic [FCW-1:0] f_cfg, f_cfg_q;        // unit_rst and every cfg_* output but the two we pulses
  logic [2*tex_pkg::SIZE_W+tex_pkg::LAYER_W+40:0] f_desc, f_desc_q;  // the staged descriptor (cfg_desc_base .. _layers_m1)
  logic [FSW-1:0] f_smp, f_smp_q;        // the staged sampler (cfg_smp_wrap_u .. _border_rgba)
  logic          f_desc_we_q, f_smp_we_q, f_clear_q, f_desc_ready_q;
  logic          f_b_new, f_r_new;       // a B (R) response that was not there last clock
  logic          f_b_take, f_r_take;

  // The register map, independently of the decoder: word addresses that take a write (when the
  // write is otherwise allowed) and those that answer a read.
  // (Yosys 0.23 has no `return`: the function's name is its result.)
  function automatic logic f_writable(input logic [WA-1:0] a);
    f_writable = a == WA'('h10 >> 2) || a == WA'('h20 >> 2) || a == WA'('h24 >> 2)
              || a == WA'('h30 >> 2) || a == WA'('h34 >> 2) || a == WA'('h38 >> 2)
              || a == WA'('h3C >> 2) || a == WA'('h40 >> 2) || a == WA'('h44 >> 2)
              || a == WA'('h48 >> 2) || a == WA'('h4C >> 2) || a == WA'('h50 >> 2) || a == WA'('h54 >> 2)
              || a == WA'('h58 >> 2) || a == WA'('h5C >> 2);
  endfunction
  function automatic logic f_readable(input logic [WA-1:0] a);
    f_readable = f_writable(a) || 32'(a) < 4 || (32'(a) >= 'h80 / 4 && 32'(a) < 'h80 / 4 + 2 * NCNT);
  endfunction

  assign f_cfg = {unit_rst, cfg_desc_index, cfg_smp_index, cfg_desc_base, cfg_desc_w, cfg_desc_h, cfg_desc_last_level,
                  cfg_desc_format, cfg_desc_srgb, cfg_desc_cube, cfg_desc_layers_m1, cfg_block_morton, cfg_log2_sets, cfg_log2_ways,
                  cfg_fifo_limit, f_smp};
  assign f_desc = {cfg_desc_base, cfg_desc_layers_m1, cfg_desc_cube, cfg_desc_srgb, cfg_desc_format, cfg_desc_last_level, cfg_desc_h,
                   cfg_desc_w};
  assign f_smp  = {cfg_smp_wrap_u, cfg_smp_wrap_v, cfg_smp_min_linear, cfg_smp_mag_linear, cfg_smp_mip_mode,
                   cfg_smp_lod_bias, cfg_smp_min_lod, cfg_smp_max_lod, cfg_smp_max_aniso_m1, cfg_smp_aniso_pow2,
                   cfg_smp_border_rgba, cfg_smp_unnormalized, cfg_smp_reduction, cfg_smp_compare_op};
  assign f_b_take = s_axi_bvalid && s_axi_bready;
  assign f_r_take = s_axi_rvalid && s_axi_rready;
  assign f_b_new  = s_axi_bvalid && !f_b_stall_q;
  assign f_r_new  = s_axi_rvalid && !f_r_stall_q;
  always_ff @(posedge clk) begin
    f_b_stall_q <= !rst && s_axi_bvalid && !s_axi_bready;
    f_r_stall_q <= !rst && s_axi_rvalid && !s_axi_rready;
    f_bresp_q   <= s_axi_bresp;
    f_r_q       <= {s_axi_rresp, s_axi_rdata};
    f_cfg_q     <= f_cfg;
    f_desc_q    <= f_desc;
    f_desc_we_q <= !rst && cfg_desc_we;
    f_desc_ready_q <= cfg_desc_ready;
    f_smp_q     <= f_smp;
    f_smp_we_q  <= !rst && cfg_smp_we;
    f_clear_q   <= cnt_clear;
    if (aw_take) f_aw_addr <= s_axi_awaddr[ADDR_W-1:2];
    if (w_take) begin
      f_w_data <= s_axi_wdata;
      f_w_strb <= s_axi_wstrb;
    end
    if (ar_take) f_ar_addr <= ra;
    if (rst) begin
      f_reset_done <= 1'b1;
      f_aw_open    <= '0;
      f_w_open     <= '0;
      f_ar_open    <= '0;
    end else begin
      f_aw_open <= f_aw_open + 2'(aw_take) - 2'(f_b_take);
      f_w_open  <= f_w_open + 2'(w_take) - 2'(f_b_take);
      f_ar_open <= f_ar_open + 2'(ar_take) - 2'(f_r_take);
    end
  end

  // (Labelled p_<property>_<n>: scripts/formal.sh names a failed property by its label.)
  always_comb begin
    if (f_reset_done) begin
      // one B per write: a B only for a taken address and data not yet answered (no response
      // without a request, none twice), and one as soon as both are taken; at most one of each
      // open (the held halves are the open ones)
      p_bone_1: assert (f_aw_open <= 2'd1 && f_w_open <= 2'd1);
      // (but a DESC_COMMIT, both halves held, may wait for cfg_desc_ready)
      p_bone_2: assert (s_axi_bvalid ? (f_aw_open == 2'd1 && f_w_open == 2'd1)
                        : (f_aw_open != 2'd1 || f_w_open != 2'd1
                           || (aw_full && w_full && aw_addr_q == R_DESC_COMMIT)));
      p_bone_3: assert (aw_full == (f_aw_open == 2'd1 && !s_axi_bvalid)
                        && (!aw_full || aw_addr_q == f_aw_addr));
      p_bone_4: assert (w_full == (f_w_open == 2'd1 && !s_axi_bvalid)
                        && (!w_full || (w_data_q == f_w_data && w_strb_q == f_w_strb)));
      // one R per read: an R only for a taken address not yet answered, and at once
      p_rone_1: assert (f_ar_open <= 2'd1 && s_axi_rvalid == (f_ar_open == 2'd1));
      // hold: a stalled B (R) stays, its payload unchanged
      if (f_b_stall_q) p_bhold_1: assert (s_axi_bvalid && s_axi_bresp == f_bresp_q);
      if (f_r_stall_q) p_rhold_1: assert (s_axi_rvalid && {s_axi_rresp, s_axi_rdata} == f_r_q);
      // errors: a write to an address that takes none, or not of all 4 bytes, answers SLVERR; a
      // read of an address that answers none, SLVERR with data 0
      if (f_b_new && (!f_writable(f_aw_addr) || f_w_strb != 4'hF))
        p_slverr_1: assert (s_axi_bresp == SLVERR);
      if (f_r_new && !f_readable(f_ar_addr))
        p_slverr_2: assert (s_axi_rresp == SLVERR && s_axi_rdata == '0);
      // an answered SLVERR changed nothing at its edge: no configuration output, no descriptor
      // write, no counter clear
      if (f_b_new && s_axi_bresp == SLVERR)
        p_nochange_1: assert (f_cfg == f_cfg_q && !cfg_desc_we && !cfg_smp_we && !f_clear_q);
      // cfg_desc_we: one clock, exactly at each accepted DESC_COMMIT write (OKAY), with its index
      // and the staged descriptor unchanged
      if (cfg_desc_we)
        p_desc_1: assert (f_b_new && s_axi_bresp == OKAY && f_aw_addr == R_DESC_COMMIT
                          && cfg_desc_index == f_w_data[tex_pkg::TEX_ID_W-1:0] && f_desc == f_desc_q);
      if (f_b_new && s_axi_bresp == OKAY && f_aw_addr == R_DESC_COMMIT) p_desc_2: assert (cfg_desc_we);
      if (f_desc_we_q) p_desc_3: assert (!cfg_desc_we);
      // and only when the unit takes it: cfg_desc_ready high in the clock of the write
      if (cfg_desc_we) p_desc_4: assert (f_desc_ready_q);
      // cfg_smp_we: likewise at each accepted SMP_COMMIT, with the staged sampler unchanged
      if (cfg_smp_we)
        p_smp_1: assert (f_b_new && s_axi_bresp == OKAY && f_aw_addr == R_SMP_COMMIT
                         && cfg_smp_index == f_w_data[tex_pkg::SMP_ID_W-1:0] && f_smp == f_smp_q);
      if (f_b_new && s_axi_bresp == OKAY && f_aw_addr == R_SMP_COMMIT) p_smp_2: assert (cfg_smp_we);
      if (f_smp_we_q) p_smp_3: assert (!cfg_smp_we);
    end
  end
`endif
endmodule

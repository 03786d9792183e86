// tex_pkg: constants shared by every tex_* module. The C++ twin is model/formats.h;
// tests/model/test_params.cpp parses every localparam below (each must be a plain literal) and
// compares those that have a twin.
// Referenced as tex_pkg::NAME (Yosys 0.23 rejects `import tex_pkg::*`).
package tex_pkg;
  // ---- number formats
  localparam int REQ_COORD_W   = 32;  // req_u, req_v: signed Q8.24, 1.0 = one texture width
  localparam int COORD_FRAC    = 24;  //   fraction bits of u, v
  localparam int TEXEL_COORD_FRAC = 16;  //   of an unnormalized sampler's u, v: signed Q16.16 texels
  localparam int LOD_W         = 16;  // lambda, bias, min/max lod: signed Q8.8
  localparam int LOD_FRAC      = 8;   //   fraction bits of lambda
  localparam int WEIGHT_BITS   = 8;   // fx, fy, f: 0..255 = 0..255/256 of the second tap
  localparam int MAX_CW        = 16;  // bits per channel: CW = 1..MAX_CW

  // ---- sizes, levels, texel indices
  localparam int MAX_LOG2_SIZE   = 13;  // 8192 texels per side at most (tex_unit_cached)
  localparam int MAX_LOG2_ONCHIP = 11;  // tex_unit's per-level memories: 2048 per side at most
  localparam int LEVEL_W       = 4;   // a level index (0..13): wr_level, cfg_last_level
  localparam int SIZE_W        = 14;  // a texture's or a level's side, 1..8192: cfg_w, cfg_h
  localparam int COORD_W       = 13;  // bits of a wrapped texel index / write coordinate

  // ---- cached memory (docs/memory.md)
  localparam int MEM_ADDR_W    = 32;  // byte address of a line in external memory
  localparam int LOG2_SETS_W   = 5;   // cfg_log2_sets: sets per cache, 4 .. 2^(2^5 - 1)
  localparam int LOG2_WAYS_W   = 2;   // cfg_log2_ways: 0, 1, 2 = 1, 2, 4 ways
  localparam int TEX_ID_W      = 4;   // req_tex: a texture descriptor-table entry, 0..15
  localparam int SMP_ID_W      = 4;   // req_sampler: a sampler-table entry, 0..15
  localparam int LAYER_W       = 8;   // cfg_desc_layers_m1: an array texture's layers - 1 (1..256 layers)

  // ---- cfg_smp_wrap_u / cfg_smp_wrap_v
  localparam int WRAP_W = 3;
  localparam logic [WRAP_W-1:0] WRAP_REPEAT       = 3'd0;
  localparam logic [WRAP_W-1:0] WRAP_CLAMP        = 3'd1;  // CLAMP_TO_EDGE
  localparam logic [WRAP_W-1:0] WRAP_MIRROR       = 3'd2;  // MIRRORED_REPEAT
  localparam logic [WRAP_W-1:0] WRAP_BORDER       = 3'd3;  // CLAMP_TO_BORDER
  localparam logic [WRAP_W-1:0] WRAP_MIRROR_CLAMP = 3'd4;  // MIRROR_CLAMP_TO_EDGE
  // (internal, never a sampler's: a cube face's taps in its skirted storage, tex_front and tex_wrap;
  // a texel fetch of a face: clamp to border, then into the skirted storage)
  localparam logic [WRAP_W-1:0] WRAP_SKIRT        = 3'd5;
  localparam logic [WRAP_W-1:0] WRAP_SKIRT_BORDER = 3'd6;

  // ---- cfg_smp_mip_mode
  localparam int MIP_W = 2;
  localparam logic [MIP_W-1:0] MIP_NONE    = 2'd0;
  localparam logic [MIP_W-1:0] MIP_NEAREST = 2'd1;
  localparam logic [MIP_W-1:0] MIP_LINEAR  = 2'd2;

  // ---- cfg_smp_reduction (Vulkan's VkSamplerReductionMode values)
  localparam int REDUCTION_W = 2;
  localparam logic [REDUCTION_W-1:0] REDUCE_AVERAGE = 2'd0;  // the weighted average (filtering)
  localparam logic [REDUCTION_W-1:0] REDUCE_MIN     = 2'd1;  // the minimum of the weighed taps
  localparam logic [REDUCTION_W-1:0] REDUCE_MAX     = 2'd2;  // their maximum

  // ---- cfg_smp_compare_op (model/formats.h CompareOp, Vulkan's VkCompareOp values): `ref OP depth`
  localparam int COMPARE_W = 3;
  localparam logic [COMPARE_W-1:0] CMP_NEVER   = 3'd0;
  localparam logic [COMPARE_W-1:0] CMP_LESS    = 3'd1;
  localparam logic [COMPARE_W-1:0] CMP_EQUAL   = 3'd2;
  localparam logic [COMPARE_W-1:0] CMP_LEQUAL  = 3'd3;
  localparam logic [COMPARE_W-1:0] CMP_GREATER = 3'd4;
  localparam logic [COMPARE_W-1:0] CMP_NEQUAL  = 3'd5;
  localparam logic [COMPARE_W-1:0] CMP_GEQUAL  = 3'd6;
  localparam logic [COMPARE_W-1:0] CMP_ALWAYS  = 3'd7;

  // ---- req_op (model/formats.h Op): what a request asks
  localparam int OP_W = 2;
  localparam logic [OP_W-1:0] OP_SAMPLE = 2'd0;  // a filtered sample
  localparam logic [OP_W-1:0] OP_GATHER = 2'd1;  // textureGather: req_component of the linear taps at level 0
  localparam logic [OP_W-1:0] OP_COMPARE = 2'd2; // a depth compare: each texel's R tested against req_ref, then filtered
  localparam logic [OP_W-1:0] OP_FETCH  = 2'd3;  // texelFetch: req_u, req_v, req_lod are i, j, level

  // ---- texel formats (model/block_formats.h TexelFormat): how memory holds a texture
  localparam int FORMAT_W = 5;
  localparam logic [FORMAT_W-1:0] FMT_RGBA8     = 5'd0;
  localparam logic [FORMAT_W-1:0] FMT_BC1       = 5'd1;
  localparam logic [FORMAT_W-1:0] FMT_BC2       = 5'd2;
  localparam logic [FORMAT_W-1:0] FMT_BC3       = 5'd3;
  localparam logic [FORMAT_W-1:0] FMT_BC4       = 5'd4;
  localparam logic [FORMAT_W-1:0] FMT_BC5       = 5'd5;
  localparam logic [FORMAT_W-1:0] FMT_BC7       = 5'd7;
  localparam logic [FORMAT_W-1:0] FMT_ETC2      = 5'd8;   // ETC2 RGB8 (and ETC1)
  localparam logic [FORMAT_W-1:0] FMT_ETC2_A1   = 5'd9;   // ETC2 RGB8 with punch-through alpha
  localparam logic [FORMAT_W-1:0] FMT_ETC2_RGBA = 5'd10;  // ETC2 RGBA8: EAC alpha, then the colour
  // EAC R11 and RG11 (one or two EAC blocks of 11-bit values), unsigned and signed: 16-bit channels
  // into the CW = 16 filter, signed ones in offset binary (model/etc2.h eac_r11_code)
  localparam logic [FORMAT_W-1:0] FMT_EAC_R11        = 5'd11;
  localparam logic [FORMAT_W-1:0] FMT_EAC_R11_SNORM  = 5'd12;
  localparam logic [FORMAT_W-1:0] FMT_EAC_RG11       = 5'd13;
  localparam logic [FORMAT_W-1:0] FMT_EAC_RG11_SNORM = 5'd14;
  // ASTC LDR: one code per footprint, FMT_ASTC_4X4 + i for footprint i of 4x4, 5x4, 5x5, 6x5, 6x6,
  // 8x5, 8x6, 8x8, 10x5, 10x6, 10x8, 10x10, 12x10, 12x12 (astc_footprint)
  localparam logic [FORMAT_W-1:0] FMT_ASTC_4X4   = 5'd16;
  localparam logic [FORMAT_W-1:0] FMT_ASTC_12X12 = 5'd29;

  // A block format the unit decodes (codes 6, 15 and 30, 31 are none).
  function automatic logic block_format(input logic [FORMAT_W-1:0] fmt);
    block_format = (fmt >= FMT_BC1 && fmt <= FMT_BC5) || (fmt >= FMT_BC7 && fmt <= FMT_EAC_RG11_SNORM) ||
                   (fmt >= FMT_ASTC_4X4 && fmt <= FMT_ASTC_12X12);
  endfunction
  function automatic logic eac(input logic [FORMAT_W-1:0] fmt);
    eac = fmt >= FMT_EAC_R11 && fmt <= FMT_EAC_RG11_SNORM;
  endfunction
  function automatic logic snorm(input logic [FORMAT_W-1:0] fmt);
    snorm = fmt == FMT_EAC_R11_SNORM || fmt == FMT_EAC_RG11_SNORM;
  endfunction
  // A format with an sRGB form (the descriptor's sRGB bit is legal): not BC4, BC5 or EAC.
  function automatic logic srgb_format(input logic [FORMAT_W-1:0] fmt);
    srgb_format = fmt != FMT_BC4 && fmt != FMT_BC5 && !eac(fmt);
  endfunction
  function automatic logic astc(input logic [FORMAT_W-1:0] fmt);
    astc = fmt >= FMT_ASTC_4X4 && fmt <= FMT_ASTC_12X12;
  endfunction
  // A level side of n units (texels, or blocks of a footprint side f; n < 2^16) keeps a copy of
  // its unit column (row) 0 past its end for the repeat seam: n not a power of two, or longer than
  // an f that is not one (ASTC 5, 6, 10, 12) (docs/memory.md §1; the model's MemoryLayout).
  function automatic logic seam_copy(input logic [15:0] n, input logic [3:0] f);
    seam_copy = (n & (n - 16'd1)) != 16'd0 || ((f & (f - 4'd1)) != 4'd0 && n > 16'(f));
  endfunction
  // The texels a block covers, {height, width} (4 bits each): an ASTC format's footprint, 4 x 4
  // for the other block formats, 1 x 1 (a texel) for RGBA8.
  function automatic logic [7:0] footprint(input logic [FORMAT_W-1:0] fmt);
    case (fmt)
      FMT_RGBA8: footprint = {4'd1, 4'd1};
      5'd16: footprint = {4'd4, 4'd4};    5'd17: footprint = {4'd4, 4'd5};    5'd18: footprint = {4'd5, 4'd5};
      5'd19: footprint = {4'd5, 4'd6};    5'd20: footprint = {4'd6, 4'd6};    5'd21: footprint = {4'd5, 4'd8};
      5'd22: footprint = {4'd6, 4'd8};    5'd23: footprint = {4'd8, 4'd8};    5'd24: footprint = {4'd5, 4'd10};
      5'd25: footprint = {4'd6, 4'd10};   5'd26: footprint = {4'd8, 4'd10};   5'd27: footprint = {4'd10, 4'd10};
      5'd28: footprint = {4'd10, 4'd12};  5'd29: footprint = {4'd12, 4'd12};
      default: footprint = {4'd4, 4'd4};
    endcase
  endfunction

  // v / f for a footprint side f (1, 4, 5, 6, 8, 10, 12) and v < 2^16: shifts, and the odd factors
  // 3 and 5 as reciprocal multiplies, (v * 43691) >> 17 and (v * 52429) >> 18, exact below 2^16
  // (docs/memory.md §1; the model's MemoryLayout::block_column).
  function automatic logic [15:0] div_footprint(input logic [15:0] v, input logic [3:0] f);
    case (f)
      4'd4: div_footprint = v >> 2;
      4'd5: div_footprint = 16'((34'(v) * 34'd52429) >> 18);
      4'd6: div_footprint = 16'(((34'(v) >> 1) * 34'd43691) >> 17);
      4'd8: div_footprint = v >> 3;
      4'd10: div_footprint = 16'(((34'(v) >> 1) * 34'd52429) >> 18);
      4'd12: div_footprint = 16'(((34'(v) >> 2) * 34'd43691) >> 17);
      default: div_footprint = v;  // 1
    endcase
  endfunction

  // A cached line's kind in the data banks (tex_cache_data's wr_kind): what a bank word holds.
  localparam int LINE_KIND_W = 2;
  localparam logic [LINE_KIND_W-1:0] LINE_TEXELS   = 2'd0;
  localparam logic [LINE_KIND_W-1:0] LINE_BLOCKS8  = 2'd1;  // BC1, BC4, ETC2 RGB8, RGB8A1, EAC R11: 8-byte 4x4 blocks
  localparam logic [LINE_KIND_W-1:0] LINE_BLOCKS16 = 2'd2;  // BC2, BC3, BC5, BC7, ETC2 RGBA8, EAC RG11, ASTC: 16-byte blocks
  function automatic logic [LINE_KIND_W-1:0] line_kind(input logic [FORMAT_W-1:0] fmt);
    if (fmt == FMT_RGBA8) line_kind = LINE_TEXELS;
    else if (fmt == FMT_BC1 || fmt == FMT_BC4 || fmt == FMT_ETC2 || fmt == FMT_ETC2_A1 || fmt == FMT_EAC_R11
             || fmt == FMT_EAC_R11_SNORM) line_kind = LINE_BLOCKS8;
    else line_kind = LINE_BLOCKS16;
  endfunction
endpackage

// tex_pkg: constants shared by every tex_* module; the C++ twin is model/formats.h.
// Referenced as tex_pkg::NAME (Yosys 0.23 rejects `import tex_pkg::*`).
package tex_pkg;
  localparam int COORD_FRAC   = 24;  // u, v: signed Q8.24, 1.0 = one texture width
  localparam int LOD_FRAC     = 8;   // lambda, bias, min/max lod: signed Q8.8
  localparam int WEIGHT_BITS  = 8;   // fx, fy, f: 0..255 = 0..255/256 of the second tap
  localparam int MAX_LOG2_SIZE = 11; // 2048 texels per side at most
  localparam int COORD_W      = 11;  // bits of a wrapped texel index / write coordinate
  localparam int INDEX_W      = 21;  // signed unwrapped texel index (|u| < 128 at 2048 texels)
  localparam int SCALED_W     = 28;  // u >>> (15 - log2_w0): 32 - minimum shift of 4

  // cfg_wrap_u / cfg_wrap_v
  localparam logic [1:0] WRAP_REPEAT = 2'd0;
  localparam logic [1:0] WRAP_CLAMP  = 2'd1;  // CLAMP_TO_EDGE
  localparam logic [1:0] WRAP_MIRROR = 2'd2;  // MIRRORED_REPEAT

  // cfg_mip_mode
  localparam logic [1:0] MIP_NONE    = 2'd0;
  localparam logic [1:0] MIP_NEAREST = 2'd1;
  localparam logic [1:0] MIP_LINEAR  = 2'd2;
endpackage

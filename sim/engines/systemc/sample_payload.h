// The data of one sample transaction on the texture unit's TLM-2.0 socket (docs/systemc.md).
// Plain C++ (no SystemC), so a virtual platform's initiator can include it anywhere.
//
// A transaction is a tlm_generic_payload with
//   command     TLM_READ_COMMAND (the initiator reads one filtered texel)
//   address     kSampleAddress
//   data_ptr    -> one SampleTransfer (host byte order), data_length = sizeof(SampleTransfer)
//   streaming width = data_length, no byte enables.
// The initiator fills the request fields; the target fills `rgba` and sets TLM_OK_RESPONSE.
// Anything else completes at once with an error response status and is not sampled.
#pragma once
#include <cstdint>

namespace tex::systemc {

constexpr uint64_t kSampleAddress = 0;

struct SampleTransfer {
  // Request (written by the initiator).
  int32_t u = 0, v = 0;  // Q8.24, 1.0 = one texture width / height
  int32_t lod = 0;       // Q8.8 levels, before bias and clamp; the RTL port is 16 bits wide
  uint32_t tag = 0;      // the initiator's own; returned unchanged
  uint32_t has_derivatives = 0;  // 1: the unit computes lambda (and anisotropic probes) from these, not lod
  int32_t dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;  // Q8.24 texture widths / heights per pixel
  int32_t bias = 0;      // Q8.8, the request's own LOD bias (added to the sampler's); 16-bit RTL port
  int32_t layer = 0;     // an array texture's layer, Q16.16 (req_layer); a texel fetch's: the integer layer
  int32_t ref = 0;       // a depth compare's reference, Q8.24 (req_ref)
  int32_t w = 0;         // a cube map's direction is (u, v, w), Q8.24 of any length (req_w)
  int32_t dwdx = 0, dwdy = 0;  // and with derivatives, those of w (req_dwdx, req_dwdy)
  uint8_t texture = 0;   // the descriptor-table entry (req_tex); beyond the unit's table: an error response
  uint8_t sampler = 0;   // the sampler-table entry (req_sampler); likewise
  uint8_t op = 0;        // req_op: 0 a sample, 1 a gather, 2 a depth compare, 3 a texel fetch (u, v, lod: the integers
                         // i, j, level); another value: an error response
  uint8_t component = 0; // a gather's channel, 0..3 (req_component)
  // Response (written by the target).
  uint16_t rgba[4] = {0, 0, 0, 0};  // R, G, B, A; channel width of the texture (8 bits on the RTL)
};
static_assert(sizeof(SampleTransfer) == 72, "SampleTransfer is the socket's wire format");

// Debug transport (transport_dbg, TLM_READ_COMMAND) on the same socket reads texels of the unit's
// memory view: texel (x, y) of `level` and the ones after it along x in the same row, 8 bytes each
// (uint16_t R, G, B, A, host order); data_length a multiple of 8. Returns the bytes read (0 for an
// address outside the pyramid).
constexpr uint64_t kTexelDebugBase = uint64_t(1) << 48;
constexpr uint64_t texel_debug_address(int level, uint32_t x, uint32_t y) {
  return kTexelDebugBase | uint64_t(level) << 40 | uint64_t(y) << 20 | x;
}

}  // namespace tex::systemc

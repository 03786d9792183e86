// The AXI4-Lite register map of tex_unit_axi (rtl/tex_axil_config.sv; docs/rtl-interface.md,
// "AXI4-Lite configuration"): byte offsets, constants and the fields of the staged descriptor and
// sampler, for drivers and tests. One copy: RegisterMap.HeaderMatchesTheRtl
// (tests/rtl/test_register_map.cpp) reads every offset and constant back out of tex_axil_config.sv.
#pragma once
#include <cstdint>

#include "model/formats.h"
#include "model/memory_layout.h"
#include "model/sampler.h"

namespace tex::rtl::axil {

// Byte offsets.
constexpr uint32_t kId = 0x000, kVersion = 0x004, kCaps0 = 0x008, kCaps1 = 0x00C, kControl = 0x010;
constexpr uint32_t kCache = 0x020, kFifoLimit = 0x024;
// The staged sampler (committed by SMP_COMMIT) ...
constexpr uint32_t kFilter = 0x030, kLodBias = 0x034, kMinLod = 0x038, kMaxLod = 0x03C;
constexpr uint32_t kBorderRg = 0x050, kBorderBa = 0x054, kWrap = 0x058, kSmpCommit = 0x05C;
// ... and the staged texture descriptor (committed by DESC_COMMIT).
constexpr uint32_t kDescBase = 0x040, kDescAttr = 0x044, kDescCommit = 0x048, kDescSize = 0x04C;
constexpr uint32_t kCounterBase = 0x080;  // counter i: LO at 0x080 + 8 i, HI at + 4
constexpr int kCounters = 9;
enum Counter { kCycles, kSamples, kSampleErrors, kLookups, kMisses, kMemBytes, kOutStall, kMemWait, kReqStall };
constexpr const char* kCounterNames[kCounters] = {"CYCLES",    "SAMPLES",   "SAMPLE_ERRORS", "LOOKUPS",  "MISSES",
                                                  "MEM_BYTES", "OUT_STALL", "MEM_WAIT",      "REQ_STALL"};

// Constants and CONTROL's bits.
constexpr uint32_t kIdValue = 0x54455855;       // "TEXU"
constexpr uint32_t kVersionValue = 0x00030007;  // 3.7: any texture size (DESC_SIZE), FILTER.unnormalized, .reduction, .compare_op, DESC_ATTR.layers, .cube; DESC_ATTR.format 5 bits (ASTC); EAC formats 11..14
constexpr uint32_t kUnitReset = 1, kFreeze = 2, kClear = 4;
constexpr uint32_t kOkay = 0, kSlverr = 2;

// Every register the map defines, by its name in tex_axil_config.sv (R_<name>).
struct Register {
  const char* name;
  uint32_t offset;
};
constexpr Register kRegisters[] = {
    {"ID", kId},           {"VERSION", kVersion},     {"CAPS0", kCaps0},         {"CAPS1", kCaps1},
    {"CONTROL", kControl}, {"CACHE", kCache},         {"FIFO_LIMIT", kFifoLimit}, {"FILTER", kFilter},
    {"LOD_BIAS", kLodBias}, {"MIN_LOD", kMinLod},     {"MAX_LOD", kMaxLod},      {"DESC_BASE", kDescBase},
    {"DESC_ATTR", kDescAttr}, {"DESC_COMMIT", kDescCommit}, {"DESC_SIZE", kDescSize}, {"BORDER_RG", kBorderRg}, {"BORDER_BA", kBorderBa},
    {"WRAP", kWrap},       {"SMP_COMMIT", kSmpCommit},
};

// The staged sampler's words for a SamplerConfig (the cfg_smp_* fields, docs/rtl-interface.md).
inline uint32_t filter_word(const SamplerConfig& c) {
  return uint32_t(c.filter.texel == TexelFilter::Linear) | uint32_t(c.filter.mag == TexelFilter::Linear) << 1 |
         uint32_t(c.filter.mip) << 4 | uint32_t(c.probe_cap() - 1) << 8 | uint32_t(c.aniso_pow2) << 12 |
         uint32_t(c.unnormalized) << 13 | uint32_t(c.reduction) << 14 | uint32_t(c.compare_op) << 16;
}
inline uint32_t wrap_word(const SamplerConfig& c) { return uint32_t(c.wrap_u) | uint32_t(c.wrap_v) << 4; }
inline uint32_t border_rg_word(const SamplerConfig& c) {
  const Texel b = c.border_unorm16();
  return uint32_t(b[0]) | uint32_t(b[1]) << 16;
}
inline uint32_t border_ba_word(const SamplerConfig& c) {
  const Texel b = c.border_unorm16();
  return uint32_t(b[2]) | uint32_t(b[3]) << 16;
}
// The staged descriptor's DESC_ATTR for a texture's last level, format, sRGB flag, cube flag and
// layer count, and its DESC_SIZE.
inline uint32_t desc_attr_word(const MemoryLayout& l, bool srgb = false) {
  return uint32_t(l.levels() - 1) << 8 | uint32_t(l.format()) << 16 | uint32_t(srgb) << 21 |
         uint32_t(l.kind() == TextureKind::Cube) << 22 | uint32_t(l.layers() - 1) << 24;
}
inline uint32_t desc_size_word(Extent e) { return uint32_t(e.w) | uint32_t(e.h) << 16; }

}  // namespace tex::rtl::axil

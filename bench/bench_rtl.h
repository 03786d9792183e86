// The Verilated RTL's sampling rate per compiled configuration (bench_rtl.cpp), for `make bench`.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "engines/rtl/driver.h"

namespace bench {

// The texture of a speed workload: RGBA8 (every configuration), BC1, BC7, sRGB RGBA8, ETC2 RGBA8,
// EAC RG11 or ASTC 8x8 (the configurations with the block decoders and sRGB tables: what they cost
// when they are used).
enum class RtlTexture { Rgba8, Bc1, Bc7, Srgb, Etc2, Eac, Astc };
inline constexpr RtlTexture kRtlTextures[] = {RtlTexture::Rgba8, RtlTexture::Bc1, RtlTexture::Bc7, RtlTexture::Srgb,
                                              RtlTexture::Etc2,  RtlTexture::Eac, RtlTexture::Astc};
bool parse_rtl_texture(const std::string& name, RtlTexture& out);
const char* rtl_texture_name(RtlTexture t);
constexpr const char* kRtlTextureNames = "rgba8 | bc1 | bc7 | srgb | etc2a | eac_rg11 | astc8x8";
bool config_takes(const tex::rtl::RtlConfig& config, RtlTexture t);

// One configuration's speed workload: the driver after reset, its largest texture (at most
// 1024x1024, noise; a block format: random blocks of every mode, tests/common/stimulus.h) loaded through the backdoor and configured
// (trilinear, repeat; cached: the default caches where they fit, 16 B/clock), and 65536 random
// trilinear requests (u, v uniform in [-2, 2), lambda uniform over the levels).
struct RtlWorkload {
  std::unique_ptr<tex::rtl::Driver> unit;
  std::vector<tex::Request> requests;
};
RtlWorkload make_rtl_workload(const tex::rtl::RtlConfig& config, RtlTexture texture = RtlTexture::Rgba8);

// Registers one benchmark per configuration: "rtl_sampling/<configuration>". Each streams random
// trilinear requests through rtl::Driver with ideal timing after a backdoor load: the sampling
// phase alone, in samples/s and clocks/s (equal within 0.01% on chip; a cached configuration
// waits for its memory model, default timing, so there clocks/s is the simulator's speed).
std::vector<std::string> register_rtl_benchmarks(double min_time);

}  // namespace bench

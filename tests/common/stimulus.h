// The random stimulus every suite that drives a unit draws from (the RTL lockstep suites, the AXI
// top, the SystemC engines, the 4-state X-propagation vectors): requests, samplers, textures and
// stall profiles. Model types only (library texunit_stimulus, links texmodel alone), so that the
// suites differ in what they drive, never in what they ask.
#pragma once
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/timing.h"

namespace tex::stimulus {

// ---------------------------------------------------------------- requests
// A coordinate (Q8.24) for a side of `size` texels (any size) of a chain of last_level + 1
// levels: far outside [0, 1) ([-100, 100)), near a texel edge or centre of some level (a few raw
// units off, some periods away), in [0, 1), any 32-bit value, or an edge case (0, +-1, 1 - 2^-24,
// 1, 1 + 2^-24, -1, +-1/2, INT32_MIN, INT32_MAX).
int32_t random_coordinate(std::mt19937_64& rng, int size, int last_level);
// A lambda or bias (Q8.8): from -2 to past the last level, on level boundaries and the nearest-level
// rounding points (+-1/256), in [-1, 1], any 16-bit value, the format's two ends.
int32_t random_lod(std::mt19937_64& rng, int last_level);
// A coordinate of an unnormalized sampler, Q16.16 texels, for a side of n texels: near a texel
// edge or centre within 3 texels of the side (a few raw units off), anywhere in [-2n, 3n), any
// 32-bit value, or an edge case (0, n, beyond 2n, +-2^14 texels: past the RTL's clamp).
int32_t texel_coordinate(std::mt19937_64& rng, int n);

// One request for a texture of `size`: random_coordinate, random_lod, a quarter with the
// request's own bias (GLSL texture(s, uv, bias)); a quarter carry derivatives instead
// (random_footprint: lambda from the LOD unit). Tag 0, texture 0, sampler 0.
Request random_request(std::mt19937_64& rng, Extent size);
// n of them, tagged 0..n-1.
std::vector<Request> random_requests(std::mt19937_64& rng, Extent size, size_t n);
// Requests spread over a descriptor table's textures (their level-0 sizes) and `samplers`
// samplers: mostly a new texture and sampler per request, runs of one now and then; each a
// random_request for its texture's size.
std::vector<Request> random_requests(std::mt19937_64& rng, const std::vector<Extent>& textures, size_t samplers,
                                     size_t n);
// Requests of an unnormalized sampler: random_requests with u, v texel_coordinate()s.
std::vector<Request> random_texel_requests(std::mt19937_64& rng, Extent size, size_t n);
// A request with derivatives whose footprint takes `probes` probes (1..16) under a cap of 16, its
// major axis along u (axis 0), v (1), near the diagonal (2) or in any direction (3), from
// magnification to past the last level; 1 in 16 has raw 32-bit derivatives (the format's
// saturating ends).
Request random_footprint(std::mt19937_64& rng, Extent size, int probes, int axis);
// A texel fetch (Op::Fetch) of a texture of `size`: a level from -1 to 2 past the last (a few far
// out: 15, 16, -32768, 32767), (i, j) within 2 texels of that level's sides, on its edges, or any
// 32-bit value or the unit's largest side's edge (+-2^13). Tag 0, texture 0, sampler 0.
Request random_fetch(std::mt19937_64& rng, Extent size);
// A gather (Op::Gather) of a random component at random_coordinate()s of a texture of `size`.
Request random_gather(std::mt19937_64& rng, Extent size);
// One in `one_in` of the requests made a random_fetch or a random_gather (half each) of the texture
// it names (its tag, texture and sampler kept).
template <class SizeOf>
void fetches_and_gathers_among(std::mt19937_64& rng, std::vector<Request>& requests, int one_in, SizeOf size_of_texture) {
  for (Request& r : requests)
    if (rng() % uint64_t(one_in) == 0) {
      Request f = rng() % 2 ? random_fetch(rng, size_of_texture(r.texture)) : random_gather(rng, size_of_texture(r.texture));
      f.tag = r.tag;
      f.texture = r.texture;
      f.sampler = r.sampler;
      r = f;
    }
}

// An array's layer coordinate (Q16.16) for `layers` layers: on a tie between two layers (exactly,
// or a raw unit off), on a layer, anywhere from -2 to layers + 2, far outside (+-2^15), or any
// 32-bit value.
int32_t random_layer(std::mt19937_64& rng, int layers);
// A texel fetch's integer layer: -2 .. layers + 1, now and then far outside (+-2^31 - 1, 256).
int32_t random_fetch_layer(std::mt19937_64& rng, int layers);
// Gives every request the layer of its texture's array (layers_of_texture(texture) layers):
// random_fetch_layer for a fetch, else random_layer.
template <class LayersOf>
void layers_among(std::mt19937_64& rng, std::vector<Request>& requests, LayersOf layers_of_texture) {
  for (Request& r : requests) {
    const int n = layers_of_texture(r.texture);
    r.layer = r.op == Op::Fetch ? random_fetch_layer(rng, n) : random_layer(rng, n);
  }
}

// ---------------------------------------------------------------- samplers
// The six filters (texel filter x mip mode).
std::vector<Filter> all_filters();
// One of the five address modes.
Wrap random_wrap(std::mt19937_64& rng);
// One of the border colours (Vulkan's six or a random custom one).
void randomize_border(std::mt19937_64& rng, SamplerConfig& c);
// A third of the time, a magnification filter apart from the minification filter's texel filter.
void randomize_mag_filter(std::mt19937_64& rng, SamplerConfig& c);
// Random bias (half of the cases 0) and clamps (half of the cases the full range).
void randomize_lod_controls(std::mt19937_64& rng, SamplerConfig& c);
// A min or max reduction in a quarter of the cases (each half of them), else the weighted average.
void randomize_reduction(std::mt19937_64& rng, SamplerConfig& c);
// Anisotropic filter: cap 16 half of the time, else 1..16; probe counts rounded to powers of two
// in a quarter of the cases.
void randomize_aniso(std::mt19937_64& rng, SamplerConfig& c);
// Makes a sampler unnormalized the way Vulkan allows: its wrap modes clamp (clamp to edge or to
// border, drawn again if not), one texel filter, no anisotropy, the base level only (mipmap mode
// none, or its mode with max LOD clamped to <= 0).
void make_unnormalized(std::mt19937_64& rng, SamplerConfig& c);
// Everything at random: a filter (half the default trilinear, a third anisotropic), both address
// modes, the border colour, the magnification filter, the LOD controls, the reduction, the compare
// operator; unnormalized in 1 of `unnormalized_one_in` (0: never).
SamplerConfig random_sampler(std::mt19937_64& rng, int unnormalized_one_in = 0);

// Gives the requests of the table's unnormalized samplers texel coordinates of their texture.
template <class SizeOf>
void texel_coordinates_where_unnormalized(std::mt19937_64& rng, std::vector<Request>& requests,
                                          const SamplerTable& samplers, SizeOf size_of_texture) {
  for (Request& r : requests)
    if (samplers[r.sampler].unnormalized) {
      const Extent e = size_of_texture(r.texture);
      r.u = texel_coordinate(rng, e.w);
      r.v = texel_coordinate(rng, e.h);
    }
}

// A depth compare's reference (Q8.24): in [-1/8, 9/8), at 0 or 1 give or take a few raw units, or
// any 32-bit value.
int32_t random_reference(std::mt19937_64& rng);
// One in `one_in` of the sample requests made depth compares (random_reference) where their sampler
// takes one (SamplerConfig::compare_problem) and compares(texture) says the texture does (not an
// sRGB or EAC texture: Pyramid::depth_problem).
template <class Compares>
void compares_among(std::mt19937_64& rng, std::vector<Request>& requests, int one_in, const SamplerTable& samplers,
                    Compares compares) {
  for (Request& r : requests)
    if (r.op == Op::Sample && rng() % uint64_t(one_in) == 0 && samplers[r.sampler].compare_problem().empty() &&
        compares(r.texture)) {
      r.op = Op::Compare;
      r.ref = random_reference(rng);
    }
}

// ---------------------------------------------------------------- cube maps
// A direction (Q8.24) onto face `face` (0..5: +X .. -Z) at its (s, t) in [0, 1], of any length: the
// face table inverted (sc = 2s - 1, tc = 2t - 1, |rc| = 1), scaled by 2^-6 .. 2^6.
std::array<int32_t, 3> cube_direction(std::mt19937_64& rng, int face, double s, double t);
// A lookup of a cube map (or cube array of `layers` layers, 6 a cube) of n x n faces and levels
// 0..last_level, keeping r's texture, sampler and tag: a direction onto every face, half of them
// within a texel of an edge and a quarter of those at a corner (the skirt's neighbours and its
// average of three); a lod, or (a third) isotropic derivatives of the direction; one in 8 a gather
// of a random component, one in 8 a texel fetch of a face (i, j, face + 6 c, level; now and then
// outside). A compare stays one (a new direction, its reference kept). The cube of an array:
// random_layer's cases over the cubes.
Request cube_request(std::mt19937_64& rng, const Request& r, int n, int last_level, int layers);

// ---------------------------------------------------------------- textures
// Texels of `cw`-bit channels: noise, near-black and near-white extremes, or a few values (style
// 0, 1, 2; -1: one of them at random).
Image random_image(int w, int h, int cw, uint64_t seed, int style = 0);
// An exact-mode pyramid of random_image noise, 8-bit channels.
Pyramid random_pyramid(Extent size, uint64_t seed);
// `layers` of them (an array texture), each of its own noise.
std::vector<Pyramid> random_layers(Extent size, int layers, uint64_t seed);
// Pointers to each, for BoundTexture and Sampler.
std::vector<const Pyramid*> pointers_to(const std::vector<Pyramid>& layers);
// Random blocks of a block format (sides >= 1), every level: each BC7 block in a random one of its
// 8 modes and 1 in 16 in the reserved mode (decoded to 0); ETC2 colour blocks in each mode in turn
// (set_etc2_mode); EAC blocks of random_eac_block; ASTC blocks of random_astc_block.
Pyramid random_block_texture(TexelFormat format, Extent size, uint64_t seed);
// Sets an ETC2 colour block (8 bytes, random bits otherwise) to `mode` (model/etc2.h Etc2Mode:
// individual, differential, T, H, planar; the last three are differential blocks whose red, green
// or blue sum leaves 0..31). RGB8A1 (`punch_through`) has no individual mode: its bit 33 (opaque)
// is left as it is. `tie`: an H block's two colours made equal (the order bit's tie).
void set_etc2_mode(std::mt19937_64& rng, uint8_t* colour_block, int mode, bool punch_through, bool tie = false);
// A random ASTC block (16 bytes) for a footprint fw x fh: 1 in 16 a void-extent block (a quarter of
// those with an HDR flag, a reserved bit cleared or an empty extent: the error colour), 1 in 16
// random bits (mostly illegal), the others random bits redrawn until they make a legal block (every
// block mode, partition count, endpoint mode and range the footprint allows, in proportion to
// their encodings).
void random_astc_block(std::mt19937_64& rng, int fw, int fh, uint8_t* block);
// A random EAC block (8 bytes: EAC R11, each half of RG11, ETC2 RGBA8's alpha): random bits, with
// 1 in 8 of multiplier 0 (the modifier alone) and 1 in 4 of a base at an edge, 0, 127, 128 (signed:
// -128, read as -127) or 255, where values clamp.
void random_eac_block(std::mt19937_64& rng, uint8_t* block);

// ---------------------------------------------------------------- stall profiles
// One of: ideal, light, heavy (about 30% of clocks without a gap), long stalls (hundreds of
// clocks); its name in `name`.
Stimulus random_stalls(std::mt19937_64& rng, std::string& name);

}  // namespace tex::stimulus

#include "stimulus.h"

#include <cmath>

#include <algorithm>

#include "model/astc.h"
#include "model/block_formats.h"

namespace tex::stimulus {

int32_t random_coordinate(std::mt19937_64& rng, int size, int last_level) {
  const int kind = int(rng() % 100);
  const int64_t one = int64_t(1) << kCoordFracBits;
  if (kind < 35) {  // far outside [0, 1): [-100, 100)
    return int32_t(int64_t(rng() % uint64_t(200 * one)) - 100 * one);
  }
  if (kind < 65) {  // near a texel edge or centre of some level, a few raw units off
    const int k = int(rng() % uint64_t(last_level + 1));
    const int64_t n = std::max(size >> k, 1);
    const int64_t j = int64_t(rng() % uint64_t(n + 5)) - 2 + (rng() % 4 == 0 ? n * (int64_t(rng() % 7) - 3) : 0);
    const int64_t texel = one / n;  // (exact for a power of two)
    int64_t u = j * texel + ((rng() & 1) ? texel / 2 : 0);
    const int64_t jitter = int64_t(rng() % 257) - 128;
    u += (rng() % 3 == 0) ? 0 : jitter;
    return int32_t(std::clamp<int64_t>(u, INT32_MIN, INT32_MAX));
  }
  if (kind < 85) return int32_t(int64_t(rng() % uint64_t(one)));  // [0, 1)
  if (kind < 95) return int32_t(uint32_t(rng()));                  // any 32-bit value
  static const int32_t edges[] = {0, 1, -1, int32_t(one - 1), int32_t(one), int32_t(one + 1), int32_t(-one),
                                  INT32_MIN, INT32_MAX, int32_t(one / 2), int32_t(-one / 2)};
  return edges[rng() % (sizeof edges / sizeof edges[0])];
}

int32_t random_lod(std::mt19937_64& rng, int last_level) {
  const int kind = int(rng() % 100);
  const int top = (last_level + 2) * 256;
  if (kind < 50) return int32_t(int64_t(rng() % uint64_t(top + 512)) - 512);  // [-2, last + 2)
  if (kind < 75) {  // on a level boundary, or the nearest-level rounding point, +-1/256
    const int k = int(rng() % uint64_t(last_level + 3)) - 1;
    const int offsets[] = {-1, 0, 1, 127, 128, 129};
    return k * 256 + offsets[rng() % 6];
  }
  if (kind < 90) return int32_t(int64_t(rng() % 513) - 256);  // [-1, 1]
  if (kind < 97) return int32_t(int16_t(uint16_t(rng())));      // any 16-bit value
  return rng() % 2 ? kLodMin : kLodMax;                         // the format's ends
}

int32_t texel_coordinate(std::mt19937_64& rng, int n) {
  const int kind = int(rng() % 100);
  const int64_t one = int64_t(1) << kTexelCoordFracBits;
  if (kind < 50) {
    int64_t u = (int64_t(rng() % uint64_t(n + 6)) - 3) * one + ((rng() & 1) ? one / 2 : 0);
    if (rng() % 3) u += int64_t(rng() % 257) - 128;
    return int32_t(u);
  }
  if (kind < 80) return int32_t(int64_t(rng() % uint64_t(5 * n * one)) - 2 * n * one);
  if (kind < 92) return int32_t(uint32_t(rng()));
  const int64_t edges[] = {0, 1, -1, n * one, n * one - 1, 2 * n * one + 1, -2 * n * one - 1,
                           int64_t(1) << 30, -(int64_t(1) << 30), INT32_MIN, INT32_MAX};
  return int32_t(edges[rng() % (sizeof edges / sizeof edges[0])]);
}

Request random_request(std::mt19937_64& rng, Extent size) {
  const int last = level_count(size) - 1;
  Request r;
  if (rng() % 4 == 0) r = random_footprint(rng, size, int(rng() % 16) + 1, int(rng() % 4));
  r.u = random_coordinate(rng, size.w, last);
  r.v = random_coordinate(rng, size.h, last);
  r.lod = random_lod(rng, last);
  if (rng() % 4 == 0) r.bias = random_lod(rng, last);
  return r;
}

std::vector<Request> random_requests(std::mt19937_64& rng, Extent size, size_t n) {
  std::vector<Request> r(n);
  for (size_t i = 0; i < n; ++i) {
    r[i] = random_request(rng, size);
    r[i].tag = uint32_t(i);
  }
  return r;
}

std::vector<Request> random_requests(std::mt19937_64& rng, const std::vector<Extent>& textures, size_t samplers,
                                     size_t n) {
  std::vector<Request> out(n);
  uint8_t tex = 0, smp = 0;
  for (size_t i = 0; i < n; ++i) {
    if (rng() % 4 != 0) tex = uint8_t(rng() % textures.size());  // mostly a new texture, runs now and then
    if (rng() % 4 != 0) smp = uint8_t(rng() % samplers);      // and a new sampler
    out[i] = random_request(rng, textures[tex]);
    out[i].texture = tex;
    out[i].sampler = smp;
    out[i].tag = uint32_t(i);
  }
  return out;
}

std::vector<Request> random_texel_requests(std::mt19937_64& rng, Extent size, size_t n) {
  std::vector<Request> r = random_requests(rng, size, n);
  for (Request& q : r) {
    q.u = texel_coordinate(rng, size.w);
    q.v = texel_coordinate(rng, size.h);
  }
  return r;
}

Request random_fetch(std::mt19937_64& rng, Extent size) {
  const int last = level_count(size) - 1;
  static const int32_t far_levels[] = {15, 16, -32768, 32767};
  const int32_t level = rng() % 16 == 0 ? far_levels[rng() % 4] : int32_t(rng() % uint64_t(last + 4)) - 1;
  const Extent e = level_extent(size, std::clamp(level, 0, last));
  auto index = [&](int n) {
    const uint64_t k = rng() % 16;
    if (k == 0) return int32_t(uint32_t(rng()));
    if (k == 1) return int32_t(rng() % 2 ? 8192 : -8192) + int32_t(rng() % 3) - 1;  // the largest side's edges
    if (k < 4) return rng() % 2 ? int32_t(n) - 1 + int32_t(rng() % 3) : -1 + int32_t(rng() % 2);  // on an edge
    return int32_t(rng() % uint64_t(n + 4)) - 2;
  };
  const int32_t i = index(e.w), j = index(e.h);  // (in this order: one rng stream on every compiler)
  return fetch_request(i, j, level);
}

Request random_gather(std::mt19937_64& rng, Extent size) {
  const int last = level_count(size) - 1;
  const int32_t u = random_coordinate(rng, size.w, last), v = random_coordinate(rng, size.h, last);
  return gather_request(u, v, int(rng() % 4));
}

int32_t random_layer(std::mt19937_64& rng, int layers) {
  constexpr int32_t kOne = 1 << kTexelCoordFracBits;
  const int32_t l = int32_t(rng() % uint64_t(layers + 4)) - 2;  // -2 .. layers + 1
  switch (rng() % 6) {
    case 0: return l * kOne + kOne / 2;                               // a tie: to the even layer
    case 1: return l * kOne + kOne / 2 + int32_t(rng() % 3) - 1;      // a raw unit off a tie
    case 2: return l * kOne;                                          // on a layer
    case 3: return int32_t(rng() % uint64_t((layers + 4) * kOne)) - 2 * kOne;
    case 4: return rng() % 2 ? INT32_MIN + int32_t(rng() % 4) : INT32_MAX - int32_t(rng() % 4);
    default: return int32_t(uint32_t(rng()));
  }
}

int32_t random_fetch_layer(std::mt19937_64& rng, int layers) {
  if (rng() % 16 == 0) {
    constexpr int32_t far[] = {INT32_MIN, INT32_MAX, 256, 255, -256};
    return far[rng() % 5];
  }
  return int32_t(rng() % uint64_t(layers + 4)) - 2;
}

Request random_footprint(std::mt19937_64& rng, Extent size, int probes, int axis) {
  Request r;
  r.has_derivatives = true;
  if (rng() % 16 == 0) {
    r.deriv = {int32_t(uint32_t(rng())), int32_t(uint32_t(rng())), int32_t(uint32_t(rng())), int32_t(uint32_t(rng()))};
    return r;
  }
  // Lengths in level-0 texels: the major one from 1/8 texel to 4x the texture, the minor one so
  // that major / minor lies in (probes - 1, probes] (1: equal lengths).
  std::uniform_real_distribution<double> unit(0, 1);
  const double major = std::exp2(-3 + unit(rng) * (level_count(size) + 4));
  const double ratio = probes == 1 ? 1.0 : probes - 0.9 * unit(rng);
  const double minor = major / ratio;
  const double a = axis == 0   ? 0.0
                   : axis == 1 ? M_PI / 2
                   : axis == 2 ? M_PI / 4 + (unit(rng) - 0.5) * 0.5
                               : unit(rng) * 2 * M_PI;
  const double flip = rng() % 2 ? M_PI : 0.0;
  const double ax = a + flip, ay = a + M_PI / 2;  // the minor axis is perpendicular
  const double w = size.w, h = size.h;
  auto q = [](double x) { return int32_t(std::clamp(std::lround(x * 16777216.0), -2147483647L, 2147483647L)); };
  const bool x_major = rng() % 2;  // which screen axis is the long one
  const double lx = x_major ? major : minor, ly = x_major ? minor : major;
  const double thx = x_major ? ax : ay, thy = x_major ? ay : ax;
  r.deriv = {q(lx * std::cos(thx) / w), q(lx * std::sin(thx) / h), q(ly * std::cos(thy) / w), q(ly * std::sin(thy) / h)};
  return r;
}

std::vector<Filter> all_filters() {
  std::vector<Filter> f;
  for (TexelFilter t : {TexelFilter::Nearest, TexelFilter::Linear})
    for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) f.push_back({t, m});
  return f;
}

Wrap random_wrap(std::mt19937_64& rng) { return Wrap(rng() % kWrapModes); }

void randomize_border(std::mt19937_64& rng, SamplerConfig& c) {
  c.border = BorderColor(rng() % kBorderColors);
  for (uint16_t& v : c.border_custom) v = uint16_t(rng());
}

void randomize_mag_filter(std::mt19937_64& rng, SamplerConfig& c) {
  if (rng() % 3 == 0) c.filter.mag = TexelFilter(1 - int(c.filter.texel));  // a third: apart
}

void randomize_lod_controls(std::mt19937_64& rng, SamplerConfig& c) {
  c.lod_bias = (rng() % 2) ? 0 : int32_t(int64_t(rng() % 1537) - 768);  // [-3, 3] levels
  if (rng() % 2) {
    c.min_lod = kLodMin;
    c.max_lod = kLodMax;
  } else {
    c.min_lod = int32_t(int64_t(rng() % 1537) - 512);  // [-2, 4]
    c.max_lod = c.min_lod + int32_t(rng() % 2049);     // up to 8 levels above
  }
}

void randomize_reduction(std::mt19937_64& rng, SamplerConfig& c) {
  const uint64_t k = rng() % 8;
  c.reduction = k == 0 ? Reduction::Min : k == 1 ? Reduction::Max : Reduction::WeightedAverage;
}

void randomize_aniso(std::mt19937_64& rng, SamplerConfig& c) {
  c.filter = {TexelFilter::Linear, MipMode::Linear, true};
  c.max_aniso = rng() % 2 ? kMaxAniso : int(rng() % kMaxAniso) + 1;
  c.aniso_pow2 = rng() % 4 == 0;
}

void make_unnormalized(std::mt19937_64& rng, SamplerConfig& c) {
  c.unnormalized = true;
  for (Wrap* w : {&c.wrap_u, &c.wrap_v})
    if (*w != Wrap::Clamp && *w != Wrap::Border) *w = rng() % 2 ? Wrap::Clamp : Wrap::Border;
  c.filter.anisotropic = false;
  c.filter.mag = c.filter.texel;
  if (c.filter.mip != MipMode::None && rng() % 2) c.filter.mip = MipMode::None;
  if (c.filter.mip != MipMode::None) {  // Vulkan's form: mipmaps clamped to level 0
    c.max_lod = std::min(c.max_lod, rng() % 2 ? 0 : -int32_t(rng() % 512));
    c.min_lod = std::min(c.min_lod, c.max_lod);
  }
}

SamplerConfig random_sampler(std::mt19937_64& rng, int unnormalized_one_in) {
  SamplerConfig s;
  const std::vector<Filter> filters = all_filters();
  s.filter = rng() % 2 ? Filter{} : filters[rng() % filters.size()];
  if (rng() % 3 == 0) randomize_aniso(rng, s);
  randomize_mag_filter(rng, s);
  s.wrap_u = random_wrap(rng);
  s.wrap_v = random_wrap(rng);
  randomize_border(rng, s);
  randomize_lod_controls(rng, s);
  randomize_reduction(rng, s);
  if (unnormalized_one_in > 0 && rng() % uint64_t(unnormalized_one_in) == 0) make_unnormalized(rng, s);
  s.compare_op = CompareOp(rng() % kCompareOps);
  return s;
}

int32_t random_reference(std::mt19937_64& rng) {
  constexpr int32_t kOne = 1 << kCoordFracBits;
  switch (rng() % 5) {
    case 0: return int32_t(rng() % 5) - 2 + (rng() % 2 ? 0 : kOne);        // at 0 or 1, a few units off
    case 1: return int32_t(uint32_t(rng()));                              // any value (clamped)
    default: return int32_t(rng() % uint64_t(kOne + kOne / 4)) - kOne / 8;  // [-1/8, 9/8)
  }
}

std::array<int32_t, 3> cube_direction(std::mt19937_64& rng, int face, double s, double t) {
  const double sc = 2 * s - 1, tc = 2 * t - 1;
  double d[3] = {};
  switch (face) {  // (stage::cube_face's table, inverted)
    case 0: d[0] = 1, d[1] = -tc, d[2] = -sc; break;
    case 1: d[0] = -1, d[1] = -tc, d[2] = sc; break;
    case 2: d[0] = sc, d[1] = 1, d[2] = tc; break;
    case 3: d[0] = sc, d[1] = -1, d[2] = -tc; break;
    case 4: d[0] = sc, d[1] = -tc, d[2] = 1; break;
    default: d[0] = -sc, d[1] = -tc, d[2] = -1; break;
  }
  const double scale = std::ldexp(1.0 + double(rng() % 1000) / 1000, int(rng() % 13) - 6);
  std::array<int32_t, 3> out{};
  for (int c = 0; c < 3; ++c) out[size_t(c)] = int32_t(std::lround(d[c] * scale * (1 << kCoordFracBits)));
  return out;
}

Request cube_request(std::mt19937_64& rng, const Request& r, int n, int last_level, int layers) {
  auto unit = [&] { return double(rng() % 1000001) / 1e6; };
  Request q;
  q.texture = r.texture;
  q.sampler = r.sampler;
  q.tag = r.tag;
  const int cubes = std::max(1, layers / 6);
  if (rng() % 8 == 0 && r.op != Op::Compare) {  // a texel fetch of a face
    q.op = Op::Fetch;
    q.u = int32_t(rng() % uint64_t(n + 2)) - (rng() % 8 == 0 ? 1 : 0);
    q.v = int32_t(rng() % uint64_t(n + 2)) - (rng() % 8 == 0 ? 1 : 0);
    q.lod = int32_t(rng() % uint64_t(last_level + 2));
    q.layer = int32_t(rng() % uint64_t(layers + 1)) - (rng() % 16 == 0 ? 1 : 0);
    return q;
  }
  const int face = int(rng() % 6);
  double s = unit(), t = unit();
  if (rng() % 2) {  // within a texel of an edge, a quarter of those at a corner
    const double e = unit() / n;
    (rng() % 2 ? s : t) = rng() % 2 ? e : 1 - e;
    if (rng() % 4 == 0) (s < 1.0 / n || s > 1 - 1.0 / n ? t : s) = rng() % 2 ? unit() / n : 1 - unit() / n;
  }
  const std::array<int32_t, 3> d = cube_direction(rng, face, s, t);
  q.u = d[0];
  q.v = d[1];
  q.w = d[2];
  q.layer = cubes > 1 ? random_layer(rng, cubes) : 0;
  q.op = r.op == Op::Compare ? Op::Compare : rng() % 8 == 0 ? Op::Gather : Op::Sample;
  q.ref = r.ref;
  q.component = uint8_t(rng() % 4);
  if (q.op != Op::Gather && rng() % 3 == 0) {  // derivatives along the face, of a footprint of 1/4 to 4 texels at a level
    q.has_derivatives = true;
    const double len = std::ldexp(1.0, int(rng() % uint64_t(last_level + 4)) - 2) / n;
    const double scale = std::hypot(std::hypot(double(d[0]), double(d[1])), double(d[2]));
    auto deriv = [&] { return int32_t(std::lround((unit() * 2 - 1) * len * scale)); };
    q.deriv = {deriv(), deriv(), deriv(), deriv()};
    q.dwdx = deriv();
    q.dwdy = deriv();
  } else {
    q.lod = random_lod(rng, last_level);
  }
  return q;
}

Image random_image(int w, int h, int cw, uint64_t seed, int style) {
  Image img(w, h, cw);
  std::mt19937_64 rng(seed);
  const uint64_t mask = (uint64_t(1) << cw) - 1;
  if (style < 0) style = int(rng() % 3);
  for (Texel& t : img.texels)
    for (uint16_t& c : t) {
      const uint64_t r = rng();
      c = uint16_t(style == 0   ? r & mask
                   : style == 1 ? ((r & 1) ? mask - (r >> 1 & 1) : (r >> 1 & 1))
                                : (r % 3) * mask / 2);
    }
  return img;
}

Pyramid random_pyramid(Extent size, uint64_t seed) {
  return build_pyramid(random_image(size.w, size.h, 8, seed), PyramidMode::Exact);
}

std::vector<Pyramid> random_layers(Extent size, int layers, uint64_t seed) {
  std::vector<Pyramid> out;
  for (int l = 0; l < layers; ++l) out.push_back(random_pyramid(size, seed * 1000003 + uint64_t(l)));
  return out;
}

std::vector<const Pyramid*> pointers_to(const std::vector<Pyramid>& layers) {
  std::vector<const Pyramid*> out;
  for (const Pyramid& p : layers) out.push_back(&p);
  return out;
}

Pyramid random_block_texture(TexelFormat format, Extent size, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<uint8_t>> blocks;
  const int bytes = format_info(format).block_bytes;
  for (int k = 0; k < level_count(size); ++k) {
    const Extent s = level_extent(size, k);
    std::vector<uint8_t>& level = blocks.emplace_back(level_bytes(format, s.width(), s.height()));
    for (uint8_t& b : level) b = uint8_t(rng());
    if (format == TexelFormat::Bc7)
      for (size_t i = 0; i < level.size(); i += size_t(bytes)) {
        const int r = int(rng() % 16), mode = r % 8;  // 15: the reserved mode (byte 0 = 0)
        level[i] = r == 15 ? 0 : uint8_t((level[i] << (mode + 1)) | (1 << mode));
      }
    if (is_etc2(format))
      for (size_t i = 0; i < level.size(); i += size_t(bytes)) {
        const size_t block = i / size_t(bytes);
        const bool punch_through = format == TexelFormat::Etc2RgbA1;
        set_etc2_mode(rng, &level[i + (format == TexelFormat::Etc2Rgba ? 8 : 0)],
                      int(block % (punch_through ? 4 : 5)) + (punch_through ? 1 : 0), punch_through, block % 20 == 3);
      }
    if (is_astc(format))
      for (size_t i = 0; i < level.size(); i += size_t(bytes))
        random_astc_block(rng, format_info(format).block_w, format_info(format).block_h, &level[i]);
    if (is_eac(format))
      for (size_t i = 0; i < level.size(); i += 8) random_eac_block(rng, &level[i]);
  }
  return pyramid_of_blocks(format, size, std::move(blocks));
}

void random_eac_block(std::mt19937_64& rng, uint8_t* block) {
  for (int i = 0; i < 8; ++i) block[i] = uint8_t(rng());
  if (rng() % 8 == 0) block[1] &= 0x0F;  // multiplier 0
  if (rng() % 4 == 0) block[0] = std::array<uint8_t, 4>{0, 127, 128, 255}[rng() % 4];
}

void random_astc_block(std::mt19937_64& rng, int fw, int fh, uint8_t* block) {
  auto fill = [&]() {
    for (int i = 0; i < 16; ++i) block[i] = uint8_t(rng());
  };
  fill();
  const int kind = int(rng() % 16);
  if (kind == 0) {  // void extent: bits 8..0 = 1 1111 1100, bit 9 LDR, bits 10, 11 set
    block[0] = 0xFC;
    block[1] = uint8_t((block[1] & 0xF0) | 0x0D);
    const int variant = int(rng() % 16);
    if (variant < 8) {  // no extent: all coordinates ones
      block[1] |= 0xF0;
      for (int i = 2; i < 8; ++i) block[i] = 0xFF;
    } else if (variant < 12) {  // an extent: s0 < s1, t0 < t1 (13 bits each from bit 12)
      uint64_t w = 0;
      for (int i = 7; i >= 0; --i) w = w << 8 | block[i];
      const uint64_t s0 = rng() % 4096, s1 = s0 + 1 + rng() % (8191 - s0), t0 = rng() % 4096,
                     t1 = t0 + 1 + rng() % (8191 - t0);
      w = (w & 0xFFF) | s0 << 12 | s1 << 25 | t0 << 38 | t1 << 51;
      for (int i = 0; i < 8; ++i, w >>= 8) block[i] = uint8_t(w);
    } else if (variant == 12) {
      block[1] |= 0x02;  // HDR
    } else if (variant == 13) {
      block[1] &= uint8_t(~(4 << int(rng() % 2)));  // a reserved bit cleared
    }  // else: random coordinates, mostly an empty extent
    return;
  }
  if (kind == 1) return;  // random bits
  for (int tries = 0; tries < 256 && astc_mode_of(block, fw, fh).error; ++tries) fill();
}

void set_etc2_mode(std::mt19937_64& rng, uint8_t* c, int mode, bool punch_through, bool tie) {
  auto set = [&](int byte, int base, int delta) { c[byte] = uint8_t(base << 3 | (delta & 7)); };
  if (!punch_through) c[3] = uint8_t((c[3] & ~2) | (mode == 0 ? 0 : 2));  // bit 33: differential
  if (mode == 0) return;
  for (int byte = 0; byte < 3; ++byte) set(byte, 4 + int(rng() % 24), int(rng() % 8) - 4);  // sums in range
  if (mode == 2) set(0, 30 + int(rng() % 2), 3);               // R + dR > 31: T
  if (mode == 3) set(1, int(rng() % 2), -4 + int(rng() % 2));  // G + dG < 0: H
  if (mode == 4) set(2, 31, 1 + int(rng() % 3));               // B + dB > 31: planar
  if (mode == 3 && tie) {
    uint64_t w = 0;
    for (int i = 0; i < 8; ++i) w = w << 8 | c[i];
    const uint64_t r1 = w >> 59 & 15, g1 = (w >> 56 & 7) << 1 | (w >> 52 & 1), b1 = (w >> 51 & 1) << 3 | (w >> 47 & 7);
    w = (w & ~(uint64_t(0xFFF) << 35)) | (r1 << 43 | g1 << 39 | b1 << 35);
    for (int i = 7; i >= 0; --i, w >>= 8) c[i] = uint8_t(w);
  }
}

Stimulus random_stalls(std::mt19937_64& rng, std::string& name) {
  Stimulus t;
  switch (rng() % 4) {
    case 0:
      name = "ideal";
      break;
    case 1:
      name = "light";
      t.gap_prob = 0.1;
      t.max_gap = 3;
      t.stall_prob = 0.1;
      t.max_stall = 3;
      break;
    case 2:  // a gap starts in 60% of the free clocks and lasts 1..6: about 30% zero-delay clocks
      name = "heavy";
      t.gap_prob = 0.6;
      t.max_gap = 6;
      t.stall_prob = 0.6;
      t.max_stall = 6;
      break;
    default:
      name = "long-stalls";
      t.gap_prob = 0.05;
      t.max_gap = 2;
      t.stall_prob = 0.2;
      t.max_stall = 4;
      t.long_stall_prob = 0.003;
      t.long_stall = 100 + int(rng() % 400);
      break;
  }
  return t;
}

}  // namespace tex::stimulus

#include "lockstep.h"

#include <cmath>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "model/error.h"

namespace tex::rtltest {

uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::optional<uint64_t> env_u64(const char* name) {
  const char* s = std::getenv(name);
  if (!s || !*s) return std::nullopt;
  return std::strtoull(s, nullptr, 0);
}

uint64_t seed_base() { return env_u64("TEX_SEED_BASE").value_or(20240601); }
int scale() { return int(std::max<uint64_t>(1, env_u64("TEX_SCALE").value_or(1))); }

std::string describe(const SamplerConfig& c) {
  std::ostringstream o;
  o << filter_name(c.filter) << " wrap " << wrap_name(c.wrap_u) << "/" << wrap_name(c.wrap_v) << " bias "
    << c.lod_bias << " min " << c.min_lod << " max " << c.max_lod << " (Q8.8)";
  if (c.unnormalized) o << " unnormalized (u, v in Q16.16 texels)";
  if (c.uses_border()) {
    const Texel b = c.border_unorm16();
    o << " border " << border_color_name(c.border) << " (" << b[0] << "," << b[1] << "," << b[2] << "," << b[3] << ")";
  }
  return o.str();
}

std::string describe(const Request& r) {
  std::ostringstream o;
  o << "u=" << r.u << " (" << r.u / 16777216.0 << ") v=" << r.v << " (" << r.v / 16777216.0 << ")";
  if (r.has_derivatives)
    o << " dudx=" << r.deriv.dudx << " dvdx=" << r.deriv.dvdx << " dudy=" << r.deriv.dudy << " dvdy=" << r.deriv.dvdy;
  else
    o << " lod=" << r.lod << " (" << r.lod / 256.0 << ")";
  if (r.bias) o << " bias=" << r.bias << " (" << r.bias / 256.0 << ")";
  if (r.texture || r.sampler) o << " texture " << int(r.texture) << " sampler " << int(r.sampler);
  return o.str();
}

std::string describe(const Texel& t) {
  std::ostringstream o;
  o << "(" << t[0] << "," << t[1] << "," << t[2] << "," << t[3] << ")";
  return o.str();
}

std::vector<uint64_t> model_clocks(rtl::Driver& unit, uint32_t fifo_depth, const std::vector<RequestWork>& work,
                                   const rtl::Timing& stim, uint64_t seed) {
  const rtl::MemoryModel* memory = unit.memory();
  TimedStream timed(rtl::unit_shape(unit.config(), fifo_depth), memory ? &memory->channel() : nullptr, stim, seed);
  for (const RequestWork& w : work) timed.push(w);
  std::vector<uint64_t> clocks;
  timed.finish(&clocks);
  return clocks;
}

std::string compare_clocks(const std::vector<uint64_t>& rtl, const std::vector<uint64_t>& model) {
  if (rtl.size() != model.size())
    return "response clocks: " + std::to_string(rtl.size()) + " from the RTL, " + std::to_string(model.size()) +
           " from the timing model";
  size_t first = rtl.size(), differ = 0;
  for (size_t i = 0; i < rtl.size(); ++i)
    if (rtl[i] != model[i] && differ++ == 0) first = i;
  if (!differ) return "";
  return "response " + std::to_string(first) + " at clock " + std::to_string(rtl[first]) + " in the RTL, " +
         std::to_string(model[first]) + " in the timing model (" + std::to_string(differ) + " of " +
         std::to_string(rtl.size()) + " responses differ)";
}

LockstepResult lockstep(rtl::Driver& unit, const Pyramid& pyramid, const SamplerConfig& config,
                        const std::vector<Request>& requests, const rtl::Timing& timing, uint64_t seed) {
  LockstepResult res;
  unit.configure(config, pyramid);
  Sampler model(pyramid, config);
  const int cw = unit.config().cw;
  std::vector<uint64_t> expected(requests.size());
  std::vector<RequestWork> work(requests.size());
  for (size_t i = 0; i < requests.size(); ++i) {
    expected[i] = rtl::pack_rgba(model.sample(requests[i]), cw);
    work[i].probes = uint8_t(tex_probe_count(requests[i], config, pyramid.extent0()));
  }
  const std::vector<uint64_t> want_clocks = model_clocks(unit, 0, work, timing, seed);
  std::vector<uint64_t> clocks(requests.size());
  std::vector<uint8_t> answered(requests.size(), 0);
  std::ostringstream report;
  try {
    res.stats = rtl::stream(unit, requests.data(), requests.size(), timing, seed, [&](size_t i, uint64_t got) {
      ++res.compared;
      clocks[i] = response_clock(unit);
      if (answered[i]++) report << "request #" << i << " answered twice\n";
      if (got != expected[i] && ++res.mismatches <= 5)
        report << "request #" << i << " " << describe(requests[i]) << ": rtl " << describe(rtl::unpack_rgba(got, cw))
               << " model " << describe(rtl::unpack_rgba(expected[i], cw)) << "\n";
    });
    for (size_t i = 0; i < requests.size(); ++i)
      if (!answered[i]) {
        report << "request #" << i << " never answered\n";
        break;
      }
    if (const std::string c = compare_clocks(clocks, want_clocks); !c.empty()) report << c << "\n";
  } catch (const Error& e) {
    report << e.what() << "\n";
  }
  if (res.mismatches > 5) report << "... " << res.mismatches << " mismatches in all\n";
  res.report = report.str();
  return res;
}

std::vector<Filter> all_filters() {
  std::vector<Filter> f;
  for (TexelFilter t : {TexelFilter::Nearest, TexelFilter::Linear})
    for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) f.push_back({t, m});
  return f;
}

namespace {

// A coordinate for a side of `size` texels (any size).
int32_t coordinate(std::mt19937_64& rng, int size, int last_level) {
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

int32_t lod_value(std::mt19937_64& rng, int last_level) {
  const int kind = int(rng() % 100);
  const int top = (last_level + 2) * 256;
  if (kind < 50) return int32_t(int64_t(rng() % uint64_t(top + 512)) - 512);  // [-2, last + 2)
  if (kind < 75) {  // on a level boundary, or the nearest-level rounding point, +-1/256
    const int k = int(rng() % uint64_t(last_level + 3)) - 1;
    const int offsets[] = {-1, 0, 1, 127, 128, 129};
    return k * 256 + offsets[rng() % 6];
  }
  if (kind < 90) return int32_t(int64_t(rng() % 513) - 256);  // [-1, 1]
  return int32_t(int16_t(uint16_t(rng())));                    // any 16-bit value
}

}  // namespace

std::vector<Request> random_requests(std::mt19937_64& rng, Extent size, size_t n) {
  const int last = level_count(size) - 1;
  std::vector<Request> r(n);
  for (size_t i = 0; i < n; ++i) {
    if (rng() % 4 == 0) r[i] = random_footprint(rng, size, int(rng() % 16) + 1, int(rng() % 3));
    r[i].u = coordinate(rng, size.w, last);
    r[i].v = coordinate(rng, size.h, last);
    r[i].lod = lod_value(rng, last);
    if (rng() % 4 == 0) r[i].bias = lod_value(rng, last);  // the request's own bias (GLSL texture(s, uv, bias))
    r[i].tag = uint32_t(i);
  }
  return r;
}

std::vector<Request> random_texel_requests(std::mt19937_64& rng, Extent size, size_t n) {
  std::vector<Request> r = random_requests(rng, size, n);
  for (Request& q : r) {
    q.u = texel_coordinate(rng, size.w);
    q.v = texel_coordinate(rng, size.h);
  }
  return r;
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
  }
  return pyramid_of_blocks(format, size, std::move(blocks));
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
  const double a = axis == 0 ? 0.0 : axis == 1 ? M_PI / 2 : M_PI / 4 + (unit(rng) - 0.5) * 0.5;
  const double flip = rng() % 2 ? M_PI : 0.0;
  const double ax = a + flip, ay = a + M_PI / 2;  // the minor axis is perpendicular
  const double w = size.w, h = size.h;
  auto q = [](double x) { return int32_t(std::clamp(std::lround(x * 16777216.0), -2147483647L, 2147483647L)); };
  Request f;
  f.has_derivatives = true;
  const bool x_major = rng() % 2;  // which screen axis is the long one
  const double lx = x_major ? major : minor, ly = x_major ? minor : major;
  const double thx = x_major ? ax : ay, thy = x_major ? ay : ax;
  f.deriv = {q(lx * std::cos(thx) / w), q(lx * std::sin(thx) / h), q(ly * std::cos(thy) / w), q(ly * std::sin(thy) / h)};
  return f;
}

void randomize_aniso(std::mt19937_64& rng, SamplerConfig& c) {
  c.filter = {TexelFilter::Linear, MipMode::Linear, true};
  c.max_aniso = rng() % 2 ? kMaxAniso : int(rng() % kMaxAniso) + 1;
  c.aniso_pow2 = rng() % 4 == 0;
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

rtl::Timing random_timing(std::mt19937_64& rng, std::string& name) {
  rtl::Timing t;
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

std::unique_ptr<rtl::Driver> make_unit(int max_log2_w, int max_log2_h, uint64_t seed, const std::string& trace,
                                        int cw) {
  for (const rtl::RtlConfig& s : rtl::compiled_configs())
    if (s.max_log2_w == max_log2_w && s.max_log2_h == max_log2_h && s.cw == cw) {
      rtl::DriverOptions o;
      o.seed = seed;
      o.trace_path = trace;
      auto unit = rtl::Driver::create(s, o);
      unit->reset();
      return unit;
    }
  throw Error("no compiled configuration " + std::to_string(max_log2_w) + "x" + std::to_string(max_log2_h) +
              " with " + std::to_string(cw) + "-bit channels");
}

}  // namespace tex::rtltest

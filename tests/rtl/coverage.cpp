#include "coverage.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "lockstep.h"
#include "model/stages.h"

namespace tex::rtltest {

size_t CoverGroup::add(const std::string& bin, const std::string& why_unreachable) {
  bins.push_back(bin);
  unreachable.push_back(why_unreachable);
  hits.push_back(0);
  return bins.size() - 1;
}

size_t CoverGroup::reachable() const {
  return size_t(std::count(unreachable.begin(), unreachable.end(), std::string()));
}

size_t CoverGroup::reachable_hit() const {
  size_t n = 0;
  for (size_t i = 0; i < bins.size(); ++i) n += unreachable[i].empty() && hits[i] > 0;
  return n;
}

namespace {

const Wrap kWraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};
constexpr size_t kNumWraps = std::size(kWraps);
const TexelFilter kTexelFilters[] = {TexelFilter::Nearest, TexelFilter::Linear};

// Level-select cases, per mip mode (exclusive: every request is in exactly one).
enum LevelCase { kMagnify, kMinifyLevel0, kRoundDown, kRoundUp, kOnLevel, kBetweenLevels, kLastLevel, kLevelCases };
static_assert(kLevelCases == 7, "level_case_bin_ in coverage.h");
const char* const kLevelCaseNames[] = {
    "magnify (lambda' <= 0)", "minify, no mipmaps (level 0)", "nearest level, rounds down",
    "nearest level, rounds up", "two levels, f == 0", "two levels, f > 0", "d == last level (clamped)"};
bool level_case_applies(MipMode m, int c) {
  switch (m) {
    case MipMode::None: return c == kMagnify || c == kMinifyLevel0;
    case MipMode::Nearest: return c == kMagnify || c == kRoundDown || c == kRoundUp || c == kLastLevel;
    case MipMode::Linear: return c == kMagnify || c == kOnLevel || c == kBetweenLevels || c == kLastLevel;
  }
  return false;
}

// Tap cases along one axis of one level (exclusive). A period is [k n, (k+1) n) of the unwrapped index.
enum TapCase { kInterior, kEdgePair, kEvenPeriod, kOddPeriod, kOneTexel, kTapCases };
const char* const kTapCaseNames[] = {"interior (period 0)", "pair across a period edge",
                                     "outside, even period", "outside, odd period", "1-texel level"};
const char* const kTapCaseMeaning[kNumWraps][kTapCases] = {
    {"", "seam: taps n-1 and 0", "wrap-around", "wrap-around", ""},                  // repeat
    {"", "edge: one tap clamped", "beyond edge", "beyond edge", ""},                 // clamp
    {"", "boundary: both taps one texel", "repeat", "reflected", ""},                // mirror
    {"", "edge: one tap the border colour", "border colour", "border colour", ""},   // border
    {"", "edge: one tap clamped or folded", "clamped", "folded (period -1) or clamped", ""}};    // mirror-clamp

size_t fi_of(Filter f) { return size_t(f.texel) * 3 + size_t(f.mip); }  // all_filters() order

// The period of the whole (unreduced) coordinate each tap falls in, on a side of n texels.
int tap_case(int32_t coord, int n, TexelFilter filter, bool unnormalized) {
  if (n == 1) return kOneTexel;
  const stage::AxisTaps t = stage::address(stage::scale(coord, n, unnormalized), filter);
  auto period = [&](int32_t i) { return i >= 0 ? i / n : -((-i + n - 1) / n); };
  const int32_t p0 = period(t.i0);
  const int32_t p1 = filter == TexelFilter::Linear ? period(t.i1) : p0;
  if (p0 != p1) return kEdgePair;
  if (p0 == 0) return kInterior;
  return (p0 & 1) ? kOddPeriod : kEvenPeriod;
}

}  // namespace

Coverage::Coverage(int max_log2_w, int max_log2_h) : max_level_(std::max(max_log2_w, max_log2_h)) {
  auto make = [&](const std::string& name) {
    groups_.push_back({name, {}, {}, {}});
    return groups_.size() - 1;
  };
  const std::vector<Filter> filters = all_filters();

  g_filter_wrap_ = make("filter x wrap_u x wrap_v");
  for (const Filter& f : filters)
    for (Wrap wu : kWraps)
      for (Wrap wv : kWraps) group(g_filter_wrap_).add(filter_name(f) + " " + wrap_name(wu) + "/" + wrap_name(wv));

  g_level_case_ = make("level select case x filter");
  for (const Filter& f : filters)
    for (int c = 0; c < kLevelCases; ++c)
      if (level_case_applies(f.mip, c)) level_case_bin_[fi_of(f)][c] = group(g_level_case_).add(filter_name(f) + ": " + kLevelCaseNames[c]);

  g_level_d_ = make("level d read (mipmapped filters)");
  for (int d = 0; d <= max_level_; ++d) group(g_level_d_).add("d = " + std::to_string(d));

  g_taps_ = make("taps: axis x texel filter x wrap x case");
  for (const char* axis : {"u", "v"})
    for (TexelFilter tf : kTexelFilters)
      for (Wrap w : kWraps)
        for (int c = 0; c < kTapCases; ++c) {
          std::string name = std::string(axis) + " " + (tf == TexelFilter::Linear ? "linear" : "nearest") + " " +
                             wrap_name(w) + ": " + kTapCaseNames[c];
          const char* meaning = kTapCaseMeaning[int(w)][c];
          if (*meaning) name += std::string(" (") + meaning + ")";
          group(g_taps_).add(name, tf == TexelFilter::Nearest && c == kEdgePair ? "nearest reads one tap: no pair" : "");
        }

  g_sign_ = make("coordinate sign x wrap");
  for (const char* axis : {"u", "v"})
    for (Wrap w : kWraps)
      for (const char* s : {">= 0", "< 0"}) group(g_sign_).add(std::string(axis) + " " + s + " " + wrap_name(w));

  g_timing_ = make("timing");
  for (const char* b : {"response stalled 0 clocks", "response stalled 1-9 clocks", "response stalled 10-99 clocks",
                        "response stalled >= 100 clocks", "request after an input gap",
                        "clock with a request held by req_ready low"})
    group(g_timing_).add(b);

  g_pyramid_ = make("pyramid mode");
  group(g_pyramid_).add("exact");
  group(g_pyramid_).add("cascade");

  g_deriv_ = make("requests with derivatives x filter");
  for (const Filter& f : filters) group(g_deriv_).add(filter_name(f));
  group(g_deriv_).add("anisotropic");

  g_mag_ = make("magnification filter x minification texel filter, magnified and minified");
  for (const char* mag : {"mag nearest", "mag linear"})
    for (const char* min : {"min nearest", "min linear"})
      for (const char* side : {"magnified", "minified"}) group(g_mag_).add(std::string(mag) + " " + min + " " + side);

  g_aniso_ = make("anisotropic: probes N x major axis");
  for (int n = 1; n <= kMaxAniso; ++n)
    for (const char* axis : {"along u", "along v", "diagonal"}) group(g_aniso_).add("N = " + std::to_string(n) + " " + axis);

  g_unnorm_ = make("unnormalized coordinates: texel filter x wrap_u x wrap_v x inside or beyond level 0");
  for (const char* tf : {"nearest", "linear"})
    for (Wrap wu : {Wrap::Clamp, Wrap::Border})
      for (Wrap wv : {Wrap::Clamp, Wrap::Border})
        for (const char* where : {"inside", "beyond"})
          group(g_unnorm_).add(std::string(tf) + " " + wrap_name(wu) + "/" + wrap_name(wv) + " " + where);

  // The taps a min/max reduction weighs (those of weight > 0) in level d, in one or two levels;
  // and over several probes.
  g_reduce_ = make("min/max reduction: taps weighed in level d x one or two levels; several probes");
  for (Reduction r : {Reduction::Min, Reduction::Max}) {
    for (const char* taps : {"1 tap", "2 taps along u", "2 taps along v", "4 taps"})
      for (const char* levels : {"one level", "two levels"})
        group(g_reduce_).add(reduction_name(r) + " " + taps + " " + levels);
    group(g_reduce_).add(reduction_name(r) + " several probes");
  }

  g_fetch_ = make("texel fetch: where (i, j, level) falls");
  for (const char* where : {"inside level 0", "inside a level above 0", "within 2 texels outside its level",
                            "further outside its level", "level below 0", "level above the last"})
    group(g_fetch_).add(where);

  g_gather_ = make("gather: component x footprint inside level 0 or across its edge");
  for (const char* c : {"R", "G", "B", "A"})
    for (const char* where : {"inside", "across an edge"}) group(g_gather_).add(std::string(c) + " " + where);

  g_compare_ = make("depth compare: operator x reference below 0, in [0, 1], above 1 (clamped)");
  for (int op = 0; op < kCompareOps; ++op)
    for (const char* where : {"below 0", "in [0, 1]", "above 1"})
      group(g_compare_).add(compare_op_name(CompareOp(op)) + " " + where);
}

void Coverage::sample(const Pyramid& pyr, const SamplerConfig& cfg, const Request& q) {
  if (q.op == Op::Fetch) {  // (no filter, no address mode: its own group)
    const int last = pyr.last_level();
    size_t bin = 5;
    if (q.lod < 0) {
      bin = 4;
    } else if (q.lod <= last) {
      const Extent e = level_extent(pyr.extent0(), q.lod);
      const bool near = q.u >= -2 && q.u < e.w + 2 && q.v >= -2 && q.v < e.h + 2;
      bin = stage::fetch_inside(q.u, q.v, q.lod, last, pyr.extent0()) ? (q.lod == 0 ? 0 : 1) : near ? 2 : 3;
    }
    ++group(g_fetch_).hits[bin];
    return;
  }
  if (q.op == Op::Gather) {  // (the linear filter's taps at level 0)
    const Extent e = pyr.extent0();
    const stage::AxisTaps tu = stage::address(
        stage::scale(stage::reduce(q.u, cfg.wrap_u, cfg.unnormalized), e.w, cfg.unnormalized), TexelFilter::Linear);
    const stage::AxisTaps tv = stage::address(
        stage::scale(stage::reduce(q.v, cfg.wrap_v, cfg.unnormalized), e.h, cfg.unnormalized), TexelFilter::Linear);
    const bool across = tu.i0 < 0 || tu.i1 >= e.w || tv.i0 < 0 || tv.i1 >= e.h;
    ++group(g_gather_).hits[size_t(q.component & 3) * 2 + across];
    return;
  }
  if (q.op == Op::Compare)  // (then filtered as a sample: the bins below too)
    ++group(g_compare_).hits[size_t(cfg.compare_op) * 3 + (q.ref < 0 ? 0 : q.ref <= (1 << kCoordFracBits) ? 1 : 2)];
  const size_t fi = fi_of(cfg.filter);
  ++group(g_filter_wrap_).hits[(fi * kNumWraps + size_t(cfg.wrap_u)) * kNumWraps + size_t(cfg.wrap_v)];
  ++group(g_pyramid_).hits[size_t(pyr.mode)];
  const Probes p = tex_probe(q, cfg, pyr.extent0());
  if (q.has_derivatives) {
    ++group(g_deriv_).hits[cfg.filter.anisotropic ? group(g_deriv_).bins.size() - 1 : fi];
    if (cfg.filter.anisotropic) {
      // The major axis in level-0 texels: along u or v when the other component is under 1/4 of it.
      const double w = double(pyr.extent0().w), h = double(pyr.extent0().h);
      const double xu = q.deriv.dudx * w, xv = q.deriv.dvdx * h, yu = q.deriv.dudy * w, yv = q.deriv.dvdy * h;
      const bool x_major = xu * xu + xv * xv >= yu * yu + yv * yv;
      const double mu = std::abs(x_major ? xu : yu), mv = std::abs(x_major ? xv : yv);
      const size_t axis = mv < mu / 4 ? 0 : mu < mv / 4 ? 1 : 2;
      ++group(g_aniso_).hits[size_t(p.n - 1) * 3 + axis];
    }
  }
  if (cfg.unnormalized) {  // (the sampler takes clamping modes only: wrap 1 or 3)
    const Extent e = pyr.extent0();
    const bool inside = q.u >= 0 && q.v >= 0 && (q.u >> kTexelCoordFracBits) < e.w && (q.v >> kTexelCoordFracBits) < e.h;
    ++group(g_unnorm_).hits[((size_t(cfg.filter.texel) * 2 + size_t(cfg.wrap_u == Wrap::Border)) * 2 +
                             size_t(cfg.wrap_v == Wrap::Border)) * 2 + !inside];
  }
  if (cfg.reduction != Reduction::WeightedAverage && p.n > 1) ++group(g_reduce_).hits[(size_t(cfg.reduction) - 1) * 9 + 8];
  for (int i = 0; i < p.n; ++i) sample_probe(pyr, cfg, p.at[size_t(i)]);
}

void Coverage::sample_probe(const Pyramid& pyr, const SamplerConfig& cfg, const Request& q) {
  const size_t fi = fi_of(cfg.filter);

  const int last = pyr.last_level();
  const int32_t lod = stage::lod_clamp(q.lod, cfg.lod_bias, cfg.min_lod, cfg.max_lod);
  const stage::LevelSelect s = stage::lod_select(lod, cfg.filter.mip, last);
  int lc = kMagnify;
  if (lod > 0) {
    switch (cfg.filter.mip) {
      case MipMode::None: lc = kMinifyLevel0; break;
      case MipMode::Nearest: lc = s.d == last ? kLastLevel : s.d > (lod >> kLodFracBits) ? kRoundUp : kRoundDown; break;
      case MipMode::Linear: lc = !s.two_levels ? kLastLevel : s.f == 0 ? kOnLevel : kBetweenLevels; break;
    }
  }
  ++group(g_level_case_).hits[level_case_bin_[fi][lc]];
  ++group(g_mag_).hits[(size_t(cfg.filter.mag) * 2 + size_t(cfg.filter.texel)) * 2 + (lod > 0)];
  const TexelFilter texel_filter = stage::texel_filter(s, cfg.filter);  // the sample's
  if (cfg.filter.mip != MipMode::None) ++group(g_level_d_).hits[size_t(s.d)];

  // Taps of every level read: d, and d1 when two levels are blended.
  const Wrap wraps[2] = {cfg.wrap_u, cfg.wrap_v};
  const int32_t coords[2] = {q.u, q.v};
  for (int k = 0; k < (s.two_levels ? 2 : 1); ++k) {
    const int level = k == 0 ? s.d : s.d1;
    const Extent shape = level_extent(pyr.extent0(), level);
    const int sizes[2] = {shape.w, shape.h};
    for (int axis = 0; axis < 2; ++axis) {
      const int c = tap_case(coords[axis], sizes[axis], texel_filter, cfg.unnormalized);
      const size_t bin =
          ((size_t(axis) * 2 + size_t(texel_filter)) * kNumWraps + size_t(wraps[axis])) * kTapCases + size_t(c);
      ++group(g_taps_).hits[bin];
    }
  }
  if (cfg.reduction != Reduction::WeightedAverage) {
    const Extent shape = level_extent(pyr.extent0(), s.d);
    const bool wx = stage::address(stage::scale(stage::reduce(q.u, cfg.wrap_u, cfg.unnormalized), shape.w, cfg.unnormalized), texel_filter).w > 0;
    const bool wy = stage::address(stage::scale(stage::reduce(q.v, cfg.wrap_v, cfg.unnormalized), shape.h, cfg.unnormalized), texel_filter).w > 0;
    ++group(g_reduce_).hits[(size_t(cfg.reduction) - 1) * 9 + (size_t(wx) + 2 * size_t(wy)) * 2 + (s.two_levels && s.f > 0)];
  }
  for (int axis = 0; axis < 2; ++axis)
    ++group(g_sign_).hits[(size_t(axis) * kNumWraps + size_t(wraps[axis])) * 2 + (coords[axis] < 0)];
}

void Coverage::timing(const rtl::StreamStats& st) {
  CoverGroup& g = group(g_timing_);
  for (size_t i = 0; i < 4; ++i) g.hits[i] += st.protocol.responses_by_stall_run[i];
  g.hits[4] += st.requests_after_gap;
  g.hits[5] += st.protocol.backpressure_cycles;
}

std::string Coverage::table(bool every_bin) const {
  std::ostringstream o;
  size_t all = 0, all_hit = 0, all_unreachable = 0;
  for (const CoverGroup& g : groups_) {
    const size_t unreachable = g.bins.size() - g.reachable();
    o << "  " << g.name << ": " << g.reachable_hit() << " / " << g.reachable() << " hit";
    if (unreachable) o << " (" << unreachable << " unreachable)";
    o << "\n";
    for (size_t i = 0; i < g.bins.size(); ++i)
      if (g.unreachable[i].empty() && g.hits[i] == 0)
        o << "    NEVER HIT: " << g.bins[i] << "\n";
      else if (every_bin)
        o << "    " << g.hits[i] << "  " << g.bins[i]
          << (g.unreachable[i].empty() ? "" : "  [unreachable: " + g.unreachable[i] + "]") << "\n";
    all += g.reachable();
    all_hit += g.reachable_hit();
    all_unreachable += unreachable;
  }
  o << "  total: " << all_hit << " / " << all << " reachable bins hit, " << all_unreachable << " unreachable\n";
  return o.str();
}

std::vector<std::string> Coverage::holes() const {
  std::vector<std::string> h;
  for (const CoverGroup& g : groups_)
    for (size_t i = 0; i < g.bins.size(); ++i) {
      if (g.unreachable[i].empty() && g.hits[i] == 0) h.push_back(g.name + ": never hit: " + g.bins[i]);
      if (!g.unreachable[i].empty() && g.hits[i] > 0)
        h.push_back(g.name + ": hit " + std::to_string(g.hits[i]) + " times but declared unreachable (" +
                    g.unreachable[i] + "): " + g.bins[i]);
    }
  return h;
}

}  // namespace tex::rtltest

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
  if (c.reduction != Reduction::WeightedAverage) o << " reduction " << reduction_name(c.reduction);
  if (c.uses_border()) {
    const Texel b = c.border_unorm16();
    o << " border " << border_color_name(c.border) << " (" << b[0] << "," << b[1] << "," << b[2] << "," << b[3] << ")";
  }
  return o.str();
}

std::string describe(const Request& r) {
  std::ostringstream o;
  if (r.op == Op::Fetch) {
    o << "fetch i=" << r.u << " j=" << r.v << " level=" << r.lod;
    if (r.layer) o << " layer=" << r.layer;
    if (r.texture || r.sampler) o << " texture " << int(r.texture) << " sampler " << int(r.sampler);
    return o.str();
  }
  if (r.op == Op::Gather) o << "gather component " << int(r.component) << " ";
  if (r.op == Op::Compare) o << "compare ref=" << r.ref << " (" << r.ref / 16777216.0 << ") ";
  o << "u=" << r.u << " (" << r.u / 16777216.0 << ") v=" << r.v << " (" << r.v / 16777216.0 << ")";
  if (r.w) o << " w=" << r.w << " (" << r.w / 16777216.0 << ")";  // (a cube's direction)
  if (r.has_derivatives)
    o << " dudx=" << r.deriv.dudx << " dvdx=" << r.deriv.dvdx << " dudy=" << r.deriv.dudy << " dvdy=" << r.deriv.dvdy;
  if (r.has_derivatives && (r.dwdx || r.dwdy)) o << " dwdx=" << r.dwdx << " dwdy=" << r.dwdy;
  else
    o << " lod=" << r.lod << " (" << r.lod / 256.0 << ")";
  if (r.bias) o << " bias=" << r.bias << " (" << r.bias / 256.0 << ")";
  if (r.layer) o << " layer=" << r.layer << " (" << r.layer / 65536.0 << ")";
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

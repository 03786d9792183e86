// `make bench`: samples/s of the golden model (fast path sample_rgba8 and reference path sample),
// of every engine this build has (tex::make_engine), of the Verilated RTL's sampling phase per
// configuration, and of OpenImageIO's TextureSystem, all on the same 1024x1024 texture and queries,
// single-threaded, in one process. Ends with summary tables of the ratios to the model's fast path.
// docs/performance.md explains the set-up and the figures.
#include <benchmark/benchmark.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <csignal>
#include <cstring>

#include <unistd.h>

#include "model/error.h"
#include "model/image.h"
#include "model/lod.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "bench_csv.h"
#include "bench_rtl.h"
#include "bench_timing.h"
#include "engines/engine.h"

namespace {

constexpr int kLog2Size = 10;              // 1024 x 1024 texture
constexpr size_t kQueries = 1 << 20;       // per query set
constexpr size_t kEngineQueries = 200000;  // per engine run (RTL engines are slow)
constexpr double kMinTime = 0.5;           // seconds per benchmark: keeps `make bench` short

// The same query twice: in the model's fixed point, and as floats for OpenImageIO.
struct TsQuery {
  float s, t, width;  // width: filter width in normalized units, 2^lambda / size
};
struct QuerySet {
  std::string name;
  std::vector<tex::Request> requests;
  std::vector<TsQuery> ts;
};

int32_t to_coord(double u) {
  int32_t out = 0;
  if (!tex::to_coord_fixed(u, out)) throw tex::Error("bench: coordinate out of range: " + std::to_string(u));
  return out;
}

// OpenImageIO gets the quantized u, v and lambda, so both sample the same point at the same LOD.
void add_query(QuerySet& set, int32_t u, int32_t v, int32_t lod) {
  set.requests.push_back(tex::lambda_request(u, v, lod, uint32_t(set.requests.size())));
  const float size = float(1 << kLog2Size);
  set.ts.push_back({float(std::ldexp(u, -24)), float(std::ldexp(v, -24)),
                    float(std::exp2(lod / 256.0) / size)});
}

// u, v uniform in [0, 1), lambda uniform over the whole pyramid [0, last level].
QuerySet random_queries() {
  QuerySet set{"random", {}, {}};
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> coord(0.0, 1.0), lambda(0.0, kLog2Size);
  for (size_t i = 0; i < kQueries; ++i) {
    int32_t lod = 0;
    tex::to_lod_fixed(lambda(rng), lod);
    const double u = coord(rng), v = coord(rng);
    add_query(set, to_coord(u), to_coord(v), lod);
  }
  return set;
}

// A rasterizer's order: 1024 x 1024 screen pixels, row by row, of a ground plane in perspective
// (far at the top, near at the bottom). lambda from the exact derivatives (model stage 1b).
QuerySet coherent_queries() {
  QuerySet set{"coherent", {}, {}};
  const int screen = 1024;
  for (int y = 0; y < screen; ++y)
    for (int x = 0; x < screen; ++x) {
      const double xs = (x + 0.5) / screen, ys = (y + 0.5) / screen;
      const double z = 1.0 / (0.05 + 0.95 * ys);  // depth: 20 at the top row, ~1 at the bottom
      const double u = (xs - 0.5) * z + 0.5, v = 0.5 * z;
      const double dz_dys = -0.95 * z * z;
      tex::Derivatives d;
      d.dudx = z / screen;
      d.dvdx = 0.0;
      d.dudy = (xs - 0.5) * dz_dys / screen;
      d.dvdy = 0.5 * dz_dys / screen;
      int32_t lod = 0;
      if (!tex::lod_from_derivatives(d, {1 << kLog2Size, 1 << kLog2Size}, lod)) throw tex::Error("bench: bad derivatives");
      add_query(set, to_coord(u), to_coord(v), lod);
    }
  return set;
}

struct Fixture {
  ~Fixture() {
    if (ts) OIIO::TextureSystem::destroy(ts);
    if (!tx_path.empty()) std::filesystem::remove(tx_path);  // no file left behind, even on error
  }
  tex::Pyramid pyramid;
  tex::SamplerConfig config;
  std::vector<QuerySet> sets;
  std::string tx_path;
  OIIO::TextureSystem* ts = nullptr;
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  OIIO::TextureSystem::Perthread* perthread = nullptr;
};
Fixture* g = nullptr;

// Ctrl-C or a kill must not leave the temporary .tx behind either.
char g_tx_path_for_signal[4096];
extern "C" void remove_tx_and_die(int sig) {
  unlink(g_tx_path_for_signal);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// The texture for OpenImageIO: level 0 as RGBA8, mip-mapped by maketx with a box filter (the same
// reduction as the model's exact pyramid, within +-1).
void make_tx(const tex::Image& level0, const std::string& path) {
  OIIO::ImageSpec spec(level0.width, level0.height, 4, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buf(spec);
  std::vector<uint8_t> pixels(level0.texels.size() * 4);
  for (size_t i = 0; i < level0.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) pixels[i * 4 + c] = uint8_t(level0.texels[i][c]);
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, pixels.data());
  OIIO::ImageSpec config;
  config.attribute("maketx:filtername", "box");
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, buf, path, config))
    throw tex::Error(path + ": make_texture failed: " + OIIO::geterror());
}

OIIO::TextureOpt trilinear_opt() {
  OIIO::TextureOpt opt;
  opt.mipmode = OIIO::TextureOpt::MipModeTrilinear;
  opt.interpmode = OIIO::TextureOpt::InterpBilinear;
  opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
  return opt;
}

// Isotropic derivatives of length `width`: OpenImageIO's filter width is then 2^lambda texels.
inline void ts_sample(OIIO::TextureOpt& opt, const TsQuery& q, float* rgba) {
  g->ts->texture(g->handle, g->perthread, opt, q.s, q.t, q.width, 0.0f, 0.0f, q.width, 4, rgba);
}

// ------------------------------------------------------------------------------ benchmarks

void BM_model_fast(benchmark::State& state, const QuerySet* set) {
  const tex::Sampler sampler(g->pyramid, g->config);
  std::vector<uint32_t> out(set->requests.size());
  for (auto _ : state) {
    sampler.sample_rgba8(set->requests.data(), set->requests.size(), out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(set->requests.size()));
}

void BM_model_reference(benchmark::State& state, const QuerySet* set) {
  tex::Sampler sampler(g->pyramid, g->config);
  for (auto _ : state) {
    uint32_t sum = 0;
    for (const tex::Request& r : set->requests) sum += sampler.sample(r)[0];
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(set->requests.size()));
}

// Cube maps on the reference path (the model samples them there): six 256x256 faces, random
// directions, lambda in [-1, 8), trilinear.
void BM_model_cube(benchmark::State& state) {
  std::vector<tex::Pyramid> faces;
  for (int f = 0; f < 6; ++f) faces.push_back(tex::build_pyramid(tex::make_pattern("noise", 256, 256)));
  std::vector<const tex::Pyramid*> cube;
  for (const tex::Pyramid& p : faces) cube.push_back(&p);
  tex::Sampler sampler(cube, tex::SamplerConfig{}, tex::SamplerPaths::Both, tex::TextureKind::Cube);
  std::mt19937_64 rng(5);
  std::vector<tex::Request> requests(65536);
  for (tex::Request& r : requests) {
    for (int32_t* c : {&r.u, &r.v, &r.w}) *c = int32_t(rng() % (2u << 24)) - (1 << 24);
    r.lod = int32_t(rng() % (9 * 256)) - 256;
  }
  for (auto _ : state) {
    uint32_t sum = 0;
    for (const tex::Request& r : requests) sum += sampler.sample(r)[0];
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(requests.size()));
}

void BM_oiio_texturesystem(benchmark::State& state, const QuerySet* set) {
  OIIO::TextureOpt opt = trilinear_opt();
  for (auto _ : state) {
    float sum = 0, rgba[4];
    for (const TsQuery& q : set->ts) {
      ts_sample(opt, q, rgba);
      sum += rgba[0];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(set->ts.size()));
}

// One engine on the first kEngineQueries queries, end to end in wall-clock time (engine set-up,
// texture load, sampling; an engine may work in a child process), with the defaults of texsim:
// ideal timing, backdoor load. "rtl-port-load" is the RTL loading through its write port.
// The sampling phase alone is reported too (stats sample_seconds).
struct BenchEngine {
  std::string label, engine;
  tex::LoadMethod load;
};
std::vector<BenchEngine> bench_engines() {
  std::vector<BenchEngine> list;
  for (const tex::EngineInfo& e : tex::engines()) list.push_back({e.name, e.name, tex::LoadMethod::Backdoor});
  list.push_back({"rtl-port-load", "rtl", tex::LoadMethod::Port});
  return list;
}

void BM_engine(benchmark::State& state, const BenchEngine& engine, const QuerySet* set) {
  const size_t n = std::min(kEngineQueries, set->requests.size());
  const std::vector<tex::Request> requests(set->requests.begin(), set->requests.begin() + ptrdiff_t(n));
  tex::EngineOptions options;
  options.load = engine.load;
  double sample_seconds = 0;
  for (auto _ : state) {
    try {
      const tex::EngineResult r = tex::make_engine(engine.engine, options)->run(g->pyramid, g->config, requests);
      benchmark::DoNotOptimize(r.texels.data());
      sample_seconds += r.stats.sample_seconds;
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
  if (sample_seconds > 0) state.counters["sampling_per_second"] = double(state.iterations()) * double(n) / sample_seconds;
}

// ------------------------------------------------------------------------------ checks

// The fast path must equal the reference path on every query (the full check is
// tests/model/test_fastpath_equivalence.cpp); a mismatch makes the benchmark meaningless.
bool check_fast_equals_reference(const QuerySet& set) {
  tex::Sampler sampler(g->pyramid, g->config);
  std::vector<uint32_t> fast(set.requests.size());
  sampler.sample_rgba8(set.requests.data(), set.requests.size(), fast.data());
  for (size_t i = 0; i < set.requests.size(); ++i) {
    const tex::Texel t = sampler.sample(set.requests[i]);
    const uint32_t ref = uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
    if (fast[i] != ref) {
      std::fprintf(stderr, "bench: %s query %zu: fast path 0x%08x != reference 0x%08x\n", set.name.c_str(), i,
                   fast[i], ref);
      return false;
    }
  }
  return true;
}

// How far OpenImageIO's answers are from the model's (in 8-bit steps), to show both filter the same
// texture at the same points; they differ in LOD blending and rounding (docs/performance.md).
// Runs over the whole set, so it also warms OpenImageIO's tile cache before timing.
void print_ts_difference(const QuerySet& set) {
  tex::Sampler sampler(g->pyramid, g->config);
  OIIO::TextureOpt opt = trilinear_opt();
  const size_t n = set.requests.size();
  double sum = 0, worst = 0;
  for (size_t i = 0; i < n; ++i) {
    const tex::Texel t = sampler.sample(set.requests[i]);
    float rgba[4];
    ts_sample(opt, set.ts[i], rgba);
    for (int c = 0; c < 4; ++c) {
      const double diff = std::fabs(rgba[c] * 255.0 - t[c]);
      sum += diff;
      worst = std::max(worst, diff);
    }
  }
  std::printf("  %-9s model vs TextureSystem over %zu queries: mean |diff| %.2f, max %.1f (of 255)\n",
              set.name.c_str(), n, sum / (4.0 * n), worst);
}

// ------------------------------------------------------------------------------ summary

// Keeps items_per_second of every run, by benchmark name, for the ratio table.
class RateReporter : public benchmark::ConsoleReporter {
 public:
  RateReporter() : ConsoleReporter(isatty(STDOUT_FILENO) ? OO_ColorTabular : OO_Tabular) {}
  std::map<std::string, double> rate, sampling_rate;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
      const auto it = r.counters.find("items_per_second");
      if (it != r.counters.end()) rate[r.run_name.function_name] = it->second.value;  // name without /min_time:...
      const auto st = r.counters.find("sampling_per_second");
      if (st != r.counters.end()) sampling_rate[r.run_name.function_name] = st->second.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  double get(const std::string& name) const {
    const auto it = rate.find(name);
    return it == rate.end() ? 0.0 : it->second;
  }
};

std::string run_name(const std::string& what, const std::string& set) { return what + "/" + set; }

void print_summary(const RateReporter& rep, const std::vector<std::string>& rtl_runs,
                   const std::vector<std::string>& csv_runs, const std::vector<std::string>& timing_sets) {
  auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  std::printf("\nSummary (samples/s, single thread, 1024x1024 RGBA8, trilinear, repeat; same process)\n");
  std::printf("%-9s %14s %14s %14s %12s %12s\n", "queries", "model fast", "model ref", "OIIO TS", "fast/TS",
              "fast/ref");
  for (const QuerySet& s : g->sets) {
    const double fast = rep.get(run_name("model_fast", s.name));
    const double ref = rep.get(run_name("model_reference", s.name));
    const double ts = rep.get(run_name("oiio_texturesystem", s.name));
    if (fast == 0 && ref == 0 && ts == 0) continue;  // filtered out
    std::printf("%-9s %12.2f M %12.2f M %12.2f M %11.2fx %11.2fx\n", s.name.c_str(), fast / 1e6, ref / 1e6,
                ts / 1e6, ratio(fast, ts), ratio(fast, ref));
  }
  std::printf("\nEngines end to end (%zu queries, one run each; texsim's defaults: no stalls, backdoor load)\n",
              kEngineQueries);
  std::printf("%-9s %-14s %14s %16s %16s %18s %14s\n", "queries", "engine", "samples/s", "vs model engine",
              "vs model fast", "sampling only/s", "vs model fast");
  for (const QuerySet& s : g->sets)
    for (const BenchEngine& e : bench_engines()) {
      const double rate = rep.get(run_name("engine_" + e.label, s.name));
      const double model = rep.get(run_name("engine_model", s.name));
      const double fast = rep.get(run_name("model_fast", s.name));
      if (rate == 0) continue;  // filtered out
      const auto sampling = rep.sampling_rate.find(run_name("engine_" + e.label, s.name));
      std::printf("%-9s %-14s %12.3f M %15.3fx %15.4fx", s.name.c_str(), e.label.c_str(), rate / 1e6,
                  ratio(rate, model), ratio(rate, fast));
      if (sampling != rep.sampling_rate.end())
        std::printf(" %16.3f M %13.4fx", sampling->second / 1e6, ratio(sampling->second, fast));
      std::printf("\n");
    }
  const double fast = rep.get(run_name("model_fast", "random"));
  std::printf("\nVerilated RTL, sampling phase per configuration (random trilinear queries, ideal timing)\n");
  std::printf("%-24s %14s %16s\n", "configuration", "samples/s", "vs model fast");
  for (const std::string& name : rtl_runs) {
    const double rate = rep.get(name);
    if (rate == 0) continue;  // filtered out
    std::printf("%-24s %12.3f M %15.4fx\n", name.substr(name.find('/') + 1).c_str(), rate / 1e6, ratio(rate, fast));
  }
  std::printf("\nTiming model vs the Verilated cached RTL (Vtex_cached_13x13, 200k requests, 8 KiB caches, "
              "latency 100; the same clock for every response)\n");
  std::printf("%-9s %16s %16s %12s\n", "queries", "RTL clocks/s", "model clocks/s", "model/RTL");
  for (const std::string& s : timing_sets) {
    const double rtl = rep.get(run_name("timing_rtl", s)), model = rep.get(run_name("timing_model", s));
    if (rtl == 0 && model == 0) continue;  // filtered out
    std::printf("%-9s %14.3f M %14.3f M %11.1fx\n", s.c_str(), rtl / 1e6, model / 1e6, ratio(model, rtl));
  }
  std::printf("\ntexsim's CSV, 1 M lines of a file (queries parsed to requests, results written)\n");
  std::printf("%-36s %14s %16s\n", "what", "lines/s", "vs model fast");
  for (const std::string& name : csv_runs) {
    const double rate = rep.get(name);
    if (rate == 0) continue;  // filtered out
    std::printf("%-36s %12.3f M %15.4fx\n", name.c_str(), rate / 1e6, ratio(rate, fast));
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Fixture fixture;
    g = &fixture;
    const tex::Image level0 = tex::make_pattern("noise", 1 << kLog2Size, 1 << kLog2Size);
    fixture.pyramid = tex::build_pyramid(level0);
    fixture.config.filter = {tex::TexelFilter::Linear, tex::MipMode::Linear};
    fixture.sets.push_back(random_queries());
    fixture.sets.push_back(coherent_queries());

    fixture.tx_path = (std::filesystem::temp_directory_path() /
                       ("texunit_bench_" + std::to_string(getpid()) + ".tx")).string();
    std::strncpy(g_tx_path_for_signal, fixture.tx_path.c_str(), sizeof g_tx_path_for_signal - 1);
    std::signal(SIGINT, remove_tx_and_die);
    std::signal(SIGTERM, remove_tx_and_die);
    make_tx(level0, fixture.tx_path);
    fixture.ts = OIIO::TextureSystem::create(false);
    fixture.ts->attribute("max_memory_MB", 512.0f);
    fixture.handle = fixture.ts->get_texture_handle(OIIO::ustring(fixture.tx_path));
    fixture.perthread = fixture.ts->get_perthread_info();
    if (!fixture.handle) throw tex::Error(fixture.tx_path + ": TextureSystem cannot open it");

    std::printf("Checks before timing:\n");
    for (const QuerySet& s : fixture.sets) {
      if (!check_fast_equals_reference(s)) return 1;
      std::printf("  %-9s fast path == reference path on all %zu queries\n", s.name.c_str(), s.requests.size());
      print_ts_difference(s);
    }
    std::printf("\n");

    for (const QuerySet& s : fixture.sets) {
      benchmark::RegisterBenchmark(("model_fast/" + s.name).c_str(), BM_model_fast, &s)->MinTime(kMinTime);
      benchmark::RegisterBenchmark(("model_reference/" + s.name).c_str(), BM_model_reference, &s)
          ->MinTime(kMinTime);
      benchmark::RegisterBenchmark(("oiio_texturesystem/" + s.name).c_str(), BM_oiio_texturesystem, &s)
          ->MinTime(kMinTime);
    }
    benchmark::RegisterBenchmark("model_cube/random", BM_model_cube)->MinTime(kMinTime);
    const std::vector<std::string> rtl_runs = bench::register_rtl_benchmarks(kMinTime);
    const std::vector<std::string> csv_runs = bench::register_csv_benchmarks(kMinTime);
    std::vector<std::pair<std::string, const std::vector<tex::Request>*>> timing_sets;
    for (const QuerySet& s : fixture.sets) timing_sets.emplace_back(s.name, &s.requests);
    const std::vector<std::string> timing_names = bench::register_timing_benchmarks(kMinTime, fixture.pyramid, timing_sets);
    static const std::vector<BenchEngine> engines = bench_engines();
    for (const QuerySet& s : fixture.sets)
      for (const BenchEngine& e : engines)
        benchmark::RegisterBenchmark(("engine_" + e.label + "/" + s.name).c_str(), BM_engine, e, &s)
            ->Iterations(1)
            ->UseRealTime();

    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    RateReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    print_summary(reporter, rtl_runs, csv_runs, timing_names);

    benchmark::Shutdown();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texunit_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}

// Query traces in and results out (sim/workloads/query_trace.h), for `make bench`: the CSV parse
// (QueryReader + QuerySource: text to the hardware's fixed-point requests) and the result write
// (CsvTexelWriter), each on 1 M lines in a temporary file, against the model's fast path in the
// same run (docs/performance.md, "The command line").
#include "bench_csv.h"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "workloads/query_trace.h"

namespace bench {

namespace {

constexpr size_t kLines = 1 << 20;

struct CsvFiles {
  std::string lod, deriv, out;
  CsvFiles() {
    const auto dir = std::filesystem::temp_directory_path();
    const std::string id = std::to_string(getpid());
    lod = (dir / ("texunit_bench_lod_" + id + ".csv")).string();
    deriv = (dir / ("texunit_bench_deriv_" + id + ".csv")).string();
    out = (dir / ("texunit_bench_out_" + id + ".csv")).string();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0), lambda(0.0, 10.0), d(-0.01, 0.01);
    std::FILE* a = std::fopen(lod.c_str(), "w");
    std::FILE* b = std::fopen(deriv.c_str(), "w");
    std::fputs("u,v,lod\n", a);
    std::fputs("u,v,dudx,dvdx,dudy,dvdy\n", b);
    for (size_t i = 0; i < kLines; ++i) {  // as texsim's users and scripts write them (6 digits)
      std::fprintf(a, "%.6f,%.6f,%.4f\n", unit(rng), unit(rng), lambda(rng));
      std::fprintf(b, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", unit(rng), unit(rng), d(rng), d(rng), d(rng), d(rng));
    }
    std::fclose(a);
    std::fclose(b);
  }
  ~CsvFiles() {
    std::filesystem::remove(lod);
    std::filesystem::remove(deriv);
    std::filesystem::remove(out);
  }
};

CsvFiles& files() {
  static CsvFiles f;
  return f;
}

void BM_csv_parse(benchmark::State& state, const std::string* path) {
  std::vector<tex::Request> chunk(4096);
  size_t total = 0;
  for (auto _ : state) {
    tex::QueryReader reader(*path);
    tex::QuerySource source(reader);
    while (const size_t n = source.read(chunk.data(), chunk.size())) {
      benchmark::DoNotOptimize(chunk.data());
      total += n;
    }
  }
  state.SetItemsProcessed(int64_t(total));
}

void BM_csv_write(benchmark::State& state) {
  std::vector<tex::Texel> texels(4096);
  std::mt19937 rng(3);
  for (tex::Texel& t : texels)
    for (uint16_t& c : t) c = uint16_t(rng() & 255);
  size_t total = 0;
  for (auto _ : state) {
    std::FILE* f = std::fopen(files().out.c_str(), "w");
    {
      tex::CsvTexelWriter writer(f);
      for (size_t i = 0; i < kLines; i += texels.size()) writer.write(texels.data(), texels.size());
    }
    std::fclose(f);
    total += kLines;
  }
  state.SetItemsProcessed(int64_t(total));
}

}  // namespace

std::vector<std::string> register_csv_benchmarks(double min_time) {
  benchmark::RegisterBenchmark("csv_parse/u,v,lod", BM_csv_parse, &files().lod)->MinTime(min_time)->UseRealTime();
  benchmark::RegisterBenchmark("csv_parse/u,v,dudx,dvdx,dudy,dvdy", BM_csv_parse, &files().deriv)
      ->MinTime(min_time)
      ->UseRealTime();
  benchmark::RegisterBenchmark("csv_write/r,g,b,a", BM_csv_write)->MinTime(min_time)->UseRealTime();
  return {"csv_parse/u,v,lod", "csv_parse/u,v,dudx,dvdx,dudy,dvdy", "csv_write/r,g,b,a"};
}

}  // namespace bench

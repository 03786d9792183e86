// texsim explore: a small sweep end to end (rows, engines, plots), the cluster path (--emit-jobs,
// --collect) against --jobs, each row against texsim render at the same point, and bad input.
#include <nlohmann/json.hpp>

#include "cli_fixture.h"

namespace {

using Row = std::map<std::string, std::string>;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, ',')) f.push_back(item);
  if (!line.empty() && line.back() == ',') f.push_back("");
  return f;
}

std::vector<Row> read_rows(const fs::path& csv) {
  std::istringstream in(read_text(csv));
  std::string line;
  std::getline(in, line);
  const auto header = split(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const auto f = split(line);
    EXPECT_EQ(f.size(), header.size()) << line;
    Row r;
    for (size_t i = 0; i < header.size() && i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(r);
  }
  return rows;
}

// The CSV without its last column (seconds: wall time).
std::string without_seconds(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

const std::string kScene =
    "explore --scene plane --width 96 --height 64 --texture testcard:256x256 --order scanline,tiled "
    "--block 4x4,8x8 --mem-latency 30,300 --fifo-depth 64,max";
const std::string kSweep = kScene + " --cache-kib 1,4";

// 300 queries along a diagonal, at lambda 1.5.
std::string diagonal_queries() {
  std::string q = "u,v,lod\n";
  for (int i = 0; i < 300; ++i) q += std::to_string(i * 0.011) + "," + std::to_string(i * 0.007) + ",1.5\n";
  return q;
}

}  // namespace

TEST_F(TexsimCli, ExploreSweepsEveryPointAndPlotsIt) {
  const Result r = run(kSweep + " --jobs 2 --confirm rtl -o ex");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // 1 KiB of 8x8 lines is 4 lines = 2 sets of 2 ways: the hardware cannot have it, said once.
  EXPECT_NE(r.err.find("left out 1 KiB, 2 ways, 8x8 blocks"), std::string::npos) << r.err;
  const auto rows = read_rows(dir / "ex/explore.csv");
  ASSERT_EQ(rows.size(), 2u * 3 * 2 * 2);  // orders x geometries x latencies x FIFO depths
  for (const Row& row : rows) {
    // Every point timed by the timing model; the RTL re-ran (--confirm rtl) those a compiled
    // configuration holds: no compiled configuration has 8x8 blocks.
    ASSERT_EQ(row.at("timing_engine"), "model");
    EXPECT_EQ(row.at("confirmed"), row.at("block") == "8x8" ? "" : "rtl");
    const double spc = std::stod(row.at("samples_per_clock"));
    EXPECT_GT(spc, 0.0);
    EXPECT_LE(spc, 1.0);
    EXPECT_TRUE(row.at("fifo_depth") == "64" || row.at("fifo_depth") == "2048") << row.at("fifo_depth");  // max = 2048
    EXPECT_EQ(std::stoull(row.at("cache_hits")) + std::stoull(row.at("cache_misses")), std::stoull(row.at("cache_lookups")));
  }
  auto find = [&](const std::string& order, const std::string& kib, const std::string& block, const std::string& lat,
                  const std::string& fifo) -> const Row& {
    for (const Row& row : rows)
      if (row.at("order") == order && row.at("cache_kib") == kib && row.at("block") == block &&
          row.at("mem_latency") == lat && row.at("fifo_depth") == fifo)
        return row;
    ADD_FAILURE() << "no row " << order << " " << kib << " " << block << " " << lat << " " << fifo;
    return rows.front();
  };
  // A FIFO shorter than the latency cannot hide it; the full FIFO does, at the same hit rate.
  const Row& shallow = find("scanline", "4", "4x4", "300", "64");
  const Row& deep = find("scanline", "4", "4x4", "300", "2048");
  EXPECT_EQ(shallow.at("cache_misses"), deep.at("cache_misses"));
  EXPECT_LT(std::stod(shallow.at("samples_per_clock")), 0.5);
  EXPECT_GT(std::stod(deep.at("samples_per_clock")), 0.8);
  // A larger cache misses less.
  EXPECT_LT(std::stoull(find("scanline", "4", "4x4", "30", "2048").at("cache_misses")),
            std::stoull(find("scanline", "1", "4x4", "30", "2048").at("cache_misses")));

  // Each row is what texsim render measures at that point.
  const std::string point = "render --scene plane --width 96 --height 64 --texture testcard:256x256 --order tiled "
                            "--memory cached --cache-kib 4 --mem-latency 300 --stats s.json -o p.png";
  ASSERT_EQ(run(point + " -e rtl").exit_code, 0);
  auto stats = nlohmann::json::parse(read_text(dir / "s.json"));
  const Row& timed = find("tiled", "4", "4x4", "300", "2048");
  EXPECT_NEAR(stats["samples_per_clock"].get<double>(), std::stod(timed.at("samples_per_clock")), 1e-5);
  EXPECT_EQ(stats["cache_hits"].get<uint64_t>(), std::stoull(timed.at("cache_hits")));
  EXPECT_EQ(stats["memory_read_bytes"].get<uint64_t>(), std::stoull(timed.at("memory_read_bytes")));
  ASSERT_EQ(run(point + " --block 8x8 --fifo-depth 64").exit_code, 0);  // the model engine (no 8x8 RTL)
  stats = nlohmann::json::parse(read_text(dir / "s.json"));
  const Row& model_only = find("tiled", "4", "8x8", "300", "64");
  EXPECT_EQ(stats["cache_misses"].get<uint64_t>(), std::stoull(model_only.at("cache_misses")));
  EXPECT_NEAR(stats["samples_per_clock"].get<double>(), std::stod(model_only.at("samples_per_clock")), 1e-5);
  EXPECT_EQ(stats["cycles"].get<uint64_t>(), std::stoull(model_only.at("cycles")));

  // Plots and the page (scripts/explore_plots.py).
  for (const char* f : {"latency.png", "throughput.png", "hit_rate.png", "bytes.png", "index.html"})
    EXPECT_GT(fs::file_size(dir / "ex" / f), 1000u) << f;
  EXPECT_NE(read_text(dir / "ex/index.html").find("0.97"), std::string::npos);
  EXPECT_NE(r.out.find("index in ex/index.html"), std::string::npos) << r.out;
}

TEST_F(TexsimCli, ExploreEmittedJobsCollectToTheSameCsv) {
  const std::string sweep = kScene + " --cache-kib 2 --no-plots";
  ASSERT_EQ(run(sweep + " -o one").exit_code, 0);
  const Result e = run(sweep + " --emit-jobs jobs.txt -o cluster");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  // A collect before the jobs ran names what is missing and writes nothing.
  expect_clean_failure("explore --collect cluster --no-plots", "cluster/explore.csv", {"4 of 4 jobs", "job000001.csv"});
  std::istringstream jobs(read_text(dir / "jobs.txt"));
  std::string cmd;
  int n = 0;
  while (std::getline(jobs, cmd)) {
    ASSERT_EQ(std::system(("cd '" + dir.string() + "' && " + cmd).c_str()), 0) << cmd;
    ++n;
  }
  EXPECT_EQ(n, 4);  // one job per (order, block): its latencies and FIFO depths in one process
  const Result c = run("explore --collect cluster --no-plots");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(without_seconds(read_text(dir / "cluster/explore.csv")), without_seconds(read_text(dir / "one/explore.csv")));
}

TEST_F(TexsimCli, ExploreTakesAQueryTrace) {
  queries(diagonal_queries());
  const Result r = run("explore -q q.csv -t noise:64x64 --cache-kib 1 --block 4x4 --mem-latency 20 --no-plots -o t");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_rows(dir / "t/explore.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("order"), "trace");
  EXPECT_EQ(rows[0].at("samples"), "300");
  EXPECT_EQ(rows[0].at("timing_engine"), "model");
  EXPECT_GT(std::stod(rows[0].at("samples_per_clock")), 0.0);
}

// --format: every workload once per format, the format in its column, compressed points timed by
// the RTL too (--timing rtl: the configuration with the block decoders) and reading fewer bytes; an
// emitted job carries its format.
TEST_F(TexsimCli, ExploreSweepsTextureFormats) {
  queries(diagonal_queries());
  const Result r = run("explore -q q.csv -t testcard:64x64 --format rgba8,bc1,bc7 --cache-kib 1 --block 4x4 "
                       "--mem-latency 20 --timing rtl --no-plots -o t");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_rows(dir / "t/explore.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("format"), "rgba8");
  EXPECT_EQ(rows[1].at("format"), "bc1");
  EXPECT_EQ(rows[2].at("format"), "bc7");
  EXPECT_EQ(rows[0].at("timing_engine"), "rtl");
  EXPECT_EQ(rows[1].at("timing_engine"), "rtl");
  EXPECT_EQ(rows[2].at("timing_engine"), "rtl");
  EXPECT_LT(std::stod(rows[1].at("bytes_per_sample")) * 4, std::stod(rows[0].at("bytes_per_sample")));
  EXPECT_LT(std::stod(rows[2].at("bytes_per_sample")) * 2, std::stod(rows[0].at("bytes_per_sample")));
  const Result e = run("explore -q q.csv -t testcard:64x64 --format bc1 --cache-kib 1 --block 4x4 --emit-jobs jobs.txt -o j");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(read_text(dir / "jobs.txt").find("--format bc1"), std::string::npos);
  expect_clean_failure("explore -q q.csv --format bc6 -o bad", "bad/explore.csv", {"--format \"bc6\""});
}

TEST_F(TexsimCli, ExploreBadInputFailsBeforeAnyWork) {
  const std::string out = "bad/explore.csv";
  expect_clean_failure("explore --cache-kib 4,,8 -o bad", out, {"--cache-kib", "empty item"});
  expect_clean_failure("explore --cache-kib 4,0 -o bad", out, {"--cache-kib \"0\"", "1 to 1024"});
  expect_clean_failure("explore --ways 3 -o bad", out, {"--ways \"3\""});
  expect_clean_failure("explore --block 3x3 -o bad", out, {"--block \"3x3\""});
  expect_clean_failure("explore --order diagonal -o bad", out, {"diagonal"});
  expect_clean_failure("explore --scene plane,nosuch -o bad", out, {"nosuch"});
  expect_clean_failure("explore --mem-latency 200,x -o bad", out, {"--mem-latency \"x\""});
  expect_clean_failure("explore --fifo-depth maximal -o bad", out, {"--fifo-depth \"maximal\""});
  expect_clean_failure("explore --timing fast -o bad", out, {"--timing \"fast\"", "model, rtl or none"});
  expect_clean_failure("explore --confirm gpu -o bad", out, {"--confirm \"gpu\""});
  expect_clean_failure("explore --confirm rtl --timing none -o bad", out, {"--confirm rtl", "--timing model"});
  expect_clean_failure("explore --scene plane -q q.csv -o bad", out, {"--scene, --queries, --model or --scene-file"});
  expect_clean_failure("explore -q missing.csv -o bad", out, {"missing.csv"});
  expect_clean_failure("explore --collect nowhere", "nowhere/explore.csv", {"nowhere/points/jobs", "--emit-jobs"});
  expect_clean_failure("explore --cache-kib 1 --block 8x8 --ways 4 -o bad", out, {"no point"});
}

// A real frame: the spider's 4 textures in one descriptor table, --timing rtl: through the RTL where a compiled
// configuration holds the point; every row's counters equal texsim render's at the same point.
TEST_F(TexsimCli, ExploreSweepsAModelsFrame) {
  const std::string model = "/usr/share/assimp/models/OBJ/spider.obj";
  const Result r = run("explore --model " + model + " --width 160 --height 120 --order tiled --cache-kib 2,8 "
                       "--block 4x4,2x2 --mem-latency 200 --timing rtl --jobs 2 --no-plots -o ex");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_rows(dir / "ex/explore.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (const Row& row : rows) {
    EXPECT_EQ(row.at("workload"), model);
    EXPECT_EQ(row.at("texture"), "4 textures");
    EXPECT_EQ(row.at("timing_engine"), row.at("block") == "4x4" ? "rtl" : "model");  // --timing rtl
  }
  const Row& row = rows[0];
  ASSERT_EQ(row.at("block"), "4x4");
  const Result render = run("render --model " + model + " --width 160 --height 120 --memory cached --engine rtl "
                            "--cache-kib " + row.at("cache_kib") + " --mem-latency 200 --out f.png --stats s.json");
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const auto s = nlohmann::json::parse(read_text(dir / "s.json"));
  EXPECT_EQ(std::to_string(s.at("samples").get<uint64_t>()), row.at("samples"));
  EXPECT_EQ(std::to_string(s.at("cache_misses").get<uint64_t>()), row.at("cache_misses"));
  EXPECT_EQ(std::to_string(s.at("cycles").get<uint64_t>()), row.at("cycles"));
  expect_clean_failure("explore --model " + model + " --scene plane -o ex2", "ex2", {"--scene", "--model"});
  expect_clean_failure("explore --model " + model + " --queries q.csv -o ex2", "ex2", {"--queries", "--model"});
}

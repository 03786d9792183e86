// texsim explore: a small sweep end to end (rows, engines, plots), the results store (a sweep
// measures only what it lacks), the emitted sweeps (GNU parallel for real, with a killed task
// resumed; Slurm's array script run task by task as Slurm would) merged by --collect into the same
// bytes as --jobs, each row against texsim render at the same point, and bad input. (A real Slurm:
// make cluster-test, scripts/cluster_test.sh.)
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
  // A shorter latency, the same FIFO: more samples per clock, fewer clocks (each point its own
  // result, whatever the store's keys share).
  const Row& near = find("scanline", "4", "4x4", "30", "64");
  EXPECT_GT(std::stod(near.at("samples_per_clock")), std::stod(shallow.at("samples_per_clock")) + 0.2);
  EXPECT_LT(std::stoull(near.at("cycles")), std::stoull(shallow.at("cycles")));
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

// The results store: a second sweep that overlaps half the first measures only the other half (the
// summary line counts them), its shared rows are the first's, and its CSV is the bytes of the same
// sweep on an empty store.
TEST_F(TexsimCli, ExploreReusesTheStore) {
  const std::string sweep = kScene + " --no-plots --store st";
  const Result first = run(sweep + " --cache-kib 1,2 -o a");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("24 points (24 measured, 0 reused"), std::string::npos) << first.out;
  const Result second = run(sweep + " --cache-kib 2,4 -o b");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("32 points (16 measured, 16 reused"), std::string::npos) << second.out;
  const Result fresh = run(kScene + " --no-plots --store other --cache-kib 2,4 -o c");
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  EXPECT_EQ(read_text(dir / "b/explore.csv"), read_text(dir / "c/explore.csv"));
  std::string shared;  // the 2 KiB rows of the first sweep are the second's
  for (const auto* csv : {"a/explore.csv", "b/explore.csv"}) {
    std::istringstream in(read_text(dir / csv));
    std::string line, rows;
    while (std::getline(in, line))
      if (line.find(",2,2,") != std::string::npos) rows += line + "\n";
    if (shared.empty()) shared = rows;
    else EXPECT_EQ(rows, shared);
  }
  EXPECT_GT(shared.size(), 100u);
  // Another texture is another workload: nothing reused.
  std::string noise = kScene;
  noise.replace(noise.find("testcard:256x256"), 16, "noise:256x256");
  const Result other = run(noise + " --no-plots --store st --cache-kib 2 -o d");
  EXPECT_NE(other.out.find("16 points (16 measured, 0 reused"), std::string::npos) << other.out << other.err;
}

namespace {

// Line k (from 0) of a text file replaced; returns the old line.
std::string replace_line(const fs::path& file, size_t k, const std::string& text) {
  std::istringstream in(read_text(file));
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  const std::string old = lines.at(k);
  lines[k] = text;
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  write_text(file, out);
  return old;
}

}  // namespace

// --emit parallel: GNU parallel runs the tasks (its job log); one task is killed, --collect names it
// ("killed by signal 9"), writes nothing and a resubmit script; the task restored, the script runs
// it again (parallel's --resume-failed: that task alone) and --collect merges the same bytes as a
// local --jobs 2 sweep.
TEST_F(TexsimCli, ExploreThroughGnuParallelResumesAKilledTask) {
  ASSERT_EQ(std::system("command -v parallel > /dev/null"), 0) << "GNU parallel is not installed (make deps)";
  const std::string sweep = kScene + " --cache-kib 2,4 --no-plots";
  ASSERT_EQ(run(sweep + " --store local -o local --jobs 2").exit_code, 0);
  const Result e = run(sweep + " --store shared --emit parallel em");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("32 points, 0 in the store already, 32 to measure in 4 tasks"), std::string::npos) << e.out;
  // Before any task ran: every task named (a line each, then the error), nothing written.
  const Result none = run("explore --collect em --no-plots");
  EXPECT_NE(none.exit_code, 0);
  EXPECT_NE(none.err.find("task 3 (8 points missing): has not run"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("32 of 32 points are missing, in 4 of 4 tasks"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(dir / "em/explore.csv"));
  const std::string kept = replace_line(dir / "em/commands.txt", 1, "sh -c 'kill -KILL $$'");
  ASSERT_NE(std::system(("cd '" + dir.string() + "' && em/run-parallel.sh --jobs 2 > /dev/null 2>&1").c_str()), 0);
  const Result c = run("explore --collect em --no-plots");
  EXPECT_NE(c.exit_code, 0);
  EXPECT_NE(c.err.find("task 1 (8 points missing): killed by signal 9"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("8 of 32 points are missing, in 1 of 4 tasks"), std::string::npos) << c.err;
  EXPECT_FALSE(fs::exists(dir / "em/explore.csv"));
  ASSERT_TRUE(fs::exists(dir / "em/resubmit.sh"));
  replace_line(dir / "em/commands.txt", 1, kept);
  ASSERT_EQ(std::system(("cd '" + dir.string() + "' && em/resubmit.sh > /dev/null 2>&1").c_str()), 0);
  size_t runs_of_1 = 0, lines = 0;  // parallel ran task 1 twice, the others once
  std::istringstream joblog(read_text(dir / "em/parallel.joblog"));
  std::string line;
  std::getline(joblog, line);
  while (std::getline(joblog, line)) {
    ++lines;
    runs_of_1 += line.size() > 2 && line.compare(line.size() - 2, 2, " 1") == 0;
  }
  EXPECT_EQ(runs_of_1, 2u);
  EXPECT_EQ(lines, 5u);
  const Result ok = run("explore --collect em --no-plots");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(read_text(dir / "em/explore.csv"), read_text(dir / "local/explore.csv"));
  // Emitted again into the same directory: every point is stored, no task; the old job log is gone
  // (its successes would make --resume-failed skip new tasks).
  const Result again = run(sweep + " --store shared --emit parallel em");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("32 points, 32 in the store already, 0 to measure in 0 tasks"), std::string::npos) << again.out;
  EXPECT_FALSE(fs::exists(dir / "em/parallel.joblog"));
  const Result collected = run("explore --collect em --no-plots");
  ASSERT_EQ(collected.exit_code, 0) << collected.err;
  EXPECT_EQ(read_text(dir / "em/explore.csv"), read_text(dir / "local/explore.csv"));
}

// --emit slurm: the job array's script (array range, throttle, log per task, task.sh), run task by
// task as Slurm runs it (SLURM_ARRAY_TASK_ID) without a Slurm here (make cluster-test submits it to
// a real one); a failing task's exit code and last log lines in --collect's report, a resubmit
// script of exactly that task, and the same bytes as a local sweep once it ran. Tasks already in
// the store are not emitted.
TEST_F(TexsimCli, ExploreEmitsASlurmArray) {
  const std::string sweep = kScene + " --cache-kib 2,4 --no-plots";
  ASSERT_EQ(run(sweep + " --store local -o local").exit_code, 0);
  ASSERT_EQ(run(kScene + " --cache-kib 2 --no-plots --store shared -o half").exit_code, 0);  // half in the store
  const Result e = run(sweep + " --store shared --emit slurm sl --throttle 3");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("32 points, 16 in the store already, 16 to measure in 4 tasks"), std::string::npos) << e.out;
  const std::string sbatch = read_text(dir / "sl/sweep.sbatch");
  EXPECT_NE(sbatch.find("#SBATCH --array=0-3%3\n"), std::string::npos) << sbatch;
  EXPECT_NE(sbatch.find("#SBATCH --output=" + (dir / "sl/logs").string()), std::string::npos) << sbatch;
  EXPECT_TRUE((fs::status(dir / "sl/task.sh").permissions() & fs::perms::owner_exec) != fs::perms::none);
  const std::string readme = read_text(dir / "sl/README.txt");
  EXPECT_NE(readme.find("sbatch " + (dir / "sl/sweep.sbatch").string()), std::string::npos) << readme;
  EXPECT_NE(readme.find("texsim explore --collect " + (dir / "sl").string()), std::string::npos) << readme;
  replace_line(dir / "sl/commands.txt", 2, "echo 'no such file: the input' >&2; exit 3");
  for (int k = 0; k < 4; ++k)
    std::system(("cd '" + dir.string() + "' && SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " bash sl/sweep.sbatch").c_str());
  const Result c = run("explore --collect sl --no-plots");
  EXPECT_NE(c.exit_code, 0);
  EXPECT_NE(c.err.find("task 2 (4 points missing): failed, exit code 3: no such file: the input"), std::string::npos) << c.err;
  const std::string resubmit = read_text(dir / "sl/resubmit.sh");
  EXPECT_NE(resubmit.find("sbatch --array=2 "), std::string::npos) << resubmit;
  // The task as emitted: run it as the resubmitted array would, then collect.
  ASSERT_EQ(run(sweep + " --store shared --emit slurm sl2").exit_code, 0);
  replace_line(dir / "sl/commands.txt", 2, [&] {
    std::istringstream in(read_text(dir / "sl2/commands.txt"));
    std::string l;
    std::getline(in, l);  // (sl2 has only the one task left)
    return l;
  }());
  ASSERT_EQ(std::system(("cd '" + dir.string() + "' && SLURM_ARRAY_TASK_ID=2 bash sl/sweep.sbatch").c_str()), 0);
  const Result ok = run("explore --collect sl --no-plots");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(read_text(dir / "sl/explore.csv"), read_text(dir / "local/explore.csv"));
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
  const Result e = run("explore -q q.csv -t testcard:64x64 --format bc1 --cache-kib 1 --block 4x4 --store new --emit parallel j");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(read_text(dir / "j/commands.txt").find("--format bc1"), std::string::npos);
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
  expect_clean_failure("explore --collect nowhere", "nowhere/explore.csv", {"nowhere/sweep.txt", "--emit slurm|parallel"});
  expect_clean_failure("explore --emit pbs cl", "cl/sweep.txt", {"--emit pbs", "slurm", "parallel"});
  expect_clean_failure("explore --emit slurm", "slurm/sweep.txt", {"--emit"});
  expect_clean_failure("explore --emit slurm cl --throttle -2", "cl/sweep.txt", {"--throttle -2"});
  expect_clean_failure("explore --emit parallel cl --sshloginfile nohosts", "cl/sweep.txt", {"--sshloginfile nohosts"});
  fs::create_directories(dir / "foreign");  // a directory of the user's: refused, nothing in it touched
  write_text(dir / "foreign/notes.txt", "mine\n");
  expect_clean_failure("explore --emit slurm foreign", "foreign/sweep.txt", {"--emit foreign", "holds other files"});
  EXPECT_EQ(read_text(dir / "foreign/notes.txt"), "mine\n");
  fs::create_directories(dir / "notasweep");
  write_text(dir / "notasweep/sweep.txt", "hello\n");
  expect_clean_failure("explore --collect notasweep", "notasweep/explore.csv", {"line 1", "not a texsim explore sweep"});
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

// render --frames N --emit parallel: a task per two frames through GNU parallel; a failing task is
// named by render --collect (its exit code and log line), which writes nothing; restored and
// resubmitted, the batch collects: every picture the bytes of a local --frames render's, and the
// frames' statistics in frame order in frames.json. Emitted again, every frame comes from the
// results store (--store): none is sampled. Bad batches are one-line errors.
TEST_F(TexsimCli, RenderFramesThroughGnuParallel) {
  ASSERT_EQ(std::system("command -v parallel > /dev/null"), 0) << "GNU parallel is not installed (make deps)";
  const std::string render = "render --scene plane --width 64 --height 48 --frames 5";
  ASSERT_EQ(run(render + " -o f.png").exit_code, 0);
  const Result e = run(render + " -o f.png --emit parallel batch --frames-per-task 2 --store st");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("5 frames in 3 tasks"), std::string::npos) << e.out;
  const std::string kept = replace_line(dir / "batch/commands.txt", 1, "echo 'frame trouble' >&2; exit 5");
  std::system(("cd '" + dir.string() + "' && batch/run-parallel.sh > /dev/null 2>&1").c_str());
  const Result c = run("render --collect batch");
  EXPECT_NE(c.exit_code, 0);
  EXPECT_NE(c.err.find("task 1 (2 frames missing): failed, exit code 5: frame trouble"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("2 of 5 frames are missing, in 1 of 3 tasks"), std::string::npos) << c.err;
  EXPECT_FALSE(fs::exists(dir / "batch/frames.json"));
  replace_line(dir / "batch/commands.txt", 1, kept);
  ASSERT_EQ(std::system(("cd '" + dir.string() + "' && batch/resubmit.sh > /dev/null 2>&1").c_str()), 0);
  const Result ok = run("render --collect batch");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  for (const char* f : {"f_000.png", "f_001.png", "f_002.png", "f_003.png", "f_004.png"}) {
    EXPECT_GT(fs::file_size(dir / f), 100u) << f;
    EXPECT_EQ(read_text(dir / "batch/frames" / f), read_text(dir / f)) << f;
  }
  const auto frames = nlohmann::json::parse(read_text(dir / "batch/frames.json"))["frames"];
  ASSERT_EQ(frames.size(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(frames[i]["frame"].get<size_t>(), i);
    EXPECT_GT(frames[i]["stats"]["samples"].get<uint64_t>(), 1000u);
  }
  // The same batch again: every frame from the store (no frame sampled), the same pictures.
  ASSERT_EQ(run(render + " -o f.png --emit parallel again --frames-per-task 2 --store st").exit_code, 0);
  ASSERT_EQ(std::system(("cd '" + dir.string() + "' && again/run-parallel.sh > /dev/null 2>&1").c_str()), 0);
  ASSERT_EQ(run("render --collect again").exit_code, 0);
  for (int t = 0; t < 3; ++t) {
    const std::string log = read_text(dir / ("again/logs/task-" + std::to_string(t) + ".log"));
    EXPECT_NE(log.find("reused from the store"), std::string::npos) << log;
    EXPECT_EQ(log.find("samples, trilinear"), std::string::npos) << log;  // (the line of a frame sampled)
  }
  for (const char* f : {"f_000.png", "f_004.png"}) EXPECT_EQ(read_text(dir / "again/frames" / f), read_text(dir / f)) << f;
  // A frame of another animation (--frames 6) is another frame: sampled.
  const Result other = run("render --scene plane --width 64 --height 48 --frames 6 --frame 2 -o o.png --store st");
  EXPECT_EQ(other.out.find("reused"), std::string::npos) << other.out;
  expect_clean_failure("render --scene plane --frames 5 -o x.png --store st", "x.png", {"--store keeps one frame"});
  expect_clean_failure("render --collect nowhere", "nowhere/frames.json", {"nowhere/render.txt", "--emit"});
  expect_clean_failure(render + " -o g.png --frame 2 --emit slurm b2", "b2/render.txt", {"no --frame"});
  expect_clean_failure(render + " -o g.png --emit slurm b2 --frames-per-task 0", "b2/render.txt", {"--frames-per-task 0"});
  expect_clean_failure(render + " -o g.png --frames-per-task 2", "g.png", {"--frames-per-task", "render --emit"});
}

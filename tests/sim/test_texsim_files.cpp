// texsim and the user's files: it never replaces what is not a regular file, never overwrites an
// input, checks its outputs before the work, leaves nothing when it fails or is interrupted, and
// streams big traces in constant memory. Also the input checks of query files, sizes and options.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "model/sampler.h"

namespace {

// `n` random explicit-lod queries, as CSV.
std::string random_queries(size_t n, unsigned seed = 1) {
  std::string s = "u,v,lod\n";
  s.reserve(n * 24);
  uint64_t x = seed * 0x9E3779B97F4A7C15ULL + 1;
  char buf[64];
  for (size_t i = 0; i < n; ++i) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = double(x >> 40) / double(1 << 24) * 3 - 1;
    const double v = double((x >> 16) & 0xFFFFFF) / double(1 << 24) * 3 - 1;
    const double lod = double(x & 0xFFFF) / 65536.0 * 9 - 1;
    s.append(buf, size_t(std::snprintf(buf, sizeof buf, "%.5f,%.5f,%.3f\n", u, v, lod)));
  }
  return s;
}

bool has_partial_file(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".partial") != std::string::npos) return true;
  return false;
}

// Starts texsim ARGS in `dir` without waiting (stdout, stderr to files there).
pid_t spawn(const fs::path& dir, const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(127);
    const int out = open("spawn_stdout.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open("spawn_stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    std::vector<char*> argv{const_cast<char*>(TEXSIM_PATH)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(TEXSIM_PATH, argv.data());
    _exit(127);
  }
  return pid;
}

// Waits (at most `seconds`) until `ready` holds; false on time-out.
template <class F>
bool wait_until(F ready, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

std::vector<pid_t> children_of(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children");
  std::vector<pid_t> out;
  for (pid_t c; f >> c;) out.push_back(c);
  return out;
}

// A process that no longer runs: gone, or a zombie waiting for its (new) parent.
bool ended(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  if (!f) return true;
  std::string stat;
  std::getline(f, stat);
  const auto close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && (stat[close + 2] == 'Z' || stat[close + 2] == 'X');
}

}  // namespace

// ---------------------------------------------------------------- what is at the output path

TEST_F(TexsimCli, SymlinkOutputWritesItsTargetAndStays) {
  queries("u,v,lod\n0.5,0.5,0\n0.25,0.25,1\n");
  write_text(dir / "real.csv", "old contents\n");
  fs::create_symlink("real.csv", dir / "link.csv");
  fs::create_symlink("sub/new.csv", dir / "dangling.csv");
  fs::create_directories(dir / "sub");
  ASSERT_EQ(run("sample -t noise:8x8 -q q.csv -o link.csv").exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(read_text(dir / "real.csv").substr(0, 8), "r,g,b,a\n");
  ASSERT_EQ(run("sample -t noise:8x8 -q q.csv -o dangling.csv").exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.csv"));
  EXPECT_EQ(read_text(dir / "sub/new.csv"), read_text(dir / "real.csv"));
  EXPECT_FALSE(has_partial_file(dir) || has_partial_file(dir / "sub"));
}

TEST_F(TexsimCli, FifoAndStandardOutputAreStreamedNotReplaced) {
  queries("u,v,lod\n0.5,0.5,0\n0.25,0.25,1\n");
  ASSERT_EQ(run("sample -t noise:8x8 -q q.csv -o want.csv").exit_code, 0);
  const std::string want = read_text(dir / "want.csv");

  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0644), 0);
  const std::string cmd = "cd '" + dir.string() + "' && (cat fifo > got.csv &) && timeout 60 '" + TEXSIM_PATH +
                          "' sample -t noise:8x8 -q q.csv -o fifo > /dev/null && sleep 0.2";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  struct stat st {};
  ASSERT_EQ(lstat((dir / "fifo").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  EXPECT_EQ(read_text(dir / "got.csv"), want);

  // "-" and /dev/stdout: the result on standard output, the summary on stderr.
  for (const std::string out : {"-", "/dev/stdout"}) {
    const Result r = run("sample -t noise:8x8 -q q.csv -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, want) << out;
    EXPECT_NE(r.err.find("texsim sample: 2 queries"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(has_partial_file(dir));
}

TEST_F(TexsimCli, CharacterDeviceIsWrittenNotReplaced) {
  queries("u,v,lod\n0.5,0.5,0\n");
  // As root texsim could replace a device node: make a private one (like /dev/null) to try.
  // Without root, /dev/null itself (which could not be replaced anyway) must still work.
  std::string device = "/dev/null";
  if (geteuid() == 0) {
    device = (dir / "null").string();
    ASSERT_EQ(mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  }
  const Result r = run("sample -t noise:8x8 -q q.csv -o " + device + " --stats " + device);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(lstat(device.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << device << " was replaced";
  EXPECT_FALSE(has_partial_file(dir));
  // A full device: the write error is reported, nothing is left.
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o /dev/full", "r.csv", {"/dev/full", "No space left"});
}

TEST_F(TexsimCli, DirectoriesAndBlockDevicesAreRefused) {
  queries("u,v,lod\n0.5,0.5,0\n");
  fs::create_directories(dir / "adir");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o adir", "r.csv", {"adir", "is a directory"});
  write_text(dir / "file.txt", "x");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o file.txt/r.csv", "r.csv", {"file.txt", "Not a directory"});
  expect_clean_failure("render --scene plane --width 8 --height 8 -o -", "r.csv", {"standard output"});
  expect_clean_failure("render --scene plane --width 8 --height 8 -o img.xyz", "img.xyz", {"img.xyz", "image writer"});
}

// ---------------------------------------------------------------- inputs are never outputs

TEST_F(TexsimCli, AnInputIsNeverOverwritten) {
  const std::string q = "u,v,lod\n0.5,0.5,0\n";
  queries(q);
  write_image(dir / "t.png", 8, 8, 3, [](int x, int y, int c) { return x * 30 + y * 3 + c; });
  const std::string png = read_text(dir / "t.png");
  fs::create_hard_link(dir / "q.csv", dir / "hard.csv");
  fs::create_symlink("q.csv", dir / "soft.csv");
  const std::pair<std::string, std::string> cases[] = {
      {"sample -t noise:8x8 -q q.csv -o q.csv", "q.csv"},
      {"sample -t noise:8x8 -q q.csv -o hard.csv", "hard.csv"},
      {"sample -t noise:8x8 -q q.csv -o soft.csv", "soft.csv"},
      {"sample -t noise:8x8 -q q.csv -o r.csv --stats q.csv", "q.csv"},
      {"sample -t t.png -q q.csv -o r.csv --stats ./t.png", "t.png"},
      {"render --scene plane --width 8 --height 8 --texture t.png --out t.png", "t.png"},
      {"mip -t t.png --layout t.png", "t.png"},
  };
  for (const auto& [args, name] : cases) {
    expect_clean_failure(args, "r.csv", {name, "input"});
    EXPECT_EQ(read_text(dir / "q.csv"), q) << args;
    EXPECT_EQ(read_text(dir / "t.png"), png) << args;
  }
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --stats r.csv", "r.csv", {"r.csv", "also the output"});
}

// ---------------------------------------------------------------- before the work, all or nothing

TEST_F(TexsimCli, OutputErrorsComeBeforeTheWork) {
  write_text(dir / "q.csv", random_queries(20000));
  // The RTL would simulate for seconds before the old write failed, leaving the trace behind.
  const auto t0 = std::chrono::steady_clock::now();
  expect_clean_failure("sample -q q.csv -e rtl --trace t.fst -o nodir/r.csv", "t.fst", {"nodir", "does not exist"});
  expect_clean_failure("sample -q q.csv -e rtl -o r.csv --stats nodir/s.json", "r.csv", {"nodir", "does not exist"});
  expect_clean_failure("sample -q q.csv -e rtl -o r.csv --trace nodir/t.fst", "r.csv", {"nodir", "does not exist"});
  expect_clean_failure("render --scene plane -o r.png --stats nodir/s.json", "r.png", {"nodir"});
  expect_clean_failure("mip --dump-levels lv --layout nodir/l.png", "lv", {"nodir"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
  // A query file with a bad line near its end fails before any sample is taken.
  write_text(dir / "q.csv", random_queries(20000) + "0.5,oops,0\n");
  const Result r = run("sample -q q.csv -e rtl --trace t.fst -o r.csv");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("q.csv:20002"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "t.fst") || fs::exists(dir / "r.csv") || has_partial_file(dir));
}

TEST_F(TexsimCli, AFailedOutputLeavesNoOutput) {
  queries("u,v,lod\n0.5,0.5,0\n");
  // The result is complete, then the stats cannot be written: the result goes too.
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --stats /dev/full", "r.csv", {"/dev/full"});
  expect_clean_failure("render --scene plane --width 8 --height 8 -o r.png --stats /dev/full", "r.png", {"/dev/full"});
}

TEST_F(TexsimCli, CtrlCWhileWritingLeavesNoPartialFile) {
  write_text(dir / "q.csv", random_queries(400000));
  const pid_t pid = spawn(dir, {"sample", "-q", "q.csv", "-e", "rtl", "-o", "r.csv"});
  // The result streams into r.partial-XXXXXX.csv while the RTL runs: interrupt it there.
  ASSERT_TRUE(wait_until(
      [&] {
        for (const auto& e : fs::directory_iterator(dir))
          if (e.path().filename().string().find(".partial") != std::string::npos && fs::file_size(e.path()) > 0)
            return true;
        return false;
      },
      60))
      << "no partial result appeared";
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  EXPECT_FALSE(has_partial_file(dir));
  EXPECT_FALSE(fs::exists(dir / "r.csv"));
}

TEST_F(TexsimCli, TerminatingSystemcEndsItsSimulationProcess) {
  write_text(dir / "q.csv", random_queries(1000000));
  const pid_t pid = spawn(dir, {"sample", "-q", "q.csv", "-e", "systemc", "--stalls", "heavy", "-o", "r.csv"});
  std::vector<pid_t> children;
  ASSERT_TRUE(wait_until([&] { return !(children = children_of(pid)).empty(); }, 60)) << "no simulation process";
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
  for (pid_t c : children) EXPECT_TRUE(wait_until([&] { return ended(c); }, 2.0)) << "child " << c << " runs on";
  EXPECT_FALSE(has_partial_file(dir));
  EXPECT_FALSE(fs::exists(dir / "r.csv"));
}

TEST_F(TexsimCli, TracedRunCommitsTheWaveformWithTheResult) {
  // (A failed simulation keeps its waveform alone: OutputSet.KeepRenamesOneOutputAndTheRestGo.)
  queries("u,v,lod\n0.5,0.5,0\n0.2,0.7,1.5\n");
  const Result r = run("sample -t noise:8x8 -q q.csv -e rtl --trace t.fst -o r.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(fs::file_size(dir / "t.fst"), 100u);
  EXPECT_TRUE(fs::exists(dir / "r.csv"));
  EXPECT_FALSE(has_partial_file(dir));
}

// ---------------------------------------------------------------- inputs

TEST_F(TexsimCli, QueryFileEncodingsAndEmptyTraces) {
  queries("u,v,lod\n0.5,0.5,0\n0.1,0.9,2\n");
  ASSERT_EQ(run("sample -t noise:8x8 -q q.csv -o want.csv").exit_code, 0);
  write_text(dir / "bom.csv", "\xEF\xBB\xBFu,v,lod\n0.5,0.5,0\n0.1,0.9,2\n");
  const Result bom = run("sample -t noise:8x8 -q bom.csv -o r.csv");
  EXPECT_EQ(bom.exit_code, 0) << bom.err;
  EXPECT_EQ(read_text(dir / "r.csv"), read_text(dir / "want.csv"));
  fs::remove(dir / "r.csv");

  write_text(dir / "utf16.csv", std::string("\xFF\xFEu\0,\0v\0", 8));
  expect_clean_failure("sample -t noise:8x8 -q utf16.csv -o r.csv", "r.csv", {"utf16.csv:1", "UTF-16"});
  write_text(dir / "nul.csv", std::string("u,v,lod\n0.5,\0,0\n", 16));
  expect_clean_failure("sample -t noise:8x8 -q nul.csv -o r.csv", "r.csv", {"nul.csv:2", "NUL"});

  // Header only: an empty result and a note (documented in docs/cli.md).
  write_text(dir / "empty.csv", "# nothing yet\nu,v,lod\n");
  const Result e = run("sample -t noise:8x8 -q empty.csv -o r.csv");
  EXPECT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(read_text(dir / "r.csv"), "r,g,b,a\n");
  EXPECT_NE(e.err.find("empty.csv has no queries"), std::string::npos) << e.err;
}

TEST_F(TexsimCli, AHugeBadTokenIsQuotedOnceAndShort) {
  const std::string token(1'000'000, 'x');
  queries("u,v,lod\n0.5," + token + ",0\n");
  const Result r = run("sample -t noise:8x8 -q q.csv -o r.csv");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_LT(r.err.size(), 300u) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find("q.csv:2"), std::string::npos);
  EXPECT_NE(r.err.find("1000000 characters"), std::string::npos) << r.err;
  // A line beyond 1 MiB is not read into memory: refused by its length, naming it.
  queries("u,v,lod\n0.5,0.5,0\n0.5," + std::string(10'000'000, 'x') + ",0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv", "r.csv", {"q.csv:3", "a line longer than 1 MiB"});
  const std::string token_10m(10'000'000, 'x');
  queries("u,v,lod\n" + token_10m + "\n");
  const Result r2 = run("sample -t noise:8x8 -q q.csv -o r.csv");
  EXPECT_LT(r2.err.size(), 300u);
  queries(token_10m + "\n");
  const Result r3 = run("sample -t noise:8x8 -q q.csv -o r.csv");
  EXPECT_LT(r3.err.size(), 300u);
  EXPECT_FALSE(fs::exists(dir / "r.csv"));
}

TEST_F(TexsimCli, SizesAreNamedRight) {
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t noise:16384x16384 -q q.csv -o r.csv", "r.csv", {"16384x16384", "too large", "8192"});
  expect_clean_failure("sample -t testcard:99999999999999999999x2 -q q.csv -o r.csv", "r.csv",
                       {"99999999999999999999", "too large"});
  // Any size 1..8192 is a texture, in every engine and both units.
  EXPECT_EQ(run("sample -t noise:100x64 -q q.csv -o model.csv").exit_code, 0);
  EXPECT_EQ(run("sample -t noise:100x63 -q q.csv -o onchip.csv -e rtl").exit_code, 0);
  for (const char* engine : {"rtl", "systemc"}) {
    const Result c = run(std::string("sample -t noise:100x63 -q q.csv -o r2.csv --memory cached -e ") + engine);
    EXPECT_EQ(c.exit_code, 0) << engine << ": " << c.err;
  }
  // Too large for every compiled unit: the error names the size as given, not rounded up.
  expect_clean_failure("sample -t noise:2000x1000 -q q.csv -o r4.csv -e rtl", "r4.csv", {"2000x1000", "does not fit"});
  // A pattern has the size it is given: no --resize hint, with or without --resize.
  const Result r = run("sample -t noise:16384x2 --resize -q q.csv -o r3.csv");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.find("--resize"), std::string::npos) << r.err;
  // A file too large without --resize suggests it.
  write_image(dir / "wide.png", 16384, 2, 3, [](int x, int, int) { return x & 255; });
  expect_clean_failure("sample -t wide.png -q q.csv -o r.csv", "r.csv", {"16384x2", "too large", "--resize"});
}

TEST_F(TexsimCli, NumericOptionsDoNotWrapAround) {
  queries("u,v,lod\n0.5,0.5,0\n");
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv -e rtl --trace t.fst --trace-window -5:-1", "t.fst",
                       {"--trace-window", "-5"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv -e rtl --trace t.fst --trace-window 9:3", "t.fst",
                       {"--trace-window", "LAST < FIRST"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --seed -1", "r.csv", {"--seed", "-1"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --seed 18446744073709551616", "r.csv", {"--seed"});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --wrap-v ''", "r.csv", {"--wrap-v", "\"\""});
  expect_clean_failure("sample -t noise:8x8 -q q.csv -o r.csv --wrap-u ''", "r.csv", {"--wrap-u"});
}

TEST_F(TexsimCli, QueriesFromStandardInput) {
  write_text(dir / "q.csv", random_queries(5000));
  ASSERT_EQ(run("sample -t noise:64x64 -q q.csv -o want.csv").exit_code, 0);
  for (const std::string engine : {"model", "rtl", "systemc"}) {
    const Result r = run("sample -t noise:64x64 -q - -e " + engine + " -o r.csv", (dir / "q.csv").string());
    EXPECT_EQ(r.exit_code, 0) << engine << ": " << r.err;
    EXPECT_EQ(read_text(dir / "r.csv"), read_text(dir / "want.csv")) << engine;
  }
  // A bad line arriving through the pipe: the error names it, and no output is left.
  write_text(dir / "bad.csv", random_queries(3000) + "1,2\n");
  const Result r = run("sample -t noise:64x64 -q - -e rtl -o r2.csv", (dir / "bad.csv").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("standard input:3002"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "r2.csv") || has_partial_file(dir));
}

// ---------------------------------------------------------------- memory

TEST_F(TexsimCli, SampleStreamsInConstantMemory) {
  // Peak memory of texsim sample must not grow with the number of queries past the files it keeps
  // in memory (issue: 5 M queries took 1.1 GB). The peak is texsim's own (--stats'
  // peak_memory_bytes, VmHWM): a forked child's maxrss would include this test's memory.
  // Streamed (above 48 MiB): 2.4 M and 4.8 M queries, model and RTL. Kept: at most a Request per
  // query (sizeof(Request): 64 bytes) more.
  write_text(dir / "small.csv", random_queries(100000));
  write_text(dir / "kept.csv", random_queries(1000000, 2));
  write_text(dir / "large.csv", random_queries(2400000, 3));
  write_text(dir / "larger.csv", random_queries(4800000, 4));
  ASSERT_GT(fs::file_size(dir / "large.csv"), uint64_t(48) << 20);
  auto peak = [&](const std::string& file, const std::string& engine) -> double {
    const Result r = run("sample -t noise:256x256 -q " + file + " -e " + engine + " -o /dev/null --stats s.json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const double bytes = nlohmann::json::parse(read_text(dir / "s.json")).value("peak_memory_bytes", 0.0);
    EXPECT_GT(bytes, 1e6) << file;
    return bytes;
  };
  for (const std::string engine : {"model", "rtl"}) {
    const double large = peak("large.csv", engine), larger = peak("larger.csv", engine);
    // 2.4 M more queries held in memory would be 2.4 M x (Request + Texel) > 100 MB.
    EXPECT_LT(larger, large + 8e6) << engine << ": " << large << " vs " << larger << " bytes";
  }
  const double small = peak("small.csv", "model"), kept = peak("kept.csv", "model");
  EXPECT_LT(kept, small + 900000 * double(sizeof(tex::Request)) + 8e6) << small << " vs " << kept << " bytes";
}

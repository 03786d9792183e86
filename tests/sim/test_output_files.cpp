// OutputSet (sim/workloads/output_files.h) directly: staging, commit, keep, clean-up, modes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "model/error.h"
#include "workloads/output_files.h"

namespace fs = std::filesystem;
using namespace tex;

namespace {

class OutputSetTest : public ::testing::Test {
 protected:
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("output_set_" + std::to_string(getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  size_t files() const { return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator())); }
  static void put(OutputFile& o, const std::string& text) {
    std::fputs(text.c_str(), o.open());
    o.close();
  }
  static std::string text(const std::string& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  }
};

}  // namespace

TEST_F(OutputSetTest, NothingAppearsBeforeCommitAndAllAtCommit) {
  std::ofstream(path("old.txt")) << "old";
  {
    OutputSet outputs;
    put(outputs.declare(path("a.txt"), "-a"), "A");
    put(outputs.declare(path("old.txt"), "-b"), "B");
    EXPECT_FALSE(fs::exists(path("a.txt")));
    EXPECT_EQ(text(path("old.txt")), "old");
    outputs.commit();
  }
  EXPECT_EQ(text(path("a.txt")), "A");
  EXPECT_EQ(text(path("old.txt")), "B");
  EXPECT_EQ(files(), 2u);
}

TEST_F(OutputSetTest, WithoutCommitNothingIsLeftAndNothingTouched) {
  std::ofstream(path("old.txt")) << "old";
  {
    OutputSet outputs;
    outputs.make_directory(path("new/deeper"), "--dir");
    put(outputs.declare(path("new/deeper/x.txt"), "-x"), "X");
    put(outputs.declare(path("old.txt"), "-b"), "B");
  }
  EXPECT_EQ(text(path("old.txt")), "old");
  EXPECT_FALSE(fs::exists(path("new"))) << "a directory created for the outputs stays behind";
  EXPECT_EQ(files(), 1u);
}

TEST_F(OutputSetTest, KeepRenamesOneOutputAndTheRestGo) {
  {
    OutputSet outputs;
    put(outputs.declare(path("result.csv"), "--out"), "R");
    OutputFile& trace = outputs.declare(path("t.fst"), "--trace", OutputSet::Kind::File);
    EXPECT_FALSE(outputs.keep(trace)) << "an empty staged file is not kept";
    std::ofstream(trace.write_path()) << "waveform";
    EXPECT_TRUE(outputs.keep(trace));
  }
  EXPECT_EQ(text(path("t.fst")), "waveform");
  EXPECT_FALSE(fs::exists(path("result.csv")));
  EXPECT_EQ(files(), 1u);
}

TEST_F(OutputSetTest, ReplacedFileKeepsItsModeAndNewFilesFollowTheUmask) {
  std::ofstream(path("exec.sh")) << "old";
  fs::permissions(path("exec.sh"), fs::perms(0754));
  const mode_t mask = umask(022);
  {
    OutputSet outputs;
    put(outputs.declare(path("exec.sh"), "-a"), "new");
    put(outputs.declare(path("fresh.txt"), "-b"), "new");
    outputs.commit();
  }
  umask(mask);
  struct stat a {}, b {};
  ASSERT_EQ(stat(path("exec.sh").c_str(), &a), 0);
  ASSERT_EQ(stat(path("fresh.txt").c_str(), &b), 0);
  EXPECT_EQ(a.st_mode & 07777, 0754u);
  EXPECT_EQ(b.st_mode & 07777, 0644u);
}

TEST_F(OutputSetTest, RefusalsNameThePathAndTheOption) {
  std::ofstream(path("in.csv")) << "u,v,lod\n";
  OutputSet outputs;
  outputs.add_input(path("in.csv"), "--queries");
  auto error_of = [&](const std::string& p, OutputSet::Kind kind = OutputSet::Kind::Stream) -> std::string {
    try {
      outputs.declare(p, "--out", kind);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of(path("in.csv")).find("is also the input --queries"), std::string::npos);
  EXPECT_NE(error_of(dir.string()).find("is a directory"), std::string::npos);
  EXPECT_NE(error_of(path("no/such/dir/x")).find("does not exist"), std::string::npos);
  EXPECT_NE(error_of("-", OutputSet::Kind::File).find("standard output"), std::string::npos);
  EXPECT_NE(error_of("/dev/null", OutputSet::Kind::File).find("not a regular file"), std::string::npos);
  EXPECT_NE(error_of("").find("empty file name"), std::string::npos);
  outputs.declare(path("x.csv"), "--out");
  EXPECT_NE(error_of(path("./x.csv")).find("is also the output --out"), std::string::npos);
}

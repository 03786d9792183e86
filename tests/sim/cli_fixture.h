// The fixture of the texsim command-line tests: a scratch directory per test, texsim runs with
// captured stdout/stderr, and the check that a bad input fails cleanly.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "workloads/image_module.h"

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void write_text(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

// Image files go through OpenImageIO in texsim's image module (workloads/image_module.h), loaded on
// the first use: the suite's executable does not link OpenImageIO's 260 libraries, which cost every
// test process half a second at start.

// Writes an 8-bit image with `channels` channels, pixel values from `value(x, y, c)`.
template <class F>
void write_image(const fs::path& p, int w, int h, int channels, F value) {
  tex::images::Pixels px{w, h, channels, false, std::vector<uint8_t>(size_t(w) * h * channels)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) px.values[(size_t(y) * w + x) * channels + c] = uint8_t(value(x, y, c));
  std::string error;
  ASSERT_TRUE(tex::images::module().write(p.string(), p.string(), px, error)) << p << ": " << error;
}

// RGBA8 pixels of an image file as stored (no alpha premultiplication); empty when the file is
// unreadable or not RGBA.
inline std::vector<uint8_t> read_image(const fs::path& p, int& w, int& h) {
  tex::images::Pixels px;
  std::string error;
  if (!tex::images::module().read(p.string(), nullptr, 0, UINT64_MAX, px, error) || px.channels != 4) return {};
  w = px.width;
  h = px.height;
  return px.values;
}

inline std::vector<std::vector<int>> read_csv_rows(const fs::path& p, std::string& header) {
  std::istringstream in(read_text(p));
  std::getline(in, header);
  std::vector<std::vector<int>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<int> row;
    std::stringstream ls(line);
    std::string f;
    while (std::getline(ls, f, ',')) row.push_back(std::stoi(f));
    rows.push_back(row);
  }
  return rows;
}

class TexsimCli : public ::testing::Test {
 protected:
  fs::path dir;
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("texsim_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // Runs texsim ARGS in the test's directory; `input` is its standard input. Its default results
  // store (explore) is the test's own, not the user's.
  Result run(const std::string& args, const std::string& input = "/dev/null") {
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string cmd = "cd '" + dir.string() + "' && TEXSIM_STORE='" + (dir / "store").string() + "' timeout 300 '" +
                            std::string(TEXSIM_PATH) + "' " + args + " > '" +
                            out.string() + "' 2> '" + err.string() + "' < '" + input + "'";
    const int status = std::system(cmd.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  // A bad input: non-zero exit, exactly one line on stderr that contains every `needles`, and
  // neither the output file nor any *.partial* file in the directory.
  void expect_clean_failure(const std::string& args, const std::string& output,
                            const std::vector<std::string>& needles) {
    const Result r = run(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\nstderr: " << r.err;
    EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << "stderr: " << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' missing in: " << r.err;
    EXPECT_FALSE(fs::exists(dir / output)) << args << " left " << output << " behind";
    for (const auto& e : fs::recursive_directory_iterator(dir))
      EXPECT_EQ(e.path().filename().string().find("partial"), std::string::npos) << "left " << e.path();
  }

  void queries(const std::string& text) { write_text(dir / "q.csv", text); }
};


// What every fuzz target shares (tests/fuzz/README.md): the input as a file of its own, and the
// error contract checked on every input. A target's input either parses or throws tex::Error
// whose message is one non-empty line naming the file; anything else (a crash, a sanitizer
// report, another exception, a message of several lines or none) is a finding.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/error.h"

namespace tex::fuzz {

// Writes the input to `name` in a folder of this process's own (under $TMPDIR or /tmp) and returns
// its path: the parsers under test read files, as texsim does.
inline std::string input_file(const uint8_t* data, size_t size, const std::string& name) {
  struct Folder {  // removed at exit
    std::filesystem::path path;
    Folder() {
      const char* tmp = std::getenv("TMPDIR");
      path = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / ("texsim-fuzz-" + std::to_string(::getpid()));
      std::filesystem::create_directories(path);
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  const std::filesystem::path path = folder.path / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path.string();
}

// The one-line error contract: a message that breaks it aborts (a finding, like a crash).
// TEXSIM_FUZZ_VERBOSE set: each message printed (a replay shows which seeds parse).
inline void check_error(const Error& e, const std::string& path) {
  const std::string what = e.what();
  if (std::getenv("TEXSIM_FUZZ_VERBOSE")) std::fprintf(stderr, "  error: %s\n", what.c_str());
  const char* broken = what.empty()                                ? "an empty message"
                       : what.find('\n') != std::string::npos      ? "a message of several lines"
                       : what.find(path) == std::string::npos      ? "a message that does not name the file"
                                                                   : nullptr;
  if (!broken) return;
  std::fprintf(stderr, "fuzz: %s: \"%s\" (file %s)\n", broken, what.c_str(), path.c_str());
  std::abort();
}

}  // namespace tex::fuzz

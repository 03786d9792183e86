// One exception type for bad input: its message is the one-line error the user sees.
#pragma once
#include <stdexcept>
#include <string>

namespace tex {
struct Error : std::runtime_error {
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};
}  // namespace tex

#include "workloads/text.h"

namespace tex {

std::string quote_clipped(std::string_view text) {
  constexpr size_t kMax = 80;
  if (text.size() <= kMax) return "\"" + std::string(text) + "\"";
  return "\"" + std::string(text.substr(0, kMax - 3)) + "...\" (" + std::to_string(text.size()) + " characters)";
}

}  // namespace tex

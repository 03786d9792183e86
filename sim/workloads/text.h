// Small text helpers shared by every error message of the simulator.
#pragma once
#include <string>
#include <string_view>

namespace tex {

// At most ~80 characters of `text`, quoted, for error messages.
std::string quote_clipped(std::string_view text);

}  // namespace tex

// Small text helpers shared by every error message and list option of the simulator.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace tex {

// At most ~80 characters of `text`, quoted, for error messages.
std::string quote_clipped(std::string_view text);

// The comma-separated items of an option's list (--texture-layers, --cube, --envmap), empty ones kept.
std::vector<std::string> split_commas(std::string_view text);

}  // namespace tex

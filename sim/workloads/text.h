// Small text helpers shared by every error message and list option of the simulator.
#pragma once
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace tex {

// At most ~80 characters of `text`, quoted, for error messages: control characters written as
// escapes (\n, \t, \xNN), so that text from a file never breaks the message's one line.
std::string quote_clipped(std::string_view text);
// The same between single quotes (names from model files: meshes, materials).
std::string quote_name(std::string_view text);

// The comma-separated items of an option's list (--texture-layers, --cube, --envmap), empty ones kept.
std::vector<std::string> split_commas(std::string_view text);

// Reads the next line of a text file (without its '\n') into `line`; false at the end. A line
// of more than `max_bytes` is not read into memory: tex::Error "WHERE:LINE: line longer than
// MAX bytes", `where` naming the file. A NUL byte: tex::Error "...: a NUL byte (not a text file)".
// `line_no` counts the lines read.
bool read_text_line(std::istream& in, std::string& line, size_t max_bytes, const std::string& where, int& line_no);

}  // namespace tex

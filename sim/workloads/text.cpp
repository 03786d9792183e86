#include "workloads/text.h"

#include "model/error.h"

namespace tex {

namespace {

std::string escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7F) {
      const char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

std::string clipped(std::string_view text, char quote) {
  constexpr size_t kMax = 80;
  const std::string q(1, quote);
  if (text.size() <= kMax) return q + escaped(text) + q;
  return q + escaped(text.substr(0, kMax - 3)) + "..." + q + " (" + std::to_string(text.size()) + " characters)";
}

}  // namespace

std::string quote_clipped(std::string_view text) { return clipped(text, '"'); }
std::string quote_name(std::string_view text) { return clipped(text, '\''); }

std::vector<std::string> split_commas(std::string_view text) {
  std::vector<std::string> out;
  for (size_t at = 0;;) {
    const size_t comma = text.find(',', at);
    out.emplace_back(text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
    if (comma == std::string_view::npos) return out;
    at = comma + 1;
  }
}

bool read_text_line(std::istream& in, std::string& line, size_t max_bytes, const std::string& where, int& line_no) {
  line.clear();
  if (!in.good()) return false;
  const auto at = [&] { return where + ":" + std::to_string(line_no) + ": "; };
  ++line_no;
  for (char c; in.get(c);) {
    if (c == '\n') return true;
    if (c == '\0') throw Error(at() + "a NUL byte (not a text file)");
    if (line.size() == max_bytes) throw Error(at() + "line longer than " + std::to_string(max_bytes) + " bytes");
    line.push_back(c);
  }
  if (in.bad()) throw Error(where + ": cannot read");
  if (line.empty()) --line_no;  // (the end, after a last '\n')
  return !line.empty();
}

}  // namespace tex

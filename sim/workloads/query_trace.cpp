#include "workloads/query_trace.h"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "model/error.h"

namespace tex {

namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Splits at commas into at most `max` fields (one more means "too many"); returns the count.
int split(std::string_view line, std::string_view* fields, int max) {
  int n = 0;
  for (;;) {
    const auto comma = line.find(',');
    if (n == max) return n + 1;
    fields[n++] = trim(line.substr(0, comma));
    if (comma == std::string_view::npos) return n;
    line.remove_prefix(comma + 1);
  }
}

}  // namespace

std::string quote_clipped(std::string_view text) {
  constexpr size_t kMax = 80;
  if (text.size() <= kMax) return "\"" + std::string(text) + "\"";
  return "\"" + std::string(text.substr(0, kMax - 3)) + "...\" (" + std::to_string(text.size()) + " characters)";
}

QueryReader::QueryReader(const std::string& path) : name_(path == "-" ? "standard input" : path) {
  if (path == "-") {
    file_ = stdin;
  } else {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw Error(path + ": cannot open query file (" + std::strerror(errno) + ")");
    owned_ = true;
    struct stat st {};
    if (::fstat(fileno(file_), &st) == 0 && S_ISDIR(st.st_mode)) {
      std::fclose(file_);
      throw Error(path + ": is a directory, not a query file");
    }
    rewindable_ = S_ISREG(st.st_mode);
  }
}

QueryReader::~QueryReader() {
  if (owned_) std::fclose(file_);
  std::free(buf_);
}

void QueryReader::rewind() {
  std::rewind(file_);
  line_no_ = columns_ = 0;
}

bool QueryReader::next_line(std::string_view& line) {
  errno = 0;
  const ssize_t n = ::getline(&buf_, &cap_, file_);
  if (n < 0) {
    if (std::ferror(file_)) throw Error(name_ + ": cannot read (" + std::strerror(errno) + ")");
    return false;
  }
  ++line_no_;
  line = std::string_view(buf_, size_t(n));
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  if (line_no_ == 1) {
    if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 byte-order mark
    if (line.substr(0, 2) == "\xFF\xFE" || line.substr(0, 2) == "\xFE\xFF")
      throw Error(name_ + ":1: the file is UTF-16; save it as UTF-8 or ASCII");
  }
  if (std::memchr(line.data(), '\0', line.size()))
    throw Error(name_ + ":" + std::to_string(line_no_) + ": NUL byte in the line (a binary file, not CSV?)");
  return true;
}

bool QueryReader::next(Query& q) {
  std::string_view raw;
  while (next_line(raw)) {
    const std::string_view line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string at = name_ + ":" + std::to_string(line_no_) + ": ";
    std::string_view f[7];
    const int n = split(line, f, 6);
    if (columns_ == 0) {
      std::string header;
      for (int i = 0; i < std::min(n, 6); ++i) header += (i ? "," : "") + std::string(f[i]);
      if (header == "u,v,lod") columns_ = 3;
      else if (header == "u,v,dudx,dvdx,dudy,dvdy" && n == 6) columns_ = 6;
      else throw Error(at + "unknown header " + quote_clipped(line) + " (expected u,v,lod or u,v,dudx,dvdx,dudy,dvdy)");
      continue;
    }
    if (n != columns_)
      throw Error(at + "expected " + std::to_string(columns_) + " values, got " + (n > 6 ? "more" : std::to_string(n)) +
                  ": " + quote_clipped(line));
    double v[6];
    for (int i = 0; i < columns_; ++i) {
      std::string_view s = f[i];
      if (!s.empty() && s[0] == '+') s.remove_prefix(1);
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v[i]);
      // The whole line is quoted if it is short; otherwise the bad value alone.
      const std::string shown = line.size() <= 80 ? quote_clipped(line) : quote_clipped(f[i]);
      if (f[i].empty() || (ec != std::errc() && ec != std::errc::result_out_of_range) || end != s.data() + s.size())
        throw Error(at + "value " + std::to_string(i + 1) + " is not a number: " + shown);
      if (ec == std::errc::result_out_of_range || !std::isfinite(v[i]))
        throw Error(at + "value " + std::to_string(i + 1) + " is not finite: " + shown);
    }
    q = Query{};
    q.line = line_no_;
    q.u = v[0];
    q.v = v[1];
    q.explicit_lod = columns_ == 3;
    if (q.explicit_lod) q.lod = v[2];
    else q.deriv = {v[2], v[3], v[4], v[5]};
    return true;
  }
  if (columns_ == 0) throw Error(name_ + ": no header line (expected u,v,lod or u,v,dudx,dvdx,dudy,dvdy)");
  return false;
}

Request to_request(const Query& q, const std::string& name, uint32_t tag) {
  Request r;
  r.tag = tag;
  auto at = [&] { return name + ":" + std::to_string(q.line) + ": "; };
  if (!to_coord_fixed(q.u, r.u)) throw Error(at() + "u = " + std::to_string(q.u) + " is outside [-128, 128)");
  if (!to_coord_fixed(q.v, r.v)) throw Error(at() + "v = " + std::to_string(q.v) + " is outside [-128, 128)");
  if (q.explicit_lod) {
    if (!to_lod_fixed(q.lod, r.lod)) throw Error(at() + "lod = " + std::to_string(q.lod) + " is outside [-128, 128)");
  } else {
    if (!to_lod_derivatives(q.deriv, r.deriv)) throw Error(at() + "a derivative is not a finite number");
    r.has_derivatives = true;
  }
  return r;
}

std::vector<Request> to_requests(const std::vector<Query>& queries, const std::string& name) {
  std::vector<Request> out;
  out.reserve(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) out.push_back(to_request(queries[i], name, uint32_t(i)));
  return out;
}

size_t QuerySource::read(Request* out, size_t max) {
  size_t n = 0;
  Query q;
  while (n < max && reader_.next(q)) {
    out[n] = to_request(q, reader_.name(), uint32_t(count_));
    ++n;
    ++count_;
  }
  return n;
}

CsvTexelWriter::CsvTexelWriter(std::FILE* out) : out_(out) { std::fputs("r,g,b,a\n", out_); }

void CsvTexelWriter::write(const Texel* texels, size_t n) {
  char buf[4096 + 32];
  size_t len = 0;
  auto put = [&](unsigned v, char end) {  // a channel: at most 5 digits
    char digits[8];
    int k = 0;
    do {
      digits[k++] = char('0' + v % 10);
      v /= 10;
    } while (v != 0 && k < 5);
    while (k > 0) buf[len++] = digits[--k];
    buf[len++] = end;
  };
  for (size_t i = 0; i < n; ++i) {
    const Texel& t = texels[i];
    put(t[0], ',');
    put(t[1], ',');
    put(t[2], ',');
    put(t[3], '\n');
    if (len > 4096) {
      std::fwrite(buf, 1, len, out_);
      len = 0;
    }
  }
  std::fwrite(buf, 1, len, out_);
}

}  // namespace tex

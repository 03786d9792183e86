#include "workloads/query_trace.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.h"

namespace tex {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) out.push_back(trim(field));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::string where(const std::string& name, int line) {
  return name + ":" + std::to_string(line) + ": ";
}

double parse_number(const std::string& field, const std::string& name, int line, const std::string& text) {
  const char* s = field.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  if (field.empty() || end == s || *end != '\0')
    throw Error(where(name, line) + "'" + field + "' is not a number in \"" + text + "\"");
  if (!std::isfinite(v) || errno == ERANGE)
    throw Error(where(name, line) + "'" + field + "' is not finite in \"" + text + "\"");
  return v;
}

}  // namespace

std::vector<Query> parse_queries(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  int columns = 0;
  std::vector<Query> out;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const auto fields = split(line);
    if (columns == 0) {
      std::string header;
      for (const auto& f : fields) header += (header.empty() ? "" : ",") + f;
      if (header == "u,v,lod") columns = 3;
      else if (header == "u,v,dudx,dvdx,dudy,dvdy") columns = 6;
      else
        throw Error(where(name, line_no) + "unknown header \"" + line +
                    "\" (expected u,v,lod or u,v,dudx,dvdx,dudy,dvdy)");
      continue;
    }
    if (int(fields.size()) != columns)
      throw Error(where(name, line_no) + "expected " + std::to_string(columns) + " values, got " +
                  std::to_string(fields.size()) + " in \"" + line + "\"");
    double v[6];
    for (int i = 0; i < columns; ++i) v[i] = parse_number(fields[i], name, line_no, line);
    Query q;
    q.line = line_no;
    q.u = v[0];
    q.v = v[1];
    q.explicit_lod = columns == 3;
    if (q.explicit_lod) q.lod = v[2];
    else q.deriv = {v[2], v[3], v[4], v[5]};
    out.push_back(q);
  }
  if (columns == 0) throw Error(name + ": no header line (expected u,v,lod or u,v,dudx,dvdx,dudy,dvdy)");
  return out;
}

std::vector<Query> read_queries(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot open query file");
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw Error(path + ": cannot read query file");
  return parse_queries(ss.str(), path);
}

std::vector<Request> to_requests(const std::vector<Query>& queries, int log2_w0, int log2_h0,
                                 const std::string& name) {
  std::vector<Request> out;
  out.reserve(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    Request r;
    r.tag = uint32_t(i);
    const std::string at = name + ":" + std::to_string(q.line) + ": ";
    if (!to_coord_fixed(q.u, r.u)) throw Error(at + "u = " + std::to_string(q.u) + " is outside [-128, 128)");
    if (!to_coord_fixed(q.v, r.v)) throw Error(at + "v = " + std::to_string(q.v) + " is outside [-128, 128)");
    if (q.explicit_lod) {
      if (!to_lod_fixed(q.lod, r.lod)) throw Error(at + "lod = " + std::to_string(q.lod) + " is outside [-128, 128)");
    } else if (!lod_from_derivatives(q.deriv, log2_w0, log2_h0, r.lod)) {
      throw Error(at + "a derivative is 32768 texels or more");
    }
    out.push_back(r);
  }
  return out;
}

std::string format_results(const std::vector<Texel>& texels) {
  std::string s = "r,g,b,a\n";
  s.reserve(texels.size() * 16 + 8);
  char buf[64];
  for (const Texel& t : texels) {
    const int n = std::snprintf(buf, sizeof buf, "%u,%u,%u,%u\n", t[0], t[1], t[2], t[3]);
    s.append(buf, size_t(n));
  }
  return s;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  const std::string tmp = path + ".partial";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error(path + ": cannot write (" + std::strerror(errno) + ")");
    f << content;
    f.close();
    if (!f) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Error(path + ": write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw Error(path + ": cannot rename into place");
  }
}

}  // namespace tex

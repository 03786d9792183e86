// Query traces (CSV in) and results (CSV out), streamed: memory does not grow with the trace.
#pragma once
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "engines/engine.h"
#include "model/lod.h"
#include "model/sampler.h"

namespace tex {

struct Query {
  double u = 0, v = 0;
  bool explicit_lod = true;
  double lod = 0;     // levels, when explicit_lod
  Derivatives deriv;  // otherwise
  int line = 0;       // line number in the file, for error messages
};

// Reads a query trace line by line. Header `u,v,lod` or `u,v,dudx,dvdx,dudy,dvdy`; `#` lines are
// comments, blank lines are skipped; a UTF-8 byte-order mark is skipped. A file with only the
// header has no queries (not an error). Throws tex::Error naming the file, the line number and
// the text of a bad line (quoted once, at most 80 characters): no header, a NUL byte (a binary
// file), UTF-16, a wrong number of values, a value that is not a finite number.
class QueryReader {
 public:
  explicit QueryReader(const std::string& path);  // "-" = standard input
  ~QueryReader();
  QueryReader(const QueryReader&) = delete;
  QueryReader& operator=(const QueryReader&) = delete;

  bool next(Query& q);  // false at the end
  const std::string& name() const { return name_; }
  // True for a regular file: it can be read twice (a check pass before the work).
  bool rewindable() const { return rewindable_; }
  void rewind();

 private:
  bool next_line(std::string_view& line);
  std::string name_;
  std::FILE* file_ = nullptr;
  bool owned_ = false, rewindable_ = false;
  char* buf_ = nullptr;
  size_t cap_ = 0;
  int line_no_ = 0, columns_ = 0;
};

// The queries of a reader as the hardware's fixed-point requests (tag = index), for the engines.
// Throws tex::Error for a value out of the fixed-point range, naming the line.
class QuerySource final : public RequestSource {
 public:
  explicit QuerySource(QueryReader& reader) : reader_(reader) {}
  size_t read(Request* out, size_t max) override;
  size_t count() const { return count_; }

 private:
  QueryReader& reader_;
  size_t count_ = 0;
};

Request to_request(const Query& q, const std::string& name, uint32_t tag);
std::vector<Request> to_requests(const std::vector<Query>& queries, const std::string& name);

// Writes `r,g,b,a` then one line per texel.
class CsvTexelWriter final : public TexelSink {
 public:
  explicit CsvTexelWriter(std::FILE* out);
  void write(const Texel* texels, size_t n) override;

 private:
  std::FILE* out_;
};

// At most ~80 characters of `text`, quoted, for error messages.
std::string quote_clipped(std::string_view text);

}  // namespace tex

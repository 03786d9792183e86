// Query traces (CSV in) and results (CSV out), streamed: memory does not grow with the trace.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "engines/engine.h"
#include "model/lod.h"
#include "model/sampler.h"
#include "workloads/text.h"

namespace tex {

struct Query {
  double u = 0, v = 0;
  bool explicit_lod = true;
  double lod = 0;     // levels, when explicit_lod
  Derivatives deriv;  // otherwise
  int line = 0;       // line number in the file, for error messages
  // Real frames (docs/scenes.md): the descriptor-table entry sampled, the 2x2 quad the query
  // belongs to (numbered in issue order), its pixel, and whether it is a helper lane (sampled
  // for the quad's derivatives, its result not drawn).
  int texture = 0;
  uint32_t quad = 0;
  int x = -1, y = -1;
  bool helper = false;
};

// The trace of a rendered frame (texsim render --trace-queries): texture id, u, v, the quad's four
// derivatives, the quad number, the pixel and the helper flag (0 or 1) of every request.
constexpr const char* kFrameTraceHeader = "tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper";

// Reads a query trace line by line. Header `u,v,lod` or `u,v,dudx,dvdx,dudy,dvdy`, either with a
// leading `tex` column (the descriptor-table entry, 0..15), or kFrameTraceHeader; `#` lines are
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
  // True for a regular file: it can be read twice (check_query_file before the work).
  bool rewindable() const { return rewindable_; }

 private:
  friend void check_query_file(const std::string& path, unsigned threads);
  // The lines of bytes [begin, end) of `header`'s file (begin is the start of a line after the
  // header), numbered as in the whole file: one part of a parallel check pass.
  QueryReader(const QueryReader& header, uint64_t begin, uint64_t end);
  void read_header();       // reads up to and including the header line
  uint64_t offset() const;  // the file offset of the next unread byte
  bool next_line(std::string_view& line);
  static bool parse_values(std::string_view line, int columns, double* v);
  void parse_values_checked(std::string_view line, double* v);
  std::string name_, path_;
  std::FILE* file_ = nullptr;
  bool owned_ = false, rewindable_ = false;
  std::vector<char> buf_;      // [begin_, end_): read, not yet split into lines
  size_t begin_ = 0, end_ = 0;
  uint64_t file_pos_ = 0, file_end_ = UINT64_MAX;  // offset of buf_[end_]; where reading stops
  bool eof_ = false;
  int line_no_ = 0, columns_ = 0;
  bool texture_ = false, lod_ = false, quad_ = false;  // the header's columns
};

// What a frame's queries ask for (texsim's frame figures): quads are runs of one quad number.
struct QueryCounts {
  uint64_t samples = 0, quads = 0, helper_samples = 0;
  uint32_t textures_used = 0;  // bit t: texture t was sampled
  void add(const Query& q);

 private:
  uint32_t last_quad_ = 0;
};

// The queries of a reader as the hardware's fixed-point requests (tag = index), for the engines.
// Throws tex::Error for a value out of the fixed-point range, naming the line.
class QuerySource final : public RequestSource {
 public:
  explicit QuerySource(QueryReader& reader) : reader_(reader) {}
  size_t read(Request* out, size_t max) override;
  size_t count() const { return count_; }
  const QueryCounts& counts() const { return counts_; }

 private:
  QueryReader& reader_;
  size_t count_ = 0;
  QueryCounts counts_;
};

// The check pass over a regular query file before the work: every line read and converted as the
// engines will, the file cut at line starts into `threads` parts checked in parallel. Throws the
// error of the file's first bad line (the same message a single pass gives).
void check_query_file(const std::string& path, unsigned threads);

Request to_request(const Query& q, const std::string& name, uint32_t tag);
std::vector<Request> to_requests(const std::vector<Query>& queries, const std::string& name);

// Writes kFrameTraceHeader, then one line per query (doubles in their shortest exact form).
class QueryTraceWriter {
 public:
  explicit QueryTraceWriter(std::FILE* out);
  void write(const Query& q);
  void comment(const std::string& text);  // a `# text` line

 private:
  std::FILE* out_;
};

// Writes `header` (`r,g,b,a`; `r16,g16,b16,a16` for linear unorm16 results of sRGB textures) then
// one line per texel.
class CsvTexelWriter final : public TexelSink {
 public:
  explicit CsvTexelWriter(std::FILE* out, const char* header = "r,g,b,a");
  void write(const Texel* texels, size_t n) override;

 private:
  std::FILE* out_;
};

}  // namespace tex

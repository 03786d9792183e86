// Query traces (CSV in) and results (CSV out), streamed: memory does not grow with the trace.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <string_view>
#include <vector>

#include "engines/streams.h"
#include "model/lod.h"
#include "model/sampler.h"
#include "workloads/text.h"

namespace tex {

struct Query {
  bool fetch = false;  // a texel fetch (header i,j,level): u, v, lod hold the integers i, j, level
  bool gather = false; // a gather (header u,v): u, v alone
  double u = 0, v = 0;
  double layer = 0;   // an array texture's layer coordinate (a `layer` column; a fetch's: a whole number)
  bool compare = false;  // a depth compare (a `ref` column after u,v[,layer])
  bool cube = false;     // a cube map's direction (x, y, z) = (u, v, w) (an x,y,z header)
  double w = 0;
  double dwdx = 0, dwdy = 0;  // with derivatives: dz/dx, dz/dy (deriv: dx/dx, dy/dx, dx/dy, dy/dy)
  double ref = 0;        // its reference depth, 0..1 (clamped by the unit)
  bool explicit_lod = true;
  double lod = 0;     // levels, when explicit_lod
  Derivatives deriv;  // otherwise
  double bias = 0;    // levels: the request's own LOD bias (a `bias` column after the derivatives)
  int line = 0;       // line number in the file, for error messages
  // Real frames (docs/scenes.md): the descriptor-table entry sampled, the 2x2 quad the query
  // belongs to (numbered in issue order), its pixel, and whether it is a helper lane (sampled
  // for the quad's derivatives, its result not drawn).
  int texture = 0;
  int sampler = -1;   // the sampler-table entry; -1 (no `smp` column): the texture's own, entry `texture`
  uint32_t quad = 0;
  int x = -1, y = -1;
  bool helper = false;
};

// The trace of a rendered frame (texsim render --trace-queries): texture id, u, v, the quad's four
// derivatives, the quad number, the pixel and the helper flag (0 or 1) of every request.
constexpr const char* kFrameTraceHeader = "tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper";

// Reads a query trace line by line. Header `u,v,lod` or `u,v,dudx,dvdx,dudy,dvdy`, either with a
// leading `tex` column (the descriptor-table entry, 0..15) or `tex,smp` columns (and the
// sampler-table entry, 0..15), the derivative forms optionally with a trailing `bias` column (the
// request's own LOD bias in levels, GLSL texture(s, uv, bias)), or kFrameTraceHeader; texel
// fetches: `i,j,level` (whole numbers: i, j 32-bit, level 16-bit), gathers `u,v`, each also with
// `tex` or `tex,smp`; each but the frame trace with a `layer` column after u,v (i,j): an array
// texture's layer coordinate (Q16.16 when converted; a fetch's a whole number), and each sample form
// with a `ref` column after those: a depth compare's reference (Q8.24); `#` lines are
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
  // The header's operation (it reads the header if not yet read): Op::Fetch for i,j,level,
  // Op::Gather for u,v, Op::Compare with a ref column.
  Op op();
  bool cube();  // the header is a cube map's (x,y,z)
  std::string header() const { return header_; }  // (after op() or next())
  // True for a regular file: it can be read twice (QueryFileParser before the work).
  bool rewindable() const { return rewindable_; }

 private:
  friend class QueryFileParser;
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
  bool texture_ = false, sampler_ = false, lod_ = false, bias_ = false, quad_ = false, fetch_ = false, gather_ = false,
       layer_ = false, ref_ = false, cube_ = false;  // the header's columns
  std::string header_;
};

// What a frame's queries ask for (texsim's frame figures): quads are runs of one quad number.
struct QueryCounts {
  uint64_t samples = 0, quads = 0, helper_samples = 0;
  uint32_t textures_used = 0;  // bit t: texture t was sampled
  void add(const Query& q);
  // The counts of the queries that follow these (a quad cut in two counts once).
  void append(const QueryCounts& later);

 private:
  uint32_t first_quad_ = 0, last_quad_ = 0;
};

// Which samplers of a table take unnormalized coordinates: bit s for entry s. A query of such a
// sampler gives u, v in texels of the texture's level 0 (signed Q16.16), any other in texture
// widths (Q8.24); derivatives are texture widths per pixel either way.
uint32_t unnormalized_samplers(const SamplerTable& samplers);

// How queries become requests: which samplers take texel coordinates (unnormalized_samplers), and
// the component a gather query (header u,v) gathers.
struct QueryForm {
  uint32_t unnormalized = 0;
  uint8_t component = 0;
  uint32_t no_compare = 0;  // bit s: sampler s takes no depth compare (SamplerConfig::compare_problem)
};

// The queries of a reader as the hardware's fixed-point requests (tag = index), for the engines.
// Throws tex::Error for a value out of the fixed-point range, naming the line.
class QuerySource final : public RequestSource {
 public:
  explicit QuerySource(QueryReader& reader, QueryForm form = {}) : reader_(reader), form_(form) {}
  size_t read(Request* out, size_t max) override;
  size_t count() const { return count_; }
  const QueryCounts& counts() const { return counts_; }

 private:
  QueryReader& reader_;
  QueryForm form_;
  size_t count_ = 0;
  QueryCounts counts_;
};

// The check pass over a regular query file: every line read and converted as the engines will,
// the file cut at line starts into parts parsed by threads of their own, started by the
// constructor. wait() returns when all are done and throws the error of the file's first bad
// line (the same message a single pass gives).
// With `keep`, a file of at most kMaxFileBytes also keeps its requests (tag = index, in file
// order) and read() hands them out while the parse goes on: the engine works on the first ones
// as the threads convert the rest, and the file is parsed once. read() throws the file's first
// bad line as soon as a thread finds it (and the threads before it are done), wherever the
// engine is. Longer files keep nothing: the caller checks them with wait(), then streams them
// in constant memory.
class QueryFileParser final : public RequestSource {
 public:
  // About 2 M `u,v,lod` queries, 80 MB of requests.
  static constexpr uint64_t kMaxFileBytes = uint64_t(48) << 20;
  QueryFileParser(const std::string& path, unsigned threads, bool keep, QueryForm form = {});
  ~QueryFileParser() override;  // (stops the threads)
  QueryFileParser(const QueryFileParser&) = delete;
  QueryFileParser& operator=(const QueryFileParser&) = delete;

  void wait();
  bool kept() const { return keep_; }
  size_t read(Request* out, size_t max) override;
  // After wait(), or after read() returned 0:
  size_t count() const;
  const QueryCounts& counts() const { return counts_; }
  double parse_seconds() const { return parse_seconds_; }  // start to the last part's end

 private:
  struct Part;
  void parse(size_t k);
  void finish_locked();  // the totals, once every part is done
  std::unique_ptr<QueryReader> first_;  // (part 0's reader, past the header)
  bool keep_ = false;
  QueryForm form_;
  std::vector<std::unique_ptr<Part>> parts_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stop_ = false;
  size_t parts_done_ = 0;
  QueryCounts counts_;
  double parse_seconds_ = 0;
  std::chrono::steady_clock::time_point start_;
  size_t part_ = 0, at_ = 0, part_base_ = 0;  // read()'s position
};

// QueryFileParser(path, threads, false).wait(): the check pass alone.
void check_query_file(const std::string& path, unsigned threads);

Request to_request(const Query& q, const std::string& name, uint32_t tag, QueryForm form = {});
std::vector<Request> to_requests(const std::vector<Query>& queries, const std::string& name, QueryForm form = {});
// A frame's queries (coordinates in texture widths, as a rasterizer interpolates them) for the
// table's samplers: those of an unnormalized sampler scaled to texels of their texture's level 0
// (sizes[t]), as a shader computes a rectangle texture's coordinates, within +-2n texels (the
// clamping modes read the same taps beyond).
std::vector<Query> in_sampler_coordinates(std::vector<Query> queries, const SamplerTable& samplers,
                                          const std::vector<Extent>& sizes);

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
  std::vector<char> buffer_;  // a run of formatted lines
};

}  // namespace tex

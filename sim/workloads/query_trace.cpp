#include "workloads/query_trace.h"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <thread>

#include "model/error.h"
#include "model/huge_pages.h"

namespace tex {

namespace {

// (Plain loops: find_first_not_of calls memchr on its set for every character, a tenth of the
// parse of a line.)
bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
std::string_view trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && blank(s[b])) ++b;
  while (e > b && blank(s[e - 1])) --e;
  return s.substr(b, e - b);
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

QueryReader::QueryReader(const std::string& path) : name_(path == "-" ? "standard input" : path), path_(path) {
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

namespace {

// Line breaks in the first `bytes` bytes of `file` (read from its start).
int count_lines(std::FILE* file, uint64_t bytes, const std::string& name) {
  std::vector<char> buf(size_t(1) << 20);
  int lines = 0;
  std::rewind(file);
  while (bytes > 0) {
    const size_t n = std::fread(buf.data(), 1, size_t(std::min<uint64_t>(bytes, buf.size())), file);
    if (n == 0) throw Error(name + ": cannot read (" + std::strerror(errno) + ")");
    lines += int(std::count(buf.data(), buf.data() + n, '\n'));
    bytes -= n;
  }
  return lines;
}

}  // namespace

QueryReader::QueryReader(const QueryReader& header, uint64_t begin, uint64_t end) : QueryReader(header.path_) {
  line_no_ = count_lines(file_, begin, name_);
  if (std::fseek(file_, long(begin), SEEK_SET) != 0) throw Error(name_ + ": cannot seek (" + std::strerror(errno) + ")");
  file_pos_ = begin;
  file_end_ = end;
  columns_ = header.columns_;
  texture_ = header.texture_;
  sampler_ = header.sampler_;
  bias_ = header.bias_;
  lod_ = header.lod_;
  quad_ = header.quad_;
}

uint64_t QueryReader::offset() const { return file_pos_ - (end_ - begin_); }

QueryReader::~QueryReader() {
  if (owned_) std::fclose(file_);
}

// Lines come out of a large buffer (1 MiB, grown for a longer line): no read call and no copy per line.
bool QueryReader::next_line(std::string_view& line) {
  if (buf_.empty()) buf_.resize(size_t(1) << 20);  // (memchr and memmove take no null pointer, even for 0 bytes)
  for (;;) {
    const char* at = buf_.data() + begin_;
    if (const void* nl = std::memchr(at, '\n', end_ - begin_)) {
      line = std::string_view(at, size_t(static_cast<const char*>(nl) - at));
      begin_ += line.size() + 1;
      break;
    }
    if (eof_) {
      if (begin_ == end_) return false;
      line = std::string_view(at, end_ - begin_);  // the last line has no line break
      begin_ = end_;
      break;
    }
    // Keep the partial line, then read more after it.
    std::memmove(buf_.data(), at, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
    if (end_ == buf_.size())  // (a line is a few numbers: the buffer never grows)
      throw Error(name_ + ":" + std::to_string(line_no_ + 1) + ": a line longer than " +
                  std::to_string(buf_.size() >> 20) + " MiB (not a query trace?)");
    errno = 0;
    const size_t want = size_t(std::min<uint64_t>(buf_.size() - end_, file_end_ - file_pos_));
    const size_t n = want ? std::fread(buf_.data() + end_, 1, want, file_) : 0;
    if (n == 0) {
      if (std::ferror(file_)) throw Error(name_ + ": cannot read (" + std::strerror(errno) + ")");
      eof_ = true;
    }
    end_ += n;
    file_pos_ += n;
  }
  ++line_no_;
  if (line_no_ == 1) {
    if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 byte-order mark
    if (line.substr(0, 2) == "\xFF\xFE" || line.substr(0, 2) == "\xFE\xFF")
      throw Error(name_ + ":1: the file is UTF-16; save it as UTF-8 or ASCII");
  }
  if (std::memchr(line.data(), '\0', line.size()))
    throw Error(name_ + ":" + std::to_string(line_no_) + ": NUL byte in the line (a binary file, not CSV?)");
  return true;
}

namespace {

// The headers a trace may have: the columns, in order.
struct TraceFormat {
  const char* header;
  // a tex column; a smp column; u,v,lod (else the four derivatives); a bias column; quad,x,y,helper;
  // i,j,level (a texel fetch, in place of u,v,lod); u,v alone (a gather); a layer column after u,v
  // (i,j) (an array texture's layer) and a ref column after those (a depth compare's reference):
  // layered_formats; a cube's x,y,z direction in place of u,v and its six derivatives
  bool texture, sampler, lod, bias, quad, fetch = false, gather = false, layer = false, ref = false, cube = false;
};
constexpr TraceFormat kFormats[] = {
    {"u,v,lod", false, false, true, false, false},
    {"u,v,dudx,dvdx,dudy,dvdy", false, false, false, false, false},
    {"u,v,dudx,dvdx,dudy,dvdy,bias", false, false, false, true, false},
    {"tex,u,v,lod", true, false, true, false, false},
    {"tex,u,v,dudx,dvdx,dudy,dvdy", true, false, false, false, false},
    {"tex,u,v,dudx,dvdx,dudy,dvdy,bias", true, false, false, true, false},
    {"tex,smp,u,v,lod", true, true, true, false, false},
    {"tex,smp,u,v,dudx,dvdx,dudy,dvdy", true, true, false, false, false},
    {"tex,smp,u,v,dudx,dvdx,dudy,dvdy,bias", true, true, false, true, false},
    {kFrameTraceHeader, true, false, false, false, true},
    {"i,j,level", false, false, true, false, false, true},
    {"tex,i,j,level", true, false, true, false, false, true},
    {"tex,smp,i,j,level", true, true, true, false, false, true},
    {"u,v", false, false, false, false, false, false, true},
    {"tex,u,v", true, false, false, false, false, false, true},
    {"tex,smp,u,v", true, true, false, false, false, false, true},
};
constexpr int kMaxColumns = 14;  // tex,smp,x,y,z,layer,ref,dxdx,dydx,dzdx,dxdy,dydy,dzdy,bias

// kFormats and, for each but the frame trace, its forms with a layer column after u,v (i,j), and
// for a sample's a ref column after those (a depth compare); and each form of u,v as a cube map's
// x,y,z (its derivatives dxdx,dydx,dzdx,dxdy,dydy,dzdy).
struct NamedFormat {
  std::string header;
  TraceFormat format;
};
const std::vector<NamedFormat>& layered_formats() {
  static const std::vector<NamedFormat> all = [] {
    std::vector<NamedFormat> out;
    for (const TraceFormat& f : kFormats) {
      out.push_back({f.header, f});
      if (f.quad) continue;
      for (int layer = 0; layer < 2; ++layer)
        for (int ref = 0; ref < 2; ++ref) {
          if ((!layer && !ref) || (ref && (f.fetch || f.gather))) continue;
          std::string h = f.header;
          h.insert(h.find(f.fetch ? "i,j" : "u,v") + 3, std::string(layer ? ",layer" : "") + (ref ? ",ref" : ""));
          TraceFormat v = f;
          v.layer = layer;
          v.ref = ref;
          out.push_back({h, v});
        }
    }
    const size_t planar = out.size();
    for (size_t i = 0; i < planar; ++i) {  // the cube forms
      const NamedFormat& n = out[i];
      if (n.format.quad || n.format.fetch) continue;
      std::string h = n.header;
      h.replace(h.find("u,v"), 3, "x,y,z");
      if (const size_t d = h.find("dudx,dvdx,dudy,dvdy"); d != std::string::npos)
        h.replace(d, 19, "dxdx,dydx,dzdx,dxdy,dydy,dzdy");
      TraceFormat c = n.format;
      c.cube = true;
      out.push_back({h, c});
    }
    return out;
  }();
  return all;
}

// The headers of kFormats, in short: [tex,[smp,]] before u,v,lod and u,v,dudx,...
std::string known_headers() {
  return "[tex,[smp,]]u,v|x,y,z[,layer][,ref],lod|dudx,...[,bias] (gather: no lod), i,j[,layer],level, or "
         "tex,u,v,...,helper; texsim sample --help";
}

}  // namespace

namespace {

// A plain decimal (an optional '-', at most 15 digits with at most one '.', no exponent), by
// Clinger's fast path: the digits as an exact integer m < 10^15 < 2^53 and one division by an
// exact power of ten, which IEEE arithmetic rounds correctly: the same double as std::from_chars,
// in a few nanoseconds. False (nothing consumed) for anything else; std::from_chars takes those.
bool parse_plain_decimal(const char*& p, const char* e, double& out) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* s = p;
  const bool negative = s < e && *s == '-';
  s += negative;
  uint64_t m = 0;
  const char* const start = s;
  for (unsigned d; s < e && (d = unsigned(*s) - unsigned('0')) < 10; ++s) m = m * 10 + d;
  int digits = int(s - start), fraction = 0;
  if (s < e && *s == '.') {
    const char* const point = ++s;
    for (unsigned d; s < e && (d = unsigned(*s) - unsigned('0')) < 10; ++s) m = m * 10 + d;
    fraction = int(s - point);
    digits += fraction;
  }
  if (digits == 0 || digits > 15 || (s < e && (*s == 'e' || *s == 'E'))) return false;
  const double v = double(m) / kPow10[fraction];
  out = negative ? -v : v;
  p = s;
  return true;
}

}  // namespace

// The fast path: a well-formed line of `columns` finite numbers separated by commas (spaces and
// tabs around them). Anything else, valid or not, goes to parse_values_checked().
bool QueryReader::parse_values(std::string_view line, int columns, double* v) {
  const char* p = line.data();
  const char* const e = p + line.size();
  for (int i = 0; i < columns; ++i) {
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (!parse_plain_decimal(p, e, v[i])) {
      const auto [next, ec] = std::from_chars(p, e, v[i]);
      if (ec != std::errc() || !std::isfinite(v[i])) return false;
      p = next;
    }
    while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    if (i + 1 < columns) {
      if (p == e || *p != ',') return false;
      ++p;
    }
  }
  return p == e;
}

// Every value of a line, field by field (a leading '+' allowed), or the one-line error naming the
// file, the line, the value and its column: what the fast path does not take.
void QueryReader::parse_values_checked(std::string_view line, double* v) {
  const std::string at = name_ + ":" + std::to_string(line_no_) + ": ";
  std::string_view f[kMaxColumns + 1];
  const int n = split(line, f, kMaxColumns);
  if (n != columns_)
    throw Error(at + "expected " + std::to_string(columns_) + " values, got " +
                (n > kMaxColumns ? "more" : std::to_string(n)) + ": " + quote_clipped(line));
  for (int i = 0; i < columns_; ++i) {
    std::string_view s = f[i];
    if (!s.empty() && s[0] == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v[i]);
    // The whole line is quoted if it is short; otherwise the bad value alone.
    auto where = [&] {
      return "value " + std::to_string(i + 1) + " (column " + std::to_string(f[i].data() - line.data() + 1) + ")";
    };
    const std::string shown = line.size() <= 80 ? quote_clipped(line) : quote_clipped(f[i]);
    if (f[i].empty() || (ec != std::errc() && ec != std::errc::result_out_of_range) || end != s.data() + s.size())
      throw Error(at + where() + " is not a number: " + shown);
    if (ec == std::errc::result_out_of_range || !std::isfinite(v[i])) throw Error(at + where() + " is not finite: " + shown);
  }
}

void QueryReader::read_header() {
  std::string_view raw;
  while (columns_ == 0 && next_line(raw)) {
    const std::string_view line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string at = name_ + ":" + std::to_string(line_no_) + ": ";
    std::string_view f[kMaxColumns + 1];
    const int n = split(line, f, kMaxColumns);
    std::string header;
    for (int i = 0; i < std::min(n, kMaxColumns); ++i) header += (i ? "," : "") + std::string(f[i]);
    for (const auto& [name, format] : layered_formats())
      if (header == name && n <= kMaxColumns) {
        columns_ = int(std::count(header.begin(), header.end(), ',')) + 1;
        texture_ = format.texture;
        sampler_ = format.sampler;
        bias_ = format.bias;
        lod_ = format.lod;
        quad_ = format.quad;
        fetch_ = format.fetch;
        gather_ = format.gather;
        layer_ = format.layer;
        ref_ = format.ref;
        cube_ = format.cube;
        header_ = header;
      }
    if (columns_ == 0) throw Error(at + "unknown header " + quote_clipped(line) + " (expected " + known_headers() + ")");
  }
  if (columns_ == 0) throw Error(name_ + ": no header line (expected " + known_headers() + ")");
}

bool QueryReader::cube() {
  if (columns_ == 0) read_header();
  return cube_;
}

Op QueryReader::op() {
  if (columns_ == 0) read_header();
  return fetch_ ? Op::Fetch : gather_ ? Op::Gather : ref_ ? Op::Compare : Op::Sample;
}

bool QueryReader::next(Query& q) {
  if (columns_ == 0) read_header();
  std::string_view raw;
  while (next_line(raw)) {
    const std::string_view line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    double v[kMaxColumns];
    if (!parse_values(line, columns_, v)) parse_values_checked(line, v);
    // Whole-number columns: the texture id, the quad number and pixel, the helper flag.
    auto whole = [&](int i, double lo, double hi, const char* what) {
      if (v[i] != std::floor(v[i]) || v[i] < lo || v[i] > hi) {
        std::string_view f[kMaxColumns + 1];
        split(line, f, kMaxColumns);
        throw Error(name_ + ":" + std::to_string(line_no_) + ": " + what + " " + quote_clipped(f[i]) +
                    " is not a whole number from " + std::to_string(int64_t(lo)) + " to " + std::to_string(int64_t(hi)));
      }
      return int64_t(v[i]);
    };
    q = Query{};
    q.line = line_no_;
    int c = 0;
    if (texture_) q.texture = int(whole(c++, 0, kMaxTextures - 1, "texture"));
    if (sampler_) q.sampler = int(whole(c++, 0, kMaxSamplers - 1, "sampler"));
    if (fetch_) {
      q.fetch = true;
      q.u = double(whole(c++, INT32_MIN, INT32_MAX, "i"));
      q.v = double(whole(c++, INT32_MIN, INT32_MAX, "j"));
      if (layer_) q.layer = double(whole(c++, INT32_MIN, INT32_MAX, "layer"));
      q.lod = double(whole(c++, kLodMin, kLodMax, "level"));
      return true;
    }
    q.u = v[c++];
    q.v = v[c++];
    if (cube_) {
      q.cube = true;
      q.w = v[c++];
    }
    if (layer_) q.layer = v[c++];
    if (ref_) {
      q.compare = true;
      q.ref = v[c++];
    }
    if (gather_) {
      q.gather = true;
      return true;
    }
    q.explicit_lod = lod_;
    if (lod_) {
      q.lod = v[c++];
    } else {
      if (cube_) {  // dxdx,dydx,dzdx,dxdy,dydy,dzdy
        q.deriv = {v[c], v[c + 1], v[c + 3], v[c + 4]};
        q.dwdx = v[c + 2];
        q.dwdy = v[c + 5];
        c += 6;
      } else {
        q.deriv = {v[c], v[c + 1], v[c + 2], v[c + 3]};
        c += 4;
      }
      if (bias_) q.bias = v[c++];
    }
    if (quad_) {
      q.quad = uint32_t(whole(c++, 0, 4294967295.0, "quad"));
      q.x = int(whole(c++, 0, 65535, "x"));
      q.y = int(whole(c++, 0, 65535, "y"));
      q.helper = whole(c++, 0, 1, "helper") != 0;
    }
    return true;
  }
  return false;
}

struct QueryFileParser::Part {
  uint64_t begin = 0, end = 0;  // bytes of the file
  // The requests, in chunks of kChunk (huge pages, no copy as the part grows; tags count from 0
  // in each part). Written by the part's thread; [0, ready) is read under the mutex.
  static constexpr size_t kChunk = (size_t(4) << 20) / sizeof(Request);
  std::vector<std::unique_ptr<Request[], void (*)(Request*)>> chunks;
  size_t ready = 0;
  bool done = false;
  std::exception_ptr error;
  QueryCounts counts;
  size_t count = 0;
};

QueryFileParser::QueryFileParser(const std::string& path, unsigned threads, bool keep, QueryForm form)
    : first_(std::make_unique<QueryReader>(path)), form_(form), start_(std::chrono::steady_clock::now()) {
  QueryReader& first = *first_;
  first.read_header();
  struct stat st {};
  const uint64_t size = ::fstat(fileno(first.file_), &st) == 0 ? uint64_t(st.st_size) : 0;
  keep_ = keep && size <= kMaxFileBytes;
  // Cuts at line starts after the header, about size / threads apart (none for small files: a
  // thread costs more than it saves there).
  constexpr uint64_t kMinPart = uint64_t(4) << 20;
  std::vector<uint64_t> cuts = {first.offset()};
  for (unsigned k = 1; k < threads && size > first.file_pos_ + 2 * kMinPart; ++k) {
    // (past what the first part has already read)
    uint64_t at = std::max(std::max(cuts.back(), first.file_pos_) + kMinPart, size / threads * k);
    if (at >= size) break;
    // The next line start at or after `at`.
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f || std::fseek(f, long(at - 1), SEEK_SET) != 0) {
      if (f) std::fclose(f);
      break;
    }
    for (int ch; (ch = std::fgetc(f)) != EOF && ch != '\n';) ++at;
    std::fclose(f);
    if (at >= size) break;
    cuts.push_back(at);
  }
  cuts.push_back(size);
  first.file_end_ = cuts[1];
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    parts_.push_back(std::make_unique<Part>());
    parts_.back()->begin = cuts[k];
    parts_.back()->end = cuts[k + 1];
  }
  for (size_t k = 0; k < parts_.size(); ++k) threads_.emplace_back([this, k] { parse(k); });
}

QueryFileParser::~QueryFileParser() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

void QueryFileParser::parse(size_t k) {
  Part& part = *parts_[k];
  std::exception_ptr error;
  try {
    std::unique_ptr<QueryReader> own;
    if (k > 0) own.reset(new QueryReader(*first_, part.begin, part.end));  // (a private constructor)
    QuerySource source(k > 0 ? *own : *first_, form_);
    std::vector<Request> scratch(keep_ ? 0 : 4096);
    for (;;) {
      {
        std::lock_guard lock(mutex_);
        if (stop_) return;
      }
      if (!keep_) {
        if (source.read(scratch.data(), scratch.size()) == 0) break;
        continue;
      }
      const size_t at = part.ready % Part::kChunk;  // (only this thread writes `ready`)
      if (at == 0 && part.ready / Part::kChunk == part.chunks.size()) {
        // Raw storage: every element is written before it is read.
        HugePageAllocator<Request> alloc;
        Request* c = alloc.allocate(Part::kChunk);
        std::lock_guard lock(mutex_);
        part.chunks.emplace_back(c, [](Request* p) { HugePageAllocator<Request>().deallocate(p, Part::kChunk); });
      }
      Request* chunk = part.chunks[part.ready / Part::kChunk].get();  // (the pointer does not move)
      // A slice at a time, so that the engine starts early.
      const size_t n = source.read(chunk + at, std::min<size_t>(4096, Part::kChunk - at));
      if (n == 0) break;
      std::lock_guard lock(mutex_);
      part.ready += n;
      changed_.notify_all();
    }
    part.counts = source.counts();
    part.count = source.count();
  } catch (...) {
    error = std::current_exception();
  }
  std::lock_guard lock(mutex_);
  part.error = error;
  part.done = true;
  if (++parts_done_ == parts_.size()) finish_locked();
  changed_.notify_all();
}

void QueryFileParser::finish_locked() {
  parse_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  for (const auto& p : parts_) counts_.append(p->counts);
}

void QueryFileParser::wait() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return parts_done_ == parts_.size(); });
  }
  // Joined, not only done: a thread still ending frees its memory, and the SystemC engine forks
  // next (an allocator lock held by a thread at the fork stays held in the child).
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
  for (const auto& p : parts_)
    if (p->error) std::rethrow_exception(p->error);
}

size_t QueryFileParser::count() const {
  size_t n = 0;
  for (const auto& p : parts_) n += p->count;
  return n;
}

size_t QueryFileParser::read(Request* out, size_t max) {
  if (!keep_) throw Error("QueryFileParser::read: " + first_->name() + " is too long to keep");
  std::unique_lock lock(mutex_);
  // The file's first bad line, once known: a part's error with every part before it done.
  auto first_error = [&]() -> std::exception_ptr {
    for (const auto& q : parts_) {
      if (q->error) return q->error;
      if (!q->done) return nullptr;
    }
    return nullptr;
  };
  size_t n = 0;
  while (n < max && part_ < parts_.size()) {
    const Part& p = *parts_[part_];
    changed_.wait(lock, [&] { return p.ready > at_ || p.done || first_error(); });
    if (const std::exception_ptr e = first_error()) std::rethrow_exception(e);
    if (p.ready == at_) {  // (p is done, without error)
      part_base_ += p.count;
      ++part_;
      at_ = 0;
      continue;
    }
    const size_t m = std::min({max - n, p.ready - at_, Part::kChunk - at_ % Part::kChunk});
    const Request* from = p.chunks[at_ / Part::kChunk].get() + at_ % Part::kChunk;
    lock.unlock();
    for (size_t i = 0; i < m; ++i) {
      out[n + i] = from[i];
      out[n + i].tag += uint32_t(part_base_);  // (each part counted from 0)
    }
    lock.lock();
    n += m;
    at_ += m;
  }
  return n;
}

void check_query_file(const std::string& path, unsigned threads) { QueryFileParser(path, threads, false).wait(); }

uint32_t unnormalized_samplers(const SamplerTable& samplers) {
  uint32_t mask = 0;
  for (size_t s = 0; s < samplers.size(); ++s) mask |= uint32_t(samplers[s].unnormalized) << s;
  return mask;
}

std::vector<Query> in_sampler_coordinates(std::vector<Query> queries, const SamplerTable& samplers,
                                          const std::vector<Extent>& sizes) {
  for (Query& q : queries) {
    const size_t s = size_t(q.sampler < 0 ? q.texture : q.sampler);
    if (s < samplers.size() && samplers[s].unnormalized && size_t(q.texture) < sizes.size()) {
      // Within +-2n texels (a rasterized plane reaches far): beyond, the clamping modes of an
      // unnormalized sampler read the same edge or border taps, so the picture is unchanged.
      const double w = sizes[size_t(q.texture)].w, h = sizes[size_t(q.texture)].h;
      q.u = std::clamp(q.u * w, -2 * w, 2 * w);
      q.v = std::clamp(q.v * h, -2 * h, 2 * h);
    }
  }
  return queries;
}

Request to_request(const Query& q, const std::string& name, uint32_t tag, QueryForm form) {
  Request r;
  r.tag = tag;
  auto at = [&] { return name + ":" + std::to_string(q.line) + ": "; };
  if (q.texture < 0 || q.texture >= kMaxTextures)
    throw Error(at() + "texture " + std::to_string(q.texture) + " is outside 0.." + std::to_string(kMaxTextures - 1));
  r.texture = uint8_t(q.texture);
  if (q.sampler >= kMaxSamplers)
    throw Error(at() + "sampler " + std::to_string(q.sampler) + " is outside 0.." + std::to_string(kMaxSamplers - 1));
  // No sampler column: the texture's own (entry t of a texture list is texture t and sampler t).
  r.sampler = uint8_t(q.sampler < 0 ? q.texture : q.sampler);
  if (q.fetch) {  // (whole numbers in range: QueryReader)
    r.op = Op::Fetch;
    r.u = int32_t(q.u);
    r.v = int32_t(q.v);
    r.lod = int32_t(q.lod);
    r.layer = int32_t(q.layer);
    return r;
  }
  if (!to_texel_coord_fixed(q.layer, r.layer))
    throw Error(at() + "layer = " + std::to_string(q.layer) + " is outside [-32768, 32768)");
  const bool texels = form.unnormalized >> r.sampler & 1;
  if (q.compare) {
    if (form.no_compare >> r.sampler & 1)  // (VkSamplerCreateInfo: compareEnable rules)
      throw Error(at() + "a depth compare through sampler " + std::to_string(r.sampler) +
                  ", which has a min/max reduction or unnormalized coordinates: Vulkan does not compare so");
    r.op = Op::Compare;
    if (!to_coord_fixed(q.ref, r.ref)) throw Error(at() + "ref = " + std::to_string(q.ref) + " is outside [-128, 128)");
  }
  if (q.gather) {
    if (texels)  // (VkSamplerCreateInfo: not with OpImage*Gather)
      throw Error(at() + "a gather through sampler " + std::to_string(r.sampler) +
                  ", which is unnormalized: Vulkan does not gather so");
    r.op = Op::Gather;
    r.component = form.component;
  }  // an unnormalized sampler's: texels of level 0, Q16.16
  auto coordinate = [&](double value, const char* axis, int32_t& out) {
    if (texels ? to_texel_coord_fixed(value, out) : to_coord_fixed(value, out)) return;
    throw Error(at() + axis + " = " + std::to_string(value) +
                (texels ? " texels (unnormalized sampler " + std::to_string(r.sampler) + ") is outside [-32768, 32768)"
                        : std::string(" is outside [-128, 128)")));
  };
  coordinate(q.u, q.cube ? "x" : "u", r.u);
  coordinate(q.v, q.cube ? "y" : "v", r.v);
  if (q.cube) {
    if (texels) throw Error(at() + "a cube map's direction through sampler " + std::to_string(r.sampler) +
                            ", which is unnormalized: Vulkan does not sample a cube so");
    coordinate(q.w, "z", r.w);
  }
  if (q.gather) return r;
  if (q.explicit_lod) {
    if (!to_lod_fixed(q.lod, r.lod)) throw Error(at() + "lod = " + std::to_string(q.lod) + " is outside [-128, 128)");
  } else {
    if (!to_lod_derivatives(q.deriv, r.deriv)) throw Error(at() + "a derivative is not a finite number");
    if (q.cube) {  // dz/dx, dz/dy as the others (saturated at +-128)
      LodDerivatives z;
      if (!to_lod_derivatives({q.dwdx, q.dwdy, 0, 0}, z)) throw Error(at() + "a derivative is not a finite number");
      r.dwdx = z.dudx;
      r.dwdy = z.dvdx;
    }
    r.has_derivatives = true;
    if (!to_lod_fixed(q.bias, r.bias)) throw Error(at() + "bias = " + std::to_string(q.bias) + " is outside [-128, 128)");
  }
  return r;
}

std::vector<Request> to_requests(const std::vector<Query>& queries, const std::string& name, QueryForm form) {
  std::vector<Request> out;
  out.reserve(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) out.push_back(to_request(queries[i], name, uint32_t(i), form));
  return out;
}

size_t QuerySource::read(Request* out, size_t max) {
  size_t n = 0;
  Query q;
  while (n < max && reader_.next(q)) {
    out[n] = to_request(q, reader_.name(), uint32_t(count_), form_);
    counts_.add(q);
    ++n;
    ++count_;
  }
  return n;
}

void QueryCounts::add(const Query& q) {
  ++samples;
  helper_samples += q.helper;
  if (samples == 1) first_quad_ = q.quad;
  if (samples == 1 || q.quad != last_quad_) ++quads;
  last_quad_ = q.quad;
  textures_used |= 1u << q.texture;
}

void QueryCounts::append(const QueryCounts& later) {
  if (later.samples == 0) return;
  if (samples == 0) {
    *this = later;
    return;
  }
  quads += later.quads - (later.first_quad_ == last_quad_ ? 1 : 0);
  samples += later.samples;
  helper_samples += later.helper_samples;
  textures_used |= later.textures_used;
  last_quad_ = later.last_quad_;
}

QueryTraceWriter::QueryTraceWriter(std::FILE* out) : out_(out) {
  std::fputs(kFrameTraceHeader, out_);
  std::fputc('\n', out_);
}

void QueryTraceWriter::comment(const std::string& text) { std::fprintf(out_, "# %s\n", text.c_str()); }

void QueryTraceWriter::write(const Query& q) {
  // Shortest round-trip decimal of every double: the replay reads back the same bits.
  std::string line;
  auto num = [&](auto value, char sep) {
    char digits[32];  // a double's shortest form has at most 24 characters
    line.append(digits, std::to_chars(digits, digits + sizeof digits, value).ptr);
    line.push_back(sep);
  };
  num(q.texture, ',');
  num(q.u, ',');
  num(q.v, ',');
  num(q.deriv.dudx, ',');
  num(q.deriv.dvdx, ',');
  num(q.deriv.dudy, ',');
  num(q.deriv.dvdy, ',');
  num(q.quad, ',');
  num(q.x, ',');
  num(q.y, ',');
  num(int(q.helper), '\n');
  std::fwrite(line.data(), 1, line.size(), out_);
}

CsvTexelWriter::CsvTexelWriter(std::FILE* out, const char* header) : out_(out) {
  std::fputs(header, out_);
  std::fputc('\n', out_);
}

namespace {

// The decimal text of 0..999, left-aligned in 3 bytes, and its length: a channel is one copy.
struct Decimal {
  char text[3];
  uint8_t length;
};
const std::array<Decimal, 1000> kDecimals = [] {
  std::array<Decimal, 1000> t{};
  for (unsigned v = 0; v < 1000; ++v) {
    char* end = std::to_chars(t[v].text, t[v].text + 3, v).ptr;
    t[v].length = uint8_t(end - t[v].text);
  }
  return t;
}();

}  // namespace

void CsvTexelWriter::write(const Texel* texels, size_t n) {
  constexpr size_t kFlush = size_t(1) << 18;  // (big writes go past stdio's buffer)
  if (buffer_.size() < kFlush + 64) buffer_.resize(kFlush + 64);
  char* const buf = buffer_.data();
  size_t len = 0;
  auto put = [&](unsigned v, char end) {
    if (v < 1000) {
      std::memcpy(buf + len, kDecimals[v].text, 3);
      len += kDecimals[v].length;
    } else {  // unorm16 results of sRGB textures
      len = size_t(std::to_chars(buf + len, buf + len + 8, v).ptr - buf);
    }
    buf[len++] = end;
  };
  for (size_t i = 0; i < n; ++i) {
    const Texel& t = texels[i];
    put(t[0], ',');
    put(t[1], ',');
    put(t[2], ',');
    put(t[3], '\n');
    if (len > kFlush) {
      std::fwrite(buf, 1, len, out_);
      len = 0;
    }
  }
  std::fwrite(buf, 1, len, out_);
}

}  // namespace tex

// QueryReader's parse (sim/workloads/query_trace.cpp): the fast path for plain decimals must give
// the very doubles std::from_chars gives, for every way a number can be written, and the checked
// path must still take what the fast one leaves (a '+' sign, an exponent, long mantissas).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "model/error.h"
#include "workloads/query_trace.h"

using namespace tex;

namespace {

std::string number(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> any(-100.0, 100.0);
  const double x = any(rng) * std::pow(10.0, -int(rng() % 6));
  char buf[64];
  switch (rng() % 8) {
    case 0: std::snprintf(buf, sizeof buf, "%.*f", int(rng() % 17), x); break;  // 0..16 decimals
    case 1: std::snprintf(buf, sizeof buf, "%.17g", x); break;                   // 17 digits
    case 2: std::snprintf(buf, sizeof buf, "%.6e", x); break;                    // an exponent
    case 3: std::snprintf(buf, sizeof buf, "%d.", int(x)); break;                // "12."
    case 4: std::snprintf(buf, sizeof buf, ".%u", unsigned(rng() % 1000000)); break;  // ".5"
    case 5: std::snprintf(buf, sizeof buf, "+%.5f", std::fabs(x)); break;        // a '+' sign
    case 6: std::snprintf(buf, sizeof buf, "%llu", (unsigned long long)(rng() % 1000000000000000000ull)); break;
    default: std::snprintf(buf, sizeof buf, " %.9f\t", x); break;               // spaces around
  }
  return buf;
}

double reference(std::string s) {  // the field as the checked path reads it
  s.erase(0, s.find_first_not_of(" \t"));
  s.erase(s.find_last_not_of(" \t") + 1);
  if (!s.empty() && s[0] == '+') s.erase(0, 1);
  double v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

}  // namespace

TEST(QueryTrace, FastDecimalsEqualFromChars) {
  const auto path = std::filesystem::temp_directory_path() / ("query_trace_" + std::to_string(getpid()) + ".csv");
  std::mt19937_64 rng(17);
  std::vector<std::array<double, 6>> want;
  {
    std::ofstream out(path);
    out << "u,v,dudx,dvdx,dudy,dvdy\n";
    for (int i = 0; i < 200000; ++i) {
      std::array<double, 6> w;
      for (int c = 0; c < 6; ++c) {
        std::string s = number(rng);
        if (c < 2) s = std::to_string(int(rng() % 200) - 100) + "." + std::to_string(rng() % 1000000);  // |u| < 128
        w[size_t(c)] = reference(s);
        out << s << (c < 5 ? "," : "\n");
      }
      want.push_back(w);
    }
  }
  QueryReader reader(path.string());
  Query q;
  size_t i = 0;
  while (reader.next(q)) {
    ASSERT_LT(i, want.size());
    const double got[6] = {q.u, q.v, q.deriv.dudx, q.deriv.dvdx, q.deriv.dudy, q.deriv.dvdy};
    for (int c = 0; c < 6; ++c)
      ASSERT_EQ(std::memcmp(&got[c], &want[i][size_t(c)], sizeof(double)), 0)
          << "line " << i + 2 << " value " << c + 1 << ": " << got[c] << " vs " << want[i][size_t(c)];
    ++i;
  }
  EXPECT_EQ(i, want.size());
  std::filesystem::remove(path);
}

// A bad value names its line, its value number and its column.
TEST(QueryTrace, BadValueNamesLineAndColumn) {
  const auto path = std::filesystem::temp_directory_path() / ("query_trace_bad_" + std::to_string(getpid()) + ".csv");
  std::ofstream(path) << "u,v,lod\n0.5,0.5,1\n0.25,  x1,2\n";
  QueryReader reader(path.string());
  Query q;
  ASSERT_TRUE(reader.next(q));
  try {
    reader.next(q);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(":3: value 2 (column 8) is not a number"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// ReadAheadSource hands out the source's requests in order, then the source's error where the
// source threw it; dropped before the end, it stops its thread (no hang).
TEST(QueryTrace, ReadAheadKeepsOrderAndErrors) {
  struct Counting final : RequestSource {
    size_t next = 0, fail_at;
    explicit Counting(size_t fail) : fail_at(fail) {}
    size_t read(Request* out, size_t max) override {
      size_t n = 0;
      while (n < max && next < fail_at) out[n++].tag = uint32_t(next++);
      if (n == 0) throw Error("bad query " + std::to_string(next));
      return n;
    }
  };
  Counting inner(100000);
  ReadAheadSource ahead(inner, 777, 3);
  std::vector<Request> buf(1000);
  size_t seen = 0;
  try {
    while (const size_t n = ahead.read(buf.data(), buf.size()))
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(buf[i].tag, uint32_t(seen++));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "bad query 100000");
  }
  EXPECT_EQ(seen, 100000u);
  Counting endless(1u << 30);
  {
    ReadAheadSource early(endless, 4096, 2);
    EXPECT_EQ(early.read(buf.data(), 10), 10u);
  }  // destroyed with chunks pending: must return
}

// The check pass cuts a big file into parts read in parallel: each bad line is reported with its
// line number in the whole file, and with several bad lines the first one wins, wherever the cut.
TEST(QueryTrace, ParallelCheckReportsTheFirstBadLine) {
  const auto path = std::filesystem::temp_directory_path() / ("query_trace_check_" + std::to_string(getpid()) + ".csv");
  constexpr int kLines = 600000;  // about 15 MB: the file is cut into parts
  auto write = [&](std::vector<int> bad) {
    std::ofstream out(path);
    out << "# a comment before the header\nu,v,lod\n";
    for (int line = 3; line < kLines + 3; ++line) {
      if (std::find(bad.begin(), bad.end(), line) != bad.end())
        out << "0.5,oops,1\n";
      else
        out << "0.123456,0.654321," << (line % 7) << ".25\n";
    }
  };
  auto error_of = [&]() -> std::string {
    try {
      check_query_file(path.string(), 2);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  write({});
  EXPECT_EQ(error_of(), "");
  EXPECT_GT(std::filesystem::file_size(path), 12u << 20);
  for (int line : {4, kLines / 2 - 1, kLines / 2 + 3, kLines + 2}) {
    write({line});
    EXPECT_NE(error_of().find(":" + std::to_string(line) + ": value 2 (column 5) is not a number"), std::string::npos)
        << "bad line " << line << ": " << error_of();
  }
  write({kLines - 10, 100});  // the first bad line is in the first part, the other in the second
  EXPECT_NE(error_of().find(":100: "), std::string::npos) << error_of();
  write({kLines / 4 * 3, kLines - 5});  // both in the second part
  EXPECT_NE(error_of().find(":" + std::to_string(kLines / 4 * 3) + ": "), std::string::npos) << error_of();
  std::filesystem::remove(path);
}

namespace {

// A frame trace of `lines` queries (quads of 4, two textures); quad 1000 covers the middle tenth
// of the file, so that wherever the parser cuts it, a quad runs across the cut.
void write_frame_trace(const std::filesystem::path& path, int lines, const std::vector<int>& bad = {}) {
  std::ofstream out(path);
  out << kFrameTraceHeader << "\n";
  for (int i = 0; i < lines; ++i) {
    const int line = i + 2;
    const bool middle = i > lines / 2 - lines / 20 && i < lines / 2 + lines / 20;
    const int quad = middle ? 1000 : i / 4 + (i > lines / 2 ? 2000 : 0);
    if (std::find(bad.begin(), bad.end(), line) != bad.end()) {
      out << "0,0.5,oops,0,0,0,0," << quad << ",0,0,0\n";
      continue;
    }
    out << (i % 7 == 0) << "," << (i % 1000) * 0.001 << "," << (i % 977) * 0.002 - 0.5 << ",0.01,"
        << (i % 13) * 0.001 << ",0,0.02," << quad << "," << i % 640 << "," << i / 640 % 480 << "," << (i % 4 == 3)
        << "\n";
  }
}

std::vector<Request> read_all(RequestSource& source) {
  std::vector<Request> all, buf(3000);  // (not a divisor of the parser's slices)
  while (const size_t n = source.read(buf.data(), buf.size())) all.insert(all.end(), buf.begin(), buf.begin() + n);
  return all;
}

bool same(const Request& a, const Request& b) {
  return a.u == b.u && a.v == b.v && a.lod == b.lod && a.tag == b.tag && a.texture == b.texture &&
         a.has_derivatives == b.has_derivatives && a.deriv.dudx == b.deriv.dudx && a.deriv.dvdx == b.deriv.dvdx &&
         a.deriv.dudy == b.deriv.dudy && a.deriv.dvdy == b.deriv.dvdy;
}

}  // namespace

// The parser's kept requests are the ones a single stream gives, tag for tag, and its counts (quads
// cut in two by the parts count once) are the stream's.
TEST(QueryTrace, KeptRequestsEqualTheStreamedOnes) {
  const auto path = std::filesystem::temp_directory_path() / ("query_trace_keep_" + std::to_string(getpid()) + ".csv");
  constexpr int kLines = 300000;  // about 15 MB: two parts
  write_frame_trace(path, kLines);
  ASSERT_GT(std::filesystem::file_size(path), 12u << 20);  // (cut in two)
  QueryReader reader(path.string());
  QuerySource streamed(reader);
  const std::vector<Request> want = read_all(streamed);
  QueryFileParser parser(path.string(), 2, true);
  ASSERT_TRUE(parser.kept());
  const std::vector<Request> got = read_all(parser);
  parser.wait();
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(parser.count(), want.size());
  for (size_t i = 0; i < want.size(); ++i) ASSERT_TRUE(same(got[i], want[i])) << "request " << i;
  const QueryCounts& a = parser.counts();
  const QueryCounts& b = streamed.counts();
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.quads, b.quads);
  EXPECT_EQ(a.helper_samples, b.helper_samples);
  EXPECT_EQ(a.textures_used, b.textures_used);
  EXPECT_EQ(b.textures_used, 3u);
  std::filesystem::remove(path);
}

// Reading kept requests stops at the file's first bad line, never handing out a request from past
// it, whichever part it is in and however far the other part got; a parser dropped early stops.
TEST(QueryTrace, KeptParseStopsAtTheFirstBadLine) {
  const auto path = std::filesystem::temp_directory_path() / ("query_trace_keepbad_" + std::to_string(getpid()) + ".csv");
  constexpr int kLines = 300000;
  for (const std::vector<int>& bad :
       std::vector<std::vector<int>>{{kLines - 10, 100}, {kLines / 4 * 3}, {kLines / 2 + 1, kLines - 3}, {5}}) {
    write_frame_trace(path, kLines, bad);
    const int first = *std::min_element(bad.begin(), bad.end());
    QueryFileParser parser(path.string(), 2, true);
    std::vector<Request> buf(3000);
    size_t seen = 0;
    std::string error;
    try {
      while (const size_t n = parser.read(buf.data(), buf.size())) seen += n;
    } catch (const Error& e) {
      error = e.what();
    }
    EXPECT_NE(error.find(":" + std::to_string(first) + ": value 3 (column 7) is not a number"), std::string::npos)
        << "first bad line " << first << ": " << error;
    EXPECT_LE(seen, size_t(first - 2)) << "requests handed out past the bad line " << first;
  }
  write_frame_trace(path, kLines);
  {
    QueryFileParser early(path.string(), 2, true);
    std::vector<Request> buf(10);
    EXPECT_EQ(early.read(buf.data(), buf.size()), 10u);
  }  // destroyed mid-parse: must return
  std::filesystem::remove(path);
}

// WriteBehindSink passes every texel on in order, and an error of the sink it writes to comes out
// of finish() (or the next write); dropped with chunks queued, it stops its thread.
TEST(QueryTrace, WriteBehindKeepsOrderAndErrors) {
  struct Collect final : TexelSink {
    std::vector<Texel> got;
    size_t fail_after = SIZE_MAX;
    void write(const Texel* t, size_t n) override {
      if (got.size() + n > fail_after) throw Error("disk full");
      got.insert(got.end(), t, t + n);
    }
  };
  std::vector<Texel> texels(100003);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = {uint16_t(i), uint16_t(i >> 16), 7, uint16_t(i * 3)};
  Collect inner;
  {
    WriteBehindSink behind(inner, 777, 3);
    for (size_t i = 0; i < texels.size(); i += 1000) behind.write(&texels[i], std::min<size_t>(1000, texels.size() - i));
    behind.finish();
  }
  ASSERT_EQ(inner.got.size(), texels.size());
  for (size_t i = 0; i < texels.size(); ++i) ASSERT_EQ(inner.got[i], texels[i]) << "texel " << i;
  Collect failing;
  failing.fail_after = 5000;
  std::string error;
  try {
    WriteBehindSink behind(failing, 777, 3);
    for (size_t i = 0; i < texels.size(); i += 1000) behind.write(&texels[i], std::min<size_t>(1000, texels.size() - i));
    behind.finish();
  } catch (const Error& e) {
    error = e.what();
  }
  EXPECT_EQ(error, "disk full");
  Collect slow;
  {
    WriteBehindSink early(slow, 100, 2);
    early.write(texels.data(), 150);
  }  // destroyed without finish(): must return
}

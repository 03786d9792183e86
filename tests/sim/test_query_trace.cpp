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

// The CSV parse and write of texsim sample (bench_csv.cpp), for `make bench`.
#pragma once
#include <string>
#include <vector>

namespace bench {

// Registers "csv_parse/<header>" (1 M lines of a file to fixed-point requests) and
// "csv_write/r,g,b,a" (1 M results to a file); returns their names.
std::vector<std::string> register_csv_benchmarks(double min_time);

}  // namespace bench

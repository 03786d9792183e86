// Query traces (CSV in) and results (CSV out).
#pragma once
#include <string>
#include <vector>

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

// Header `u,v,lod` or `u,v,dudx,dvdx,dudy,dvdy`; `#` lines are comments, blank lines are skipped.
// Throws tex::Error naming the file, line number and text of the first bad line.
std::vector<Query> read_queries(const std::string& path);
std::vector<Query> parse_queries(const std::string& text, const std::string& name);

// Converts to the hardware's fixed-point requests (tag = index). Throws tex::Error for a value
// out of the fixed-point range.
std::vector<Request> to_requests(const std::vector<Query>& queries, int log2_w0, int log2_h0,
                                 const std::string& name);

// `r,g,b,a` then one line per texel.
std::string format_results(const std::vector<Texel>& texels);

// Writes to PATH.partial and renames, so a failure leaves no file behind. Throws tex::Error.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace tex

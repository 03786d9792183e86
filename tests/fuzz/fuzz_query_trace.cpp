// Query traces (workloads/query_trace.h): the streamed reader (QuerySource over QueryReader, as
// texsim reads standard input) and the parallel check pass that keeps its requests
// (QueryFileParser, as texsim reads a file) must give the same requests, or the same error.
#include <cstring>
#include <vector>

#include "fuzz_target.h"
#include "workloads/query_trace.h"

namespace {

using namespace tex;

bool same(const Request& a, const Request& b) {
  return a.u == b.u && a.v == b.v && a.lod == b.lod && a.bias == b.bias && a.tag == b.tag && a.texture == b.texture &&
         a.sampler == b.sampler && a.op == b.op && a.component == b.component && a.layer == b.layer && a.ref == b.ref &&
         a.w == b.w && a.dwdx == b.dwdx && a.dwdy == b.dwdy && a.has_derivatives == b.has_derivatives &&
         std::memcmp(&a.deriv, &b.deriv, sizeof a.deriv) == 0;
}

// Every request of a source, or its error's message ("" if none).
std::string drain(RequestSource& source, std::vector<Request>& out) {
  try {
    Request batch[64];
    while (const size_t n = source.read(batch, 64)) out.insert(out.end(), batch, batch + n);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::input_file(data, size, "queries.csv");
  const QueryForm form{0x5555u, uint8_t(size % 4), 0x0F0Fu};  // texel coordinates for half the samplers
  std::vector<Request> streamed, kept;
  std::string streamed_error, kept_error;
  try {
    QueryReader reader(path);
    reader.op();
    QuerySource source(reader, form);
    streamed_error = drain(source, streamed);
  } catch (const Error& e) {
    streamed_error = e.what();
  }
  try {
    QueryFileParser parser(path, 2, true, form);
    kept_error = drain(parser, kept);
    if (kept_error.empty()) parser.wait();
  } catch (const Error& e) {
    kept_error = e.what();
  }
  if (!streamed_error.empty()) fuzz::check_error(Error(streamed_error), path);
  bool agree = streamed_error == kept_error && streamed.size() == kept.size();
  for (size_t i = 0; agree && i < streamed.size(); ++i) agree = same(streamed[i], kept[i]);
  if (!agree) {
    std::fprintf(stderr, "fuzz: the streamed reader and the parallel parser differ: %zu requests \"%s\" against %zu \"%s\"\n",
                 streamed.size(), streamed_error.c_str(), kept.size(), kept_error.c_str());
    std::abort();
  }
  return 0;
}

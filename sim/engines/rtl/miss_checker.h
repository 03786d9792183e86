// Cached mode: the golden model's caches predict every line the RTL reads from memory. predict()
// looks each request up, in request order, before the RTL can read for it; compare() takes the
// RTL's reads so far and checks them one for one against the predicted misses (then hands them to
// the miss sink). Any difference is a tex::SimulationError naming the read. check_error() compares
// each response's rsp_error with the model's prediction (a memory error, --mem-error-at). Used by
// --engine rtl and by the SystemC wrapper's RTL backend.
#pragma once
#include <cstdint>
#include <deque>
#include <vector>

#include "engines/engine.h"
#include "model/texture_cache.h"

namespace tex::rtl {

class MissChecker {
 public:
  MissChecker(TextureCache& cache, MissSink* sink) : cache_(cache), sink_(sink) {}
  void predict(const Request& r) { errors_.push_back(cache_.lookup_sample(r, &predicted_).error); }
  // The next response (request `index`) came with rsp_error = `error`.
  void check_error(uint64_t index, bool error);
  // The RTL's reads since the last call; at the end, every predicted miss must have been read.
  void compare(const std::vector<uint32_t>& actual, bool at_end);

 private:
  TextureCache& cache_;
  MissSink* sink_;
  std::vector<uint32_t> predicted_;
  std::deque<bool> errors_;  // predicted rsp_error of the requests not yet answered
  uint64_t done_ = 0;
};

}  // namespace tex::rtl

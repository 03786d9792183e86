#include "engines/rtl/miss_checker.h"

#include "engines/rtl/memory_model.h"

namespace tex::rtl {

void MissChecker::compare(const std::vector<uint32_t>& actual, bool at_end) {
  size_t matched = 0;
  for (uint32_t a : actual) {
    if (matched == predicted_.size())
      throw SimulationError("the RTL read line " + hex_address(a) + " from memory (read #" + std::to_string(done_) +
                            ") that the model's caches do not miss");
    if (predicted_[matched] != a)
      throw SimulationError("memory read #" + std::to_string(done_) + ": the RTL read line " + hex_address(a) +
                            ", the model's caches miss line " + hex_address(predicted_[matched]));
    ++matched;
    ++done_;
  }
  if (sink_ && matched) sink_->write(predicted_.data(), matched);
  predicted_.erase(predicted_.begin(), predicted_.begin() + long(matched));
  if (at_end && !predicted_.empty())
    throw SimulationError("the model's caches miss " + std::to_string(predicted_.size()) +
                          " more lines than the RTL read (first: " + hex_address(predicted_.front()) + ")");
}

void MissChecker::check_error(uint64_t index, bool error) {
  if (errors_.empty()) throw SimulationError("response to request #" + std::to_string(index) + " with none predicted");
  const bool want = errors_.front();
  errors_.pop_front();
  if (error != want)
    throw SimulationError("request #" + std::to_string(index) + ": the RTL " +
                          (error ? "flags a memory error (rsp_error) that the model does not"
                                 : "does not flag the memory error (rsp_error) that the model predicts"));
}

}  // namespace tex::rtl

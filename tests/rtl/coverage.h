// Functional coverage of the lockstep random tests (docs/verification.md, "Functional coverage").
// Every compared request is classified with the model's own stage functions (model/stages.h)
// into named bins; a suite asserts that every reachable bin was hit and that no bin declared
// unreachable was (so each reason given for unreachability is itself checked).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/pyramid.h"
#include "model/sampler.h"
#include "engines/rtl/driver.h"

namespace tex::rtltest {

// A group of bins, e.g. "filter x wrap_u x wrap_v". Bins are fixed when the group is made, so a
// bin that is never hit is still listed by name.
struct CoverGroup {
  std::string name;
  std::vector<std::string> bins;
  std::vector<std::string> unreachable;  // empty = reachable; else why no stimulus can hit it
  std::vector<uint64_t> hits;
  size_t add(const std::string& bin, const std::string& why_unreachable = "");
  size_t reachable() const;
  size_t reachable_hit() const;
};

class Coverage {
 public:
  // max_log2_w/h: the Verilated configuration (its level memory holds levels 0..max of the two).
  Coverage(int max_log2_w, int max_log2_h);

  // One compared request of a texture with this config.
  void sample(const Pyramid& pyramid, const SamplerConfig& config, const Request& request);
  // The timing of one stream() call.
  void timing(const rtl::StreamStats& stats);

  // Compact table: per group "hit / reachable", then every reachable bin never hit, by name;
  // every_bin: also every other bin with its count.
  std::string table(bool every_bin = false) const;
  // Reachable bins never hit, and unreachable bins that were hit (empty = complete).
  std::vector<std::string> holes() const;
  const std::vector<CoverGroup>& groups() const { return groups_; }

 private:
  CoverGroup& group(size_t g) { return groups_[g]; }
  std::vector<CoverGroup> groups_;
  void sample_probe(const Pyramid& pyramid, const SamplerConfig& config, const Request& probe);
  size_t g_filter_wrap_, g_level_case_, g_level_d_, g_taps_, g_sign_, g_timing_, g_pyramid_, g_deriv_, g_aniso_,
      g_mag_, g_unnorm_, g_reduce_, g_fetch_, g_gather_, g_compare_;
  int max_level_;
  size_t level_case_bin_[6][7] = {};  // [filter][level case] -> bin of g_level_case_ (only the cases of its mip mode)
};

}  // namespace tex::rtltest

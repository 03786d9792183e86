// render --store DIR: a frame kept in the results store (reports/result_store.h, docs/cluster.md
// "Frame batches") under a key of what determines it: texsim's build, the render's arguments (but
// those naming its outputs), and the frame's requests, textures and samplers as loaded (so a
// changed model, texture or sampler in a model file is another frame). Its picture and its
// statistics are kept beside the key; a frame found there is written from the store, not sampled.
#pragma once
#include <string>
#include <vector>

#include "engines/engine.h"
#include "reports/result_store.h"
#include "workloads/output_files.h"

namespace tex {

class FrameStore {
 public:
  // `args`: the render's arguments as given (those that name outputs are left out of the key).
  FrameStore(const std::string& dir, const std::vector<std::string>& args);
  // The frame's inputs, before it is sampled: they complete its key.
  void set_inputs(const std::vector<Request>& requests, const TextureTable& table, const SamplerTable& samplers);
  // Writes the stored frame's picture (and statistics, if asked) to the outputs; false if the
  // store has no such frame.
  bool reuse(const OutputFile& picture, OutputFile* stats) const;
  // After the outputs are committed: keeps the picture and the statistics (written to a file, or
  // none).
  void keep(const std::string& picture_path, const std::string& stats_path) const;
  const std::string& dir() const { return store_.dir(); }

 private:
  ResultStore store_;
  std::string args_, key_;
};

}  // namespace tex

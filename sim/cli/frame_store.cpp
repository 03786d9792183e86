#include "cli/frame_store.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "model/error.h"
#include "reports/sweep_tasks.h"

namespace tex {

namespace fs = std::filesystem;

FrameStore::FrameStore(const std::string& dir, const std::vector<std::string>& args) : store_(dir) {
  // The options that name outputs, with their values, are no part of what the frame is.
  const std::set<std::string> outputs = {"--out", "-o", "--stats", "--store"};
  std::vector<std::string> kept;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& w = args[i];
    const std::string name = w.rfind("--", 0) == 0 && w.find('=') != std::string::npos ? w.substr(0, w.find('=')) : w;
    if (outputs.count(name)) {
      i += name == w ? 1 : 0;
      continue;
    }
    kept.push_back(w);
  }
  args_ = shell_line(kept);
}

void FrameStore::set_inputs(const std::vector<Request>& requests, const TextureTable& table, const SamplerTable& samplers) {
  Fingerprint f;
  add_requests(f, requests);
  add_table(f, table);
  f.number(int64_t(samplers.size()));
  for (const SamplerConfig& s : samplers) add_sampler(f, s);
  key_ = "render/1 texsim=" + executable_fingerprint() + " inputs=" + f.hex() + " args=" + args_;
}

bool FrameStore::reuse(const OutputFile& picture, OutputFile* stats) const {
  const std::optional<std::string> stored = store_.get(key_);
  const std::string ext = fs::path(picture.path()).extension().string();
  std::error_code ec;
  if (!stored || !fs::is_regular_file(store_.file_of(key_, ext), ec)) return false;
  if (stats && stored->empty()) return false;  // (kept by a run without --stats)
  if (!fs::copy_file(store_.file_of(key_, ext), picture.write_path(), fs::copy_options::overwrite_existing, ec))
    throw Error("--store: cannot copy the stored picture to " + picture.path() + " (" + ec.message() + ")");
  if (stats) {  // as write_stats writes it (the stored line is the same JSON, compact)
    const nlohmann::json j = nlohmann::json::parse(*stored, nullptr, false);
    if (j.is_discarded()) return false;
    std::fputs((j.dump(2) + "\n").c_str(), stats->open());
    stats->close();
  }
  return true;
}

void FrameStore::keep(const std::string& picture_path, const std::string& stats_path) const {
  std::error_code ec;
  std::string stats;
  if (!stats_path.empty() && fs::is_regular_file(stats_path, ec)) {
    std::ifstream in(stats_path);
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (!j.is_discarded()) stats = j.dump();  // (one line)
  }
  store_.put_file(key_, fs::path(picture_path).extension().string(), picture_path);
  store_.put(key_, stats);
}

}  // namespace tex

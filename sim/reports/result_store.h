// Measured results kept for reuse across sweeps (docs/cluster.md, "Results are reused").
//
// A result is stored under a key: the text of everything that determines it (texsim's executable,
// the workload's fingerprint, every parameter of the point). The store is a directory of one small
// file per key, DIR/<2 hex>/<16 hex>.txt, the key's hash as its name: line 1 the key's text, line 2
// the result. A file is written under a temporary name in its own directory and renamed into place:
// rename is atomic on POSIX file systems, NFS included, so any number of tasks on any number of
// nodes write at once without a lock or a server (SQLite's locks are unreliable on NFS, where
// cluster homes live), and two writers of one key write the same bytes. A reader checks line 1:
// a hash collision, a truncated or foreign file reads as "not stored" and is measured again.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tex {

// FNV-1a, 64 bits: a fingerprint of bytes, numbers and strings fed in order (stable across
// builds and machines: the store's file names depend on it).
class Fingerprint {
 public:
  Fingerprint& bytes(const void* data, size_t n);
  Fingerprint& number(int64_t v);  // as 8 little-endian bytes
  Fingerprint& text(const std::string& s);  // its length, then its bytes
  uint64_t value() const { return h_; }
  std::string hex() const;  // 16 hex digits

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

struct Pyramid;
struct Request;
struct SamplerConfig;
struct BoundTexture;
// What a sampled result depends on, fed to a fingerprint field by field (no padding bytes): a
// pyramid (format, sRGB, every level's size, channel width and texels, every level's blocks), the
// requests (every field), a sampler (every field), a descriptor table (kinds, layers, pyramids).
void add_pyramid(Fingerprint& f, const Pyramid& p);
void add_requests(Fingerprint& f, const std::vector<Request>& requests);
void add_sampler(Fingerprint& f, const SamplerConfig& s);
void add_table(Fingerprint& f, const std::vector<BoundTexture>& table);

// The fingerprint of the running executable's file (texsim and the model, the timing layer and
// the RTL compiled into it): results of another build are never reused. Read once.
const std::string& executable_fingerprint();

// The default store: $TEXSIM_STORE, else $XDG_CACHE_HOME/texsim/results, else
// ~/.cache/texsim/results.
std::string default_store_dir();

class ResultStore {
 public:
  // Creates the directory if it does not exist. Throws tex::Error if it cannot.
  explicit ResultStore(std::string dir);
  const std::string& dir() const { return dir_; }
  // The result stored for this key, if any (its file present, complete and of this key).
  std::optional<std::string> get(const std::string& key) const;
  // Stores a result (one line, no line break) for a key (one line). Throws tex::Error on a write error.
  void put(const std::string& key, const std::string& result) const;
  std::string path_of(const std::string& key) const;
  // A file kept beside a key's result (a frame's picture): DIR/<2 hex>/<16 hex><suffix>. Store it
  // before put() stores the result, so that a stored result's files are complete (put_file copies
  // `from` by a temporary name and a rename). Throws tex::Error.
  void put_file(const std::string& key, const std::string& suffix, const std::string& from) const;
  std::string file_of(const std::string& key, const std::string& suffix) const;

 private:
  std::string dir_;
};

}  // namespace tex

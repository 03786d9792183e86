#include "reports/result_store.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engines/engine.h"
#include "model/error.h"
#include "model/pyramid.h"
#include "model/sampler.h"

namespace tex {

namespace fs = std::filesystem;

Fingerprint& Fingerprint::bytes(const void* data, size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
  return *this;
}

Fingerprint& Fingerprint::number(int64_t v) {
  unsigned char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(uint64_t(v) >> (8 * i));
  return bytes(b, 8);
}

Fingerprint& Fingerprint::text(const std::string& s) {
  number(int64_t(s.size()));
  return bytes(s.data(), s.size());
}

std::string Fingerprint::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

void add_pyramid(Fingerprint& f, const Pyramid& p) {
  f.number(int(p.format)).number(p.srgb).number(int64_t(p.levels.size()));
  for (const Image& l : p.levels) {
    f.number(l.width).number(l.height).number(l.channel_bits);
    f.bytes(l.texels.data(), l.texels.size() * sizeof(Texel));
  }
  f.number(int64_t(p.blocks.size()));
  for (const auto& b : p.blocks) f.number(int64_t(b.size())).bytes(b.data(), b.size());
}

void add_requests(Fingerprint& f, const std::vector<Request>& requests) {
  f.number(int64_t(requests.size()));
  for (const Request& q : requests) {
    for (int32_t v : {q.u, q.v, q.lod, q.bias, q.layer, q.ref, q.w, q.dwdx, q.dwdy, q.deriv.dudx, q.deriv.dvdx,
                      q.deriv.dudy, q.deriv.dvdy})
      f.number(v);
    f.number(q.tag).number(q.texture).number(q.sampler).number(int(q.op)).number(q.component).number(q.has_derivatives);
  }
}

void add_sampler(Fingerprint& f, const SamplerConfig& s) {
  f.number(int(s.filter.texel)).number(int(s.filter.mip)).number(s.filter.anisotropic).number(int(s.filter.mag));
  f.number(int(s.wrap_u)).number(int(s.wrap_v)).number(s.lod_bias).number(s.min_lod).number(s.max_lod);
  f.number(s.max_aniso).number(s.aniso_pow2).number(int(s.border));
  for (uint16_t c : s.border_custom) f.number(c);
  f.number(s.unnormalized).number(int(s.reduction)).number(int(s.compare_op));
}

void add_table(Fingerprint& f, const std::vector<BoundTexture>& table) {
  f.number(int64_t(table.size()));
  for (const BoundTexture& t : table) {
    f.number(int(t.kind)).number(t.layers());
    for (const Pyramid* p : t.all_layers()) add_pyramid(f, *p);
  }
}

const std::string& executable_fingerprint() {
  static const std::string value = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    if (!in) throw Error("cannot read /proc/self/exe to fingerprint texsim");
    Fingerprint f;
    std::vector<char> buf(1 << 20);
    while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) f.bytes(buf.data(), size_t(in.gcount()));
    return f.hex();
  }();
  return value;
}

std::string default_store_dir() {
  if (const char* s = std::getenv("TEXSIM_STORE"); s && *s) return s;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "texsim" / "results").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "texsim" / "results").string();
  return (fs::temp_directory_path() / "texsim-results").string();
}

ResultStore::ResultStore(std::string dir) {
  std::error_code ec;
  dir_ = fs::absolute(dir, ec).lexically_normal().string();  // (tasks run elsewhere: the manifest and their commands name it)
  if (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_, ec)) throw Error("--store " + dir_ + ": cannot create the results directory");
  if (access(dir_.c_str(), W_OK | X_OK) != 0)
    throw Error("--store " + dir_ + ": cannot write in the results directory (" + std::strerror(errno) + ")");
}

std::string ResultStore::path_of(const std::string& key) const {
  const std::string h = Fingerprint().text(key).hex();
  return (fs::path(dir_) / h.substr(0, 2) / (h + ".txt")).string();
}

std::optional<std::string> ResultStore::get(const std::string& key) const {
  std::ifstream in(path_of(key), std::ios::binary);
  if (!in) return std::nullopt;
  std::string k, result, rest;
  if (!std::getline(in, k) || k != key || !std::getline(in, result) || in.eof() || std::getline(in, rest))
    return std::nullopt;  // (the result line ends in a line break: a file cut short is not a result)
  return result;
}

std::string ResultStore::file_of(const std::string& key, const std::string& suffix) const {
  const fs::path p = path_of(key);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

void ResultStore::put_file(const std::string& key, const std::string& suffix, const std::string& from) const {
  const fs::path target = file_of(key, suffix);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  const fs::path tmp = target.parent_path() / (".tmp-" + target.filename().string() + "-" + std::to_string(getpid()));
  if (!fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec) ||
      std::rename(tmp.c_str(), target.c_str()) != 0) {
    fs::remove(tmp, ec);
    throw Error("--store: cannot keep " + from + " as " + target.string());
  }
}

void ResultStore::put(const std::string& key, const std::string& result) const {
  if (key.find('\n') != std::string::npos || result.find('\n') != std::string::npos)
    throw Error("ResultStore::put: a key or result of more than one line");
  const fs::path target = path_of(key);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  std::string tmp = (target.parent_path() / (".tmp-" + target.filename().string() + "-XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0) throw Error("--store: cannot write in " + target.parent_path().string() + " (" + std::strerror(errno) + ")");
  const std::string text = key + "\n" + result + "\n";
  bool ok = write(fd, text.data(), text.size()) == ssize_t(text.size());
  ok = (fchmod(fd, 0644) == 0) && ok;
  ok = (close(fd) == 0) && ok;
  if (!ok || std::rename(tmp.c_str(), target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw Error("--store: cannot write " + target.string() + " (" + why + ")");
  }
}

}  // namespace tex

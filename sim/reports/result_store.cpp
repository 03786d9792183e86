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

#include "model/error.h"

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

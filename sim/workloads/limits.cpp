#include "workloads/limits.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>
#include <filesystem>

#include "model/error.h"
#include "workloads/text.h"

namespace tex {

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

uint64_t g_limit = 0;  // 0: not set yet (the default)
double g_import_seconds = 0;  // 0: by the file's size
uint64_t g_import_bytes = 0;  // 0: by the file's size
thread_local AllocationBudget* t_budget = nullptr;

}  // namespace

uint64_t default_memory_limit() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  uint64_t half = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) / 2 : uint64_t(4) << 30;
  rlimit data{};
  if (!kSanitized && ::getrlimit(RLIMIT_DATA, &data) == 0 && data.rlim_cur != RLIM_INFINITY)
    half = std::min<uint64_t>(half, data.rlim_cur);
  return half;
}

void set_memory_limit(uint64_t bytes) {
  g_limit = bytes;
  if (kSanitized) return;
  rlimit data{};
  if (::getrlimit(RLIMIT_DATA, &data) != 0) return;
  if (data.rlim_max != RLIM_INFINITY && bytes > data.rlim_max)
    throw Error("--max-memory " + memory_words(bytes) + " is above this process's hard data limit (" +
                memory_words(data.rlim_max) + ")");
  data.rlim_cur = bytes;
  ::setrlimit(RLIMIT_DATA, &data);
}

uint64_t memory_limit() { return g_limit ? g_limit : (g_limit = default_memory_limit()); }

void check_memory(uint64_t bytes, const std::string& what) {
  if (bytes <= memory_limit()) return;
  throw Error(what + " needs " + memory_words(bytes) + ", more than --max-memory allows (" + memory_words(memory_limit()) +
              ")");
}

void check_json_memory(const std::string& path) {
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (!ec) check_memory(32 * size, path + ": a JSON file of " + memory_words(size) + ", parsed,");
}

void set_import_memory(uint64_t bytes) { g_import_bytes = bytes; }
bool import_memory_given() { return g_import_bytes != 0; }

uint64_t import_memory(uint64_t input_bytes) {
  if (g_import_bytes) return g_import_bytes;
  return std::min(memory_limit(), (uint64_t(256) << 20) + 64 * std::min<uint64_t>(input_bytes, uint64_t(1) << 50));
}

void set_import_timeout(double seconds) { g_import_seconds = seconds; }

double import_timeout(uint64_t input_bytes) {
  return g_import_seconds > 0 ? g_import_seconds : 30.0 + double(input_bytes) / double(1 << 20);
}

AllocationBudget::AllocationBudget(uint64_t bytes) : left_(int64_t(std::min<uint64_t>(bytes, INT64_MAX))) {
  t_budget = this;
}
AllocationBudget::~AllocationBudget() { t_budget = nullptr; }

void* allocate_within_budget(size_t n) {
  AllocationBudget* b = t_budget;
  if (b && (n > uint64_t(INT64_MAX) || int64_t(n) > b->left_)) {
    b->exceeded_ = true;
    throw std::bad_alloc();
  }
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  if (b) b->left_ -= int64_t(::malloc_usable_size(p));
  return p;
}

void free_within_budget(void* p) noexcept {
  if (!p) return;
  if (AllocationBudget* b = t_budget) b->left_ += int64_t(::malloc_usable_size(p));
  std::free(p);
}

uint64_t parse_memory_size(const std::string& text, const std::string& option) {
  const std::string bad = option + " " + quote_clipped(text) + " is not a size (e.g. 512M, 8G, 1.5G; K, M, G, T: binary units)";
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || !std::isfinite(number) || number <= 0) throw Error(bad);
  const std::string unit(end);
  int shift = 0;
  if (unit == "K" || unit == "KiB" || unit == "k") shift = 10;
  else if (unit == "M" || unit == "MiB") shift = 20;
  else if (unit == "G" || unit == "GiB") shift = 30;
  else if (unit == "T" || unit == "TiB") shift = 40;
  else if (!unit.empty()) throw Error(bad);
  const double bytes = std::ldexp(number, shift);
  if (bytes < 1 || bytes > std::ldexp(1.0, 60)) throw Error(bad);
  return uint64_t(bytes);
}

}  // namespace tex

// texsim's operator new and delete: malloc and free, counted against the thread's AllocationBudget
// when it has one. Every form but the aligned ones is replaced, so that a build with AddressSanitizer
// (which has its own) never frees through one what the other allocated; the aligned forms are
// neither counted nor credited.
void* operator new(size_t n) { return tex::allocate_within_budget(n); }
void* operator new[](size_t n) { return tex::allocate_within_budget(n); }
void* operator new(size_t n, const std::nothrow_t&) noexcept {
  try {
    return tex::allocate_within_budget(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](size_t n, const std::nothrow_t& tag) noexcept { return operator new(n, tag); }
void operator delete(void* p) noexcept { tex::free_within_budget(p); }
void operator delete[](void* p) noexcept { tex::free_within_budget(p); }
void operator delete(void* p, size_t) noexcept { tex::free_within_budget(p); }
void operator delete[](void* p, size_t) noexcept { tex::free_within_budget(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { tex::free_within_budget(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { tex::free_within_budget(p); }

// What one texsim run may use on any input (docs/robustness.md): memory (--max-memory) and the
// time a model's import may take (--import-timeout).
//
// Memory has two guards:
//  - the project's own parsers check what a file's header sizes (image and level sizes, layer
//    counts, JSON and line lengths) against the limit before allocating for it, and fail with one
//    line naming the file, the field and the value (check_memory);
//  - everything else, Assimp's importers and the image libraries included, runs under the
//    process's data limit (RLIMIT_DATA: private writable memory, what malloc and new take), so an
//    allocation past it fails (std::bad_alloc, a library's error) instead of taking the machine.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace tex {

// Half the machine's physical memory, or the data limit texsim inherited if that is lower (a
// cluster job's, a parent texsim's, `ulimit -d`).
uint64_t default_memory_limit();

// Sets the limit (and RLIMIT_DATA to it; not in a build with AddressSanitizer, whose shadow
// memory counts as data). Throws tex::Error if it is above the hard data limit. Before any call,
// memory_limit() is default_memory_limit().
void set_memory_limit(uint64_t bytes);
uint64_t memory_limit();

// Throws tex::Error "WHAT needs N MiB, more than --max-memory allows (M GiB)" if `bytes` exceed
// the limit. `what` names the file and the field, e.g. "a.dds: 6 faces of 8192 x 8192".
void check_memory(uint64_t bytes, const std::string& what);

// A model file's import (Assimp) is bounded by what its input needs, not only by the limit:
//  - memory: the importing thread's C++ allocations (Assimp's `new`, its vectors) may take 256 MiB
//    plus 64 times the bytes it reads (the file, a .gltf's buffers too; Assimp takes 5 to 30 times
//    a file's size on the test models), at most --max-memory, unless set_import_memory gave a
//    figure (--import-memory); past it the allocation fails and the import stops with one line;
//  - time: 30 s plus 1 s per MiB it reads (Assimp reads tens of MiB a second), unless
//    set_import_timeout gave a time (--import-timeout); past it the run stops with one line
//    (workloads/mesh_scene.cpp: Assimp's importers cannot be interrupted).
void set_import_memory(uint64_t bytes);  // > 0
uint64_t import_memory(uint64_t input_bytes);
bool import_memory_given();
void set_import_timeout(double seconds);  // > 0
double import_timeout(uint64_t input_bytes);

// texsim's operator new and delete (limits.cpp), which count against the thread's budget.
void* allocate_within_budget(size_t bytes);
void free_within_budget(void* p) noexcept;

// While alive, the C++ allocations of the thread that made it (operator new, which texsim
// replaces) fail with std::bad_alloc once they hold more than `bytes` beyond what they freed.
// One at a time per thread.
class AllocationBudget {
 public:
  explicit AllocationBudget(uint64_t bytes);
  ~AllocationBudget();
  AllocationBudget(const AllocationBudget&) = delete;
  AllocationBudget& operator=(const AllocationBudget&) = delete;
  bool exceeded() const { return exceeded_; }  // an allocation was refused

 private:
  friend void* allocate_within_budget(size_t);
  friend void free_within_budget(void*) noexcept;
  int64_t left_;
  bool exceeded_ = false;
};

// A JSON file (scene file, camera path) against the limit before it is parsed: its document takes
// up to 32 bytes per byte of text (nlohmann::json's values and strings). Throws tex::Error naming
// the file and its size.
void check_json_memory(const std::string& path);

// "512 MiB", "12 GiB", "1.5 GiB" (binary units). (Inline: the image module, which links nothing
// of texsim's, words its refusals with it too.)
inline std::string memory_words(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  double v = double(bytes);
  while (v >= 1024 && u < 6) v /= 1024, ++u;
  char text[32];
  const double tenths = std::round(v * 10) / 10;  // one decimal below 100, none where it is 0
  if (u == 0 || v >= 100 || tenths == std::floor(tenths))
    std::snprintf(text, sizeof text, "%.0f %s", v, units[u]);
  else
    std::snprintf(text, sizeof text, "%.1f %s", tenths, units[u]);
  return text;
}

// What an image of w x h pixels of `channels` 8-bit values costs once read: the values, its RGBA
// texels (8 bytes each) and their pyramid (a third more): the figure checked against the limit
// before any pixel is read.
inline uint64_t decoded_image_bytes(uint64_t width, uint64_t height, int channels) {
  return width * height * (uint64_t(channels) + 19);
}

// "8G", "512M", "1.5G", "2048K", "1T" (binary units; a bare number is bytes). Throws tex::Error
// naming `option` for anything else, 0 or a size above 2^60.
uint64_t parse_memory_size(const std::string& text, const std::string& option);

}  // namespace tex

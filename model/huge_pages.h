// An allocator for the model's big buffers (texture levels, the pyramid's sums, the fast path's
// packed copy): buffers of 2 MiB and more are aligned to 2 MiB and offered to the kernel as
// transparent huge pages, so filling a 1024x1024 texture costs a few page faults instead of
// thousands (on a VM a fault costs microseconds: texsim's set-up was half page faults).
// Smaller buffers come from operator new as usual. Elements are value-initialised as by
// std::allocator, so a vector with this allocator behaves exactly as one without.
#pragma once
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tex {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr size_t kHugePage = size_t(2) << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without THP the buffer works as before
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) {
    if (n * sizeof(T) < kHugePage)
      ::operator delete(p);
    else
      std::free(p);
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

// A vector on huge pages when it is big.
template <class T>
using BigVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace tex

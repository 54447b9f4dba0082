#pragma once
// Allocator for the large arrays the kernels read at random (the wide BVH's nodes and leaf
// blocks): allocations of 2 MB and more are 2 MB aligned and advised for transparent huge pages
// (madvise(MADV_HUGEPAGE); Debian's default THP mode is "madvise", so nothing else gets them).
// A ray touches a few nodes and blocks spread over the whole structure; with 4 KB pages most of
// those accesses also miss the TLB. Embree advises its BVH memory the same way. Where huge pages
// are off the advice is ignored and nothing changes. Elements are default-initialised (see
// construct()): a resized vector of trivial elements holds indeterminate values until written.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace pierce {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  constexpr HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = std::aligned_alloc(kHugePageBytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
    ::madvise(p, rounded, MADV_HUGEPAGE);  // advice only: its failure changes nothing but speed
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBytes) ::operator delete(p, std::align_val_t(alignof(T)));
    else std::free(p);
  }
  // Default-initialises where a vector would value-initialise: a resize of trivial elements then
  // leaves the pages untouched, for the parallel writer to fault in (and zero) where it writes.
  template <class U>
  void construct(U* p) noexcept(noexcept(::new (static_cast<void*>(p)) U)) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <class U>
  friend constexpr bool operator==(const HugePageAllocator&, const HugePageAllocator<U>&) noexcept {
    return true;
  }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace pierce

#pragma once
// Allocator for the large arrays the kernels read at random (the wide BVH's nodes and leaf
// blocks): allocations of 2 MB and more are 2 MB aligned and advised for transparent huge pages
// (madvise(MADV_HUGEPAGE); Debian's default THP mode is "madvise", so nothing else gets them).
// A ray touches a few nodes and blocks spread over the whole structure; with 4 KB pages most of
// those accesses also miss the TLB. Embree advises its BVH memory the same way. Where huge pages
// are off the advice is ignored and nothing changes. Elements are default-initialised (see
// construct()): a resized vector of trivial elements holds indeterminate values until written.
//
// advise_huge_pages() gives the same advice for a buffer allocated elsewhere (a std::vector the
// public API hands out, such as a loaded mesh or a result table), before it is first written. Each
// 4 KB page of a fresh buffer is otherwise a page fault of its own, and on virtual machines a fault
// costs microseconds: with 4 KB pages, `pierce_bench_thickness` takes about 95 000 faults to load,
// build and trace its 1.6 M-triangle shell (`/usr/bin/time -v` counts them), most of them in
// buffers filled once at full speed. (glibc can advise every large malloc() buffer,
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, but only from the environment at start-up, which a
// library does not control.)
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace pierce {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// Advises the whole 2 MB pages within [p, p + bytes) for transparent huge pages. Advice only: where
// it fails or huge pages are off, nothing changes but speed.
inline void advise_huge_pages(const void* p, std::size_t bytes) {
  const auto start = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (start + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t last = (start + bytes) & ~(kHugePageBytes - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

// v.reserve(n), with a newly allocated buffer advised for huge pages before anything writes it.
template <class Vector>
void reserve_huge(Vector& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(*v.data()));
}

// std::vector<T>(n, value), in a buffer advised for huge pages before the fill.
template <class T>
std::vector<T> huge_vector(std::size_t n, const T& value = T()) {
  std::vector<T> v;
  reserve_huge(v, n);
  v.resize(n, value);
  return v;
}

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
    advise_huge_pages(p, rounded);
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

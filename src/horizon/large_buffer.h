// Buffers of tens of megabytes that a sweep fills once per run and reads or writes all over: the
// transposed heights, the planes each direction is written into and the hull arenas. On Linux they
// ask for transparent huge pages (most systems grant them only on request), so that a 64 MB plane
// faults in with 32 faults instead of 16384, and a direction that walks columns, which writes each
// cell of its row into another row of the plane 16 KB on, does not touch a new page per cell.
// Measured in docs/benchmarks.md (Dec 4): 62 -> 71 M/s on oblique directions. Where the kernel
// declines, they are plain memory.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace skyview::detail {

struct FreeLargeBuffer {
  void operator()(void* p) const { std::free(p); }
};

template <class T>
using LargeBuffer = std::unique_ptr<T[], FreeLargeBuffer>;

// Uninitialised storage for n values of T (a trivial type).
template <class T>
LargeBuffer<T> allocate_large(std::size_t n) {
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  const std::size_t bytes = n * sizeof(T);
  if (bytes < kHuge) {
    void* p = std::malloc(bytes > 0 ? bytes : 1);
    if (!p) throw std::bad_alloc();
    return LargeBuffer<T>(static_cast<T*>(p));
  }
  const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
  void* p = std::aligned_alloc(kHuge, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure leaves ordinary pages
#endif
  return LargeBuffer<T>(static_cast<T*>(p));
}

}  // namespace skyview::detail

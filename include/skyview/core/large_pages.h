#pragma once
// Memory for buffers of tens of megabytes that are filled once and then read or written all over:
// horizon planes, transposed heights, hull arenas. On Linux, blocks of 2 MB or more ask for
// transparent huge pages (most systems grant them only on request), so that a 64 MB plane faults in
// with 32 faults instead of 16384, and a sweep direction that walks columns, which writes each cell
// of its row into another row of the plane 16 KB on, does not touch a new page per cell. Measured in
// docs/benchmarks.md (Dec 4): the oblique streamed sweep at 4000 x 4000 went from 62 to 68-72 M
// cell-directions/s, the whole-field path from 30-39 to 45-65. Where the kernel declines, this is
// plain memory.
#include <cstddef>
#include <memory>

namespace skyview {

// The size of an x86-64 huge page: blocks of at least this much start on a multiple of it and ask
// for huge pages; smaller ones are ordinary heap memory.
constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// Uninitialised storage; throws std::bad_alloc. Freed by free_large_pages only.
void* allocate_large_pages(std::size_t bytes);
void free_large_pages(void* p) noexcept;

// For containers: std::vector<float, LargePageAllocator<float>>.
template <class T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_large_pages(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { free_large_pages(p); }
  template <class U>
  bool operator==(const LargePageAllocator<U>&) const noexcept {
    return true;
  }
};

struct FreeLargePages {
  void operator()(void* p) const noexcept { free_large_pages(p); }
};

// n uninitialised values of a trivial type T.
template <class T>
using LargeBuffer = std::unique_ptr<T[], FreeLargePages>;
template <class T>
LargeBuffer<T> allocate_large(std::size_t n) {
  return LargeBuffer<T>(static_cast<T*>(allocate_large_pages(n * sizeof(T))));
}

}  // namespace skyview

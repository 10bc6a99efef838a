// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Storage for the kernel's large arrays (sphere records, neighbour rows, grid cells): blocks of
// at least one large page are aligned to it and offered to the kernel as transparent huge pages
// (madvise), because the trial loop reads them at random and, with 4 KiB pages, a bed of 10^5
// spheres and more misses the TLB on most picks. Smaller blocks come from the plain allocator.
#ifndef TAPMC_MEMORY_H
#define TAPMC_MEMORY_H

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tapmc {

constexpr std::size_t kLargePageBytes = std::size_t{2} << 20;  // x86-64 and aarch64 (4 KiB base)

template <class T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U> &)
  {
  }
  T *allocate(std::size_t n)
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kLargePageBytes) return std::allocator<T>().allocate(n);
    const std::size_t rounded = (bytes + kLargePageBytes - 1) / kLargePageBytes * kLargePageBytes;
    void *p = std::aligned_alloc(kLargePageBytes, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without THP the pages stay small
#endif
    return static_cast<T *>(p);
  }
  void deallocate(T *p, std::size_t n)
  {
    if (n * sizeof(T) < kLargePageBytes)
      std::allocator<T>().deallocate(p, n);
    else
      std::free(p);
  }
  template <class U>
  bool operator==(const LargePageAllocator<U> &) const
  {
    return true;
  }
  template <class U>
  bool operator!=(const LargePageAllocator<U> &) const
  {
    return false;
  }
};

template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace tapmc

#endif

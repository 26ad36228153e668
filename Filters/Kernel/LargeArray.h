// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LargeArray.h
 * @brief std::vector for the large arrays of one projection, on huge pages.
 *
 * A projection of 10^6 cells fills a few hundred MiB of fresh arrays (the
 * mass matrix, neighbours, stamps, solver vectors). Touched 4 KiB page by
 * 4 KiB page, they cost the process a page fault each: about a tenth of
 * the whole run was spent in the operating system's fault handler on the
 * project's benchmark machine. LargeAllocator gives blocks of 2 MiB and more
 * 2 MiB-aligned and, on Linux, advises them as transparent huge pages
 * (MADV_HUGEPAGE: honoured when the system's setting is "madvise" or
 * "always", ignored under "never"), so that one fault maps 2 MiB. Smaller
 * blocks, and other systems, get plain operator new.
 */
#ifndef MeshProjection_Kernel_LargeArray_h
#define MeshProjection_Kernel_LargeArray_h

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mp
{
template <class T>
struct LargeAllocator
{
  using value_type = T;
  static constexpr std::size_t HugePage = std::size_t(1) << 21; // 2 MiB

  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept
  {
  }

  T* allocate(std::size_t n)
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < HugePage)
    {
      return static_cast<T*>(::operator new(bytes));
    }
    const std::size_t rounded = (bytes + HugePage - 1) / HugePage * HugePage;
    void* p = std::aligned_alloc(HugePage, rounded);
    if (!p)
    {
      throw std::bad_alloc();
    }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE); // advice only: failure changes nothing
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept
  {
    if (n * sizeof(T) < HugePage)
    {
      ::operator delete(p);
    }
    else
    {
      std::free(p);
    }
  }

  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept
  {
    return true;
  }
  template <class U>
  bool operator!=(const LargeAllocator<U>&) const noexcept
  {
    return false;
  }
};

/// A std::vector whose large buffers sit on huge pages where the system allows.
template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;
} // namespace mp

#endif

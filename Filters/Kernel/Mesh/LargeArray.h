// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LargeArray.h
 * @brief std::vector for the large arrays of one projection, on huge pages.
 *
 * A projection of 10^6 cells fills a few hundred MiB of fresh arrays (the
 * mass matrix, neighbours, stamps, solver vectors). Touched 4 KiB page by
 * 4 KiB page, they cost the process a page fault each, and the operating
 * system's fault handler becomes a visible part of the run.
 * LargeAllocator gives blocks of 2 MiB and more
 * 2 MiB-aligned and, on Linux, maps them straight from the system (so that
 * they go back to it when freed, not into the C library's heap, where a
 * freed block keeps its pages) and advises them as transparent huge pages
 * (MADV_HUGEPAGE: honoured when the system's setting is "madvise" or
 * "always", ignored under "never"), so that one fault maps 2 MiB. Smaller
 * blocks get plain operator new; other systems aligned_alloc.
 */
#ifndef MeshProjection_Kernel_LargeArray_h
#define MeshProjection_Kernel_LargeArray_h

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace mp
{
template <class T>
struct LargeAllocator
{
  using value_type = T;
  static constexpr std::size_t HugePage = std::size_t(1) << 21; // 2 MiB

  static std::size_t Rounded(std::size_t bytes)
  {
    return (bytes + HugePage - 1) / HugePage * HugePage;
  }

#if defined(__linux__)
  /// What allocate() keeps mapped of a block of `bytes`: up to the next system page.
  static std::size_t Mapped(std::size_t bytes)
  {
    static const std::size_t page = [] {
      const long size = sysconf(_SC_PAGESIZE);
      return size > 0 && HugePage % static_cast<std::size_t>(size) == 0
        ? static_cast<std::size_t>(size)
        : HugePage;
    }();
    return (bytes + page - 1) / page * page;
  }
#endif

  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept
  {}

  T* allocate(std::size_t n)
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < HugePage)
    {
      return static_cast<T*>(::operator new(bytes));
    }
    const std::size_t rounded = Rounded(bytes);
#if defined(__linux__)
    // Straight from the system, 2 MiB-aligned: given back on deallocate
    // (the C library could keep a freed block of the heap for later, and
    // the process would keep its pages). No swap reserved up front: a
    // generous reservation (the assembler's block buffers) costs only the
    // pages it touches, also under strict overcommit accounting.
    void* raw = mmap(nullptr, rounded + HugePage, PROT_READ | PROT_WRITE,
      MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (raw == MAP_FAILED)
    {
      throw std::bad_alloc();
    }
    char* begin = static_cast<char*>(raw);
    char* aligned =
      begin + (HugePage - reinterpret_cast<std::uintptr_t>(begin) % HugePage) % HugePage;
    if (aligned > begin)
    {
      munmap(begin, static_cast<std::size_t>(aligned - begin));
    }
    // Mapped up to the system page after the last element only: a huge
    // page there would be faulted whole for the few bytes of the block's
    // end that it holds (on average 1 MiB of every block, some 10% of a
    // projection's peak), so the block's end is on small pages.
    const std::size_t kept = Mapped(bytes);
    const std::size_t tail =
      static_cast<std::size_t>(begin + rounded + HugePage - (aligned + kept));
    if (tail > 0)
    {
      munmap(aligned + kept, tail);
    }
#if defined(MADV_HUGEPAGE)
    // Advice only (failure changes nothing), on the whole huge pages.
    if (bytes >= HugePage)
    {
      madvise(aligned, bytes / HugePage * HugePage, MADV_HUGEPAGE);
    }
#endif
    return reinterpret_cast<T*>(aligned);
#else
    void* p = std::aligned_alloc(HugePage, rounded);
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
#endif
  }

  void deallocate(T* p, std::size_t n) noexcept
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < HugePage)
    {
      ::operator delete(p);
      return;
    }
#if defined(__linux__)
    munmap(p, Mapped(bytes));
#else
    std::free(p);
#endif
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

/**
 * LargeAllocator whose elements are default-initialized: resize() leaves
 * plain values as they are instead of writing zeros, so that a vector
 * filled afterwards by concurrent tasks is first touched by those tasks.
 * (A fresh page costs its first writer a page fault, far dearer than
 * writing the page, above all on virtual machines that hand freed memory
 * back to their host; so one thread zeroing a large array is a long
 * serial stretch of a run.)
 */
template <class T>
struct UninitializedAllocator : LargeAllocator<T>
{
  using value_type = T;
  template <class U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A LargeVector whose resize() does not initialize plain values: callers
/// write every element (see UninitializedAllocator).
template <class T>
using UninitializedLargeVector = std::vector<T, UninitializedAllocator<T>>;

/**
 * A fixed-size array on the same pages, left uninitialized: for arrays that
 * are written whole before they are read (a vector would first write
 * zeros over all of it, one thread touching every page), such as the
 * renumbered copy of a mesh.
 */
template <class T>
class LargeBuffer
{
  static_assert(std::is_trivially_copyable<T>::value, "LargeBuffer holds plain values");

public:
  LargeBuffer() = default;
  explicit LargeBuffer(std::size_t n)
    : Values(n > 0 ? LargeAllocator<T>().allocate(n) : nullptr)
    , Count(n)
  {}
  LargeBuffer(const LargeBuffer&) = delete;
  LargeBuffer& operator=(const LargeBuffer&) = delete;
  LargeBuffer(LargeBuffer&& other) noexcept { this->swap(other); }
  LargeBuffer& operator=(LargeBuffer&& other) noexcept
  {
    LargeBuffer(std::move(other)).swap(*this);
    return *this;
  }
  ~LargeBuffer()
  {
    if (this->Values)
    {
      LargeAllocator<T>().deallocate(this->Values, this->Count);
    }
  }
  void swap(LargeBuffer& other) noexcept
  {
    std::swap(this->Values, other.Values);
    std::swap(this->Count, other.Count);
  }
  T* data() noexcept { return this->Values; }
  const T* data() const noexcept { return this->Values; }
  std::size_t size() const noexcept { return this->Count; }
  bool empty() const noexcept { return this->Count == 0; }

private:
  T* Values = nullptr;
  std::size_t Count = 0;
};
} // namespace mp

#endif

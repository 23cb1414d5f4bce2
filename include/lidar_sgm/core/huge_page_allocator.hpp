#pragma once
/// @file huge_page_allocator.hpp  Large buffers on transparent huge pages.
///
/// Why: a buffer is mapped page by page when it is first written. On 4 KiB pages the images,
/// census images, cost volume and clouds of one KITTI frame take ~22,000 page faults, which on
/// the project's VM cost as much as the frame's matching: a one-shot `lidar_sgm_densify` spent
/// about 0.2 of its 0.5 s in them (BENCHMARK.md, "One scan end to end"). Blocks of at least
/// kHugePageThreshold bytes are therefore aligned to 2 MiB and advised MADV_HUGEPAGE (Debian's
/// default THP mode is "madvise", which maps nothing on huge pages unasked), so that they map in a
/// few faults; smaller blocks come from operator new as usual. Without THP (or off Linux) the
/// advice is a no-op and the block simply has small pages.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#endif

// Under AddressSanitizer the blocks come from its allocator instead (unadvised), so that it still
// checks every access to them.
#if defined(__SANITIZE_ADDRESS__)
#define LIDAR_SGM_HUGE_PAGES_MAPPED 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LIDAR_SGM_HUGE_PAGES_MAPPED 0
#endif
#endif
#if !defined(LIDAR_SGM_HUGE_PAGES_MAPPED) && defined(__linux__)
#define LIDAR_SGM_HUGE_PAGES_MAPPED 1
#elif !defined(LIDAR_SGM_HUGE_PAGES_MAPPED)
#define LIDAR_SGM_HUGE_PAGES_MAPPED 0
#endif

namespace lidar_sgm {

/// Blocks this large or larger are placed on huge pages (a 2 MiB page holds at least half data).
constexpr std::size_t kHugePageThreshold = std::size_t{1} << 20;
constexpr std::size_t kHugePageSize = std::size_t{2} << 20;
/// A block's last, partial huge page is advised when at least 1 / kHugeTailFraction of it is data.
constexpr std::size_t kHugeTailFraction = 4;

/// `bytes` rounded up to whole 2 MiB pages.
inline std::size_t hugePageBytes(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePageSize - 1) / kHugePageSize * kHugePageSize;
  if (rounded < bytes) throw std::bad_alloc();
  return rounded;
}

/// hugePageBytes(bytes) of zeroed memory, 2 MiB aligned and advised as huge pages (the last, partial
/// page only when at least a quarter of it is data, kHugeTailFraction), mapped for this
/// block alone: the advice leaves with the block (inside malloc's heap it would outlive the block
/// and put later small blocks on huge pages too). Release it with freeHugePages. Throws
/// std::bad_alloc.
inline void* allocateHugePages(std::size_t bytes) {
  const std::size_t rounded = hugePageBytes(bytes);
#if LIDAR_SGM_HUGE_PAGES_MAPPED
  // One page more than needed, then the unaligned ends given back.
  const std::size_t span = rounded + kHugePageSize;
  void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto begin = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (begin + kHugePageSize - 1) / kHugePageSize * kHugePageSize;
  if (aligned > begin) munmap(raw, aligned - begin);
  const std::uintptr_t end = begin + span;
  if (end > aligned + rounded) munmap(reinterpret_cast<void*>(aligned + rounded), end - (aligned + rounded));
  // A hint (without THP, small pages). The last, partial page is advised too when at least a
  // quarter of it is data: a tail of t bytes on small pages costs t / 4 KiB first writes, ~14 us
  // each on the project's VM, a huge page ~0.18 ms there (64 MiB written once in 5.6 ms): the huge
  // page is quicker from ~50 KiB on, and a quarter keeps the unused memory under 1.5 MiB a block.
  // (A frame's new cloud of 433,497 points had a 0.96 MiB tail, 246 faults a frame, at a half.)
  const std::size_t whole = bytes / kHugePageSize * kHugePageSize;
  const std::size_t advised = (bytes - whole) * kHugeTailFraction >= kHugePageSize ? rounded : whole;
  if (advised > 0) madvise(reinterpret_cast<void*>(aligned), advised, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
#else
  void* memory = std::aligned_alloc(kHugePageSize, rounded);
  if (memory == nullptr) throw std::bad_alloc();
  return memory;
#endif
}

/// Releases a block of allocateHugePages(bytes).
inline void freeHugePages(void* block, std::size_t bytes) noexcept {
  if (block == nullptr) return;
#if LIDAR_SGM_HUGE_PAGES_MAPPED
  munmap(block, (bytes + kHugePageSize - 1) / kHugePageSize * kHugePageSize);
#else
  (void)bytes;
  std::free(block);
#endif
}

/// Advises the whole 2 MiB pages inside [data, data + bytes) as huge pages, for a block someone
/// else allocated (a PCL cloud, a cv::Mat) and nobody has written yet: call it after reserve() or
/// create() and before the first write. Smaller blocks are left alone.
inline void adviseHugePages(const void* data, std::size_t bytes) {
#ifdef __linux__
  if (data == nullptr || bytes < kHugePageThreshold) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePageSize - 1) / kHugePageSize * kHugePageSize;
  const std::uintptr_t last = (begin + bytes) / kHugePageSize * kHugePageSize;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

/// Reserves `n` elements of a vector-like container and advises them as huge pages before they
/// are written (see adviseHugePages).
template <typename Container>
void reserveOnHugePages(Container& container, std::size_t n) {
  container.reserve(n);
  adviseHugePages(container.data(), container.capacity() * sizeof(*container.data()));
}

/// A std::allocator for containers that may grow large (Image, the backends' buffers): blocks of
/// kHugePageThreshold bytes or more from allocateHugePages, smaller ones from std::allocator.
template <typename T>
class HugePageAllocator {
 public:
  using value_type = T;

  HugePageAllocator() noexcept = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor): rebinding

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    if (!huge(n)) return std::allocator<T>().allocate(n);
    return static_cast<T*>(allocateHugePages(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (huge(n)) {
      freeHugePages(p, n * sizeof(T));
    } else {
      std::allocator<T>().deallocate(p, n);
    }
  }

  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
  template <typename U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept {
    return false;
  }

 private:
  static bool huge(std::size_t n) { return n * sizeof(T) >= kHugePageThreshold; }
};

/// A std::vector whose large storage lies on huge pages.
template <typename T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace lidar_sgm

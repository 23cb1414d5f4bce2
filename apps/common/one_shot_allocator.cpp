// Why a one-shot tool allocates through jemalloc on huge pages: a process that densifies one frame
// writes every buffer for the first time, and each 4 KiB page costs a page fault when it is first
// written. On the project's VM that costs ~14 us a page (64 MiB written once: 225 ms on 4 KiB
// pages, 6 ms on 2 MiB pages once the memory is the process's), and lidar_sgm_densify took ~12,500
// page faults on a KITTI frame. The frame's large buffers are already on huge pages (HugePageAllocator);
// the rest (images below 1 MiB, the scan, the PNG rows, the PCL cloud, vectors of the passes) come
// from malloc. jemalloc with `thp:always` puts all of its memory on huge pages and keeps freed
// memory for the next block: ~2,100 faults, and the whole process 244 -> 137 ms (BENCHMARK.md,
// "One scan end to end"). A sequence (lidar_sgm_batch) pays the faults once and
// measured no gain, so it keeps the C library's malloc.
#include "common/one_shot_allocator.hpp"

#include <cstdint>
#include <cstdlib>

#ifdef LIDAR_SGM_WITH_JEMALLOC
#include <jemalloc/jemalloc.h>

// jemalloc reads its options from this symbol of the executable when it starts (before main):
// every mapping advised MADV_HUGEPAGE (Debian's THP mode "madvise" maps none unasked), its own
// metadata too once it grows, and one arena (the tools' threads allocate little in their loops;
// jemalloc's default of 4 per core held 7 MiB more at the peak, at the same speed).
extern "C" {
JEMALLOC_EXPORT const char* malloc_conf = "thp:always,metadata_thp:auto,narenas:1";
}
#endif

namespace lidar_sgm {
namespace apps {

std::string allocatorDescription() {
#ifdef LIDAR_SGM_WITH_JEMALLOC
  const char* version = nullptr;
  const char* thp = nullptr;
  std::size_t size = sizeof(const char*);
  const bool known = mallctl("version", &version, &size, nullptr, 0) == 0 &&
                     mallctl("opt.thp", &thp, &size, nullptr, 0) == 0;
  // Whether malloc itself is jemalloc's (not only linked): this thread's count of bytes jemalloc
  // allocated grows by a block malloc hands out.
  std::uint64_t before = 0;
  std::uint64_t after = 0;
  size = sizeof(std::uint64_t);
  mallctl("thread.allocated", &before, &size, nullptr, 0);
  void* volatile block = std::malloc(1 << 16);
  mallctl("thread.allocated", &after, &size, nullptr, 0);
  std::free(block);
  if (known && after > before) {
    const std::string release(version);  // "5.3.0-0-g<commit>": the release is before the first '-'
    return "jemalloc " + release.substr(0, release.find('-')) + ", transparent huge pages: " + thp;
  }
#endif
  return "the C library's malloc";
}

}  // namespace apps
}  // namespace lidar_sgm

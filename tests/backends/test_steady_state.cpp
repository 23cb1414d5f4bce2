// After the first frame of a given size, a fast backend's frame allocates nothing: every buffer
// is kept ("no allocation per frame after the first frame of a given size"). Counted
// with a replaced global operator new, so this suite is its own executable.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "backend_test_scenes.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace {
std::atomic<long> allocations{0};
}  // namespace

// g++ 12 at -O1 and above sees a `new` inlined into a caller and then our free() in the replaced
// delete, and calls them mismatched: they are malloc/free underneath, as the replacement intends.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace lidar_sgm {
namespace {

TEST(SteadyState, SecondFrameOfASizeAllocatesNothing) {
  int tested = 0;
  for (const std::string name : {"cpu", "cuda"}) {
    if (!isAvailable(backendFromString(name))) continue;
    ++tested;
    for (const int paths : {4, 8}) {
      for (const bool stereo : {true, false}) {
        Parameters params;
        params.numDisparities = 64;
        params.paths = paths;
        params.threads = 2;
        const test::BackendScene scene = test::makeBackendScene(131, 61, 0, 64, 5);
        auto matcher = Matcher::create(backendFromString(name), params);
        Image<std::int16_t> out(131, 61);
        const GrayImageView right = stereo ? GrayImageView(scene.right8.view()) : GrayImageView();
        const long first = allocations.load();
        matcher->compute(scene.left8.view(), right, &scene.lidar, out.view());  // allocates its buffers
        EXPECT_GT(allocations.load() - first, 0) << "the counter must see the first frame's buffers";
        const long before = allocations.load();
        matcher->compute(scene.left8.view(), right, &scene.lidar, out.view());
        EXPECT_EQ(allocations.load() - before, 0) << name << ", " << paths << " paths, "
                                                  << (stereo ? "fused" : "LiDAR-only");
      }
    }
  }
  if (tested == 0) GTEST_SKIP() << "no fast backend is built (cpu_ref makes no such promise)";
}

}  // namespace
}  // namespace lidar_sgm

// Large buffers on transparent huge pages (lidar_sgm/core/huge_page_allocator.hpp): the blocks are
// placed and advised as the header says, and hold what is written to them like any vector.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace {

bool alignedToHugePage(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kHugePageSize == 0; }

// The kernel's flags of the mapping that holds `address` ("hg": advised MADV_HUGEPAGE), from
// /proc/self/smaps; empty where there is no such file or mapping.
std::string vmFlagsAt(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0;
    std::uintptr_t end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = a >= begin && a < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line.substr(8);
    }
  }
  return {};
}

// Whether this kernel offers huge pages to a process that asks (THP mode "always" or "madvise").
bool kernelAdvisesHugePages() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(mode, text);
  return text.find("[always]") != std::string::npos || text.find("[madvise]") != std::string::npos;
}

bool advised(const void* address) { return vmFlagsAt(address).find(" hg") != std::string::npos; }

TEST(HugePages, LargeBlocksAreAlignedAndAdvisedSmallOnesAreNot) {
  HugePageVector<std::uint16_t> large(kHugePageThreshold / sizeof(std::uint16_t) + 7, 3);
  ASSERT_TRUE(alignedToHugePage(large.data()));
  EXPECT_EQ(large.front(), 3);
  EXPECT_EQ(large.back(), 3);
  std::vector<std::uint8_t> beside(64 << 10);  // an ordinary block from the same heap
  HugePageVector<std::uint8_t> small(kHugePageThreshold - 1, 5);
  EXPECT_EQ(small[small.size() - 1], 5);
  if (!kernelAdvisesHugePages()) GTEST_SKIP() << "this kernel offers no transparent huge pages";
  if (!LIDAR_SGM_HUGE_PAGES_MAPPED) GTEST_SKIP() << "the sanitizer's allocator holds the blocks";
  EXPECT_TRUE(advised(large.data())) << vmFlagsAt(large.data());
  EXPECT_FALSE(advised(beside.data())) << vmFlagsAt(beside.data());
}

TEST(HugePages, ALastPageLessThanAQuarterUsedKeepsSmallPages) {
  // Two whole pages and an eighth: the eighth would leave 1.75 MiB of a huge page unused.
  HugePageVector<std::uint8_t> eighth(2 * kHugePageSize + kHugePageSize / 8, 1);
  // Two whole pages and three eighths: the last page's 0.75 MiB cost 192 small-page faults, more
  // than the huge page's one fault and clearing.
  HugePageVector<std::uint8_t> threeEighths(2 * kHugePageSize + 3 * kHugePageSize / 8, 2);
  ASSERT_TRUE(alignedToHugePage(eighth.data()));
  ASSERT_TRUE(alignedToHugePage(threeEighths.data()));
  EXPECT_EQ(eighth.back(), 1);
  EXPECT_EQ(threeEighths.back(), 2);
  if (!kernelAdvisesHugePages()) GTEST_SKIP() << "this kernel offers no transparent huge pages";
  if (!LIDAR_SGM_HUGE_PAGES_MAPPED) GTEST_SKIP() << "the sanitizer's allocator holds the blocks";
  EXPECT_TRUE(advised(eighth.data() + kHugePageSize)) << vmFlagsAt(eighth.data() + kHugePageSize);
  EXPECT_FALSE(advised(eighth.data() + 2 * kHugePageSize)) << vmFlagsAt(eighth.data() + 2 * kHugePageSize);
  EXPECT_TRUE(advised(threeEighths.data() + 2 * kHugePageSize)) << vmFlagsAt(threeEighths.data() + 2 * kHugePageSize);
}

TEST(HugePages, VectorsGrowCopyAndCompareLikeAnyVector) {
  HugePageVector<int> v;
  for (int i = 0; i < 600000; ++i) v.push_back(i);  // crosses the threshold while growing
  const HugePageVector<int> copy = v;
  EXPECT_EQ(copy, v);
  EXPECT_EQ(copy[599999], 599999);
  v.resize(10);
  v.shrink_to_fit();  // back below the threshold: freed the way it was allocated
  EXPECT_EQ(v.back(), 9);
}

TEST(HugePages, AFrameSizedImageLiesOnHugePages) {
  Image<std::uint64_t> census(1242, 375);
  EXPECT_TRUE(alignedToHugePage(census.data()));
  census(1241, 374) = 42;
  EXPECT_EQ(census.view()(1241, 374), 42u);
  Image<std::uint8_t> thumbnail(64, 48, 1);
  EXPECT_EQ(thumbnail(63, 47), 1);
}

TEST(HugePages, ReserveOnHugePagesAdvisesAnotherAllocatorsBlock) {
  std::vector<float> cloud;
  reserveOnHugePages(cloud, 3 * kHugePageSize / sizeof(float));
  ASSERT_GE(cloud.capacity(), 3 * kHugePageSize / sizeof(float));
  // The first whole huge page inside the block.
  const auto begin = reinterpret_cast<std::uintptr_t>(cloud.data());
  const auto firstPage = reinterpret_cast<const void*>((begin + kHugePageSize - 1) / kHugePageSize * kHugePageSize);
  cloud.assign(cloud.capacity(), 1.5f);
  EXPECT_EQ(cloud.back(), 1.5f);
  if (!kernelAdvisesHugePages()) GTEST_SKIP() << "this kernel offers no transparent huge pages";
  if (!LIDAR_SGM_HUGE_PAGES_MAPPED) GTEST_SKIP() << "the sanitizer's allocator holds the blocks";
  EXPECT_TRUE(advised(firstPage)) << vmFlagsAt(firstPage);
}

// A frame's buffer alternating between two sizes (the Densifier's matcher: the half-scale witness,
// then the frame) keeps its pixels: neither reallocated nor cleared when it grows back; its views,
// fill and emptiness follow the size asked for.
TEST(HugePages, AnImageThatShrinksAndGrowsBackKeepsItsPixels) {
  Image<std::int16_t> image(1242, 375, 7);
  const std::int16_t* pixels = image.data();
  image.resize(621, 188);
  EXPECT_EQ(image.view().width, 621);
  EXPECT_EQ(image.view().height, 188);
  image.fill(3);
  image.resize(1242, 375);
  EXPECT_EQ(image.data(), pixels);
  EXPECT_EQ(image(0, 0), 3);
  EXPECT_EQ(image(1241, 374), 7) << "the pixels beyond the smaller size were cleared";
  image.resize(0, 0);
  EXPECT_TRUE(image.empty());
  image.resize(2, 2);
  EXPECT_FALSE(image.empty());
}

}  // namespace
}  // namespace lidar_sgm

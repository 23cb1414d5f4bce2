// The LiDAR gate's second pass (lidar_search_windows.hpp), fast CPU backend: each row's extremes
// over +-rows rows as the host takes them (lidarSearchRowExtremes, on the rows that hold a point), then each pixel's window
// (search_window_rule.hpp's searchWindowOf) for a whole vector of pixels at once in 16-bit
// lanes. The rule's branches become masks; every intermediate value fits 16 bits (x16
// disparities in [-32768, 32767] give pixel disparities in [-2048, 2048], the margin and the
// range's ends at most 512 in magnitude: Parameters' limits), and ceil(h / 16) is computed
// without h + 15, which would wrap at the clamped extreme.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/search_window_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "backends/common/lidar_search_windows.hpp"
#include "backends/common/search_window_rule.hpp"
#include "backends/common/search_windows.hpp"
#include "backends/cpu/cpu_kernels.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// searchWindowOf for the Lanes(d) pixels whose neighbourhoods' extremes are low and high.
template <class DI>
HWY_INLINE void WindowsOf(DI d, hn::Vec<DI> low, hn::Vec<DI> high, int minDisparity, int numDisparities, int margin,
                          std::int16_t* first, std::int16_t* count) {
  const auto zero = hn::Zero(d);
  const auto D = hn::Set(d, static_cast<std::int16_t>(numDisparities));
  const auto offset = hn::Set(d, static_cast<std::int16_t>(margin + minDisparity));  // below: - margin - minD
  const auto reach = hn::Set(d, static_cast<std::int16_t>(margin - minDisparity));   // above: + margin - minD
  // floor(low / 16) and ceil(high / 16): arithmetic shifts, the latter plus one where high has a
  // remainder (a true mask is -1).
  const auto below = hn::Sub(hn::ShiftRight<4>(low), offset);
  const auto hasRemainder = hn::VecFromMask(d, hn::Ne(hn::And(high, hn::Set(d, std::int16_t{15})), zero));
  const auto above = hn::Add(hn::Sub(hn::ShiftRight<4>(high), hasRemainder), reach);
  const auto lowest = hn::Max(below, zero);
  const auto last = hn::Min(above, hn::Sub(D, hn::Set(d, std::int16_t{1})));
  // Widened upward to a multiple of 16 indices, then moved down to end inside the range.
  const auto widened = hn::ShiftLeft<4>(hn::ShiftRight<4>(hn::Add(hn::Sub(last, lowest), hn::Set(d, std::int16_t{16}))));
  const auto windowCount = hn::Min(widened, D);
  const auto windowFirst = hn::Min(lowest, hn::Sub(D, windowCount));
  // The whole range without a point, or when every point lies outside the range.
  const auto whole = hn::Or(hn::Gt(low, high), hn::Gt(lowest, last));
  hn::StoreU(hn::IfThenElse(whole, zero, windowFirst), d, first);
  hn::StoreU(hn::IfThenElse(whole, D, windowCount), d, count);
}

// lidarSearchRowExtremes over the rows that hold a point only: pass 1 left the others at the
// sentinels (kSearchNoLowest, kSearchNoHighest), which change no minimum and no maximum. A KITTI
// scan has a point on one row in three or four of its lower part and on none above it.
void RowExtremesOfPointRows(const LidarPoints& points, int rows, int y, std::int16_t* low16, std::int16_t* high16,
                            const SearchWindows& windows) {
  const int width = windows.width();
  const int height = windows.height();
  const SearchWindows::Scratch& scratch = windows.scratch();
  std::fill(low16, low16 + width, kSearchNoLowest);
  std::fill(high16, high16 + width, kSearchNoHighest);
  for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows); ++ny) {
    if (rowPoints(points, ny, 0, width).empty()) continue;  // no point on row ny
    const std::size_t rowStart = static_cast<std::size_t>(ny) * width;
    const std::int16_t* lowRow = scratch.lowest16.data() + rowStart;
    const std::int16_t* highRow = scratch.highest16.data() + rowStart;
    for (int x = 0; x < width; ++x) {
      low16[x] = std::min(low16[x], lowRow[x]);
      high16[x] = std::max(high16[x], highRow[x]);
    }
  }
}

void SearchWindowRowsImpl(const LidarPoints& points, int minDisparity, int rows, int margin, int y0, int y1,
                          std::int16_t* low16, std::int16_t* high16, SearchWindows& windows) {
  const hn::ScalableTag<std::int16_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const int width = windows.width();
  const int numDisparities = windows.numDisparities();
  for (int y = y0; y < y1; ++y) {
    RowExtremesOfPointRows(points, rows, y, low16, high16, windows);
    std::int16_t* first = windows.firstRowToSet(y);
    std::int16_t* count = windows.countRowToSet(y);
    int x = 0;
    for (; x + N <= width; x += N) {
      WindowsOf(d, hn::LoadU(d, low16 + x), hn::LoadU(d, high16 + x), minDisparity, numDisparities, margin, first + x,
                count + x);
    }
    for (; x < width; ++x) {
      int f = 0;
      int n = 0;
      searchWindowOf(low16[x], high16[x], minDisparity, numDisparities, margin, f, n);
      first[x] = static_cast<std::int16_t>(f);
      count[x] = static_cast<std::int16_t>(n);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(SearchWindowRowsImpl);

void searchWindowRows(const LidarPoints& points, int minDisparity, int rows, int margin, int y0, int y1,
                      std::int16_t* low16, std::int16_t* high16, SearchWindows& windows) {
  HWY_DYNAMIC_DISPATCH(SearchWindowRowsImpl)(points, minDisparity, rows, margin, y0, y1, low16, high16, windows);
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE

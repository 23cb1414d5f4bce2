#pragma once
// Row kernels of the fast CPU backend, shared by its whole-volume stages (cpu_stages.hpp) and
// its streaming matcher (row_costs.cpp, sweeps.cpp). Each is dispatched once per row (Highway
// picks the widest instruction set the CPU has), never per pixel, so dispatch costs nothing
// measurable.
//
// Layouts. A cost row holds D = numDisparities bytes per pixel (disparity innermost, as the
// volumes). A path row holds pathSlot(D) = D + 2 elements per pixel: [0] and [D + 1] are
// sentinels (all ones, so that L(d -+ 1) + P1 saturates and never wins past the range ends) and
// [1 .. D] the path costs L_r(p, d) of Eq. 1. D is a multiple of 16 (Parameters).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "backends/common/search_windows.hpp"
#include "backends/common/stages.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace cpu {

inline int pathSlot(int numDisparities) { return numDisparities + 2; }

// The search windows of one row (Parameters::gatedSearch, search_windows.hpp): pixel x searches
// disparity indices [first[x], first[x] + count[x]). Null pointers: every pixel the whole range.
// A gated pixel's path slots hold the sentinel outside its window, so that the next pixel on the
// path reads the terms of Eq. 1 outside it as absent (gated_stages.hpp), and the kernels step
// and select over the window only.
//
// The path kernels read a gated row's costs either in the whole range's layout (pixel x's window
// at (x - costX0) * D + first[x]) or packed: each pixel's window alone, pixel x's from
// costOffset[x] on (the cost volume of a gated frame, cpu_matcher.hpp).
struct RowWindows {
  const std::int16_t* first = nullptr;
  const std::int16_t* count = nullptr;
  const std::uint32_t* costOffset = nullptr;
};

// census.cpp: one row of the census transform (cpu_ref's bit order, border pixels repeated).
void censusTransformRow(ImageView<const std::uint8_t> image, CensusType type, int y, std::uint64_t* out);
void censusTransformRow(ImageView<const std::uint16_t> image, CensusType type, int y, std::uint64_t* out);
// ... of columns x0 .. x1-1 only, into out[x] (the same bits as the whole row's).
void censusTransformRow(ImageView<const std::uint8_t> image, CensusType type, int y, int x0, int x1,
                        std::uint64_t* out);
void censusTransformRow(ImageView<const std::uint16_t> image, CensusType type, int y, int x0, int x1,
                        std::uint64_t* out);

// census_cost.cpp: the right census row as 8 byte planes (plane k holds byte k), columns in
// reverse order from index `pad`, zero-padded by `pad` on both sides (planeStride = width + 2 pad).
int censusPlanePad(int minDisparity, int numDisparities);
void censusPlanes(const std::uint64_t* row, int width, int pad, std::uint8_t* planes, std::size_t planeStride);
// ... of columns xr0 .. xr1-1 only, pads untouched: enough for C_S of pixels x0 .. x1-1 with
// xr0 = max(0, x0 - minDisparity - D + 1), xr1 = min(width, x1 - minDisparity) (row_costs.cpp), since
// the cost kernels replace every lane whose right pixel lies outside the image (censusCostRow).
void censusPlanes(const std::uint64_t* row, int width, int pad, int xr0, int xr1, std::uint8_t* planes,
                  std::size_t planeStride);
// C_S for pixels x0 .. x1-1 of one row into cost[(x - x0) * D + d]; with `windows` only the d of
// each pixel's window (the other entries are left as they were), or with windows.costOffset the
// window alone from cost[costOffset[x]] on (a packed row).
void censusCostRow(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride, int pad,
                   CensusType type, int width, int x0, int x1, int minDisparity, int numDisparities,
                   std::uint8_t* cost, RowWindows windows = {});

// C_S fused at once with C_L (Eq. 5) as in fuseCosts: `lidar` holds C_L (D per pixel from x0)
// of the pixels marked in `touched` (per pixel from x = 0); the others have C_L = 0, or keep C_S
// with stereoCostWithoutLidar. The LiDAR weight is weights[x] (per pixel from x = 0), or
// alphaWeight256 everywhere when weights is nullptr (a fixed alpha).
struct CostFusion {
  const std::uint8_t* lidar;
  const std::uint8_t* touched;
  const std::uint16_t* weights;
  int alphaWeight256;
  bool stereoCostWithoutLidar;
};
void censusCostFusedRow(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride,
                        int pad, CensusType type, int width, int x0, int x1, int minDisparity, int numDisparities,
                        const std::uint8_t* lidar, const std::uint8_t* touched, const std::uint16_t* weights,
                        int alphaWeight256, bool stereoCostWithoutLidar, std::uint8_t* cost, RowWindows windows = {});

// vertical_census_cost.cpp: Triple-SGM C_V for pixels x0 .. x1-1 of row y.
void verticalCensusCostRow(const std::uint64_t* leftRow, ImageView<const std::uint64_t> upCensus, int y, int x0,
                           int x1, int ratio16, int minDisparity, int numDisparities, int scale, std::uint8_t* cost);

// combine_camera_costs.cpp: out = (h + v + 1) >> 1 over n bytes.
void combineCameraCostRow(const std::uint8_t* horizontal, const std::uint8_t* vertical, std::size_t n,
                          std::uint8_t* combined);

// lidar_cost.cpp: Eq. 4's table laid out per point. A point at d_P (x16) costs
// table(16 * (q + j) - d_P) at the whole disparity q + j, q = floor((d_P - reach) / 16); with
// r = d_P - reach - 16 q in [0, 16) that is table(16 j - reach - r), which depends on r alone. So
// row r holds it for j in [0, width()), the cap beyond reach, and a point's costs are one
// element-wise minimum of a row over the pixel's disparities from q on: no per-disparity lookup.
class LidarCostRows {
 public:
  LidarCostRows() = default;
  explicit LidarCostRows(const LidarCostTable& table);
  int cap() const { return cap_; }
  int reach() const { return reach_; }
  int width() const { return width_; }  // a multiple of 16, past the last entry below the cap
  const std::uint8_t* row(int r) const { return rows_.data() + static_cast<std::size_t>(r) * width_; }

 private:
  int cap_ = 0;
  int reach_ = 0;
  int width_ = 0;
  std::vector<std::uint8_t> rows_;
};

// The points of row y whose pixels lie in columns [x0, x1): slots [begin, end) of LidarPoints'
// arrays, which hold a row's points side by side in pixel order. The LiDAR passes read a row's
// run of points this way instead of visiting every pixel, most of which hold none.
struct RowPoints {
  const int* disparity16 = nullptr;  ///< LidarPoints::disparities16()
  const int* pixel = nullptr;        ///< LidarPoints::pointPixels()
  int begin = 0;
  int end = 0;
  int rowStart = 0;  ///< the pixel index of the row's column 0
  int column(int slot) const { return pixel[slot] - rowStart; }
  bool empty() const { return begin == end; }
};
inline RowPoints rowPoints(const LidarPoints& points, int y, int x0, int x1) {
  RowPoints row;
  row.disparity16 = points.disparities16().data();
  row.pixel = points.pointPixels().data();
  row.rowStart = y * points.width();
  const int* starts = points.pixelStarts().data();
  row.begin = starts[row.rowStart + x0];
  row.end = starts[row.rowStart + x1];  // pixelStarts()[W * H] ends the last row
  return row;
}

// search_window_rows.cpp: lidarSearchWindowRows (lidar_search_windows.hpp) for `points`, the same
// windows bit for bit, a vector of pixels at a time.
void searchWindowRows(const LidarPoints& points, int minDisparity, int rows, int margin, int y0, int y1,
                      std::int16_t* low16, std::int16_t* high16, SearchWindows& windows);

// lidar_cost.cpp: C_L (Eq. 4) of row y's pixels x0 .. x1-1 whose `touched` (lidarTouchedRow) is
// set into cost + (x - x0) * numDisparities; the other pixels' costs are left as they are (C_L is
// 0 there: no point, no information).
void lidarCostRow(const LidarPoints& points, const LidarCostRows& rows, int y, int x0, int x1, int minDisparity,
                  int numDisparities, const std::uint8_t* touched, std::uint8_t* cost);

// lidar_cost.cpp: 1 where a point lies in the pixel's 3x3 neighbourhood, else 0.
void lidarTouchedRow(const LidarPoints& points, int y, std::uint8_t* touched);

// fusion.cpp: Eq. 5 over n bytes: (w * C_L + (256 - w) * C_S + 128) >> 8.
void fuseCostRow(const std::uint8_t* lidar, const std::uint8_t* stereo, std::size_t n, int alphaWeight256,
                 std::uint8_t* fused);

// aggregation.cpp. Path rows hold uint8 when pathCostsFit8Bits(largest matching cost, P2),
// else uint16 (see aggregation.cpp); each kernel has both.
bool pathCostsFit8Bits(int maxCost, int P2);
template <typename T>
constexpr T pathSentinel() {
  return static_cast<T>(~T{0});
}
/// A row of `width` path slots with their sentinels set (the kernels never write them).
template <typename T>
std::vector<T> pathRowBuffer(int width, int numDisparities) {
  return std::vector<T>(static_cast<std::size_t>(width) * pathSlot(numDisparities), pathSentinel<T>());
}
// Eq. 1 along a vertical or diagonal path for pixels x0 .. x1-1 of one row. `previous` is the
// path row of the previous image row on the path (nullptr: the path starts in this row) and
// pixel x continues the path of previous pixel x - dx (outside the image: the path starts
// here, L = C). Writes out[x * slot + 1 + d] and outMin[x] = min_d L. costRow holds pixels from
// costX0 on.
void pathRowFromPrevious(const std::uint8_t* costRow, int costX0, const std::uint8_t* previous,
                         const std::uint16_t* previousMin, int dx, int width, int x0, int x1, int numDisparities,
                         int P1, int P2, std::uint8_t* out, std::uint16_t* outMin, RowWindows windows = {});
void pathRowFromPrevious(const std::uint8_t* costRow, int costX0, const std::uint16_t* previous,
                         const std::uint16_t* previousMin, int dx, int width, int x0, int x1, int numDisparities,
                         int P1, int P2, std::uint16_t* out, std::uint16_t* outMin, RowWindows windows = {});
// Eq. 1 along the row itself: dx = +1 (left to right) or -1 (right to left), whole row.
void pathRowHorizontal(const std::uint8_t* costRow, int dx, int width, int numDisparities, int P1, int P2,
                       std::uint8_t* out);
void pathRowHorizontal(const std::uint8_t* costRow, int dx, int width, int numDisparities, int P1, int P2,
                       std::uint16_t* out);
// Both: left to right into `rightward`, right to left into `leftward`, interleaved.
void pathRowsHorizontal(const std::uint8_t* costRow, int width, int numDisparities, int P1, int P2,
                        std::uint8_t* rightward, std::uint8_t* leftward, RowWindows windows = {});
void pathRowsHorizontal(const std::uint8_t* costRow, int width, int numDisparities, int P1, int P2,
                        std::uint16_t* rightward, std::uint16_t* leftward, RowWindows windows = {});
// The sum of `count` path rows for x0 .. x1-1 into a stored row (D per pixel, indexed from x0)
// of either type (the other nullptr); the caller guarantees the sum fits.
void storePathSum(const std::uint8_t* const* paths, int count, int x0, int x1, int numDisparities,
                  std::uint8_t* stored8, std::uint16_t* stored16);
void storePathSum(const std::uint16_t* const* paths, int count, int x0, int x1, int numDisparities,
                  std::uint8_t* stored8, std::uint16_t* stored16);
// sumRow[x * D + d] += path[x * slot + 1 + d] for x0 .. x1-1.
void addPathRow(const std::uint8_t* path, int x0, int x1, int numDisparities, std::uint16_t* sumRow);
void addPathRow(const std::uint16_t* path, int x0, int x1, int numDisparities, std::uint16_t* sumRow);

// selection.cpp: Eq. 2 (winner-takes-all, uniqueness, parabola) for pixels x0 .. x1-1 from
// total[(x - x0) * D + d].
void selectRow(const std::uint16_t* total, int x0, int x1, int numDisparities, int minDisparity,
               int uniquenessRatio, bool subpixel, std::int16_t* disparity16, std::int16_t* bestIndex);
// sumPathRows and selectRow in one pass per pixel (total keeps the row's S for the LR check), over
// `count` = 4 or 8 path rows (Parameters::paths; std::invalid_argument otherwise).
/// What sumSelectRow also computes from each pixel's S while it is still in the L1 cache, with
/// the code of the stand-alone row kernels below (null pointers: not wanted): the right view's
/// winners (rightDisparityIndexRow; needs the whole row: x0 = 0, x1 = width) and the peak-ratio
/// margin and S1 of the winners (peakRatioMarginRow).
struct WinnerExtras {
  int width = 0;
  std::uint16_t* rightScratch = nullptr;  ///< rightIndexScratchSize() uint16
  std::int16_t* rightIndex = nullptr;
  std::uint8_t* margin = nullptr;
  std::uint16_t* bestCost = nullptr;
  /// `total` holds only the current pixel's S (D uint16) when no one reads the row's S later:
  /// it then stays in the L1 cache instead of streaming a whole row of S through it.
  bool pixelTotal = false;
};
/// With `windows`, S, the winner, the right view's bids and the margin run over each pixel's
/// window (gated_stages.hpp); `total` then holds the window's S from its first entry.
void sumSelectRow(const std::uint8_t* const* paths, int count, const std::uint8_t* stored8,
                  const std::uint16_t* stored16, int x0, int x1, int numDisparities, int minDisparity,
                  int uniquenessRatio, bool subpixel, std::uint16_t* total, std::int16_t* disparity16,
                  std::int16_t* bestIndex, const WinnerExtras* extras = nullptr, RowWindows windows = {});
void sumSelectRow(const std::uint16_t* const* paths, int count, const std::uint8_t* stored8,
                  const std::uint16_t* stored16, int x0, int x1, int numDisparities, int minDisparity,
                  int uniquenessRatio, bool subpixel, std::uint16_t* total, std::int16_t* disparity16,
                  std::int16_t* bestIndex, const WinnerExtras* extras = nullptr, RowWindows windows = {});

// lr_check.cpp: the right view's winners of one row from its total S (D per pixel), with
// rightIndexScratchSize() uint16 of scratch; and the check of one row.
std::size_t rightIndexScratchSize(int width, int numDisparities, int minDisparity);
void rightDisparityIndexRow(const std::uint16_t* totalRow, int width, int numDisparities, int minDisparity,
                            std::uint16_t* scratch, std::int16_t* rightIndex);
void leftRightCheckRow(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                       ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                       bool keepNoCounterpart, int y);

// confidence_inputs.cpp: the confidence inputs of one row, from its total S (D per pixel) and
// winners (before the left-right check).
void peakRatioMarginRow(const std::uint16_t* totalRow, int width, int numDisparities, const std::int16_t* bestIndex,
                        std::uint8_t* margin, std::uint16_t* bestCost);
void leftRightDifferenceRow(const std::int16_t* bestIndex, const std::int16_t* rightIndex, int width,
                            int minDisparity, std::uint8_t* difference);

// median.cpp: one output row of the median filter; `columns`: 5 * width int16 of scratch.
void medianRow(ImageView<const std::int16_t> in, int size, int y, std::int16_t* columns, std::int16_t* out);

}  // namespace cpu
}  // namespace lidar_sgm

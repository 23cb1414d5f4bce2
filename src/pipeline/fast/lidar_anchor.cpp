// anchorToLidar (lidar_anchor.cpp, the specification), fast: its steps on row ranges split among
// threads (lidar_anchor_rows.hpp says why any split gives the same bytes).
#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"
#include "pipeline/lidar_anchor_rows.hpp"

namespace lidar_sgm {
namespace fast {

std::size_t anchorToLidar(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                          const LidarAnchorOptions& options, LidarAnchorBuffers& sums, FastPassBuffers& buffers,
                          int threads) {
  AnchorPlan& plan = buffers.anchorPlan;
  if (!planAnchoring(disparity16, samples, options, plan, sums)) return 0;
  const int rows = plan.lastRow - plan.firstRow + 1;
  parallelRanges(rows, threads, [&](int, int r0, int r1) {
    accumulateAnchors(disparity16, samples, plan, plan.firstRow + r0, plan.firstRow + r1, sums);
  });
  // Every range's sums are complete before any pixel moves: the sums read the pixels.
  std::vector<std::size_t>& moved = buffers.anchoredPerRange;
  moved.assign(static_cast<std::size_t>(rangeCount(rows, threads)), 0);
  parallelRanges(rows, threads, [&](int t, int r0, int r1) {
    moved[static_cast<std::size_t>(t)] =
        correctAnchored(disparity16, plan, plan.firstRow + r0, plan.firstRow + r1, sums);
  });
  std::size_t total = 0;
  for (const std::size_t n : moved) total += n;
  return total;
}

}  // namespace fast
}  // namespace lidar_sgm

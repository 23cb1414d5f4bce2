#pragma once
// anchorToLidar (lidar_anchor.hpp) in its steps, for a caller that splits the rows among threads
// (fast/lidar_anchor.cpp): planAnchoring once, accumulateAnchors on row ranges that cover
// [firstRow, lastRow], then, after every one of them, correctAnchored on such ranges. Within a step
// the ranges are independent (a range writes only its own rows' sums and pixels; the sums are
// integers, so their order does not matter): the result is anchorToLidar's for any split.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"

namespace lidar_sgm {

struct AnchorPlan {
  LidarAnchorOptions options;
  int maxD = 0, agreement = 0, gap = 0;  // x16
  std::vector<int> weights;              // (2 halfHeight + 1) rows of 2 halfWidth + 1, in 1/1024
  int firstRow = 0, lastRow = -1;        // the rows any anchoring point reaches

  /// Whether sample `s` anchors (inside the image, on a far valid pixel dq it agrees with), and its
  /// residual r = d_LiDAR - dq.
  bool anchors(ImageView<const std::int16_t> disparity, const LidarSample& s, int& residual, int& dq) const;
};

/// Validates `options`; false when nothing can be anchored. Otherwise sizes `buffers` for the
/// plan's rows.
bool planAnchoring(ImageView<const std::int16_t> disparity, const std::vector<LidarSample>& samples,
                   const LidarAnchorOptions& options, AnchorPlan& plan, LidarAnchorBuffers& buffers);
/// The sums of rows [y0, y1) (inside [firstRow, lastRow]), cleared first.
void accumulateAnchors(ImageView<const std::int16_t> disparity, const std::vector<LidarSample>& samples,
                       const AnchorPlan& plan, int y0, int y1, LidarAnchorBuffers& buffers);
/// The corrections of rows [y0, y1); returns how many of their pixels moved.
std::size_t correctAnchored(ImageView<std::int16_t> disparity, const AnchorPlan& plan, int y0, int y1,
                            const LidarAnchorBuffers& buffers);

}  // namespace lidar_sgm

// The Densifier's confidence of the valid pixels and applyMinConfidence (min_confidence.cpp, the
// specification), fast and in one pass: a row kernel compiled for every instruction set Highway
// targets (the compiler vectorises it), chosen at run time, rows split among threads.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pipeline/fast/min_confidence.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <stdexcept>

#include "lidar_sgm/pipeline/min_confidence.hpp"
#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace fast {
namespace HWY_NAMESPACE {

// confidence = matched where d is valid, else 0; below `threshold` (0: none) the pixel loses both.
void ConfidenceRow(std::int16_t* HWY_RESTRICT d, const std::uint8_t* HWY_RESTRICT matched, int width, int threshold,
                   std::uint8_t* HWY_RESTRICT confidence) {
  for (int x = 0; x < width; ++x) {
    const int c = d[x] == kInvalidDisparity ? 0 : matched[x];
    const bool drop = c < threshold;
    confidence[x] = static_cast<std::uint8_t>(drop ? 0 : c);
    d[x] = drop ? kInvalidDisparity : d[x];
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace fast
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace fast {

HWY_EXPORT(ConfidenceRow);

void confidenceOfValidPixels(ImageView<std::int16_t> disparity, ImageView<const std::uint8_t> matched,
                             ImageView<std::uint8_t> confidence, double minConfidence, int threads) {
  const int threshold = confidenceThreshold(minConfidence);  // validates
  if (disparity.width != confidence.width || disparity.height != confidence.height ||
      disparity.width != matched.width || disparity.height != matched.height) {
    throw std::invalid_argument("applyMinConfidence: the disparity and confidence images differ in size");
  }
  parallelRanges(disparity.height, threads, [&](int, int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      HWY_DYNAMIC_DISPATCH(ConfidenceRow)(disparity.row(y), matched.row(y), disparity.width, threshold,
                                          confidence.row(y));
    }
  });
}

}  // namespace fast
}  // namespace lidar_sgm
#endif  // HWY_ONCE

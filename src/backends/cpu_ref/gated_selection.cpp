// Disparity selection (Eq. 2) on the gated search's windows, reference backend: winner-takes-all,
// uniqueness, parabola, each over the pixel's window only.
#include <cstdlib>

#include "backends/common/gated_stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

// Rounded (half away from zero) integer division, as selection.cpp.
int roundedDivide(int numerator, int denominator) {
  const int half = denominator / 2;
  return numerator >= 0 ? (numerator + half) / denominator : -((-numerator + half) / denominator);
}

}  // namespace

void selectDisparity(const WindowedAggregatedCost& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out) {
  const SearchWindows& windows = sum.windows();
  for (int y = 0; y < sum.height(); ++y) {
    for (int x = 0; x < sum.width(); ++x) {
      const int first = windows.first(x, y);
      const int end = first + windows.count(x, y);
      int best = first;  // first minimum wins ties
      for (int d = first + 1; d < end; ++d) {
        if (sum(x, y, d) < sum(x, y, best)) best = d;
      }
      bool unique = true;
      if (uniquenessRatio > 0) {
        for (int d = first; d < end && unique; ++d) {
          if (std::abs(d - best) > 1 && sum(x, y, d) * (100 - uniquenessRatio) < sum(x, y, best) * 100) unique = false;
        }
      }
      if (!unique) {
        out.disparity16(x, y) = kInvalidDisparity;
        out.bestIndex(x, y) = -1;
        continue;
      }
      int offset16 = 0;
      if (subpixel && best > first && best < end - 1) {
        // Vertex of the parabola through (best-1, best, best+1), both neighbours in the window.
        const int before = sum(x, y, best - 1);
        const int after = sum(x, y, best + 1);
        const int curvature = before + after - 2 * sum(x, y, best);
        if (curvature > 0) offset16 = roundedDivide((before - after) * kDisparityScale, 2 * curvature);
      }
      out.disparity16(x, y) = static_cast<std::int16_t>((minDisparity + best) * kDisparityScale + offset16);
      out.bestIndex(x, y) = static_cast<std::int16_t>(best);
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm

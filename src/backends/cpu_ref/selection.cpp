// Disparity selection (Eq. 2), reference backend: winner-takes-all, uniqueness, parabola.
#include <cstdlib>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

// Rounded (half away from zero) integer division, so every backend gets the same sub-pixel value.
int roundedDivide(int numerator, int denominator) {
  const int half = denominator / 2;
  return numerator >= 0 ? (numerator + half) / denominator : -((-numerator + half) / denominator);
}

}  // namespace

void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio,
                     bool subpixel, SelectedDisparity out) {
  const int D = sum.numDisparities();
  for (int y = 0; y < sum.height(); ++y) {
    for (int x = 0; x < sum.width(); ++x) {
      const std::uint16_t* S = sum.at(x, y);
      int best = 0;  // first minimum wins ties
      for (int d = 1; d < D; ++d) {
        if (S[d] < S[best]) best = d;
      }
      bool unique = true;
      if (uniquenessRatio > 0) {
        // OpenCV's rule: every cost farther than 1 px from the winner must exceed it by the ratio.
        for (int d = 0; d < D && unique; ++d) {
          if (std::abs(d - best) > 1 && S[d] * (100 - uniquenessRatio) < S[best] * 100) unique = false;
        }
      }
      if (!unique) {
        out.disparity16(x, y) = kInvalidDisparity;
        out.bestIndex(x, y) = -1;
        continue;
      }
      int offset16 = 0;
      if (subpixel && best > 0 && best < D - 1) {
        // Vertex of the parabola through (best-1, best, best+1): (S- - S+) / (2 (S- + S+ - 2 S)).
        const int before = S[best - 1];
        const int after = S[best + 1];
        const int curvature = before + after - 2 * S[best];
        if (curvature > 0) offset16 = roundedDivide((before - after) * kDisparityScale, 2 * curvature);
      }
      out.disparity16(x, y) = static_cast<std::int16_t>((minDisparity + best) * kDisparityScale + offset16);
      out.bestIndex(x, y) = static_cast<std::int16_t>(best);
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm

#pragma once
// Eq. 3 backwards, z = f * b / d, once per value of the x16 disparity instead of once per pixel:
// the fast reprojection divided five times per pixel that gives a point (z for the depth image,
// again to count the row's points, then z, x and y of the point), and a double division costs
// several multiplications. The table holds the very quotient the specification computes
// (reprojection.cpp), so the depths it gives are the same doubles; x and y keep their divisions.

#include <cstdint>
#include <vector>

namespace lidar_sgm {
namespace fast {

class DepthTable {
 public:
  /// The table for `focalBaseline` (f * b in pixel metres); kept while it stays the same.
  void prepare(double focalBaseline);

  /// z of a positive x16 disparity d16 (in [1, 32767]).
  double depth(int d16) const { return depth_[static_cast<std::size_t>(d16)]; }

  /// The smallest positive d16 whose z is at most `maxDepth` (32768: none). z falls as d16
  /// grows (a correctly rounded quotient of a fixed numerator is monotone), so a pixel gives a
  /// point exactly when its d16 is at least this.
  int firstWithin(double maxDepth) const;

 private:
  double focalBaseline_ = 0.0;  // 0: not built yet
  std::vector<double> depth_;   // depth_[d16]; depth_[0] is unused
};

}  // namespace fast
}  // namespace lidar_sgm
